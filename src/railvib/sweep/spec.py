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

:func:`load_sweep` and :func:`sweep_from_dict` return a :class:`SweepSpec`: the
resolved sweep as a frozen, picklable object (base case after presets and base
files, every axis with its values). :meth:`SweepSpec.as_dict` gives it back as
the plain JSON-able dict that is hashed (less the title, which changes no result)
into the sweep's fingerprint and stored in the manifest.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
import warnings
from collections.abc import Iterator, Mapping, Sequence
from numbers import Integral
from pathlib import Path
from typing import Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from railvib.case import Case, build_pad, build_system, case_from_dict, merge_case_dicts
from railvib.case.build import build_grid, build_vehicle
from railvib.case.errors import case_error
from railvib.case.load import case_with_table
from railvib.case.plausibility import physical_memory_bytes
from railvib.case.schema import check_label
from railvib.errors import CaseError, RailvibDeprecationWarning, did_you_mean
from railvib.io import check_nesting, read_toml
from railvib.outputs import LOSS_OF_CONTACT_NOTE
from railvib.results.variables import PER_FREQUENCY, VARIABLES
from railvib.solve import criteria_settings
from railvib.vehicle import Vehicle

__all__ = [
    "MAX_AXIS_VALUES",
    "MAX_SWEEP_CASES",
    "PER_FREQUENCY_VARIABLES",
    "SUMMARY_VARIABLES",
    "AxisSpec",
    "SweepAxis",
    "SweepFile",
    "SweepSpec",
    "TRAIN_LENGTH_FIELDS",
    "is_train_length_field",
    "load_sweep",
    "nested_override",
    "sweep_from_dict",
]

#: per-frequency variables a sweep may keep, with their extra dimension
PER_FREQUENCY_VARIABLES = {name: VARIABLES[name].extra_dim for name in PER_FREQUENCY}

#: PSD variables whose summary (peak, dominant frequency, band RMS) a sweep may store
SUMMARY_VARIABLES = ("psd_acceleration", "psd_displacement")

#: case fields that cannot vary: every case shares one grid and one set of summary bands
_FIXED_PREFIXES = ("frequency", "output", "title")
#: keys of a case file that are not case fields: merged before the axes apply
_NOT_FIELDS = ("preset",)
#: case fields of the other modes: a sweep runs the stationary model only
_MODE_FIELDS = ("mode", "moving", "speed_profile", "nonstationary")
#: where each other mode's sweep lives instead
_MODE_HINT = (
    "a sweep runs the stationary model only; the moving vehicle over speed: "
    "railvib.movingrun.moving_speed_sweep (docs/moving-vehicle.md), a non-stationary run: "
    "one `railvib run` per case"
)
#: the case fields an axis can vary (the top of their dotted names)
_VARIABLE_FIELDS = (
    "speed_kmh, rail_model, vehicle.*, train.*, track.*, contact.* and irregularity.*"
)

#: the case fields that set the number of cars of a train: an axis over them varies the
#: response and wheel axes, laid out as the longest train's (:mod:`railvib.sweep.trains`)
TRAIN_LENGTH_FIELDS = ("train", "train.cars")

