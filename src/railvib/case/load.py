"""Load and validate case files, and build the physics objects they describe."""

from __future__ import annotations

import copy
import warnings
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from pydantic import ValidationError

from railvib.case.build import build_grid, build_pad, build_track
from railvib.case.errors import case_error
from railvib.case.plausibility import check_grid_size, plausibility_warnings
from railvib.case.schema import FAMILY_TABLES, Case
from railvib.errors import CaseError
from railvib.io import check_nesting, read_toml
from railvib.pads import PadModel
from railvib.presets import DEFAULT_PRESET, load_preset, load_vehicle_preset
from railvib.registry import merge_tables, resolve_paths

__all__ = [
    "case_from_dict",
    "case_with_table",
    "load_case",
    "load_preset_case",
    "merge_case_dicts",
]


def load_case(path: str | Path, *, force: bool = False) -> Case:
    """Read and validate a TOML case file.

    A case may start from a preset with ``preset = "<name>"`` (see
    :func:`railvib.presets.list_presets`); its other keys then override the
    preset's field by field. Legal but suspicious values warn (see
    :func:`case_from_dict`).

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file.
    force : bool
        Accept a grid of more than :data:`railvib.case.plausibility.MAX_FREQUENCIES`
        frequencies.

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
    return case_from_dict(data, base_dir=path.parent, force=force)


def case_from_dict(
    data: dict[str, Any],
    base_dir: str | Path | None = None,
    *,
    force: bool = False,
    warn: bool = True,
) -> Case:
    """Validate a case given as a plain dict (the parsed TOML).

    After validation, legal but suspicious values (an implausible speed, pad
    stiffness or pad temperature, a very large grid; see
    :func:`railvib.case.plausibility.plausibility_warnings`) each issue one
    :class:`~railvib.errors.PlausibilityWarning` naming the field, and a grid of more
    than :data:`railvib.case.plausibility.MAX_FREQUENCIES` frequencies is refused
    unless `force`.

    Parameters
    ----------
    data : dict
        Case tables; may contain ``preset = "<name>"``.
    base_dir : str or pathlib.Path, optional
        Directory against which relative file paths in the case are resolved.
    force : bool
        Accept a grid of any size (``railvib run --force``).
    warn : bool
        Issue the plausibility warnings (False where a case already loaded is
        validated again, e.g. inside a sweep's workers).

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        With the dotted field name, the value and what is allowed.
    """
    check_nesting(data, "case")  # before anything recurses into it
    data = copy.deepcopy(data)
    preset = data.pop("preset", None)
    own_track = data.get("track")
    temperature_given = isinstance(own_track, dict) and "pad_temperature_c" in own_track
    output = data.get("output")
    bands_given = isinstance(output, dict) and "rms_bands" in output
    _resolve_vehicle(data, None if base_dir is None else Path(base_dir))
    if preset is not None:
        data = merge_case_dicts(load_preset(preset), data)
        _resolve_vehicle(data, None)
    if base_dir is not None:
        _resolve_paths(data, Path(base_dir))
    try:
        case = Case.model_validate(data)
    except ValidationError as exc:
        raise case_error(exc, Case) from None
    check_grid_size(case, force=force)  # before the grid is built
    pad, f = _check_models(case)
    case = _fit_bands(case, f, bands_given)
    if warn:
        for warning in plausibility_warnings(case, pad, f, temperature_given=temperature_given):
            warnings.warn(warning, stacklevel=2)
    return case


def case_with_table(
    base_data: dict[str, Any],
    base_case: Case,
    key: str,
    value: Any,
    base_dir: str | Path | None = None,
    *,
    warn: bool = True,
) -> Case:
    """Validate the case `base_data` with `value` merged onto its table `key`.

    The same checks, errors and warnings as ``case_from_dict(merge_case_dicts(base_data,
    {key: value}), base_dir)``, without validating again what `value` cannot change:
    the other tables are taken from `base_case` as they are (validated sections are
    not validated again) and their family tables are not built again. The grid size,
    the track and pad on the grid, the RMS bands and the plausibility warnings are
    checked as :func:`case_from_dict` checks them. For a sweep's axis values, each
    checked against one base case.

    Parameters
    ----------
    base_data : dict
        A resolved case without a preset (e.g. a sweep's base case, as a JSON-able table).
    base_case : Case
        ``case_from_dict(base_data, base_dir)``.
    key : str
        A top-level table or field of the case, e.g. ``"track"``.
    value : object
        Merged onto ``base_data[key]`` (:func:`merge_case_dicts`).
    base_dir : str or pathlib.Path, optional
        Directory against which relative file paths in `value` are resolved.
    warn : bool
        Issue the plausibility warnings.

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        With the dotted field name, the value and what is allowed.
    """
    if key == "preset" or "preset" in base_data:
        raise ValueError("case_with_table takes a resolved base case and a case field")
    old = {key: base_data[key]} if key in base_data else {}
    data = merge_case_dicts(old, {key: value})  # a copy
    check_nesting(data, "case")
    tables = {**base_data, **data}
    own_track, output = tables.get("track"), tables.get("output")
    temperature_given = isinstance(own_track, dict) and "pad_temperature_c" in own_track
    bands_given = isinstance(output, dict) and "rms_bands" in output
    if key == "vehicle":
        _resolve_vehicle(data, None if base_dir is None else Path(base_dir))
    if base_dir is not None:
        for location, family in FAMILY_TABLES.items():
            if location[0] == key:
                resolve_paths(_table_at(data, location), family, Path(base_dir))
    fields = {name: getattr(base_case, name) for name in Case.model_fields}
    fields = {name: v for name, v in fields.items() if v is not None} | data
    try:
        case = Case.model_validate(fields)
    except ValidationError as exc:
        raise case_error(exc, Case) from None
    check_grid_size(case)
    pad, f = _check_models(case, key)
    case = _fit_bands(case, f, bands_given)
    if warn:
        for warning in plausibility_warnings(case, pad, f, temperature_given=temperature_given):
            warnings.warn(warning, stacklevel=2)
    return case


def load_preset_case(name: str = DEFAULT_PRESET) -> Case:
    """The validated case of preset `name` (``railvib.load_preset_case``).

    Parameters
    ----------
    name : str
        A preset (:func:`railvib.presets.list_presets`); default: the paper's analysis.

    Returns
    -------
    Case
        The preset as a validated case.
    """
    return case_from_dict({"preset": name})


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


def _resolve_vehicle(data: dict[str, Any], base_dir: Path | None) -> None:
    """Replace a ``[vehicle]`` table that names a vehicle file or preset by its contents.

    ``[vehicle] file = "my_car.toml"`` (relative to the case file) or ``[vehicle] preset =
    "<name>"`` (:func:`railvib.presets.list_vehicle_presets`); the table takes no other key.
    The file's table names its ``model`` (omitted: ``multibody``), so it replaces a preset's
    vehicle whole (:func:`railvib.registry.merge_tables`).
    """
    table = data.get("vehicle")
    if not isinstance(table, dict) or not ({"file", "preset"} & set(table)):
        return
    key = "file" if "file" in table else "preset"
    for other in table:
        if other != key:
            raise CaseError(
                f"vehicle.{other}",
                table[other],
                f"no other key beside vehicle.{key} (write it in the vehicle file)",
            )
    value = table[key]
    if not isinstance(value, str) or not value:
        raise CaseError(f"vehicle.{key}", value, "a file path" if key == "file" else "a name")
    if key == "preset":
        loaded = load_vehicle_preset(value)
    else:
        path = Path(value)
        if not path.is_absolute() and base_dir is not None:
            path = base_dir / path
        loaded = read_toml(path, "vehicle.file", "docs/vehicles.md shows one")
    loaded.setdefault("model", "multibody")
    data["vehicle"] = loaded


def _resolve_paths(data: dict[str, Any], base_dir: Path) -> None:
    """Make the ``path`` parameters of the case's family tables relative to the case file."""
    for location, family in FAMILY_TABLES.items():
        resolve_paths(_table_at(data, location), family, base_dir)


def _table_at(data: Any, location: tuple[str, ...]) -> Any:
    for part in location:
        data = data.get(part) if isinstance(data, dict) else None
    return data


def _check_models(case: Case, key: str | None = None) -> tuple[PadModel, NDArray[np.float64]]:
    """Build every family table of the case, and evaluate the pad on the case's grid.

    So an unknown model, a bad parameter, a pad that is not passive somewhere on
    the grid, or a temperature the pad's WLF law cannot take, is reported as a case
    error before anything runs. Returns the pad and the grid's frequencies (Hz).
    With `key`, only the family tables of the case's table `key` are built (the
    others were built when the case they come from was validated).
    """
    data = case.model_dump(mode="python")
    for location, family in FAMILY_TABLES.items():
        if key is not None and location[0] != key:
            continue
        table = _table_at(data, location)
        if table is not None:  # an optional table left out (its model's needs are checked)
            family.from_dict(table, ".".join(location))
    f = build_grid(case).f
    build_track(case).check_frequencies(f)
    temperature = case.track.pad_temperature_c
    pad = build_pad(case)
    try:
        pad.check_passive(f, temperature, field="track.pad")
    except CaseError as exc:
        if exc.field.startswith("track.pad") and exc.field != "track.pad_temperature_c":
            raise
        raise CaseError("track.pad_temperature_c", temperature, exc.allowed) from None
    return pad, f


def _fit_bands(case: Case, f: NDArray[np.float64], given: bool) -> Case:
    """`case` with RMS bands its grid resolves: each holds at least two grid frequencies.

    A band outside the grid or between two grid points has no trapezoidal integral
    (one grid point would give an RMS of 0). A band the case file gives is refused
    then, when the case is loaded, so a run writes all its outputs or none; bands the
    case did not set (a preset's, or the default ones) that the grid does not reach
    are left out of the summary: the user never asked for them. A band reaching past
    the grid is integrated over the part on the grid, as before.

    Parameters
    ----------
    case : Case
        The validated case.
    f : numpy.ndarray
        Frequencies of its grid, Hz.
    given : bool
        Whether the case file (not a preset or the default) sets ``[output] rms_bands``.

    Returns
    -------
    Case
        `case`, or a copy without the inherited bands the grid cannot hold.
    """
    fr = case.frequency
    keep = []
    for i, (lo, hi) in enumerate(case.output.rms_bands):
        inside = int(np.count_nonzero((f >= lo) & (f <= hi)))
        if inside >= 2:
            keep.append((lo, hi))
        elif given:
            raise CaseError(
                f"output.rms_bands[{i}]",
                [lo, hi],
                f"a band holding at least two frequencies of the grid [{fr.f_min:g}, "
                f"{fr.f_max:g}] Hz (this one holds {inside}); widen or move the band, or "
                "change [frequency] (Hz)",
            )
    if len(keep) == len(case.output.rms_bands):
        return case
    output = case.output.model_copy(update={"rms_bands": keep})
    return case.model_copy(update={"output": output})
