"""Pad models to and from plain dicts (case-file tables), measurement CSVs and TOML.

Dict format (one table, e.g. ``[track.pad]`` of a case file): ``model`` names the
model and the other keys are its parameters in SI units, named with their unit.
An optional ``tts`` sub-table wraps the model in :class:`~railvib.pads.tts.TemperatureShifted`.
"""

from __future__ import annotations

import csv
import math
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import tomli_w
from numpy.typing import NDArray

from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.pads.simple import ConstantPhase, Hysteretic, LogLinear, SpringDamper
from railvib.pads.tabulated import TabulatedPad
from railvib.pads.tts import DEFAULT_EXPANSION_COEFFICIENT_PER_K, WLF, TemperatureShifted
from railvib.pads.viscoelastic import FractionalZener, GeneralizedMaxwell

__all__ = [
    "MODEL_ALIASES",
    "PAD_MODELS",
    "Measurements",
    "load_pad_toml",
    "pad_from_dict",
    "pad_to_dict",
    "pad_toml",
    "read_measurements_csv",
    "wj7_example_csv",
]

_FLOAT, _BOOL = "number", "boolean"


@dataclass(frozen=True)
class _Spec:
    cls: Callable[..., PadModel]
    #: dict key -> (constructor argument, kind, default or ... when required)
    keys: dict[str, tuple[str, str, Any]]


_REQUIRED = ...

#: Every pad model that ``pad_from_dict`` builds, by its ``model`` name.
PAD_MODELS: dict[str, _Spec] = {
    "spring_damper": _Spec(
        SpringDamper,
        {
            "stiffness_n_per_m": ("stiffness_n_per_m", _FLOAT, _REQUIRED),
            "damping_ns_per_m": ("damping_ns_per_m", _FLOAT, 0.0),
        },
    ),
    "hysteretic": _Spec(
        Hysteretic,
        {
            "stiffness_n_per_m": ("stiffness_n_per_m", _FLOAT, _REQUIRED),
            "loss_factor": ("loss_factor_", _FLOAT, _REQUIRED),
        },
    ),
    "log_linear": _Spec(
        LogLinear,
        {
            "k0_n_per_m": ("k0_n_per_m", _FLOAT, _REQUIRED),
            "f0_hz": ("f0_hz", _FLOAT, 5.0),
            "exponent": ("exponent", _FLOAT, 0.07),
            "damping_ns_per_m": ("damping_ns_per_m", _FLOAT, 0.0),
            "hold_below_f0": ("hold_below_f0", _BOOL, True),
        },
    ),
    "constant_phase": _Spec(
        ConstantPhase,
        {
            "k0_n_per_m": ("k0_n_per_m", _FLOAT, _REQUIRED),
            "f0_hz": ("f0_hz", _FLOAT, 5.0),
            "exponent": ("exponent", _FLOAT, 0.07),
        },
    ),
    "fractional_zener": _Spec(
        FractionalZener,
        {
            "k0_n_per_m": ("k0_n_per_m", _FLOAT, _REQUIRED),
            "k_inf_n_per_m": ("k_inf_n_per_m", _FLOAT, _REQUIRED),
            "tau_s": ("tau_s", _FLOAT, _REQUIRED),
            "alpha": ("alpha", _FLOAT, _REQUIRED),
        },
    ),
    "generalized_maxwell": _Spec(
        GeneralizedMaxwell,
        {
            "k_inf_n_per_m": ("k_inf_n_per_m", _FLOAT, _REQUIRED),
            "k_n_per_m": ("k_n_per_m", _FLOAT + "s", _REQUIRED),
            "tau_s": ("tau_s", _FLOAT + "s", _REQUIRED),
        },
    ),
    "tabulated": _Spec(
        TabulatedPad,
        {
            "frequency_hz": ("frequency_hz", _FLOAT + "s", _REQUIRED),
            "storage_n_per_m": ("storage_n_per_m", _FLOAT + "s", _REQUIRED),
            "loss_n_per_m": ("loss_n_per_m", _FLOAT + "s", _REQUIRED),
        },
    ),
}

#: Other accepted spellings of model names.
MODEL_ALIASES = {"zener": "fractional_zener", "prony": "generalized_maxwell"}

_TTS_KEYS: dict[str, tuple[str, Any]] = {
    "reference_temperature_c": (_FLOAT, _REQUIRED),
    "glass_transition_c": (_FLOAT, None),
    "c1": (_FLOAT, None),
    "c2_k": (_FLOAT, None),
    "wlf_reference_temperature_c": (_FLOAT, None),
    "vertical_shift": (_BOOL, True),
    "expansion_coefficient_per_k": (_FLOAT, DEFAULT_EXPANSION_COEFFICIENT_PER_K),
}


