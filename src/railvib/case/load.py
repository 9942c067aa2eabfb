"""Load and validate case files, and build the physics objects they describe."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from pydantic import ValidationError

from railvib.case.build import build_grid, build_pad
from railvib.case.errors import case_error
from railvib.case.schema import FAMILY_TABLES, Case
from railvib.errors import CaseError
from railvib.io import read_toml
from railvib.presets import load_preset
from railvib.registry import merge_tables, resolve_paths

__all__ = ["case_from_dict", "load_case", "merge_case_dicts"]


def load_case(path: str | Path) -> Case:
    """Read and validate a TOML case file.

    A case may start from a preset with ``preset = "<name>"`` (see
    :func:`railvib.presets.list_presets`); its other keys then override the
    preset's field by field.

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file.

    Returns
    -------
    Case
        The validated case, SI units except where a key names its unit.

    Raises
    ------
    CaseError
        With the dotted field name, the value and what is allowed.
    """
    path = Path(path)
    hint = "`railvib template > case.toml` writes one"
    data = read_toml(path, "case", hint)
    if "axes" in data:
        raise CaseError(
            "case",
            str(path),
            "a case file; this is a sweep file ([[axes]]): run it with `railvib sweep`",
        )
    return case_from_dict(data, base_dir=path.parent)


def case_from_dict(data: dict[str, Any], base_dir: str | Path | None = None) -> Case:
    """Validate a case given as a plain dict (the parsed TOML).

    Parameters
    ----------
    data : dict
        Case tables; may contain ``preset = "<name>"``.
    base_dir : str or pathlib.Path, optional
        Directory against which relative file paths in the case are resolved.

    Returns
    -------
    Case
    """
    data = copy.deepcopy(data)
    preset = data.pop("preset", None)
    output = data.get("output")
    given = isinstance(output, dict) and "rms_bands" in output
    bands_from = "" if given else f"preset {preset!r}" if preset is not None else "the default"
    if preset is not None:
        data = merge_case_dicts(load_preset(preset), data)
    if base_dir is not None:
        _resolve_paths(data, Path(base_dir))
    try:
        case = Case.model_validate(data)
    except ValidationError as exc:
        raise case_error(exc, Case) from None
    _check_models(case, bands_from)
    return case


def merge_case_dicts(base: dict[str, Any], override: dict[str, Any]) -> dict[str, Any]:
    """Deep-merge `override` onto `base` (see :func:`railvib.registry.merge_tables`).

    A table that names a member (``model`` or ``type``) replaces the base table.

    Parameters
    ----------
    base : dict
        Parsed case tables, e.g. a preset.
    override : dict
        Parsed case tables merged on top, e.g. a user's case file.

    Returns
    -------
    dict
        A new dict; neither input is modified.
    """
    return merge_tables(base, override)


def _resolve_paths(data: dict[str, Any], base_dir: Path) -> None:
    """Make the ``path`` parameters of the case's family tables relative to the case file."""
    for location, family in FAMILY_TABLES.items():
        resolve_paths(_table_at(data, location), family, base_dir)


def _table_at(data: Any, location: tuple[str, ...]) -> Any:
    for part in location:
        data = data.get(part) if isinstance(data, dict) else None
    return data


def _check_models(case: Case, bands_from: str = "") -> None:
    """Build every family table of the case, and evaluate the pad on the case's grid.

    So an unknown model, a bad parameter, a pad that is not passive somewhere on
    the grid, a temperature the pad's WLF law cannot take, or an RMS band the grid
    cannot resolve, is reported as a case error before anything runs.
    """
    data = case.model_dump(mode="python")
    for location, family in FAMILY_TABLES.items():
        family.from_dict(_table_at(data, location), ".".join(location))
    grid = build_grid(case)
    _check_bands(case, grid.f, bands_from)
    temperature = case.track.pad_temperature_c
    try:
        build_pad(case).check_passive(grid.f, temperature, field="track.pad")
    except CaseError as exc:
        if exc.field.startswith("track.pad") and exc.field != "track.pad_temperature_c":
            raise
        raise CaseError("track.pad_temperature_c", temperature, exc.allowed) from None


def _check_bands(case: Case, f: NDArray[np.float64], bands_from: str = "") -> None:
    """Each ``[output] rms_bands`` band holds at least two frequencies of the case's grid.

    A band outside the grid or between two grid points has no trapezoidal integral
    (and one grid point would give an RMS of 0); it is refused when the case is
    loaded, so a run writes all its outputs or none. A band reaching past the grid
    is integrated over the part on the grid, as before. `bands_from` names where bands
    the case file did not set came from (``"preset 'wang2017_metro'"``), so the message
    says to set them for this grid.
    """
    fr = case.frequency
    for i, (lo, hi) in enumerate(case.output.rms_bands):
        inside = int(np.count_nonzero((f >= lo) & (f <= hi)))
        if inside < 2:
            fix = (
                f"the bands are those of {bands_from}: set [output] rms_bands for this grid"
                if bands_from
                else "widen or move the band, or change [frequency]"
            )
            raise CaseError(
                f"output.rms_bands[{i}]",
                [lo, hi],
                f"a band holding at least two frequencies of the grid [{fr.f_min:g}, "
                f"{fr.f_max:g}] Hz (this one holds {inside}); {fix} (Hz)",
            )
