"""Batched solution of many cases that share structure.

Cases that differ only in speed (and irregularity) share the track receptance
``R`` between the contact points, ``Q = (R + I/k_H)^-1`` and the condensed
system matrix ``A = D_v + B Q B^T``; only the excitation ``v_j = exp(-i 2 pi f
t_j)``, ``t_j = s_j / v``, changes. One ``numpy.linalg.solve`` with one
right-hand side per speed then serves all of them. Cases whose vehicle or
contact differ but whose track and wheel positions agree still share ``R``.
"""

from __future__ import annotations

import copy
import dataclasses
import json
from collections import OrderedDict
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from railvib.case import Case, build_grid, build_spectrum, build_system, case_from_dict
from railvib.case.load import merge_case_dicts
from railvib.coupling import CoupledSystem, coupled_response
from railvib.grid import trapezoid
from railvib.labels import response_labels
from railvib.outputs import ContactCheck, RideComfort
from railvib.outputs.comfort import comfort_arrays
from railvib.outputs.contact import loss_of_contact_arrays
from railvib.outputs.forces import dynamic_load_arrays
from railvib.pads import PADS, PadModel
from railvib.pads.scaled import ScaledPad
from railvib.pem import excitation_vector, wheel_delays
from railvib.response import FRF
from railvib.results.stats import summary_names
from railvib.results.variables import compute_variables, response_psds
from railvib.solve import criteria_settings
from railvib.sweep.layout import SweepLayout, is_cheap_field, is_pad_field
from railvib.sweep.spec import SweepSpec
from railvib.sweep.stacked import frf_case_stack
from railvib.sweep.trains import compute_train_chunk, length_groups
from railvib.track.compiled import use_compiled
from railvib.track.periodic import PeriodicTrack
from railvib.units import kmh_to_ms
from railvib.vehicle.assembly import WheelCondensation

__all__ = [
    "CONTACT_SUMMARY",
    "CRITERIA_SUMMARY",
    "BatchFRF",
    "case_labels",
    "compute_chunk",
    "contact_check",
    "criteria_summary",
    "frf_many_speeds",
    "summary_names",
]

#: summary variables of the contact check each case of a sweep stores, with their dimension
#: after the case (:class:`railvib.outputs.ContactCheck`)
CONTACT_SUMMARY: dict[str, tuple[str, ...]] = {
    "contact_force_rms": ("wheel",),
    "loss_of_contact_probability": ("wheel",),
    "linear_model_valid": (),
}

#: summary variables of the engineering criteria each case of a sweep stores, with their
#: dimension after the case (:class:`railvib.outputs.RideComfort` where the base case's
#: grid reaches the comfort band, :class:`railvib.outputs.WheelRailForces`)
CRITERIA_SUMMARY: dict[str, tuple[str, ...]] = {
    "comfort_aw": ("floor",),
    "mean_comfort_index": ("floor",),
    "sperling_wz": ("floor",),
    "dynamic_load_factor": ("wheel",),
    "car_dynamic_load_factor": (),
}


#: responses of several speeds of one system (one container for every solver)
BatchFRF = FRF