#: most values of one axis (each is validated against the base case, about 0.6 ms each)
MAX_AXIS_VALUES = 10_000
#: most cases of one sweep (a million cases of the paper's 10,000-frequency grid take some
#: 100 CPU-hours)
MAX_SWEEP_CASES = 1_000_000


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class AxisSpec(_Model):
    """One sweep axis: a case field and the values it takes.

    Give exactly one of ``values``; ``start``/``stop`` with ``num`` (inclusive,
    ``spacing = "linear"`` or ``"log"``); or ``start``/``stop``/``step``
    (linear, ``stop`` included where it lands).

    Attributes
    ----------
    start, stop : float or None
        First and last value of a range, in the unit of `field`.
    num : int or None
        Number of values from `start` to `stop` (both included).
    step : float or None
        Step of a linear range, in the unit of `field`.
    spacing : {"linear", "log"}
        Spacing of a `num` range.
    """

    field: str = Field(..., min_length=1, description="dotted case field, e.g. speed_kmh")
    name: str | None = Field(None, min_length=1, description="dimension name (default: field)")
    values: list[Any] | None = Field(
        None, min_length=1, max_length=MAX_AXIS_VALUES, description="explicit values"
    )
    start: float | None = None
    stop: float | None = None
    num: int | None = Field(None, ge=1, le=MAX_AXIS_VALUES)
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
            for key in ("start", "stop"):
                if not math.isfinite(getattr(self, key)):
                    raise CaseError(key, getattr(self, key), "a finite number")
            if (self.num is None) == (self.step is None):
                raise CaseError("num", self.num, "give exactly one of num and step")
            if self.spacing == "log" and not (self.start > 0 and self.stop > 0):
                raise CaseError("start", self.start, "a log range needs start, stop > 0")
            if self.step is not None and self.spacing == "log":
                raise CaseError("step", self.step, "a log range takes num, not step")
            if self.step is not None and self.stop < self.start:
                raise CaseError("stop", self.stop, f"must be >= start = {self.start}")
            if self.step is not None:
                count = math.floor((self.stop - self.start) / self.step + 1e-9) + 1
                if count > MAX_AXIS_VALUES:
                    raise CaseError(
                        "step",
                        self.step,
                        f"at most {MAX_AXIS_VALUES:,} values per axis; this step gives "
                        f"{count:,} from {self.start:g} to {self.stop:g}",
                    )
        for key in ("name", "zip"):
            if getattr(self, key) is not None:
                check_label(key, getattr(self, key), 100)
        for i, label in enumerate(self.labels or ()):
            check_label(f"labels[{i}]", label, 100)
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
    """The parsed sweep file (before the base case is resolved).

    Attributes
    ----------
    title : str
        Free text shown in the outputs.
    mode : {"product", "zip"}
        Every combination of the axes' values, or the axes varied together.
    variables : list of str
        Per-frequency variables stored for every case (the summary always is).
    summary_variable : {"psd_acceleration", "psd_displacement"}
        The PSD the summary statistics are taken from.
    axes : list of AxisSpec
        The sweep axes.
    """

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
        check_label("title", self.title)
        for i, name in enumerate(self.variables):
            if name not in PER_FREQUENCY_VARIABLES:
                raise CaseError(
                    f"variables[{i}]",
                    name,
                    f"one of {', '.join(PER_FREQUENCY_VARIABLES)}"
                    + did_you_mean(name, PER_FREQUENCY_VARIABLES),
                )
        if self.base is None and self.case is None:
            raise CaseError("case", "<missing>", "a [case] table and/or base = PATH")
        return self


# -- the resolved sweep ------------------------------------------------------------------------


class _FrozenList(tuple[Any, ...]):
    """A list of a sweep spec, frozen: a tuple that :func:`_thaw` turns back into a list.

    Kept apart from plain tuples so that :meth:`SweepSpec.as_dict` gives back
    exactly the lists and tuples it was given.
    """

    __slots__ = ()

    def __copy__(self) -> _FrozenList:
        return self

    def __deepcopy__(self, memo: dict[int, Any]) -> _FrozenList:
        return self


