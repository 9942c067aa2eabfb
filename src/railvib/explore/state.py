"""The explorer's state: its controls, the case they make, and what the page draws of a run.

Nothing here draws or serves (:mod:`railvib.explore.app` does, with Bokeh): a state of
the controls (:class:`Controls`) is applied to the base case as a plain table and
validated as any case file (:func:`railvib.case.case_from_dict`), so the page can show
only cases that ``railvib run`` would accept, and saves the same text
(:meth:`railvib.case.Case.to_toml`). The choices of track, pad and vehicle come from
the shipped presets (one per model of the registries), so the page reads no file but
the case it was started with.
"""

from __future__ import annotations

import time
import tomllib
import warnings
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.accessor import RailvibAccessor
from railvib.case import Case, case_from_dict, load_preset_case
from railvib.case.schema import MAX_TITLE_CHARS
from railvib.errors import CaseError
from railvib.io import write_text
from railvib.outputs import contact_line
from railvib.pads import PADS
from railvib.presets import list_presets, list_vehicle_presets
from railvib.results.stats import summary_table
from railvib.solve import run
from railvib.spectra import SPECTRA

__all__ = [
    "AS_CASE",
    "SPEED_RANGE_KMH",
    "TEMPERATURE_RANGE_C",
    "PAD_FACTOR_RANGE",
    "Controls",
    "Explorer",
    "Frame",
    "controls_from_values",
]

#: the choice that keeps the case's own track, pad or vehicle
AS_CASE = "as in the case"

#: range of the speed control, km/h (widened to hold the case's own speed)
SPEED_RANGE_KMH = (10.0, 400.0)

#: range of the pad-temperature control, degC (widened to hold the case's own)
TEMPERATURE_RANGE_C = (-40.0, 60.0)

#: range of the factor on the pad's stiffnesses (every N/m parameter of its table), dimensionless
PAD_FACTOR_RANGE = (0.25, 4.0)


@dataclass(frozen=True)
class Controls:
    """One state of the explorer's controls.

    Parameters
    ----------
    speed_kmh : float
        Vehicle speed, km/h.
    pad_temperature_c : float
        Pad temperature, degC (matters for temperature-dependent pads only).
    fra_class : int or None
        FRA class (1 worst to 6 best) of every FRA spectrum of the irregularity; None:
        the case has no FRA spectrum.
    track : str
        A key of :attr:`Explorer.tracks` (a preset's ``[track]`` with its ``rail_model``).
    pad : str
        A key of :attr:`Explorer.pads` (:data:`AS_CASE`: the track's own pad).
    pad_factor : float
        Factor on every stiffness (N/m) parameter of the pad table, dimensionless.
    vehicle : str
        :data:`AS_CASE` or a vehicle preset (:func:`railvib.presets.list_vehicle_presets`).
    """

    speed_kmh: float
    pad_temperature_c: float
    fra_class: int | None
    track: str = AS_CASE
    pad: str = AS_CASE
    pad_factor: float = 1.0
    vehicle: str = AS_CASE


@dataclass(frozen=True)
class Frame:
    """What the page shows of one run.

    Attributes
    ----------
    case : Case
        The validated case of the controls.
    frequency : numpy.ndarray
        Frequencies, Hz.
    psd : dict of str to numpy.ndarray
        Acceleration PSD of each response drawn, in its ``units`` (``psd_units``).
    psd_units : dict of str to str
        Unit of each PSD drawn, e.g. ``(m/s^2)^2/Hz``.
    pad_storage_kn_per_mm : numpy.ndarray
        The pad's storage stiffness K'(f), kN/mm (the beam model's, at the case's temperature).
    pad_loss_factor : numpy.ndarray
        Its loss factor K''/K', dimensionless.
    band_nominal : numpy.ndarray
        Nominal one-third-octave mid-band frequencies, Hz.
    band_levels : dict of str to numpy.ndarray
        Acceleration level of each response drawn in each band, dB re 1e-6 m/s^2.
    summary_rows : list of dict
        One row per response: ``response``, ``rms`` and its unit, peak frequency (Hz).
    notes : tuple of str
        The plausibility warnings of the case and the contact check, one line each.
    seconds : float
        Wall time of the validation and the run, s.
    """

    case: Case
    frequency: NDArray[np.float64]
    psd: dict[str, NDArray[np.float64]]
    psd_units: dict[str, str]
    pad_storage_kn_per_mm: NDArray[np.float64]
    pad_loss_factor: NDArray[np.float64]
    band_nominal: NDArray[np.float64]
    band_levels: dict[str, NDArray[np.float64]]
    summary_rows: list[dict[str, Any]]
    notes: tuple[str, ...]
    seconds: float