def frf_many_speeds(
    system: CoupledSystem,
    f: ArrayLike,
    speeds: ArrayLike,
    receptance: NDArray[np.complex128] | None = None,
    condensation: WheelCondensation | None = None,
) -> BatchFRF:
    """Solve the coupled FRFs of `system` at several speeds in one batched solve.

    Equals :meth:`railvib.coupling.CoupledSystem.frf` at each speed (the speed
    of `system` itself is ignored).

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact stiffness and wheel positions.
    f : array_like
        Frequencies in Hz, ``(n_freq,)``.
    speeds : array_like
        Vehicle speeds in m/s, ``(n_speed,)``, each > 0.
    receptance : numpy.ndarray, optional
        Rail receptance between the contact points, ``(n_freq, n_wheel, n_wheel)``
        in m/N, if already known (it depends on the track and wheel positions only).
    condensation : WheelCondensation, optional
        The vehicle condensed onto its wheels at `f`, if already known (it depends
        on the vehicle only, so cases with many pads share it).

    Returns
    -------
    FRF
        Arrays ``(n_speed, n_freq, n)``: the speed is the leading batch axis.
    """
    f = np.atleast_1d(np.asarray(f, dtype=float))
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    x = system.wheel_positions
    rec = system.track.receptance(f, x, x) if receptance is None else receptance
    if condensation is None:
        condensation = system.vehicle.condensed_to_wheels(f)
    # excitation of every speed as columns: (n_freq, n_wheel, n_speed)
    v = np.stack(
        [excitation_vector(f, wheel_delays(system.vehicle.wheel_offsets, s)) for s in speeds],
        axis=-1,
    )
    u_v, force, rail = coupled_response(condensation, rec, system.contact_stiffness, v)

    def first(a: NDArray[Any]) -> NDArray[np.complex128]:
        return np.moveaxis(np.asarray(a, dtype=np.complex128), -1, 0)

    return FRF(
        f,
        first(u_v),
        first(rail),
        first(force),
        system.vehicle.dofs,
        rec,
        system.vehicle.wheel_names,
    )


def case_labels(system: CoupledSystem) -> list[str]:
    """Response labels of a run: vehicle DOFs, then ``rail@wheel<j>`` (a train's per car).

    Parameters
    ----------
    system : CoupledSystem
        The coupled system of a case (only its vehicle is read).

    Returns
    -------
    list of str
        The labels (see :func:`railvib.response.response_labels`).
    """
    vehicle = system.vehicle
    return list(response_labels(vehicle.dofs, len(vehicle.wheels), vehicle.wheel_names))


def _key(d: Any) -> str:
    return json.dumps(d, sort_keys=True)


@dataclass(frozen=True)
class _Built:
    """A structural group's first case, validated and built (shared by its cases)."""

    case: Case
    system: CoupledSystem
    static_loads: NDArray[np.float64]
    pad_factor: float  # rail_pair doubles the pad: the same table under another reading
    suffix: str  # what the group's track keys add to the track table (reading, positions)


@dataclass
class _Context:
    """What every chunk of one sweep shares, made once per process (a worker runs many)."""

    layout: SweepLayout
    base: dict[str, Any]
    f: NDArray[np.float64]
    criteria: dict[str, dict[str, Any]]
    groups: OrderedDict[str, _Built] = dataclasses.field(default_factory=OrderedDict)
    pads: OrderedDict[str, PadModel] = dataclasses.field(default_factory=OrderedDict)

    def built(self, key: str, case_dict: dict[str, Any]) -> _Built:
        """The group `key` of case `case_dict` built (the most recent groups are kept)."""
        if key in self.groups:
            self.groups.move_to_end(key)
            return self.groups[key]
        case = case_from_dict(case_dict, warn=False)
        system = build_system(case)
        pad = system.track.pad
        out = _Built(
            case,
            system,
            np.asarray(system.vehicle.static_wheel_loads(), dtype=float),
            pad.factor if isinstance(pad, ScaledPad) else 1.0,
            _key([case_dict["rail_model"], system.wheel_positions.tolist()]),
        )
        self.groups[key] = out
        if len(self.groups) > _GROUPS_KEPT:
            self.groups.popitem(last=False)
        return out

    def pad(self, key: str, template: PadModel, table: dict[str, Any]) -> PadModel:
        """The pad `key` of `table` as a track with pad `template` uses it (built once).

        A pad reading a data file (a ``path`` in its table) is built again at each call:
        the file may change between two runs of one sweep in one process.
        """
        if key in self.pads:
            self.pads.move_to_end(key)
            return self.pads[key]
        pad = _pad_like(template, table)
        if not _reads_file(table):
            self.pads[key] = pad
            if len(self.pads) > _PADS_KEPT:
                self.pads.popitem(last=False)
        return pad


#: structural groups kept built per process (a chunk of a sweep over pads, temperatures
#: and speeds is one group, the same in every chunk; a chunk of a rail x vehicle sweep has
#: as many as cases)
_GROUPS_KEPT = 64