def _value(field: str, value: Any, kind: str) -> Any:
    """Check the type of one dict value and convert it."""
    if kind == _BOOL:
        if not isinstance(value, bool):
            raise CaseError(field, value, "must be true or false")
        return value
    if kind == _FLOAT:
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
        ):
            raise CaseError(field, value, "must be a finite number")
        return float(value)
    if isinstance(value, str) or not isinstance(value, list | tuple):
        raise CaseError(field, value, "must be a list of finite numbers")
    return tuple(_value(f"{field}[{i}]", v, _FLOAT) for i, v in enumerate(value))


def _take(d: Mapping[str, Any], keys: Mapping[str, Any], field: str) -> dict[str, Any]:
    """Values of `keys` from `d` (kind, default) with unknown/missing/type checks."""
    unknown = sorted(set(d) - set(keys))
    if unknown:
        raise CaseError(
            f"{field}.{unknown[0]}", d[unknown[0]], f"unknown key; allowed: {', '.join(keys)}"
        )
    out = {}
    for key, (kind, default) in keys.items():
        if key in d:
            out[key] = _value(f"{field}.{key}", d[key], kind)
        elif default is _REQUIRED:
            raise CaseError(f"{field}.{key}", None, f"missing; required ({kind})")
        else:
            out[key] = default
    return out


def _relabel(err: CaseError, field: str, keys: Mapping[str, Any]) -> CaseError:
    """Rename ``track.pad.<name>`` in a model's validation error to ``<field>.<dict key>``."""
    name = err.field.removeprefix("track.pad.")
    base, _, index = name.partition("[")
    if base not in keys:
        base = next((k for k in keys if k.startswith(base)), base)
    new = f"{field}.{base}" + (f"[{index}" if index else "")
    return CaseError(new, err.value, err.allowed)


def pad_from_dict(d: Mapping[str, Any], field: str = "track.pad") -> PadModel:
    """Build a pad model from a plain dict such as a case file's ``[track.pad]`` table.

    Parameters
    ----------
    d : mapping
        ``{"model": name, <parameter keys>, "tts": {...} (optional)}``. Names and keys
        are listed in :data:`PAD_MODELS` (``zener`` and ``prony`` are accepted aliases).
        The ``tts`` table holds ``reference_temperature_c`` (degC, required), then either
        ``glass_transition_c`` (universal WLF constants at Tg, degC) or ``c1`` and
        ``c2_k`` (K) with optional ``wlf_reference_temperature_c`` (degC, default the
        reference temperature), and optionally ``vertical_shift`` (bool, default true)
        and ``expansion_coefficient_per_k`` (1/K, default 4.8e-4).
    field : str
        Dotted name of the table, used in error messages.

    Returns
    -------
    PadModel

    Raises
    ------
    CaseError
        Unknown model name, unknown or missing key, wrong type or a non-physical value.
    """
    if not isinstance(d, Mapping):
        raise CaseError(field, d, "a table with a 'model' key")
    if "model" not in d:
        raise CaseError(f"{field}.model", None, f"missing; one of {', '.join(PAD_MODELS)}")
    name = d["model"]
    name = MODEL_ALIASES.get(name, name) if isinstance(name, str) else name
    if name not in PAD_MODELS:
        raise CaseError(
            f"{field}.model", d["model"], f"one of {', '.join([*PAD_MODELS, *MODEL_ALIASES])}"
        )
    spec = PAD_MODELS[name]
    params = {k: v for k, v in d.items() if k not in ("model", "tts")}
    values = _take(
        params, {k: (kind, default) for k, (_, kind, default) in spec.keys.items()}, field
    )
    try:
        model = spec.cls(**{spec.keys[k][0]: v for k, v in values.items()})
    except CaseError as err:
        raise _relabel(err, field, spec.keys) from None
    if "tts" in d:
        model = _tts_from_dict(model, d["tts"], f"{field}.tts")
    return model