class _FrozenTable(Mapping[str, Any]):
    """A table (dict) of a sweep spec, frozen: read-only, hashable and picklable.

    Its values are frozen too (tables, lists as tuples). Unlike
    ``types.MappingProxyType`` it pickles, so a spec holding it can be sent to
    worker processes and Dask workers.
    """

    __slots__ = ("_items",)

    _items: dict[str, Any]

    def __init__(self, items: Mapping[str, Any]) -> None:
        object.__setattr__(self, "_items", {k: _freeze(v) for k, v in items.items()})

    def __getitem__(self, key: str) -> Any:
        return self._items[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is read-only")

    def __hash__(self) -> int:
        return hash(frozenset(self._items.items()))  # equal tables hash equal, any order

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._items!r})"

    def __reduce__(self) -> tuple[type[_FrozenTable], tuple[dict[str, Any]]]:
        return (type(self), (self._items,))

    def __copy__(self) -> _FrozenTable:
        return self

    def __deepcopy__(self, memo: dict[int, Any]) -> _FrozenTable:
        return self


def _freeze(value: Any) -> Any:
    """A read-only copy of a JSON-like value: dicts -> frozen tables, lists -> tuples."""
    if isinstance(value, _FrozenTable | _FrozenList):
        return value
    if isinstance(value, dict):
        return _FrozenTable(value)
    if isinstance(value, list):
        return _FrozenList(_freeze(v) for v in value)
    if isinstance(value, tuple):
        return tuple(_freeze(v) for v in value)
    return value


def _thaw(value: Any) -> Any:
    """A plain, mutable deep copy of a frozen value (the inverse of :func:`_freeze`)."""
    if isinstance(value, _FrozenTable):
        return {k: _thaw(v) for k, v in value.items()}
    if isinstance(value, _FrozenList):
        return [_thaw(v) for v in value]
    if isinstance(value, tuple):
        return tuple(_thaw(v) for v in value)
    if isinstance(value, dict | list):
        return copy.deepcopy(value)
    return value


@dataclasses.dataclass(frozen=True)
class SweepAxis:
    """One resolved axis of a sweep: a case field and the values it takes.

    Parameters
    ----------
    field : str
        Dotted case field, e.g. ``"speed_kmh"`` or ``"track.pad"``; the values
        are in the case file's units (km/h, degC, N/m, ...).
    dim : str
        Name of the axis's coordinate (the ``name`` in the sweep file, default
        the field).
    group : str
        The sweep dimension the axis runs along: its own `dim`, the ``zip``
        label it shares with other axes, or ``"case"`` in ``mode = "zip"``.
    values : tuple
        The values, in order: numbers, strings, booleans, or whole tables
        (frozen: read-only mappings, lists as tuples).
    coords : tuple
        Coordinate labels, one per value: the values themselves, or the
        ``labels`` given for tables.
    """

    field: str
    dim: str
    group: str
    values: tuple[Any, ...]
    coords: tuple[Any, ...]

    def __post_init__(self) -> None:
        for name in ("field", "dim", "group"):
            text = getattr(self, name)
            if not isinstance(text, str) or not text:
                raise CaseError(f"axes.{name}", text, "a non-empty string")
        values = tuple(_freeze(v) for v in self.values)
        coords = tuple(_freeze(c) for c in self.coords)
        if not values:
            raise CaseError(f"axes.{self.field}.values", list(values), "at least one value")
        if len(coords) != len(values):
            raise CaseError(
                f"axes.{self.field}.coords", len(coords), f"{len(values)}, one per value"
            )
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "coords", coords)

    @property
    def size(self) -> int:
        """Number of values."""
        return len(self.values)

    def value(self, i: int) -> Any:
        """Return value `i` as a plain, mutable copy (tables as dicts, lists as lists)."""
        return _thaw(self.values[i])

    def as_dict(self) -> dict[str, Any]:
        """Return ``{field, dim, group, values, coords}`` with plain (mutable) values."""
        return {
            "field": self.field,
            "dim": self.dim,
            "group": self.group,
            "values": [_thaw(v) for v in self.values],
            "coords": [_thaw(c) for c in self.coords],
        }