#: pads kept built per process: a sweep over pad parameters x temperatures meets each
#: pad again at each temperature
_PADS_KEPT = 4096

#: the context of the sweep this process computes chunks of, by the (frozen, hashable) spec:
#: each task brings its own copy of the spec, equal to the last one
_CONTEXT: dict[SweepSpec, _Context] = {}

#: contexts kept per process: a sweep over train lengths solves each length as a sweep of
#: its own, chunk after chunk
_CONTEXTS_KEPT = 64


def _context(spec: SweepSpec) -> _Context:
    """The chunks' shared context of `spec` (made at this process's first chunk of it)."""
    if spec not in _CONTEXT:
        if len(_CONTEXT) >= _CONTEXTS_KEPT:
            _CONTEXT.clear()  # one sweep at a time (its train lengths each their own)
        base = spec.base_case_dict()
        case = case_from_dict(base, warn=False)
        f = build_grid(case).f
        criteria = criteria_settings(case, build_system(case), f)
        _CONTEXT[spec] = _Context(SweepLayout(spec), base, f, criteria)
    return _CONTEXT[spec]


def compute_chunk(spec: SweepSpec, chunk_id: int) -> dict[str, NDArray[Any]]:
    """Solve every case of one chunk of a sweep, batching cases that share structure.

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep (:func:`railvib.sweep.spec.sweep_from_dict`).
    chunk_id : int
        Chunk number (C order over the chunk grid).

    Returns
    -------
    dict of numpy.ndarray
        Per-frequency variables ``(n_case, n_freq, n_resp or n_wheel)``
        (``irregularity_psd``: ``(n_case, n_freq)``), summary variables
        ``(n_case, n_resp)`` and the contact check (:data:`CONTACT_SUMMARY`:
        ``(n_case, n_wheel)`` and ``(n_case,)``); cases in C order over the chunk block.
        Over trains of several lengths, the longest train's responses and wheels, NaN
        where a shorter train has none (:mod:`railvib.sweep.trains`).
    """
    if length_groups(spec):  # each train length is another coupled system: solved alone
        return compute_train_chunk(
            spec, chunk_id, _compute_layout, {**CONTACT_SUMMARY, **CRITERIA_SUMMARY}
        )
    return _compute_layout(spec, chunk_id)


def _compute_layout(spec: SweepSpec, chunk_id: int) -> dict[str, NDArray[Any]]:
    """:func:`compute_chunk` of cases that share one response and wheel layout."""
    context = _context(spec)
    layout, f = context.layout, context.f
    cases, groups = _chunk_groups(spec, layout, chunk_id, context.base)
    # the compiled wave kernel where the whole sweep pays for loading it
    compiled = use_compiled(len(cases) * f.size, work=layout.n_cases * f.size)
    frf, s_r, loads = _solve_groups(context, cases, groups, compiled)
    needed = dict.fromkeys([*spec.variables, "psd_force", spec.summary_variable])
    values = _chunk_variables(frf, s_r, needed)  # each variable computed once
    out: dict[str, NDArray[Any]] = {name: values[name] for name in spec.variables}
    psd_force = np.asarray(values["psd_force"], dtype=float)
    out.update(criteria_summary(spec, f, frf, s_r, psd_force, loads))
    target = np.asarray(values[spec.summary_variable], dtype=float)
    out.update(_summary(f, target, spec.rms_bands))
    return out


def _chunk_variables(
    frf: FRF, s_r: NDArray[np.float64], names: dict[str, None]
) -> dict[str, NDArray[Any]]:
    """:func:`railvib.results.variables.compute_variables`, the response PSDs in place.

    The response PSDs by :func:`railvib.results.variables.response_psds` (bit for bit the
    same values, half the time); the others by :func:`compute_variables`.
    """
    psds = {"psd_acceleration": True, "psd_displacement": False}
    out = compute_variables(frf, s_r, [n for n in names if n not in psds])
    for name in names:
        if name in psds:
            out[name] = response_psds(frf, s_r, psds[name])
    return {name: out[name] for name in names}