def _fra_tables(table: Any) -> Iterator[dict[str, Any]]:
    """Every FRA spectrum table inside an irregularity table (combined ones nest)."""
    if isinstance(table, dict):
        if table.get(SPECTRA.tag) == "fra":
            yield table
        for value in table.values():
            yield from _fra_tables(value)


def _first_per_model(kind: str) -> dict[str, dict[str, Any]]:
    """``{label: case table}`` of the first preset of each track or pad model."""
    out: dict[str, dict[str, Any]] = {}
    seen: set[str] = set()
    for name in list_presets():
        data = load_preset_case(name).model_dump(mode="json", exclude_none=True)
        if kind == "track":
            model = str(data["track"].get("model", "rigid_base"))
            table = {"rail_model": data["rail_model"], "track": data["track"]}
        else:
            model = str(data["track"]["pad"]["model"])
            table = data["track"]["pad"]
        if model not in seen:
            seen.add(model)
            out[f"{model} ({name})"] = table
    return out


class Explorer:
    """The cases and results behind the explorer's page, for one base case.

    Parameters
    ----------
    base : Case
        The case the page starts from (a case file, or the default preset).
    """

    def __init__(self, base: Case) -> None:
        self.base = base
        self._table = base.model_dump(mode="json", exclude_none=True)
        #: the track choices: the case's own, then one preset per track model
        self.tracks = {AS_CASE: {}, **_first_per_model("track")}
        #: the pad choices: the track's own, then one preset per pad model
        self.pads = {AS_CASE: {}, **_first_per_model("pad")}
        #: the vehicle choices: the case's own, then the vehicle presets
        self.vehicles = [AS_CASE, *list_vehicle_presets()]
        fra = SPECTRA.get("fra").parameters[0]
        #: the FRA classes the irregularity control offers (empty: the case has no FRA spectrum)
        self.fra_classes = (
            [int(c) for c in fra.choices or ()]
            if any(True for _ in _fra_tables(self._table["irregularity"]))
            else []
        )

    def initial(self) -> Controls:
        """The controls as the base case sets them.

        Returns
        -------
        Controls
        """
        classes = [t["class_number"] for t in _fra_tables(self._table["irregularity"])]
        return Controls(
            speed_kmh=float(self.base.speed_kmh),
            pad_temperature_c=float(self.base.track.pad_temperature_c),
            fra_class=int(classes[0]) if classes else None,
        )

    def table(self, controls: Controls) -> dict[str, Any]:
        """The case table of `controls`: the base case with the controls' values.

        Parameters
        ----------
        controls : Controls
            The state of the controls.

        Returns
        -------
        dict
            A case table (not yet validated).

        Raises
        ------
        railvib.errors.CaseError
            A choice the explorer does not offer (``explore.track``, ...).
        """
        for field, value, allowed in (
            ("explore.track", controls.track, list(self.tracks)),
            ("explore.pad", controls.pad, list(self.pads)),
            ("explore.vehicle", controls.vehicle, self.vehicles),
        ):
            if value not in allowed:
                raise CaseError(field, value, f"one of {allowed}")
        data = _copy(self._table)
        data["title"] = self.title(controls)
        data["speed_kmh"] = float(controls.speed_kmh)
        if controls.track != AS_CASE:
            chosen = _copy(self.tracks[controls.track])
            data["rail_model"] = chosen["rail_model"]
            data["track"] = chosen["track"]
        track = data["track"]
        if controls.pad != AS_CASE:
            track["pad"] = _copy(self.pads[controls.pad])
        track["pad"] = _scaled_pad(track["pad"], float(controls.pad_factor))
        track["pad_temperature_c"] = float(controls.pad_temperature_c)
        if controls.fra_class is not None:
            for fra in _fra_tables(data["irregularity"]):
                fra["class_number"] = int(controls.fra_class)
        if controls.vehicle != AS_CASE:
            data.pop("train", None)  # a vehicle preset is one car
            data["vehicle"] = {"preset": controls.vehicle}
        return data

    def title(self, controls: Controls) -> str:
        """The case's title, followed by what the controls changed (the saved file says it).

        Parameters
        ----------
        controls : Controls
            The state of the controls.

        Returns
        -------
        str
            E.g. ``"<title> [explored: speed_kmh 120, pad_factor 1.3]"``; the base title when
            nothing changed (at most :data:`railvib.case.schema.MAX_TITLE_CHARS` characters).
        """
        start = self.initial()
        changed = [
            f"{name} {_text(getattr(controls, name))}"
            for name in Controls.__dataclass_fields__
            if getattr(controls, name) != getattr(start, name)
        ]
        if not changed:
            return self.base.title
        return f"{self.base.title} [explored: {', '.join(changed)}]"[:MAX_TITLE_CHARS]

    def case(self, controls: Controls) -> tuple[Case, tuple[str, ...]]:
        """The validated case of `controls` and its plausibility warnings.

        Parameters
        ----------
        controls : Controls
            The state of the controls.

        Returns
        -------
        (Case, tuple of str)
            The case, and each warning as one line.

        Raises
        ------
        railvib.errors.CaseError
            The controls make a case ``railvib run`` refuses (as it would say it).
        """
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            case = case_from_dict(self.table(controls))
        return case, tuple(f"warning: {w.message}" for w in caught)

    def frame(self, controls: Controls, responses: list[str] | None = None) -> Frame:
        """Run the case of `controls` and collect what the page draws.

        Parameters
        ----------
        controls : Controls
            The state of the controls.
        responses : list of str, optional
            Responses drawn; None: :meth:`railvib.accessor.RailvibAccessor.default_responses`.

        Returns
        -------
        Frame

        Raises
        ------
        railvib.errors.CaseError
            The controls make a case ``railvib run`` refuses.
        """
        start = time.perf_counter()
        case, notes = self.case(controls)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            # the page solves the stationary case only (railvib.run refuses the other modes)
            stationary = {"mode": "stationary", "moving": None}
            stationary |= {"speed_profile": None, "nonstationary": None}
            ds = run(case if case.mode == "stationary" else case.model_copy(update=stationary))
        notes = (*notes, *(f"warning: {w.message}" for w in caught))
        if case.mode != "stationary":  # the page solves the stationary case only
            notes = (
                f"note: mode = {case.mode!r} in the case: shown is the stationary response at "
                f"the speed control's {case.speed_kmh:g} km/h "
                f"(railvib run solves the {case.mode} one)",
                *notes,
            )
        return _frame(case, ds, responses, notes, start)

    def save(self, controls: Controls, path: str | Path) -> Path:
        """Write the case of `controls` to `path` (TOML), validated first, atomically.

        Parameters
        ----------
        controls : Controls
            The state of the controls.
        path : str or pathlib.Path
            The case file to write (the one ``railvib explore -o`` names).

        Returns
        -------
        pathlib.Path
            `path`; ``railvib run`` accepts it and runs the case the page showed.

        Raises
        ------
        railvib.errors.CaseError
            The controls make a case ``railvib run`` refuses: nothing is written.
        """
        case, _ = self.case(controls)
        text = case.to_toml()
        case_from_dict(tomllib.loads(text), warn=False)  # the text read back is a valid case
        return write_text(path, text)