@dataclasses.dataclass(frozen=True)
class SweepSpec:
    """A resolved sweep: the base case and the axes over it (frozen, picklable).

    Made by :func:`load_sweep` or :func:`sweep_from_dict`, which validate it;
    it fully determines the results, so :meth:`as_dict` (less the title) is what
    the sweep's fingerprint (:func:`railvib.sweep.fingerprint`) hashes.

    Parameters
    ----------
    title : str
        Title of the sweep (the dataset's ``title`` attribute).
    mode : {"product", "zip"}
        ``"product"``: full factorial over the axis groups; ``"zip"``: all axes
        vary together along one dimension ``case``.
    chunk_size : int
        At most this many cases per stored chunk (>= 1).
    variables : tuple of str
        Per-frequency variables kept (see :data:`PER_FREQUENCY_VARIABLES`);
        empty: summaries only.
    summary_variable : {"psd_acceleration", "psd_displacement"}
        The PSD summarised by peak, dominant frequency and band RMS.
    base_case : mapping
        The fully resolved, validated base case as a JSON-able table (as
        ``Case.model_dump(mode="json", exclude_none=True)`` gives it), frozen:
        read-only, nested tables read-only, lists as tuples. Use
        :meth:`base_case_dict` for a mutable copy.
    axes : tuple of SweepAxis
        The axes, in file order.
    """

    title: str
    mode: Literal["product", "zip"]
    chunk_size: int
    variables: tuple[str, ...]
    summary_variable: Literal["psd_acceleration", "psd_displacement"]
    base_case: Mapping[str, Any] = dataclasses.field(repr=False)
    axes: tuple[SweepAxis, ...]

    def __post_init__(self) -> None:
        if self.mode not in ("product", "zip"):
            raise CaseError("mode", self.mode, "'product' or 'zip'")
        size = self.chunk_size
        if isinstance(size, bool) or not isinstance(size, Integral) or size < 1:
            raise CaseError("chunk_size", size, "an integer >= 1 (cases)")
        variables = tuple(self.variables)
        for i, name in enumerate(variables):
            if name not in PER_FREQUENCY_VARIABLES:
                raise CaseError(
                    f"variables[{i}]",
                    name,
                    f"one of {', '.join(PER_FREQUENCY_VARIABLES)}"
                    + did_you_mean(name, PER_FREQUENCY_VARIABLES),
                )
        if self.summary_variable not in SUMMARY_VARIABLES:
            raise CaseError(
                "summary_variable",
                self.summary_variable,
                f"one of {', '.join(SUMMARY_VARIABLES)}"
                + did_you_mean(self.summary_variable, SUMMARY_VARIABLES),
            )
        if not isinstance(self.base_case, Mapping):
            raise CaseError("base_case", type(self.base_case).__name__, "a resolved case table")
        axes = tuple(self.axes)
        if not axes or not all(isinstance(ax, SweepAxis) for ax in axes):
            raise CaseError("axes", list(axes), "one or more SweepAxis")
        dims = [ax.dim for ax in axes]
        if len(set(dims)) != len(dims):
            raise CaseError("axes.dim", dims, "distinct dimension names")
        _check_groups(axes)
        object.__setattr__(self, "chunk_size", int(size))
        object.__setattr__(self, "variables", variables)
        object.__setattr__(self, "base_case", _freeze(dict(self.base_case)))
        object.__setattr__(self, "axes", axes)

    @property
    def fields(self) -> tuple[str, ...]:
        """The dotted case field of every axis, in file order."""
        return tuple(ax.field for ax in self.axes)

    @property
    def rms_bands(self) -> tuple[tuple[float, float], ...]:
        """The base case's ``output.rms_bands``: ``(f_lo, f_hi)`` in Hz, shared by every case."""
        bands = self.base_case["output"]["rms_bands"]
        return tuple((float(lo), float(hi)) for lo, hi in bands)

    @property
    def loss_of_contact_threshold(self) -> float:
        """The base case's ``output.loss_of_contact_threshold`` (probability), for every case."""
        output = self.base_case["output"]
        return float(output.get("loss_of_contact_threshold", LOSS_OF_CONTACT_NOTE))

    def base_case_dict(self) -> dict[str, Any]:
        """Return the base case as a plain, mutable deep copy (a case dict)."""
        out: dict[str, Any] = _thaw(self.base_case)
        return out

    def __getitem__(self, key: str) -> Any:
        """Deprecated dict-style access (``spec["axes"]``): use the attributes or :meth:`as_dict`.

        Parameters
        ----------
        key : str
            A key of :meth:`as_dict`.
        """
        warnings.warn(
            f'spec["{key}"] is deprecated: the sweep spec is a SweepSpec; use its attributes '
            f"(spec.{key}) or spec.as_dict()",
            RailvibDeprecationWarning,
            stacklevel=2,
        )
        return self.as_dict()[key]

    def as_dict(self) -> dict[str, Any]:
        """Return the sweep as a plain JSON-able dict (what older railvib versions passed around).

        Returns
        -------
        dict
            ``title``, ``mode``, ``chunk_size``, ``variables``,
            ``summary_variable``, ``base_case`` and ``axes`` (a list of
            :meth:`SweepAxis.as_dict`), in this order; a fresh copy.
        """
        return {
            "title": self.title,
            "mode": self.mode,
            "chunk_size": self.chunk_size,
            "variables": list(self.variables),
            "summary_variable": self.summary_variable,
            "base_case": self.base_case_dict(),
            "axes": [ax.as_dict() for ax in self.axes],
        }

    def to_json(self) -> str:
        """Return :meth:`as_dict` as canonical JSON (sorted keys; the ``sweep_spec_json`` attr)."""
        return json.dumps(self.as_dict(), sort_keys=True, default=str)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> SweepSpec:
        """Rebuild a spec from :meth:`as_dict` output (e.g. a manifest's ``spec``).

        The base case is taken as resolved (not validated again).

        Parameters
        ----------
        data : mapping
            A dict with the keys :meth:`as_dict` writes.

        Returns
        -------
        SweepSpec
        """
        try:
            return cls(
                title=data["title"],
                mode=data["mode"],
                chunk_size=data["chunk_size"],
                variables=tuple(data["variables"]),
                summary_variable=data["summary_variable"],
                base_case=data["base_case"],
                axes=tuple(
                    SweepAxis(
                        field=ax["field"],
                        dim=ax["dim"],
                        group=ax["group"],
                        values=tuple(ax["values"]),
                        coords=tuple(ax["coords"]),
                    )
                    for ax in data["axes"]
                ),
            )
        except KeyError as exc:
            raise CaseError(f"sweep.{exc.args[0]}", "<missing>", "required") from None