def _summary(
    f: NDArray[np.float64], psd: NDArray[np.float64], bands: Sequence[Sequence[float]]
) -> dict[str, NDArray[np.float64]]:
    """:func:`railvib.results.stats.summary` of PSDs ``(n_case, n_freq, n_resp)`` in NumPy.

    The same operations on the same values (maximum, first frequency of the maximum,
    trapezoidal rule over the grid points in each band), without labelled arrays: the
    trapezoids' terms are formed once and each band sums its own run of them (the terms
    :func:`railvib.grid.trapezoid` of the band's points forms, summed in the same order).
    """
    first = psd.argmax(axis=1)
    terms = (f[1:] - f[:-1])[None, :, None] * (psd[:, 1:] + psd[:, :-1]) / 2.0
    out = {
        "summary/peak": np.take_along_axis(psd, first[:, None], axis=1)[:, 0],
        "summary/dominant_frequency": f[first],
        "summary/rms": np.sqrt(terms.sum(axis=1)),
    }
    for (lo, hi), name in zip(bands, summary_names(bands)[3:], strict=True):
        inside = np.flatnonzero((f >= lo) & (f <= hi))
        if not inside.size:
            raise ValueError(f"band {(lo, hi)} Hz holds no grid frequency")
        if inside[-1] - inside[0] == inside.size - 1:  # a run of the grid: its own terms
            band = terms[:, inside[0] : inside[-1]].sum(axis=1)
        else:
            band = trapezoid(psd[:, inside], f[inside], axis=1)
        out[f"summary/{name}"] = np.sqrt(band)
    return out


def criteria_summary(
    spec: SweepSpec,
    f: NDArray[np.float64],
    frf: FRF,
    irregularity_psd: NDArray[np.float64],
    psd_force: NDArray[np.float64],
    static_loads: NDArray[np.float64],
) -> dict[str, NDArray[Any]]:
    """The contact check and the criteria of many cases, as ``summary/<name>`` arrays.

    What :class:`railvib.outputs.ContactCheck`, :class:`railvib.outputs.WheelRailForces`
    and :class:`railvib.outputs.RideComfort` give a run, bit for bit, on NumPy arrays
    over the chunk's cases at once (:func:`railvib.outputs.contact.loss_of_contact_arrays`,
    :func:`railvib.outputs.forces.dynamic_load_arrays`,
    :func:`railvib.outputs.comfort.comfort_arrays`); the force RMS is integrated once
    for both. The floor points and the comfort band are those of the base case
    (:func:`railvib.solve.criteria_settings`): a sweep over the vehicle's geometry keeps
    the base case's floor points.

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    f : numpy.ndarray
        Frequencies, Hz, ``(n_freq,)``.
    frf : FRF
        Responses of the cases, ``(n_case, n_freq, ...)``, per metre of irregularity.
    irregularity_psd : numpy.ndarray
        One-sided irregularity PSDs, m^2/Hz, ``(n_case, n_freq)``.
    psd_force : numpy.ndarray
        Contact force PSDs, N^2/Hz, ``(n_case, n_freq, n_wheel)``.
    static_loads : numpy.ndarray
        Static wheel loads, N, ``(n_case, n_wheel)``.

    Returns
    -------
    dict of numpy.ndarray
        :data:`CONTACT_SUMMARY` and :data:`CRITERIA_SUMMARY` variables, case first.
    """
    settings = _context(spec).criteria
    sigma = np.sqrt(trapezoid(psd_force, f, axis=1))
    probability, valid = loss_of_contact_arrays(sigma, static_loads, spec.loss_of_contact_threshold)
    factor, car_factor = dynamic_load_arrays(sigma, static_loads)
    values: dict[str, NDArray[Any]] = {
        "contact_force_rms": sigma,
        "loss_of_contact_probability": probability,
        "linear_model_valid": valid,
        "dynamic_load_factor": factor,
        "car_dynamic_load_factor": car_factor,
    }
    if "ride_comfort" in settings:
        comfort = RideComfort(**settings["ride_comfort"])
        dofs = list(frf.dofs)
        values.update(
            comfort_arrays(
                comfort,
                f,
                frf.vehicle[..., dofs.index(f"{comfort.body}.bounce")],
                frf.vehicle[..., dofs.index(f"{comfort.body}.pitch")],
                irregularity_psd,
            )
        )
    return {
        f"summary/{name}": values[name]
        for name in (*CONTACT_SUMMARY, *CRITERIA_SUMMARY)
        if name in values
    }


