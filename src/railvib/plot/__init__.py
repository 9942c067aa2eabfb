"""Plotting: functions take result datasets and return matplotlib axes or figures.

This package module loads no matplotlib; its submodules do.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from railvib.labels import rail_label

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["DEFAULT_SWEEP_RESPONSES", "OVERVIEW_GROUPS", "OVERVIEW_STEMS", "save_run_figures"]

#: responses drawn by :func:`railvib.plot.sweep.save_sweep_plots` when none is given
DEFAULT_SWEEP_RESPONSES = ("carbody.bounce", "wheelset1.bounce", rail_label(1))

#: (file stem, title, responses) of the response figures written by ``railvib run``
OVERVIEW_GROUPS: tuple[tuple[str, str, tuple[str, ...]], ...] = (
    ("psd_carbody", "Car body", ("carbody.bounce",)),
    ("psd_bogie", "Bogies", ("bogie1.bounce", "bogie2.bounce")),
    ("psd_wheelset", "Wheelsets", tuple(f"wheelset{i}.bounce" for i in range(1, 5))),
    ("psd_rail", "Rail under the wheels", tuple(rail_label(i) for i in range(1, 5))),
    ("psd_pitch", "Pitch", ("carbody.pitch", "bogie1.pitch", "bogie2.pitch")),
)

#: the file stems of every figure :func:`railvib.plot.psd.save_overview` may write (the
#: groups, then the contact forces, the irregularity and the pad), known without
#: matplotlib (``railvib run`` replaces an earlier run's figures with its own)
OVERVIEW_STEMS = (
    *(stem for stem, _, _ in OVERVIEW_GROUPS),
    "psd_force",
    "irregularity_psd",
    "pad_stiffness",
)


def save_run_figures(ds: xr.Dataset, outdir: str | Path) -> list[Path]:
    """Write every figure of ``railvib run``: the overview, then the criteria figures.

    :func:`railvib.plot.psd.save_overview` and
    :func:`railvib.plot.criteria.save_criteria_plots`, loading matplotlib on the call (so
    that ``railvib run`` can draw them in a second process,
    :meth:`railvib.io.StagedFolder.background`, while it writes its other files).

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset of :func:`railvib.run`.
    outdir : str or pathlib.Path
        Folder for the PNG files.

    Returns
    -------
    list of pathlib.Path
        The files written, in that order.
    """
    from railvib.plot.criteria import save_criteria_plots  # matplotlib: when drawing
    from railvib.plot.psd import save_overview

    return [*save_overview(ds, outdir), *save_criteria_plots(ds, outdir)]
