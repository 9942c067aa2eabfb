"""Sweep files: a base case plus axes, validated like case files.

A sweep file is TOML::

    title = "pad temperature x speed"
    mode = "product"                 # full factorial ("zip": all axes vary together)
    chunk_size = 50                  # cases per stored chunk
    variables = ["psd_acceleration"] # per-frequency variables kept ([] = summary only)

    [case]                           # the base case, inline (or base = "case.toml")
    preset = "wang2017_metro"

    [[axes]]
    field = "track.pad_temperature_c"
    start = -40.0
    stop = 40.0
    step = 10.0

    [[axes]]
    field = "speed_kmh"
    values = [40.0, 80.0, 120.0, 160.0]

Every error is a :class:`~railvib.errors.CaseError` naming the field
(``axes[1].step``, ``speed_kmh``, ...).
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from pathlib import Path
from typing import Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from railvib.case import Case, case_from_dict, merge_case_dicts
from railvib.errors import CaseError
from railvib.results.variables import PER_FREQUENCY, VARIABLES

__all__ = [
    "PER_FREQUENCY_VARIABLES",
    "AxisSpec",
    "SweepFile",
    "load_sweep",
    "nested_override",
    "sweep_from_dict",
]

#: per-frequency variables a sweep may keep, with their extra dimension
PER_FREQUENCY_VARIABLES = {name: VARIABLES[name].extra_dim for name in PER_FREQUENCY}

#: case fields that cannot vary: every case shares one grid and one set of summary bands
_FIXED_PREFIXES = ("frequency", "output", "title")


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class AxisSpec(_Model):
    """One sweep axis: a case field and the values it takes.

    Give exactly one of ``values``; ``start``/``stop`` with ``num`` (inclusive,
    ``spacing = "linear"`` or ``"log"``); or ``start``/``stop``/``step``
    (linear, ``stop`` included where it lands).
    """

    field: str = Field(..., min_length=1, description="dotted case field, e.g. speed_kmh")
    name: str | None = Field(None, min_length=1, description="dimension name (default: field)")
    values: list[Any] | None = Field(None, min_length=1, description="explicit values")
    start: float | None = None
    stop: float | None = None
    num: int | None = Field(None, ge=1)
    step: float | None = Field(None, gt=0.0)
    spacing: Literal["linear", "log"] = "linear"
    labels: list[str] | None = Field(None, description="coordinate labels (tables as values)")
    zip: str | None = Field(None, min_length=1, description="axes with one zip label vary together")

    @model_validator(mode="after")
    def _one_kind(self) -> AxisSpec:
        ranged = self.start is not None or self.stop is not None
        if self.values is not None and (ranged or self.num is not None or self.step is not None):
            raise CaseError("values", "values and start/stop/num/step", "give one of the two")
        if self.values is None:
            if self.start is None or self.stop is None:
                raise CaseError("start", None, "values, or start and stop with num or step")
            if (self.num is None) == (self.step is None):
                raise CaseError("num", self.num, "give exactly one of num and step")
            if self.spacing == "log" and not (self.start > 0 and self.stop > 0):
                raise CaseError("start", self.start, "a log range needs start, stop > 0")
            if self.step is not None and self.spacing == "log":
                raise CaseError("step", self.step, "a log range takes num, not step")
            if self.step is not None and self.stop < self.start:
                raise CaseError("stop", self.stop, f"must be >= start = {self.start}")
        return self

    @property
    def dim(self) -> str:
        """The dimension (coordinate) name of this axis."""
        return self.name or self.field

    def resolved_values(self) -> list[Any]:
        """Return the axis values as plain Python scalars (or tables)."""
        if self.values is not None:
            return list(self.values)
        assert self.start is not None
        assert self.stop is not None
        if self.step is not None:
            n = int(math.floor((self.stop - self.start) / self.step + 1e-9)) + 1
            arr = self.start + self.step * np.arange(n)
        elif self.spacing == "log":
            arr = np.geomspace(self.start, self.stop, int(self.num or 1))
        else:
            arr = np.linspace(self.start, self.stop, int(self.num or 1))
        return [float(v) for v in arr]


class SweepFile(_Model):
    """The parsed sweep file (before the base case is resolved)."""

    title: str = "railvib sweep"
    base: str | None = Field(None, description="path of a base case file (relative to the sweep)")
    case: dict[str, Any] | None = Field(None, description="inline base case or overrides of base")
    mode: Literal["product", "zip"] = "product"
    chunk_size: int = Field(50, ge=1, description="cases per stored chunk")
    variables: list[str] = Field(default_factory=lambda: ["psd_acceleration"])
    summary_variable: Literal["psd_acceleration", "psd_displacement"] = "psd_acceleration"
    axes: list[AxisSpec] = Field(..., min_length=1)

    @model_validator(mode="after")
    def _check(self) -> SweepFile:
        for i, name in enumerate(self.variables):
            if name not in PER_FREQUENCY_VARIABLES:
                raise CaseError(
                    f"variables[{i}]", name, f"one of {', '.join(PER_FREQUENCY_VARIABLES)}"
                )
        if self.base is None and self.case is None:
            raise CaseError("case", "<missing>", "a [case] table and/or base = PATH")
        return self


def load_sweep(path: str | Path) -> dict[str, Any]:
    """Read, validate and resolve a TOML sweep file.

    Parameters
    ----------
    path : str or pathlib.Path
        The sweep file.

    Returns
    -------
    dict
        The resolved sweep (see :func:`sweep_from_dict`).

    Raises
    ------
    CaseError
        With the dotted field name, the value and what is allowed.
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise CaseError("sweep", str(path), f"a readable TOML file ({exc.strerror})") from None
    except tomllib.TOMLDecodeError as exc:
        raise CaseError("sweep", str(path), f"valid TOML ({exc})") from None
    return sweep_from_dict(data, base_dir=path.parent)