def contact_check(
    f: NDArray[np.float64],
    psd_force: NDArray[np.float64],
    static_loads: NDArray[np.float64],
    loss_of_contact_threshold: float,
) -> dict[str, xr.DataArray]:
    """The contact check of many cases (:class:`railvib.outputs.ContactCheck`, the run's code).

    Parameters
    ----------
    f : numpy.ndarray
        Frequencies, Hz, ``(n_freq,)``.
    psd_force : numpy.ndarray
        One-sided contact force PSDs, N^2/Hz, ``(n_case, n_freq, n_wheel)``.
    static_loads : numpy.ndarray
        Static load of each contact, N, ``(n_case, n_wheel)``.
    loss_of_contact_threshold : float
        Largest probability of loss of contact (dimensionless) within the linear model.

    Returns
    -------
    dict of xarray.DataArray
        ``contact_force_rms`` (N) and ``loss_of_contact_probability`` over ``(case,
        wheel)``, ``linear_model_valid`` over ``case``.
    """
    ds = xr.Dataset(
        {
            "psd_force": (("case", "frequency", "wheel"), psd_force),
            "static_contact_load": (("case", "wheel"), static_loads),
        },
        coords={"frequency": f},
    )
    check = ContactCheck(loss_of_contact_threshold=loss_of_contact_threshold)
    out = check.compute(ds)
    return {name: out[name].transpose("case", ...) for name in CONTACT_SUMMARY}


def _chunk_cases(
    spec: SweepSpec, layout: SweepLayout, chunk_id: int
) -> tuple[list[dict[str, Any]], list[list[int]]]:
    """The case dicts of a chunk, and the groups of cases that share all but pad and speed."""
    cases, groups = _chunk_groups(spec, layout, chunk_id, spec.base_case_dict())
    return cases, list(groups.values())


def _chunk_groups(
    spec: SweepSpec, layout: SweepLayout, chunk_id: int, base: dict[str, Any]
) -> tuple[list[dict[str, Any]], dict[str, list[int]]]:
    """:func:`_chunk_cases` with the groups keyed by what their cases override.

    The keys are what the cases override beyond pad and speed (JSON); the case dicts
    share the tables off their overridden paths with the base case dict `base`.
    """
    cheap = [is_cheap_field(field) or is_pad_field(field) for field in spec.fields]
    cases: list[dict[str, Any]] = []
    groups: dict[str, list[int]] = {}
    for i, index in enumerate(layout.chunk_indices(chunk_id)):
        full = base
        struct_override: dict[str, Any] = {}
        for (field, value), is_cheap in zip(layout.overrides(index), cheap, strict=True):
            full = _with_field(full, field.split("."), value)
            if not is_cheap:
                struct_override[field] = value
        cases.append(full)
        groups.setdefault(_key(struct_override), []).append(i)
    return cases, groups


def _with_field(d: Mapping[str, Any], parts: list[str], value: Any) -> dict[str, Any]:
    """``merge_case_dicts(d, nested_override(field, value))``, copying only the path to it.

    The tables off the path are shared with `d` (cases of a chunk are read, never
    modified: :func:`railvib.case.case_from_dict` copies its input).
    """
    out = dict(d)
    key, old = parts[0], d.get(parts[0])
    if len(parts) > 1:
        out[key] = _with_field(old if isinstance(old, Mapping) else {}, parts[1:], value)
    elif isinstance(value, Mapping):  # a table merges (or, naming a member, replaces)
        out[key] = merge_case_dicts({key: old}, {key: value})[key]
    else:
        out[key] = copy.deepcopy(value)
    return out