def load_sweep(path: str | Path) -> SweepSpec:
    """Read, validate and resolve a TOML sweep file.

    Parameters
    ----------
    path : str or pathlib.Path
        The sweep file.

    Returns
    -------
    SweepSpec
        The resolved sweep (see :func:`sweep_from_dict`).

    Raises
    ------
    CaseError
        With the dotted field name, the value and what is allowed.
    """
    path = Path(path)
    hint = "docs/sweeps.md shows one"
    data = read_toml(path, "sweep", hint)
    base = data.get("base")
    if isinstance(base, str) and _same_file(path.parent / base, path):
        raise CaseError(
            "base",
            base,
            "a case file, not this sweep file itself: name the case file the sweep varies "
            '(base = "case.toml"), or give the case inline as a [case] table',
        )
    if "axes" not in data and "case" not in data and "base" not in data and _CASE_KEYS & set(data):
        raise CaseError(
            "sweep",
            str(path),
            "a sweep file ([case] or base = PATH, and [[axes]]); this is a case file: run it "
            f'with `railvib run`, or write base = "{path.name}" in a sweep file ({hint})',
        )
    return sweep_from_dict(data, base_dir=path.parent)


def _same_file(a: Path, b: Path) -> bool:
    """Whether paths `a` and `b` name one existing file."""
    try:
        return a.samefile(b)
    except OSError:
        return False