def sweep_from_dict(data: dict[str, Any], base_dir: str | Path | None = None) -> dict[str, Any]:
    """Validate a sweep given as a plain dict and resolve it.

    Parameters
    ----------
    data : dict
        The parsed sweep file.
    base_dir : str or pathlib.Path, optional
        Directory against which ``base`` and data-file paths are resolved.

    Returns
    -------
    dict
        JSON-able: ``title``, ``mode``, ``chunk_size``, ``variables``,
        ``summary_variable``, ``base_case`` (the fully resolved, validated base
        case as a dict) and ``axes`` (list of ``{field, dim, group, values,
        coords}``). It fully determines the results, so its hash is the sweep's
        fingerprint.
    """
    base_dir = Path(base_dir) if base_dir is not None else Path.cwd()
    try:
        spec = SweepFile.model_validate(data)
    except ValidationError as exc:
        raise _sweep_error(exc) from None
    base_case = _resolve_base(spec, base_dir)
    axes = _resolve_axes(spec, base_case, base_dir)
    return {
        "title": spec.title,
        "mode": spec.mode,
        "chunk_size": spec.chunk_size,
        "variables": list(spec.variables),
        "summary_variable": spec.summary_variable,
        "base_case": base_case,
        "axes": axes,
    }


def nested_override(field: str, value: Any) -> dict[str, Any]:
    """``"a.b.c", v`` -> ``{"a": {"b": {"c": v}}}`` (a deep copy of `value`)."""
    out: dict[str, Any] = {}
    node = out
    parts = field.split(".")
    for part in parts[:-1]:
        node[part] = {}
        node = node[part]
    node[parts[-1]] = copy.deepcopy(value)
    return out


def _case_dump(case: Case) -> dict[str, Any]:
    return case.model_dump(mode="json", exclude_none=True)


def _resolve_base(spec: SweepFile, base_dir: Path) -> dict[str, Any]:
    data: dict[str, Any] = {}
    if spec.base is not None:
        from railvib.case import load_case

        p = Path(spec.base)
        data = _case_dump(load_case(p if p.is_absolute() else base_dir / p))
        if spec.case and "preset" in spec.case:
            raise CaseError("case.preset", spec.case["preset"], "not allowed together with base")
    if spec.case:
        override = copy.deepcopy(spec.case)
        preset = override.pop("preset", None)
        if preset is not None:
            from railvib.presets import load_preset

            data = load_preset(preset)
        data = merge_case_dicts(data, override)
    return _case_dump(case_from_dict(data, base_dir=base_dir))


