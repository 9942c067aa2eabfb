"""Load and validate case files, and build the physics objects they describe."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from railvib.case.schema import Case
from railvib.errors import CaseError

__all__ = ["case_from_dict", "load_case", "merge_case_dicts"]

#: tables replaced wholesale (not merged) when an override names a new model/type
_MODEL_TABLES = {("track", "pad"): "model", ("irregularity",): "type"}


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
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise CaseError("case", str(path), f"a readable TOML file ({exc.strerror})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError("case", str(path), f"valid TOML ({exc})") from None
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
    if preset is not None:
        from railvib.presets import load_preset

        data = merge_case_dicts(load_preset(preset), data)
    if base_dir is not None:
        _resolve_paths(data, Path(base_dir))
    try:
        case = Case.model_validate(data)
    except ValidationError as exc:
        raise _case_error(exc) from None
    _check_models(case)
    return case


def merge_case_dicts(base: dict[str, Any], override: dict[str, Any]) -> dict[str, Any]:
    """Deep-merge `override` onto `base` (model/type tables replaced when the model changes)."""
    return _merge(copy.deepcopy(base), override, ())


def _merge(base: dict[str, Any], override: dict[str, Any], path: tuple[str, ...]) -> dict[str, Any]:
    for key, value in override.items():
        here = (*path, key)
        old = base.get(key)
        tag = _MODEL_TABLES.get(here)
        replace = tag is not None and isinstance(value, dict) and tag in value
        if isinstance(value, dict) and isinstance(old, dict) and not replace:
            base[key] = _merge(old, value, here)
        else:
            base[key] = copy.deepcopy(value)
    return base


def _resolve_paths(data: dict[str, Any], base_dir: Path) -> None:
    """Make ``path`` entries of model tables relative to the case file."""
    for table in (data.get("irregularity"), data.get("track", {}).get("pad")):
        if isinstance(table, dict):
            for sub in (table, table.get("long_wave"), table.get("short_wave")):
                if isinstance(sub, dict) and isinstance(sub.get("path"), str):
                    p = Path(sub["path"])
                    if not p.is_absolute():
                        sub["path"] = str(base_dir / p)


def _check_models(case: Case) -> None:
    """Build the pad and spectrum, and evaluate the pad on the case's grid, at load time.

    So a pad that is not passive somewhere on the grid, or a temperature the pad's
    WLF law cannot take, is reported as a case error before anything runs.
    """
    from railvib.case.build import build_grid, build_pad, build_spectrum

    pad = build_pad(case)
    build_spectrum(case)
    temperature = case.track.pad_temperature_c
    try:
        pad.check_passive(build_grid(case).f, temperature, field="track.pad")
    except CaseError as exc:
        if exc.field.startswith("track.pad") and exc.field != "track.pad_temperature_c":
            raise
        raise CaseError("track.pad_temperature_c", temperature, exc.allowed) from None


def _case_error(exc: ValidationError) -> CaseError:
    """Turn the first pydantic error into a one-line CaseError with units."""
    err = exc.errors()[0]
    inner = (err.get("ctx") or {}).get("error")
    if isinstance(inner, CaseError):
        return inner
    loc = [str(p) for p in err["loc"]]
    field = ".".join(loc) if loc else "case"
    unit = _unit_of(loc)
    unit_txt = f" ({unit})" if unit else ""
    kind = err["type"]
    value = err.get("input")
    ctx = err.get("ctx") or {}
    if kind == "missing":
        return CaseError(field, "<missing>", f"required{unit_txt}")
    if kind == "extra_forbidden":
        allowed = ", ".join(_allowed_keys(loc[:-1]))
        return CaseError(field, value, f"unknown key; allowed here: {allowed}")
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        op = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<"}.get(kind, "<=")
        bound = next(iter(ctx.values()))
        return CaseError(field, value, f"must be {op} {bound}{unit_txt}")
    if kind == "literal_error":
        return CaseError(field, value, f"must be one of {ctx.get('expected')}")
    if kind in ("float_parsing", "float_type", "int_parsing", "int_type", "int_from_float"):
        what = "an integer" if kind.startswith("int") else "a number"
        return CaseError(field, value, f"must be {what}{unit_txt}")
    return CaseError(field, value, err["msg"] + unit_txt)


def _model_at(loc: list[str]) -> Any:
    model: Any = Case
    for part in loc:
        fields = getattr(model, "model_fields", None)
        if not fields or part not in fields:
            return None
        model = fields[part].annotation
    return model


def _allowed_keys(loc: list[str]) -> list[str]:
    model = _model_at(loc)
    return sorted(getattr(model, "model_fields", {}))


def _unit_of(loc: list[str]) -> str:
    if not loc:
        return ""
    parent = _model_at(loc[:-1])
    fields = getattr(parent, "model_fields", {})
    info = fields.get(loc[-1])
    extra = getattr(info, "json_schema_extra", None) or {}
    return str(extra.get("unit", "")) if isinstance(extra, dict) else ""