#: top-level keys of a case file (a case given where a sweep file is expected)
_CASE_KEYS = {"preset", "rail_model", "speed_kmh", "vehicle", "track", "irregularity"}


def sweep_from_dict(data: dict[str, Any], base_dir: str | Path | None = None) -> SweepSpec:
    """Validate a sweep given as a plain dict and resolve it.

    Parameters
    ----------
    data : dict
        The parsed sweep file.
    base_dir : str or pathlib.Path, optional
        Directory against which ``base`` and data-file paths are resolved.

    Returns
    -------
    SweepSpec
        The base case fully resolved and validated, the axes with their values
        (each value validated against the base case). It fully determines the
        results; the hash of :meth:`SweepSpec.as_dict` (less the title) is the sweep's
        fingerprint.

    Raises
    ------
    CaseError
        With the dotted field name, the value and what is allowed.
    """
    base_dir = Path(base_dir) if base_dir is not None else Path.cwd()
    check_nesting(data, "sweep")
    try:
        spec = SweepFile.model_validate(data)
    except ValidationError as exc:
        raise case_error(exc, SweepFile) from None
    base_case = _resolve_base(spec, base_dir)
    axes = _resolve_axes(spec, base_case, base_dir)
    return SweepSpec(
        title=spec.title,
        mode=spec.mode,
        chunk_size=spec.chunk_size,
        variables=tuple(spec.variables),
        summary_variable=spec.summary_variable,
        base_case=base_case,
        axes=axes,
    )


def nested_override(field: str, value: Any) -> dict[str, Any]:
    """``"a.b.c", v`` -> ``{"a": {"b": {"c": v}}}`` (a deep copy of `value`).

    Parameters
    ----------
    field : str
        Dotted case field, e.g. ``"track.pad_temperature_c"``.
    value : object
        The field's value.

    Returns
    -------
    dict
        Nested tables holding (a deep copy of) `value` at `field`.
    """
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
        data = _load_base(spec.base, base_dir)
        if spec.case and "preset" in spec.case:
            raise CaseError("case.preset", spec.case["preset"], "not allowed together with base")
    if spec.case:
        # a preset stays a preset (case_from_dict merges it), so the case knows which of
        # its values the sweep file gives and which it inherits (e.g. the RMS bands)
        data = merge_case_dicts(data, copy.deepcopy(spec.case))
    case = case_from_dict(data, base_dir=base_dir)
    if case.mode != "stationary":  # before any axis is checked or anything computed
        raise CaseError("case.mode", case.mode, f'"stationary": {_MODE_HINT}')
    return _case_dump(case)


def _load_base(base: str, base_dir: Path) -> dict[str, Any]:
    """The case file `base` (relative to `base_dir`), resolved; its errors name ``base``."""
    p = Path(base)
    path = p if p.is_absolute() else base_dir / p
    data = read_toml(path, "base", "`railvib template > case.toml` writes a case file")
    if "axes" in data:
        raise CaseError(
            "base", base, "a case file; this is a sweep file ([[axes]]), not the case it varies"
        )
    return _case_dump(case_from_dict(data, base_dir=path.parent))