def _resolve_axes(spec: SweepFile, base: dict[str, Any], base_dir: Path) -> list[dict[str, Any]]:
    axes: list[dict[str, Any]] = []
    dims: set[str] = set()
    for i, ax in enumerate(spec.axes):
        where = f"axes[{i}]"
        if ax.field.split(".")[0] in _FIXED_PREFIXES:
            raise CaseError(
                f"{where}.field", ax.field, "frequency.*, output.* and title cannot vary (one grid)"
            )
        if ax.dim in dims:
            raise CaseError(f"{where}.name", ax.dim, "a dimension name not used by another axis")
        dims.add(ax.dim)
        values = ax.resolved_values()
        tables = any(isinstance(v, dict | list) for v in values)
        if ax.labels is not None and len(ax.labels) != len(values):
            raise CaseError(f"{where}.labels", ax.labels, f"{len(values)} labels, one per value")
        if tables and ax.labels is None:
            raise CaseError(f"{where}.labels", None, "required when the values are tables")
        if len(set(map(_canonical, values))) != len(values):
            raise CaseError(f"{where}.values", values, "distinct values")
        for j, value in enumerate(values):
            _check_value(base, ax.field, value, base_dir, f"{where}.values[{j}]")
        group = "case" if spec.mode == "zip" else (ax.zip or ax.dim)
        coords = list(ax.labels) if ax.labels is not None else values
        axes.append(
            {"field": ax.field, "dim": ax.dim, "group": group, "values": values, "coords": coords}
        )
    _check_temperature_axis(base, [entry["field"] for entry in axes], base_dir)
    sizes: dict[str, int] = {}
    for entry in axes:
        n = sizes.setdefault(entry["group"], len(entry["values"]))
        if n != len(entry["values"]):
            raise CaseError(
                f"axes.{entry['field']}",
                len(entry["values"]),
                f"zipped axes of group {entry['group']!r} need equal lengths ({n})",
            )
    for entry in axes:
        if entry["dim"] in sizes and entry["dim"] != entry["group"]:
            raise CaseError(
                f"axes.{entry['field']}",
                entry["dim"],
                "an axis name distinct from other groups' zip labels",
            )
    return axes


def _check_temperature_axis(base: dict[str, Any], fields: list[str], base_dir: Path) -> None:
    """Refuse a pad-temperature axis that cannot change anything (pad not temperature-shifted)."""
    if TEMPERATURE_FIELD not in fields or any(
        f == "track.pad" or f.startswith("track.pad.") for f in fields
    ):
        return
    from railvib.case import build_pad

    pad = build_pad(case_from_dict(base, base_dir=base_dir))
    if not pad.temperature_dependent:
        raise CaseError(
            f"axes.{TEMPERATURE_FIELD}",
            pad.model_name,
            "a temperature-dependent pad: the base case's pad ignores temperature, so this "
            "axis would change nothing; give [track.pad] a [track.pad.tts] table (e.g. from "
            "'railvib pad fit') or sweep track.pad instead",
        )


def _check_value(base: dict[str, Any], field: str, value: Any, base_dir: Path, where: str) -> None:
    """Validate the base case with one axis value, so a bad value is named at load time."""
    override = nested_override(field, value)
    try:
        case_from_dict(merge_case_dicts(base, override), base_dir=base_dir)
    except CaseError as exc:
        raise CaseError(
            exc.field, exc.value, f"{exc.allowed} [sweep {where}, field {field}]"
        ) from None


#: the case field holding the railpad temperature
TEMPERATURE_FIELD = "track.pad_temperature_c"


def _canonical(value: Any) -> str:
    return json.dumps(value, sort_keys=True, default=str)


def _sweep_error(exc: ValidationError) -> CaseError:
    """Convert the first pydantic error to a one-line CaseError with the dotted field name."""
    err = exc.errors()[0]
    inner = (err.get("ctx") or {}).get("error")
    loc = _indexed(err["loc"])
    if isinstance(inner, CaseError):
        field = f"{loc}.{inner.field}" if loc else inner.field
        return CaseError(field, inner.value, inner.allowed)
    kind = err["type"]
    if kind == "missing":
        return CaseError(loc, "<missing>", "required")
    if kind == "extra_forbidden":
        return CaseError(loc, err.get("input"), "unknown key")
    return CaseError(loc or "sweep", err.get("input"), err["msg"])


def _indexed(loc: tuple[Any, ...]) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
    return out