def controls_from_values(start: Controls, values: dict[str, Any]) -> Controls:
    """`start` with the values the page sent (each converted; nothing else is read).

    Parameters
    ----------
    start : Controls
        The controls the values replace.
    values : dict
        Control name -> value as the page holds it (a number, or a choice's name; the
        FRA class as its text, None where the case has none).

    Returns
    -------
    Controls

    Raises
    ------
    railvib.errors.CaseError
        ``explore.<name>``: a name that is no control, or a value of the wrong kind.
    """
    kinds = {"speed_kmh": float, "pad_factor": float, "pad_temperature_c": float}
    out: dict[str, Any] = {}
    for name, value in values.items():
        if name not in Controls.__dataclass_fields__:
            raise CaseError("explore", name, f"one of {list(Controls.__dataclass_fields__)}")
        try:
            if name == "fra_class":
                out[name] = None if value is None else int(str(value))
            else:
                out[name] = kinds[name](value) if name in kinds else str(value)
        except (TypeError, ValueError):
            raise CaseError(f"explore.{name}", value, "a number") from None
    return replace(start, **out)


def _text(value: Any) -> str:
    """A control's value in a title: numbers in ``%g``."""
    return f"{value:g}" if isinstance(value, float) else str(value)


def _copy(table: Any) -> Any:
    """A deep copy of a case table (dicts, lists and scalars)."""
    if isinstance(table, dict):
        return {k: _copy(v) for k, v in table.items()}
    if isinstance(table, list):
        return [_copy(v) for v in table]
    return table