def _resolve_axes(spec: SweepFile, base: dict[str, Any], base_dir: Path) -> tuple[SweepAxis, ...]:
    axes: list[SweepAxis] = []
    dims: set[str] = set()
    # first: its axis values would each warn that the pad ignores the temperature
    _check_temperature_axis(base, [ax.field for ax in spec.axes], base_dir)
    _check_count(spec)  # before each value is validated (about 0.6 ms each)
    base_case = case_from_dict(base, base_dir=base_dir, warn=False)
    for i, ax in enumerate(spec.axes):
        where = f"axes[{i}]"
        if ax.field.split(".")[0] in _NOT_FIELDS:
            raise CaseError(
                f"{where}.field",
                ax.field,
                "a case field, not 'preset': a preset is merged into the base case before "
                "the axes apply, so this axis would change nothing; sweep the fields the "
                f"presets differ in ({_VARIABLE_FIELDS}), or run one sweep per preset",
            )
        if ax.field.split(".")[0] in _MODE_FIELDS:
            raise CaseError(f"{where}.field", ax.field, f"a stationary case field: {_MODE_HINT}")
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
            _check_value(base, base_case, ax.field, value, base_dir, f"{where}.values[{j}]")
        group = "case" if spec.mode == "zip" else (ax.zip or ax.dim)
        coords = list(ax.labels) if ax.labels is not None else values
        axes.append(
            SweepAxis(
                field=ax.field, dim=ax.dim, group=group, values=tuple(values), coords=tuple(coords)
            )
        )
    _check_groups(axes)
    _check_size(axes, spec, base, base_dir)
    _check_criteria(base, base_dir)
    return tuple(axes)


def _check_criteria(base: dict[str, Any], base_dir: Path) -> None:
    """Refuse ``[criteria]`` settings of the base case that do not apply, before any case runs."""
    case = case_from_dict(base, base_dir=base_dir, warn=False)
    criteria_settings(case, build_system(case), build_grid(case).f)


def _groups(spec: SweepFile) -> dict[str, int]:
    """Number of values along each sweep dimension (zip label, axis name, or ``case``)."""
    sizes: dict[str, int] = {}
    for ax in spec.axes:
        group = "case" if spec.mode == "zip" else (ax.zip or ax.dim)
        sizes[group] = max(sizes.get(group, 0), len(ax.resolved_values()))
    return sizes


def _check_count(spec: SweepFile) -> None:
    """Refuse a sweep of more than :data:`MAX_SWEEP_CASES` cases."""
    sizes = _groups(spec)
    cases = math.prod(sizes.values())
    if cases > MAX_SWEEP_CASES:
        what = " x ".join(f"{n:,} ({group})" for group, n in sizes.items())
        raise CaseError(
            "axes", f"{cases:,} cases", f"at most {MAX_SWEEP_CASES:,} cases; this sweep has {what}"
        )


def _check_size(
    axes: Sequence[SweepAxis], spec: SweepFile, base: dict[str, Any], base_dir: Path
) -> None:
    """Refuse a sweep whose results do not fit in this machine's memory.

    The assembled sweep holds the per-frequency variables it keeps (float64) of every
    case in memory: ``cases x frequencies x (values per frequency) x 8`` bytes.
    """
    sizes = {ax.group: ax.size for ax in axes}
    cases = math.prod(sizes.values())
    what = " x ".join(f"{n:,} ({group})" for group, n in sizes.items())
    memory = physical_memory_bytes()
    if memory is None or not spec.variables:
        return
    case = case_from_dict(base, base_dir=base_dir, warn=False)
    vehicle = build_vehicle(case)
    for ax in axes:  # the dataset is laid out as the longest train's
        if is_train_length_field(ax.field):
            for value in ax.values:
                train = build_vehicle(
                    case_from_dict(
                        merge_case_dicts(base, nested_override(ax.field, _thaw(value))),
                        base_dir=base_dir,
                        warn=False,
                    )
                )
                vehicle = max(vehicle, train, key=lambda v: len(v.wheels))
    extra = {"response": len(vehicle.dofs) + len(vehicle.wheels), "wheel": len(vehicle.wheels)}
    per_frequency = sum(extra.get(str(PER_FREQUENCY_VARIABLES[v]), 1) for v in spec.variables)
    n_freq = len(build_grid(case))
    needed = cases * n_freq * per_frequency * 8
    if needed > memory:
        raise CaseError(
            "axes",
            f"{cases:,} cases",
            f"a sweep whose results fit in this machine's {memory / 1e9:.3g} GB of memory: "
            f"{what} cases of {n_freq:,} frequencies keeping {', '.join(spec.variables)} need "
            f"about {needed / 1e9:.3g} GB (keep fewer variables, or split the sweep)",
        )