def _tts_from_dict(base: PadModel, d: Any, field: str) -> TemperatureShifted:
    if not isinstance(d, Mapping):
        raise CaseError(field, d, "a table")
    v = _take(d, _TTS_KEYS, field)
    t_ref = v["reference_temperature_c"]
    has_c = v["c1"] is not None or v["c2_k"] is not None
    if (v["glass_transition_c"] is None) == (not has_c):
        raise CaseError(
            field,
            dict(d),
            "give either glass_transition_c (degC) or both c1 and c2_k (K), not both",
        )
    try:
        if has_c:
            for key in ("c1", "c2_k"):
                if v[key] is None:
                    raise CaseError(f"{field}.{key}", None, "missing; c1 and c2_k go together")
            t_wlf = v["wlf_reference_temperature_c"]
            wlf = WLF(v["c1"], v["c2_k"], t_ref if t_wlf is None else t_wlf)
        else:
            if v["wlf_reference_temperature_c"] is not None:
                raise CaseError(
                    f"{field}.wlf_reference_temperature_c",
                    v["wlf_reference_temperature_c"],
                    "only with c1 and c2_k (glass_transition_c is the WLF reference)",
                )
            wlf = WLF.universal(v["glass_transition_c"])
        return TemperatureShifted(
            base, wlf, t_ref, v["vertical_shift"], v["expansion_coefficient_per_k"]
        )
    except CaseError as err:
        if err.field.startswith(field):
            raise
        key = err.field.rpartition(".")[2]
        if key == "reference_temperature_c" and err.field.startswith("wlf"):
            key = "wlf_reference_temperature_c"
        raise CaseError(f"{field}.{key}", err.value, err.allowed) from None


def pad_to_dict(model: PadModel) -> dict[str, Any]:
    """Return the plain dict of `model`, such that ``pad_from_dict(pad_to_dict(m)) == m``.

    Parameters
    ----------
    model : PadModel
        One of the models in :data:`PAD_MODELS`, optionally wrapped in
        :class:`~railvib.pads.tts.TemperatureShifted`.

    Returns
    -------
    dict
        TOML-ready (floats, booleans, lists of floats and one nested ``tts`` table).
    """
    if isinstance(model, TemperatureShifted):
        shifted = pad_to_dict(model.base)
        shifted["tts"] = {
            "reference_temperature_c": float(model.reference_temperature_c),
            "c1": float(model.wlf.c1),
            "c2_k": float(model.wlf.c2_k),
            "wlf_reference_temperature_c": float(model.wlf.reference_temperature_c),
            "vertical_shift": bool(model.vertical_shift),
            "expansion_coefficient_per_k": float(model.expansion_coefficient_per_k),
        }
        return shifted
    name = model.model_name
    if name not in PAD_MODELS or not isinstance(model, PAD_MODELS[name].cls):  # type: ignore[arg-type]
        raise CaseError("track.pad.model", type(model).__name__, f"one of {', '.join(PAD_MODELS)}")
    out: dict[str, Any] = {"model": name}
    for key, (attr, kind, _) in PAD_MODELS[name].keys.items():
        value = getattr(model, attr)
        out[key] = (
            [float(x) for x in value]
            if kind == _FLOAT + "s"
            else (bool(value) if kind == _BOOL else float(value))
        )
    return out


def pad_toml(model: PadModel, table: str = "track.pad", header: str = "") -> str:
    """TOML text of `model` under ``[table]``, with `header` lines as ``#`` comments."""
    doc: dict[str, Any] = pad_to_dict(model)
    for part in reversed(table.split(".")):
        doc = {part: doc}
    comments = "".join(f"# {line}\n" if line else "#\n" for line in header.splitlines())
    return comments + tomli_w.dumps(doc)


def load_pad_toml(path: str | Path, table: str = "track.pad") -> PadModel:
    """Read a pad model from a TOML file (as written by ``railvib pad fit``).

    Parameters
    ----------
    path : str or Path
        TOML file holding ``[track.pad]`` (or the dotted `table`).
    table : str
        Dotted name of the pad table.
    """
    with open(path, "rb") as fh:
        doc: Any = tomllib.load(fh)
    for part in table.split("."):
        if not isinstance(doc, Mapping) or part not in doc:
            raise CaseError(table, str(path), "the file must contain this table")
        doc = doc[part]
    return pad_from_dict(doc, table)