def _scaled_pad(pad: dict[str, Any], factor: float) -> dict[str, Any]:
    """`pad` with every stiffness parameter (unit N/m) of its model times `factor`."""
    if factor == 1.0:
        return pad
    member = PADS.get(str(pad.get(PADS.tag)), "track.pad.model")
    out = dict(pad)
    for p in member.parameters:
        value = out.get(p.key)
        if p.unit != "N/m" or value is None:
            continue
        out[p.key] = [v * factor for v in value] if isinstance(value, list) else value * factor
    return out


def _frame(
    case: Case,
    ds: xr.Dataset,
    responses: list[str] | None,
    notes: tuple[str, ...],
    start: float,
) -> Frame:
    """The :class:`Frame` of a run's dataset `ds`."""
    accessor = RailvibAccessor(ds)
    chosen = responses if responses is not None else accessor.default_responses()
    psd = ds["psd_acceleration"]
    units = psd.coords.get("psd_acceleration_unit")
    stats = accessor.summary(list(case.output.rms_bands))
    table = summary_table(stats)
    rows = [
        {
            "response": str(label),
            "rms": float(row["rms"]),
            "rms_unit": str(row["rms_unit"]),
            "peak_hz": float(row["dominant_frequency [Hz]"]),
        }
        for label, row in table.iterrows()
    ]
    k = np.asarray(ds["pad_stiffness"].values)
    levels = ds.get("octave_level_acceleration")
    return Frame(
        case=case,
        frequency=ds["frequency"].values,
        psd={r: psd.sel(response=r).values for r in chosen},
        psd_units={
            r: str(units.sel(response=r).item()) if units is not None else str(psd.attrs["units"])
            for r in chosen
        },
        pad_storage_kn_per_mm=k.real / 1e6,
        pad_loss_factor=k.imag / k.real,
        band_nominal=np.asarray(levels["band_nominal"].values)
        if levels is not None
        else np.array([]),
        band_levels={r: levels.sel(response=r).values for r in chosen}
        if levels is not None
        else {},
        summary_rows=rows,
        notes=(*notes, contact_line(ds)),
        seconds=time.perf_counter() - start,
    )