def _solve_groups(
    context: _Context, cases: list[dict[str, Any]], groups: dict[str, list[int]], compiled: bool
) -> tuple[FRF, NDArray[np.float64], NDArray[np.float64]]:
    """Responses of every case, ``(n_case, n_freq, ...)``, its irregularity PSD and wheel loads.

    The irregularity PSD applied is in m^2/Hz, ``(n_case, n_freq)``; the static wheel
    loads in N, ``(n_case, n_wheel)``.

    A group's cases share everything but the pad, its temperature, the speed and the
    irregularity: its first case is validated and built once per process (the group is
    kept in `context` for the next chunks), the others' pads are built from their
    (validated) pad tables. Every case of the chunk, whatever its group, is then one
    stack (:func:`railvib.sweep.stacked.frf_case_stack`): cases with the same track table
    and wheel positions share one track solution, cases with the same vehicle table one
    condensation; cases with the same irregularity and speed one irregularity PSD.
    """
    f = context.f
    n_case = len(cases)
    s_r = np.empty((n_case, f.size))
    systems: list[CoupledSystem | None] = [None] * n_case
    loads: list[NDArray[np.float64] | None] = [None] * n_case
    track_keys: list[tuple[str, str]] = [("", "")] * n_case
    pads: dict[str, PadModel] = {}  # this chunk's
    spectra: dict[str, Any] = {}
    temporal: dict[tuple[str, float], NDArray[np.float64]] = {}
    # the key of a table the cases share with the base case (the same object), made once
    known: dict[int, tuple[Any, str]] = {}

    def shared(table: Any) -> str:
        if id(table) not in known:
            known[id(table)] = (table, _key(table))  # the table kept: its id stays its own
        return known[id(table)][1]

    for key, members in groups.items():
        built = context.built(key, cases[members[0]])
        system = built.system
        tracks: dict[str, PeriodicTrack] = {}
        for i in members:
            track = cases[i]["track"]
            tkey = _key(track)
            if tkey not in tracks:
                pkey = _key([track["pad"], built.pad_factor])
                if pkey not in pads:
                    pads[pkey] = context.pad(pkey, system.track.pad, track["pad"])
                tracks[tkey] = replace(
                    system.track, pad=pads[pkey], pad_temperature=track.get("pad_temperature_c")
                )
            speed = kmh_to_ms(cases[i]["speed_kmh"])
            systems[i] = replace(system, track=tracks[tkey], speed=speed)
            loads[i] = built.static_loads
            track_keys[i] = (tkey, built.suffix)
            ikey = shared(cases[i]["irregularity"])
            if ikey not in spectra:
                spectra[ikey] = build_spectrum(_with_irregularity(built.case, cases[i]))
            if (ikey, speed) not in temporal:
                temporal[ikey, speed] = spectra[ikey].temporal(f, speed)
            s_r[i] = temporal[ikey, speed]
    frf = frf_case_stack(
        f,
        [s for s in systems if s is not None],
        track_keys,
        # the vehicle as built: its table, the train it repeats in, and half_car halving it
        [
            f"{shared(c['vehicle'])}|{shared(c.get('train'))}|{c['rail_model'] == 'half_car'}"
            for c in cases
        ],
        compiled=compiled,
    )
    return frf, s_r, np.stack([w for w in loads if w is not None])


def _pad_like(template: PadModel, table: dict[str, Any]) -> PadModel:
    """The pad of `table` as the track of the case uses it (doubled for a rail pair)."""
    pad = PADS.from_dict(table, "track.pad")
    if isinstance(template, ScaledPad):
        return ScaledPad(pad, template.factor)
    return pad


def _reads_file(node: Any) -> bool:
    """Whether a table (or anything in it) names a data file (a ``path``)."""
    if isinstance(node, Mapping):
        return "path" in node or any(_reads_file(v) for v in node.values())
    if isinstance(node, list | tuple):
        return any(_reads_file(v) for v in node)
    return False


def _with_irregularity(case: Case, full: dict[str, Any]) -> Case:
    """`case` with the irregularity table of the case dict `full` (validated)."""
    if full["irregularity"] == case.irregularity:
        return case
    return case.model_copy(update={"irregularity": full["irregularity"]})
