"""Pad models to and from plain dicts (case-file tables), measurement CSVs and TOML.

Dict format (one table, e.g. ``[track.pad]`` of a case file): ``model`` names the
model and the other keys are its parameters in SI units, named with their unit.
An optional ``tts`` sub-table wraps the model in :class:`~railvib.pads.tts.TemperatureShifted`.
"""

from __future__ import annotations

import csv
from collections.abc import Mapping
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import tomli_w
from numpy.typing import NDArray

from railvib.errors import CaseError, did_you_mean, excerpt
from railvib.io import MAX_TABLE_BYTES, read_text, read_toml
from railvib.pads.base import PADS, PadModel
from railvib.pads.tts import TemperatureShifted, tts_to_dict

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

#: Every pad model ``pad_from_dict`` builds, by its ``model`` name (a live view of PADS).
PAD_MODELS = PADS.as_mapping()
#: Other accepted spellings of model names (a live view).
MODEL_ALIASES = PADS.aliases_mapping()


def pad_from_dict(d: Mapping[str, Any], field: str = "track.pad") -> PadModel:
    """Build a pad model from a plain dict such as a case file's ``[track.pad]`` table.

    Parameters
    ----------
    d : mapping
        ``{"model": name, <parameter keys>, "tts": {...} (optional)}``. Names and keys
        are those of the registered models (``railvib models pad``; ``zener`` and
        ``prony`` are aliases). The ``tts`` table (:data:`railvib.pads.tts.TTS_PARAMETERS`)
        holds ``reference_temperature_c`` (degC, required), then either
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
    return PADS.from_dict(d, field)


def pad_to_dict(model: PadModel) -> dict[str, Any]:
    """Return the plain dict of `model`, such that ``pad_from_dict(pad_to_dict(m)) == m``.

    Parameters
    ----------
    model : PadModel
        A registered model, optionally wrapped in :class:`~railvib.pads.tts.TemperatureShifted`.

    Returns
    -------
    dict
        TOML-ready (floats, booleans, lists of floats and one nested ``tts`` table).
    """
    if isinstance(model, TemperatureShifted):
        return {**PADS.to_dict(model.base), "tts": tts_to_dict(model)}
    try:
        return PADS.to_dict(model)
    except CaseError as err:
        raise CaseError("track.pad.model", err.value, err.allowed) from None


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
    doc: Any = read_toml(path, "pad", "`railvib pad fit` writes one")
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


#: the columns a measurements CSV needs, as said in errors
EXPECTED_COLUMNS = (
    "temperature_c, frequency_hz, storage_n_per_m or storage_kn_per_mm, and loss_n_per_m, "
    "loss_kn_per_mm or loss_factor"
)
#: where a user finds a good file, as said in errors
_EXAMPLE_HINT = "`railvib pad example` writes one"


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

    Raises
    ------
    CaseError
        ``data = '<path>': ...`` for a file that :func:`railvib.io.read_text` refuses
        (unreadable, not a regular file, over :data:`railvib.io.MAX_TABLE_BYTES`, binary,
        not UTF-8), that is not a CSV of these columns (e.g. a case file) or has no data
        row; ``data.<column>`` for an unknown, repeated or non-numeric column.
    """
    path = Path(path)
    text = read_text(
        path, "data", "measurements CSV", hint=_EXAMPLE_HINT, max_bytes=MAX_TABLE_BYTES
    )
    lines = text.splitlines()
    try:
        rows = [r for r in csv.reader(lines) if r and not r[0].lstrip().startswith("#")]
    except csv.Error as exc:
        raise CaseError("data", str(path), f"a measurements CSV ({exc})") from None
    if not rows:
        raise CaseError(
            "data", str(path), f"a measurements CSV with columns {EXPECTED_COLUMNS}; it is empty"
        )
    header = [h.strip().lower() for h in rows[0]]
    unknown = [h for h in header if h not in _COLUMNS]
    if len(unknown) == len(header):  # no known column at all: not a measurements CSV
        first = next(line for line in lines if line.strip() and not line.lstrip().startswith("#"))
        first = first.strip()
        what = (
            "not a TOML file (a case file?)"
            if first.startswith("[") or "=" in first.split(",")[0]
            else f"whose header row names its columns (this one is {excerpt(first, 24)!r})"
        )
        raise CaseError(
            "data",
            str(path),
            f"a measurements CSV, {what}; the columns are {EXPECTED_COLUMNS}; {_EXAMPLE_HINT}",
        )
    if unknown:
        close = did_you_mean(unknown[0], _COLUMNS)
        raise CaseError(
            f"data.{unknown[0]}",
            str(path),
            f"unknown column; columns from {', '.join(_COLUMNS)}{close}",
        )
    if len(rows) < 2:
        raise CaseError("data", str(path), "a header row and at least one data row")
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
                f"data.{need}", str(path), f"required column; the columns are {EXPECTED_COLUMNS}"
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