@dataclass(frozen=True, eq=False)
class Measurements:
    """Dynamic stiffness measured at several temperatures and frequencies.

    Parameters
    ----------
    temperature_c : numpy.ndarray
        Test temperatures, degC, shape ``(n,)``.
    frequency_hz : numpy.ndarray
        Test frequencies, Hz (> 0), shape ``(n,)``.
    storage_n_per_m : numpy.ndarray
        Storage stiffness K', N/m (> 0), shape ``(n,)``.
    loss_n_per_m : numpy.ndarray
        Loss stiffness K'', N/m (>= 0), shape ``(n,)``.
    """

    temperature_c: NDArray[np.float64]
    frequency_hz: NDArray[np.float64]
    storage_n_per_m: NDArray[np.float64]
    loss_n_per_m: NDArray[np.float64]

    def __post_init__(self) -> None:
        arrays = {}
        for name in ("temperature_c", "frequency_hz", "storage_n_per_m", "loss_n_per_m"):
            a = np.asarray(getattr(self, name), dtype=float).ravel()
            if a.size == 0 or not np.all(np.isfinite(a)):
                raise CaseError(f"measurements.{name}", a, "non-empty, finite values")
            arrays[name] = a
            object.__setattr__(self, name, a)
        if len({a.size for a in arrays.values()}) != 1:
            raise CaseError("measurements", {k: a.size for k, a in arrays.items()}, "equal lengths")
        for name, ok, allowed in (
            ("frequency_hz", self.frequency_hz > 0, "> 0 (Hz)"),
            ("storage_n_per_m", self.storage_n_per_m > 0, "> 0 (N/m)"),
            ("loss_n_per_m", self.loss_n_per_m >= 0, ">= 0 (N/m), a passive pad"),
        ):
            if not np.all(ok):
                i = int(np.flatnonzero(~ok)[0])
                raise CaseError(f"measurements.{name}[{i}]", float(getattr(self, name)[i]), allowed)

    @property
    def stiffness(self) -> NDArray[np.complex128]:
        """``K' + i K''``, N/m."""
        return self.storage_n_per_m + 1j * self.loss_n_per_m


#: CSV column -> (Measurements field, factor to SI)
_COLUMNS = {
    "temperature_c": ("temperature_c", 1.0),
    "frequency_hz": ("frequency_hz", 1.0),
    "storage_n_per_m": ("storage_n_per_m", 1.0),
    "storage_kn_per_mm": ("storage_n_per_m", 1e6),
    "loss_n_per_m": ("loss_n_per_m", 1.0),
    "loss_kn_per_mm": ("loss_n_per_m", 1e6),
    "loss_factor": ("loss_factor", 1.0),
}


def read_measurements_csv(path: str | Path) -> Measurements:
    """Read measurements from a CSV file with a header row; ``#`` lines are comments.

    Required columns: ``temperature_c``, ``frequency_hz``, storage as
    ``storage_n_per_m`` or ``storage_kn_per_mm``, and loss as ``loss_n_per_m``,
    ``loss_kn_per_mm`` or ``loss_factor`` (dimensionless, ``K'' = eta K'``).

    Parameters
    ----------
    path : str or Path
        CSV file.

    Returns
    -------
    Measurements
    """
    path = Path(path)
    try:
        with path.open(newline="") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    except OSError as exc:
        raise CaseError("data", str(path), f"a readable CSV file ({exc.strerror})") from None
    if len(rows) < 2:
        raise CaseError("data", str(path), "a header row and at least one data row")
    header = [h.strip().lower() for h in rows[0]]
    unknown = [h for h in header if h not in _COLUMNS]
    if unknown:
        raise CaseError(f"data.{unknown[0]}", str(path), f"columns from {', '.join(_COLUMNS)}")
    cols: dict[str, NDArray[np.float64]] = {}
    for j, name in enumerate(header):
        target, factor = _COLUMNS[name]
        if target in cols:
            raise CaseError(f"data.{name}", str(path), "one column per quantity")
        try:
            cols[target] = factor * np.array([float(r[j]) for r in rows[1:]])
        except (ValueError, IndexError):
            raise CaseError(f"data.{name}", str(path), "a number in every row") from None
    if "loss_factor" in cols and "storage_n_per_m" in cols:
        cols["loss_n_per_m"] = cols.pop("loss_factor") * cols["storage_n_per_m"]
    for need in ("temperature_c", "frequency_hz", "storage_n_per_m", "loss_n_per_m"):
        if need not in cols:
            raise CaseError(
                f"data.{need}", str(path), "required column (see read_measurements_csv)"
            )
    return Measurements(**cols)


def wj7_example_csv(name: str = "wj7_synthetic_0p3hz.csv") -> Path:
    """Path of a shipped synthetic WJ-7 data file (see ``railvib/data/wj7/README.md``).

    Parameters
    ----------
    name : str
        ``"wj7_synthetic_0p3hz.csv"`` (the seed's 0.3 Hz protocol) or
        ``"wj7_synthetic_multifrequency.csv"`` (0.3-30 Hz at each temperature).
    """
    return Path(str(resources.files("railvib") / "data" / "wj7" / name))
