"""Many cases of one structure solved in one stack: (case, frequency) points end to end.

Cases that differ in their railpad (model, parameters, temperature) and in speed
share the rail, the sleeper spacing, the vehicle, the contact and the wheel positions.
Their ``n_case x n_freq`` points are laid on one leading axis (case-major) and solved by
one call of each kernel (``docs/design/0006-stacked-batches.md``):

* the pad's ``K*(f, T)`` of every case is evaluated into the stack, and the track's own
  wave solution (:meth:`railvib.track.PeriodicTrack.receptance`) runs once over it, with
  a stand-in pad (:class:`PadStack`) that hands it the stacked values;
* the vehicle is condensed once on the frequencies and broadcast over the cases;
* the coupled 4x4 solve runs on entry arrays ``(n_case, n_freq)``, each case with its
  own speed's excitation.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.coupling import FREQUENCY_BLOCK, CoupledSystem
from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.response import FRF
from railvib.stack import dot, put, solve, to_numpy
from railvib.track.slab import SlabTrack
from railvib.track.stacked import receptance_entries, stacked_waves
from railvib.vehicle.assembly import WheelCondensation

__all__ = ["PadStack", "frf_pad_stack", "frf_stack"]


@dataclass(frozen=True, eq=False)
class PadStack(PadModel):
    """Railpad stiffness given point by point over a stack (not a case-file model).

    Parameters
    ----------
    values : numpy.ndarray
        ``K*`` in N/m at each point of the stack, ``(n_point,)``; :meth:`stiffness` must
        be asked at exactly that many frequencies.
    """

    values: NDArray[np.complex128]

    def __post_init__(self) -> None:
        """Nothing to check: the values come from validated pad models."""

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """The stacked ``K*`` in N/m (`f`, Hz, only fixes the count; `temperature` ignored)."""
        n = np.size(f)
        if n != self.values.size:
            raise CaseError("frequency", n, f"the {self.values.size} points of the pad stack")
        return self.values


def frf_pad_stack(
    system: CoupledSystem,
    f: ArrayLike,
    pads: Sequence[PadModel],
    temperatures: Sequence[float | None],
    speeds: ArrayLike,
    condensation: WheelCondensation | None = None,
) -> FRF:
    """Coupled FRFs of cases differing in pad, pad temperature and speed, in one stack.

    Equals :meth:`railvib.coupling.CoupledSystem.frf` of each case (`system` with its
    pad, temperature and speed replaced) to rounding.

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
    f = np.atleast_1d(np.asarray(f, dtype=float))
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    n_case = speeds.size
    if len(pads) != n_case or len(temperatures) != n_case:
        raise CaseError("pads", len(pads), f"one pad and temperature per speed ({n_case})")
    # the distinct (pad, temperature) pairs: one track solution each
    distinct: dict[tuple[int, float | None], int] = {}
    which = np.array(
        [
            distinct.setdefault((id(p), t), len(distinct))
            for p, t in zip(pads, temperatures, strict=True)
        ]
    )
    first = {k: pads[int(np.flatnonzero(which == i)[0])] for k, i in distinct.items()}
    k_pad = np.concatenate([first[k].stiffness(f, k[1]) for k in distinct]).astype(np.complex128)
    x = system.wheel_positions
    points = np.tile(f, len(distinct))
    rec = np.empty((points.size, x.size, x.size), dtype=np.complex128)
    # the stacked pad ignores the temperature, but the track's other layers (a ballasted
    # track's ballast) take it: the points are solved in cache-sized blocks of one
    # temperature each
    rows = np.arange(points.size).reshape(len(distinct), f.size)
    for temperature in dict.fromkeys(t for _, t in distinct):
        at = rows[[i for i, (_, t) in enumerate(distinct) if t == temperature]].ravel()
        for start in range(0, at.size, FREQUENCY_BLOCK):
            idx = at[start : start + FREQUENCY_BLOCK]
            track = replace(system.track, pad=PadStack(k_pad[idx]), pad_temperature=temperature)
            rec[idx] = track.receptance(points[idx], x, x)
    vehicle = system.vehicle
    cond = vehicle.condensed_to_wheels(f) if condensation is None else condensation
    delays = vehicle.wheel_offsets[None, :] / speeds[:, None]  # (n_case, n_w)
    phase = -2j * np.pi * f[None, :, None] * delays[:, None, :]
    excitation = np.exp(phase)  # (n_case, n_freq, n_w)
    per_track = rec.reshape(len(distinct), f.size, x.size, x.size)
    step = max(1, FREQUENCY_BLOCK // f.size)  # cases per cache-sized block
    parts = [
        _coupled_stack(
            cond,
            per_track,
            system.contact_stiffness,
            excitation[c : c + step],
            which[c : c + step],
        )
        for c in range(0, n_case, step)
    ]
    u_v, rail, force = (np.concatenate([p[i] for p in parts]) for i in range(3))
    return FRF(f, u_v, rail, force, vehicle.dofs)


def _coupled_stack(
    vehicle: WheelCondensation,
    receptance: NDArray[np.complex128],
    contact_stiffness: float,
    excitation: NDArray[np.complex128],
    which: NDArray[np.int64],
    xp: Any = np,
) -> tuple[Any, Any, Any]:
    """:func:`railvib.coupling.coupled_response` on entries ``(n_case, n_freq)``.

    `receptance` holds ``(n_track, n_freq, n_w, n_w)``, the track solutions; case ``c``
    uses number ``which[c]``. The vehicle's entries ``(n_freq,)`` broadcast over the cases.
    """
    n = receptance.shape[-1]
    rec = [[receptance[which, :, a, b] for b in range(n)] for a in range(n)]
    return _coupled_entries(vehicle, rec, contact_stiffness, excitation, xp)


def _coupled_entries(
    vehicle: WheelCondensation,
    rec: list[list[Any]],
    contact_stiffness: float,
    excitation: Any,
    xp: Any,
) -> tuple[Any, Any, Any]:
    """The coupled solve on receptance entries ``(n_case, n_freq)`` (excitation last: wheel)."""
    s = vehicle.stiffness_entries
    n = len(rec)
    flex = [
        [rec[a][b] + (1.0 / contact_stiffness if a == b else 0.0) for b in range(n)]
        for a in range(n)
    ]
    system = [
        [dot(flex[a], [s[c][b] for c in range(n)]) + (1.0 if a == b else 0.0) for b in range(n)]
        for a in range(n)
    ]
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