def _check_groups(axes: Sequence[SweepAxis]) -> None:
    """Zipped axes have equal lengths; no axis is named like another group's dimension."""
    sizes: dict[str, int] = {}
    for entry in axes:
        n = sizes.setdefault(entry.group, entry.size)
        if n != entry.size:
            raise CaseError(
                f"axes.{entry.field}",
                entry.size,
                f"zipped axes of group {entry.group!r} need equal lengths ({n})",
            )
    for entry in axes:
        if entry.dim in sizes and entry.dim != entry.group:
            raise CaseError(
                f"axes.{entry.field}",
                entry.dim,
                "an axis name distinct from other groups' zip labels",
            )


def _check_temperature_axis(base: dict[str, Any], fields: list[str], base_dir: Path) -> None:
    """Refuse a pad-temperature axis that cannot change anything (pad not temperature-shifted)."""
    if TEMPERATURE_FIELD not in fields or any(
        f == "track.pad" or f.startswith("track.pad.") for f in fields
    ):
        return
    pad = build_pad(case_from_dict(base, base_dir=base_dir))
    if not pad.temperature_dependent:
        raise CaseError(
            f"axes.{TEMPERATURE_FIELD}",
            pad.model_name,
            "a temperature-dependent pad: the base case's pad ignores temperature, so this "
            "axis would change nothing; give [track.pad] a [track.pad.tts] table (e.g. from "
            "'railvib pad fit') or sweep track.pad instead",
        )


def is_train_length_field(field: str) -> bool:
    """Tell whether an axis over `field` can change the number of cars of a train.

    Parameters
    ----------
    field : str
        Dotted case field.

    Returns
    -------
    bool
        True for ``train.cars`` and the whole ``train`` table.
    """
    return field in TRAIN_LENGTH_FIELDS


def _check_value(
    base: dict[str, Any], base_case: Case, field: str, value: Any, base_dir: Path, where: str
) -> None:
    """Validate the base case with one axis value, so a bad value is named at load time.

    As ``case_from_dict`` of the base case with the value merged on, but only the table
    the value changes is validated again (:func:`railvib.case.load.case_with_table`).
    """
    key = field.split(".")[0]
    try:
        case = case_with_table(base, base_case, key, nested_override(field, value)[key], base_dir)
        if is_train_length_field(field):  # another train: its criteria settings must apply
            _check_criteria(_case_dump(case), base_dir)
    except CaseError as exc:
        raise CaseError(
            exc.field, exc.value, f"{exc.allowed} [sweep {where}, field {field}]"
        ) from None
    if is_train_length_field(field):
        return  # the cars are the base case's; the dataset is the longest train's layout
    if field.split(".")[0] in ("vehicle", "train"):
        layout = _layout(build_vehicle(case))
        base_layout = _layout(build_vehicle(base_case))
        if layout != base_layout:
            raise CaseError(
                f"axes.{field}",
                value,
                f"a value that keeps the base case's vehicle DOFs and wheels ({len(base_layout[0])}"
                f" DOFs, {len(base_layout[1])} wheels; this one has {len(layout[0])} and "
                f"{len(layout[1])}): the cases of a sweep share one response axis; run one "
                f"sweep per vehicle topology (a train length is swept with train.cars) "
                f"[sweep {where}]",
            )


def _layout(vehicle: Vehicle) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The DOF and wheel names of a vehicle: what a sweep's cases must share."""
    return vehicle.dofs, vehicle.wheel_names


#: the case field holding the railpad temperature
TEMPERATURE_FIELD = "track.pad_temperature_c"


def _canonical(value: Any) -> str:
    return json.dumps(value, sort_keys=True, default=str)
