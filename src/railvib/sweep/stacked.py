"""Many cases solved in one stack: (case, frequency) points end to end.

The cases of a sweep chunk may differ in any parameter of the rail (EI, m, loss), the
sleeper spacing, the railpad (model, parameters, temperature), the vehicle (masses,
suspension), the contact stiffness, the leading wheel position and the speed. Their
points are laid on one leading axis (case-major) and solved by one call of each kernel
in cache-sized blocks (``docs/design/0006-stacked-batches.md``):

* each distinct track's ``beta4 = m omega^2 d^4 / EI*``, support ``K*(f, T) d^3 / EI*``
  and scale ``d^3 / EI*`` are evaluated into the stack, and the stacked wave kernel
  (:mod:`railvib.track.stacked`, the track's own algorithm) runs over all of them at
  once; tracks the kernel does not cover (a Timoshenko rail) use their own solver;
* each distinct vehicle is condensed once on the frequencies;
* the coupled 4x4 solve runs on entry arrays ``(n_case, n_freq)``, each case with its
  own vehicle, contact stiffness and speed's excitation; where the compiled wave kernel
  is loaded, on the compiled point kernel instead (:mod:`railvib.coupled_kernel`), which
  writes every response straight into its result array.
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.case import build_system, load_preset_case
from railvib.coupled_kernel import coupled_points
from railvib.coupling import FREQUENCY_BLOCK, CoupledSystem, compiled_solve, track_receptances
from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.response import FRF
from railvib.stack import dot, put, solve, to_numpy
from railvib.track.compiled import COMPILED_MIN_POINTS, LOADED_MIN_POINTS, use_compiled
from railvib.track.slab import SlabTrack
from railvib.track.stacked import receptance_entries, stacked_waves
from railvib.vehicle.assembly import WheelCondensation

__all__ = ["frf_case_stack", "frf_pad_stack", "frf_stack", "load_compiled_kernels"]


def frf_case_stack(
    f: ArrayLike,
    systems: Sequence[CoupledSystem],
    track_keys: Sequence[Hashable] | None = None,
    vehicle_keys: Sequence[Hashable] | None = None,
    condensations: Mapping[Hashable, WheelCondensation] | None = None,
    compiled: bool | None = None,
) -> FRF:
    """Coupled FRFs of cases that may differ in every structural parameter, in one stack.

    Each case has its own coupled system: rail (EI, m, loss), sleeper spacing, pad and
    its temperature, vehicle (masses, suspension), contact stiffness, leading wheel
    position and speed. The track solutions of the distinct tracks are laid end to end
    as (track, frequency) points and solved by the stacked wave kernel
    (:mod:`railvib.track.stacked`) in cache-sized blocks, whatever their rail, spacing
    and pad; the distinct vehicles are condensed once each; the coupled solve runs on
    entry arrays ``(n_case, n_freq)``, each case with its own vehicle, contact stiffness
    and speed. A track the stacked kernel does not cover (a Timoshenko rail, a track
    model with its own receptance) is solved by its own
    :meth:`~railvib.track.PeriodicTrack.receptance`.

    Equals :meth:`railvib.coupling.CoupledSystem.frf` of each system to rounding.

    Parameters
    ----------
    f : array_like
        Frequencies in Hz, ``(n_freq,)``.
    systems : sequence of CoupledSystem
        The coupled system of each case, ``n_case`` (all vehicles with the same DOFs).
    track_keys : sequence of hashable, optional
        Cases with equal keys share one track solution (their tracks and wheel positions
        agree); default: the identity of the track and the wheel positions.
    vehicle_keys : sequence of hashable, optional
        Cases with equal keys share one vehicle condensation; default: the vehicle's
        identity.
    condensations : mapping, optional
        Vehicle condensations at `f` already known, by vehicle key.
    compiled : bool, optional
        Whether the track solutions use the compiled kernel
        (:func:`railvib.coupling.track_receptances`; default: where it pays for this stack).

    Returns
    -------
    FRF
        Arrays ``(n_case, n_freq, n)``: the case is the leading batch axis.
    """
    f = np.atleast_1d(np.asarray(f, dtype=float))
    n_case = len(systems)
    if track_keys is None:
        track_keys = [(id(s.track), tuple(s.wheel_positions)) for s in systems]
    if vehicle_keys is None:
        vehicle_keys = [id(s.vehicle) for s in systems]
    track_of, track_first = _distinct_keys(track_keys)
    vehicle_of, vehicle_first = _distinct_keys(vehicle_keys)
    dofs = systems[0].vehicle.dofs
    if any(systems[i].vehicle.dofs != dofs for i in vehicle_first):
        raise CaseError("vehicle", "several DOF sets", "the same vehicle DOFs in every case")
    per_track = track_receptances(
        f,
        [systems[i].track for i in track_first],
        [systems[i].wheel_positions for i in track_first],
        compiled,
    )
    known = {} if condensations is None else condensations
    conds = [
        known[vehicle_keys[i]]
        if vehicle_keys[i] in known
        else systems[i].vehicle.condensed_to_wheels(f)
        for i in vehicle_first
    ]
    contact = np.array([s.contact_stiffness for s in systems])
    delays = np.stack([s.vehicle.wheel_offsets / s.speed for s in systems])  # (n_case, n_w)
    # one excitation per distinct delays (speed and wheel offsets), picked per block
    delays, delay_of = np.unique(delays, axis=0, return_inverse=True)
    delay_of = delay_of.reshape(-1)
    excitation = np.exp(-2j * np.pi * f[None, :, None] * delays[:, None, :])
    wheels = systems[0].vehicle.wheel_names
    if compiled_solve(n_case * f.size, per_track.shape[-1], compiled):
        parts = coupled_points(
            per_track,
            track_of,
            np.stack([c.stiffness for c in conds]),
            np.stack([c.recovery for c in conds]),
            vehicle_of,
            contact,
            excitation,
            delay_of,
        )
        return FRF(f, parts[0], parts[2], parts[1], dofs, wheels=wheels)
    cond = _stacked_condensations(conds)
    step = max(1, FREQUENCY_BLOCK // f.size)  # cases per cache-sized block
    n_w = delays.shape[1]
    u_v = np.empty((n_case, f.size, len(dofs)), dtype=np.complex128)
    rail = np.empty((n_case, f.size, n_w), dtype=np.complex128)
    force = np.empty((n_case, f.size, n_w), dtype=np.complex128)
    for c in range(0, n_case, step):
        blk = slice(c, c + step)
        vehicle = cond if len(conds) == 1 else _pick(cond, vehicle_of[blk])
        n = per_track.shape[-1]
        tracks = _rows(track_of[blk])  # a view where the block's tracks run consecutively
        rec = [[per_track[tracks, :, a, b] for b in range(n)] for a in range(n)]
        rows = delay_of[blk]
        if (rows == rows[0]).all():  # the block's cases at one speed: one excitation
            v = np.broadcast_to(excitation[rows[0]], (rows.size, *excitation.shape[1:]))
        else:
            v = excitation[rows]
        parts = _coupled_entries(vehicle, rec, contact[blk, None], v, np, True)
        for whole, entries in zip((u_v, rail, force), parts, strict=True):
            for i, e in enumerate(entries):  # each entry written once, into its place
                whole[blk, :, i] = e
    return FRF(f, u_v, rail, force, dofs, wheels=wheels)


def load_compiled_kernels() -> bool:
    """Load the compiled kernels of :func:`frf_case_stack` into this process, if installed.

    One two-frequency case of the default preset is solved on them (the wave kernel and
    the coupled point kernel, with the argument types of a sweep's chunk), so that numba
    loads their machine code from its on-disk cache (or compiles it, the first time).

    Returns
    -------
    bool
        False where numba is not installed or ``RAILVIB_COMPILED=0`` turns the kernels
        off (nothing is loaded).
    """
    if not use_compiled(LOADED_MIN_POINTS, work=COMPILED_MIN_POINTS):
        return False
    system = build_system(load_preset_case())
    frf_case_stack(np.array([10.0, 20.0]), [system], compiled=True)
    return True


def frf_pad_stack(
    system: CoupledSystem,
    f: ArrayLike,
    pads: Sequence[PadModel],
    temperatures: Sequence[float | None],
    speeds: ArrayLike,
    condensation: WheelCondensation | None = None,
) -> FRF:
    """Coupled FRFs of cases differing in pad, pad temperature and speed, in one stack.

    :func:`frf_case_stack` of `system` with each case's pad, temperature and speed;
    equals :meth:`railvib.coupling.CoupledSystem.frf` of each case to rounding.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track (rail, spacing), contact stiffness and wheel positions shared by
        the cases; its pad and speed are not used.
    f : array_like
        Frequencies in Hz, ``(n_freq,)``.
    pads : sequence of PadModel
        The railpad of each case (complex stiffness per rail seat, N/m), ``n_case``.
    temperatures : sequence of float or None
        Pad temperature of each case, degC (None: the model's reference).
    speeds : array_like
        Vehicle speed of each case, m/s, ``(n_case,)``.
    condensation : WheelCondensation, optional
        The vehicle condensed onto its wheels at `f`, if already known.

    Returns
    -------
    FRF
        Arrays ``(n_case, n_freq, n)``: the case is the leading batch axis.
    """
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    if len(pads) != speeds.size or len(temperatures) != speeds.size:
        raise CaseError("pads", len(pads), f"one pad and temperature per speed ({speeds.size})")
    tracks: dict[tuple[int, float | None], Any] = {}
    systems = []
    for pad, t, v in zip(pads, temperatures, speeds, strict=True):
        if (id(pad), t) not in tracks:
            tracks[id(pad), t] = replace(system.track, pad=pad, pad_temperature=t)
        systems.append(replace(system, track=tracks[id(pad), t], speed=float(v)))
    known: dict[Hashable, WheelCondensation] | None = (
        None if condensation is None else {0: condensation}
    )
    return frf_case_stack(f, systems, None, [0] * len(systems), known)


def _distinct_keys(keys: Sequence[Hashable]) -> tuple[NDArray[np.int64], list[int]]:
    """The number of each key's distinct value, and the first case of each value."""
    number: dict[Hashable, int] = {}
    first: list[int] = []
    which = np.empty(len(keys), dtype=np.int64)
    for i, k in enumerate(keys):
        if k not in number:
            number[k] = len(first)
            first.append(i)
        which[i] = number[k]
    return which, first


def _rows(which: NDArray[np.int64]) -> slice | NDArray[np.int64]:
    """Rows `which` as a slice where they run consecutively (a view, no copy), else as given."""
    if np.array_equal(which, np.arange(which[0], which[0] + which.size)):
        return slice(int(which[0]), int(which[0]) + which.size)
    return which


def _stacked_condensations(conds: Sequence[WheelCondensation]) -> WheelCondensation:
    """Condensations of several vehicles as one, entries ``(n_vehicle, n_freq)``.

    One vehicle is returned as it is (entries ``(n_freq,)``, broadcast over the cases).
    """
    if len(conds) == 1:
        return conds[0]

    def join(name: str) -> list[list[Any]]:
        rows = getattr(conds[0], name)
        return [
            [np.stack([getattr(c, name)[a][b] for c in conds]) for b in range(len(rows[a]))]
            for a in range(len(rows))
        ]

    return WheelCondensation(join("stiffness_entries"), join("recovery_entries"))


def _pick(cond: WheelCondensation, which: NDArray[np.int64]) -> WheelCondensation:
    """The rows `which` of stacked condensations: entries ``(n_case, n_freq)``."""
    return WheelCondensation(
        [[e[which] for e in row] for row in cond.stiffness_entries],
        [[e[which] for e in row] for row in cond.recovery_entries],
    )


def _coupled_entries(
    vehicle: WheelCondensation,
    rec: list[list[Any]],
    contact_stiffness: Any,
    excitation: Any,
    xp: Any,
    as_entries: bool = False,
) -> tuple[Any, Any, Any]:
    """The coupled solve on receptance entries ``(n_case, n_freq)`` (excitation last: wheel).

    Returns the vehicle, rail and contact-force responses stacked on a last axis, or, with
    `as_entries`, as their lists of entry arrays.
    """
    s = vehicle.stiffness_entries
    n = len(rec)
    # the identities added on the diagonals only (an off-diagonal "+ 0.0" is a copy)
    flex = [
        [rec[a][b] + 1.0 / contact_stiffness if a == b else rec[a][b] for b in range(n)]
        for a in range(n)
    ]
    system = [[dot(flex[a], [s[c][b] for c in range(n)]) for b in range(n)] for a in range(n)]
    for a in range(n):
        system[a][a] = system[a][a] + 1.0
    rhs = [excitation[:, :, a] for a in range(n)]
    u_w, bad = solve(system, rhs, xp)
    if bool(xp.any(bad)):  # pivots too small for elimination without exchanges: LAPACK
        mask = to_numpy(bad)
        a_bad = np.stack([np.stack([to_numpy(e) for e in row], -1) for row in system], -2)
        fixed = np.linalg.solve(a_bad[mask], to_numpy(excitation)[mask][..., None])[..., 0]
        u_w = [put(u_w[a], bad, fixed[:, a], xp) for a in range(n)]
    force = [-dot(s[a], u_w) for a in range(n)]
    vehicle_u = [dot(row, u_w) for row in vehicle.recovery_entries]
    rail = [dot(rec[a], force) for a in range(n)]
    if as_entries:
        return vehicle_u, rail, force
    out = tuple(xp.stack(v, axis=-1) for v in (vehicle_u, rail, force))
    return out[0], out[1], out[2]


def frf_stack(
    system: CoupledSystem,
    f: ArrayLike,
    pad_stiffness: Any,
    speeds: ArrayLike,
    xp: Any = np,
    block: int | None = None,
) -> tuple[Any, Any, Any]:
    """Coupled FRFs of cases with their own pad stiffness and speed, all kernels in `xp`.

    The stacked kernels end to end on one array library (:func:`railvib.stack.namespace`:
    NumPy, CuPy or JAX): the Euler rail's waves and receptance
    (:mod:`railvib.track.stacked`), the vehicle condensation and the coupled solve.
    Nothing but the pivot and band-edge fallbacks leaves the device. The cases are
    taken in blocks of about `block` (case, frequency) points.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track (an Euler rail: no shear stiffness), contact stiffness and wheel
        positions shared by the cases; its pad and speed are not used.
    f : array_like
        Frequencies in Hz, ``(n_freq,)``.
    pad_stiffness : array
        ``K*`` of each case's pad in N/m, ``(n_case, n_freq)``, in `xp`.
    speeds : array_like
        Vehicle speed of each case, m/s, ``(n_case,)``.
    xp : module
        Array namespace.
    block : int, optional
        Points per block (default :data:`railvib.coupling.FREQUENCY_BLOCK`, sized to a
        CPU's cache; an accelerator wants millions).

    Returns
    -------
    vehicle, rail, contact_force : array
        ``(n_case, n_freq, n_dof)`` (m/m), ``(n_case, n_freq, n_wheel)`` (m/m) and
        ``(n_case, n_freq, n_wheel)`` (N/m), per metre of irregularity, in `xp`.
    """
    f_np = np.atleast_1d(np.asarray(f, dtype=float))
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    system.track.check_frequencies(f_np)
    cond = system.vehicle.condensed_to_wheels(f_np, xp)
    per_block = max(1, (FREQUENCY_BLOCK if block is None else int(block)) // f_np.size)
    parts = [
        _frf_block(
            system, f_np, pad_stiffness[c : c + per_block], speeds[c : c + per_block], cond, xp
        )
        for c in range(0, speeds.size, per_block)
    ]
    out = tuple(xp.concatenate([p[i] for p in parts], axis=0) for i in range(3))
    return out[0], out[1], out[2]


def _frf_block(
    system: CoupledSystem,
    f_np: NDArray[np.float64],
    pad_stiffness: Any,
    speeds: NDArray[np.float64],
    cond: WheelCondensation,
    xp: Any,
) -> tuple[Any, Any, Any]:
    """:func:`frf_stack` of one block of cases."""
    track = system.track
    if isinstance(track, SlabTrack):  # its slab couples the fasteners: no pad stiffness says it
        raise CaseError("track.model", type(track).__name__, "a track on independent supports")
    if track.rail.is_timoshenko:
        raise CaseError("track.rail.shear_stiffness", track.rail.shear_stiffness, "an Euler rail")
    n_case = speeds.size
    d = track.sleeper_spacing
    ei = track.rail.complex_bending_stiffness
    omega = 2.0 * np.pi * xp.asarray(f_np)
    beta4 = track.rail.mass_per_length * omega**2 * d**4 / ei + 0.0 * pad_stiffness
    waves = stacked_waves(
        xp.reshape(beta4, (-1,)), xp.reshape(pad_stiffness * (d**3 / ei), (-1,)), xp
    )
    x = system.wheel_positions / d
    rec = receptance_entries(waves, x, x, xp)
    scale = d**3 / ei
    rec = [[xp.reshape(e * scale, (n_case, f_np.size)) for e in row] for row in rec]
    vehicle = system.vehicle
    delays = xp.asarray(vehicle.wheel_offsets[None, :] / speeds[:, None])
    excitation = xp.exp(-2j * np.pi * xp.asarray(f_np)[None, :, None] * delays[:, None, :])
    return _coupled_entries(cond, rec, system.contact_stiffness, excitation, xp)
