"""Run the study's cases (each a shipped preset) and keep their result datasets."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import xarray as xr

from railvib.case import Case, case_from_dict
from railvib.reproduce.study import CASES, StudyCase
from railvib.solve import run

__all__ = ["load_study_cases", "run_cases"]


def load_study_cases(cases: Sequence[StudyCase] = CASES) -> dict[str, Case]:
    """The validated case of every study case, by case key.

    Parameters
    ----------
    cases : sequence of StudyCase
        The cases (default: all of :data:`railvib.reproduce.study.CASES`).

    Returns
    -------
    dict of str to Case
        The validated case of each study case's preset, by case key.
    """
    return {c.key: case_from_dict({"preset": c.preset}) for c in cases}


def run_cases(
    cases: Sequence[StudyCase] = CASES,
    on_case: Callable[[StudyCase], None] | None = None,
) -> dict[str, xr.Dataset]:
    """Run every study case.

    Parameters
    ----------
    cases : sequence of StudyCase
        The cases (default: all of :data:`railvib.reproduce.study.CASES`).
    on_case : callable, optional
        Called with each case after it has run (progress reporting).

    Returns
    -------
    dict of str to xarray.Dataset
        Result dataset of :func:`railvib.run` by case key.
    """
    loaded = load_study_cases(cases)
    out: dict[str, xr.Dataset] = {}
    for c in cases:
        out[c.key] = run(loaded[c.key])
        if on_case is not None:
            on_case(c)
    return out
