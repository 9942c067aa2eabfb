"""The coupled vehicle-track system, solved at every frequency at once.

With the rail receptance ``R`` between the contact points and ``Q = (R + I/k_H)^-1``
the contact condenses exactly onto the vehicle (paper Eq. 16):

    (D_v + B Q B^T) u_v = B Q r,   P = Q (B^T u_v - r),   u_rail = R P,

where ``D_v`` is the vehicle's dynamic stiffness, ``B`` maps wheel forces to
vehicle DOFs and ``P`` are the (compressive) contact forces. It is solved with
the vehicle condensed onto its wheel DOFs (bodies recovered afterwards), so
each frequency costs a few 4x4 operations once the vehicle is condensed.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.coupled_kernel import fused_kernel, fused_points
from railvib.coupled_kernel import kernel as coupled_kernel
from railvib.errors import CaseError
from railvib.pads.stack import pad_stiffnesses
from railvib.pem import excitation_vector, wheel_delays
from railvib.response import FRF
from railvib.stack import dot, entries, put, solve, stacked, to_numpy
from railvib.track.compiled import compiled_receptance, use_compiled
from railvib.track.periodic import VANISHING_LOSS_FACTOR, PeriodicTrack
from railvib.track.periodic import _warn_if_ill_conditioned as warn_if_ill_conditioned
from railvib.track.stacked import receptance_entries, stacked_waves
from railvib.vehicle.assembly import Vehicle, WheelCondensation

__all__ = [
    "DENSE_WHEELS",
    "FREQUENCY_BLOCK",
    "FREQUENCY_BLOCK_MANY_WHEELS",
    "CoupledFRF",
    "CoupledSystem",
    "compiled_solve",
    "coupled_response",
    "track_receptances",
]

#: frequencies solved at once: each entry array of a block (64 kB) and the block's working
#: set (a few hundred of them) stay in the cache; cost is linear in the number of blocks
FREQUENCY_BLOCK = 4096


#: frequencies solved at once for a train (more than DENSE_WHEELS wheels): its n x n
#: receptance stack, 16 n^2 bytes a frequency, stays near the cache (16 MB for 32 wheels)
FREQUENCY_BLOCK_MANY_WHEELS = 1024

#: more wheels than this and the coupled solve on NumPy works on dense stacks with LAPACK
#: (:func:`_coupled_dense`): the stacked elimination's Python-level cost grows as n^3 (the
#: compiled fused kernel of one case takes any number)
DENSE_WHEELS = 8

#: the coupled responses (one container for every solver; kept under its old name)
CoupledFRF = FRF


@dataclass(frozen=True)
class CoupledSystem:
    """Vehicle on the infinite periodic track through linear Hertz springs.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (wheels listed front to back).
    track : PeriodicTrack
        The track.
    contact_stiffness : float
        Linearised contact stiffness between each wheelset and the rail beam, N/m.
    leading_wheel_position : float
        Position of the leading wheel along the rail measured from a sleeper, m,
        in ``[0, d)``; the other wheels trail it (at smaller x).
    speed : float
        Vehicle speed in m/s; sets the delays of the inputs at the trailing wheels.
    """

    vehicle: Vehicle
    track: PeriodicTrack
    contact_stiffness: float
    leading_wheel_position: float
    speed: float

    def __post_init__(self) -> None:
        if not (np.isfinite(self.contact_stiffness) and self.contact_stiffness > 0):
            raise CaseError("contact.stiffness", self.contact_stiffness, "must be > 0 (N/m)")
        d = self.track.sleeper_spacing
        x0 = self.leading_wheel_position
        if not (np.isfinite(x0) and 0.0 <= x0 < d):
            raise CaseError("contact.leading_wheel_position", x0, f"must be in [0, {d}) (m)")
        if not (np.isfinite(self.speed) and self.speed > 0):
            raise CaseError("speed", self.speed, "must be > 0 (m/s)")

    @property
    def wheel_positions(self) -> NDArray[np.float64]:
        """Contact positions along the rail, m (sleepers at multiples of d)."""
        return self.leading_wheel_position - self.vehicle.wheel_offsets

    def frf(self, f: ArrayLike) -> FRF:
        """Responses to a unit-amplitude irregularity, delayed coherently at each wheel.

        Solved in blocks of :data:`FREQUENCY_BLOCK` frequencies (:meth:`frf_blocks`).

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Returns
        -------
        FRF
            With the rail receptance between the contact points.
        """
        f = np.atleast_1d(np.asarray(f, dtype=float))
        blocks = [frf for _, frf in self.frf_blocks(f)]
        if len(blocks) == 1:
            return blocks[0]
        rec = [b.receptance for b in blocks if b.receptance is not None]
        return FRF(
            f=f,
            vehicle=np.concatenate([b.vehicle for b in blocks]),
            rail=np.concatenate([b.rail for b in blocks]),
            contact_force=np.concatenate([b.contact_force for b in blocks]),
            dofs=self.vehicle.dofs,
            receptance=np.concatenate(rec),
            wheels=self.vehicle.wheel_names,
        )

    def frf_blocks(
        self,
        f: ArrayLike,
        block: int | None = None,
        observe: ArrayLike | None = None,
        into: tuple[NDArray[Any], ...] | None = None,
    ) -> Iterator[tuple[slice, FRF]]:
        """The responses of :meth:`frf` block by block, so memory is bounded by the block.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, ``(n_freq,)``.
        block : int, optional
            Frequencies per block (default :data:`FREQUENCY_BLOCK`, or
            :data:`FREQUENCY_BLOCK_MANY_WHEELS` above :data:`DENSE_WHEELS` wheels).
        observe : array_like, optional
            Further points of the rail, m (e.g. the rail seats under the wheels): their
            receptance from the wheels is taken from the same waves as the contact's, one
            track solve per block, and their displacement is ``FRF.rail_observed``.
        into : tuple of numpy.ndarray, optional
            Arrays over the whole of `f` for the vehicle ``(n_freq, n_dof)``, contact-force
            ``(n_freq, n_wheel)``, rail ``(n_freq, n_wheel)`` and observed ``(n_freq,
            n_observe)`` responses (e.g. a run's result arrays' columns): where the fused
            kernel solves a block, its responses are written straight into their rows,
            and the block's FRF holds those rows (no copy into place).

        Yields
        ------
        slice, FRF
            The block's indices into `f`, and its responses (with the receptance).

        Notes
        -----
        Where this process has loaded the compiled wave kernel, each block's vehicle
        condensation, coupled solve and body recovery run on one fused compiled kernel
        (:func:`railvib.coupled_kernel.fused_points`); the NumPy path is the reference.
        """
        f = np.atleast_1d(np.asarray(f, dtype=float))
        many = len(self.vehicle.wheels) > DENSE_WHEELS
        default = FREQUENCY_BLOCK_MANY_WHEELS if many else FREQUENCY_BLOCK
        step = default if block is None else max(1, int(block))
        x = self.wheel_positions
        delays = wheel_delays(self.vehicle.wheel_offsets, self.speed)
        # one case's run uses the compiled kernel only where this process has loaded it
        compiled = use_compiled(f.size, load=False)
        fast_solve = compiled and fused_kernel() is not None
        extra = np.empty(0) if observe is None else np.atleast_1d(np.asarray(observe, dtype=float))
        x_obs = np.concatenate([x, extra])  # the wheels first: their receptance as without
        for start in range(0, max(f.size, 1), step):
            sl = slice(start, min(start + step, f.size))
            fb = f[sl]
            if fast_solve:
                rows = None if into is None else tuple(a[sl] for a in into)
                yield sl, self._fused_block(fb, x, x_obs, delays, observe is not None, rows)
                continue
            if compiled:
                rec_obs = _compiled_receptance(self.track, fb, x, x_obs)
            else:
                rec_obs = self.track.receptance(fb, x, x_obs)
            rec = np.ascontiguousarray(rec_obs[:, : x.size]) if extra.size else rec_obs
            v = excitation_vector(fb, delays)
            cond = self.vehicle.condensed_to_wheels(fb)
            u_v, force, rail = coupled_response(cond, rec, self.contact_stiffness, v[..., None])
            observed = None
            if observe is not None:
                observed = np.einsum("fow,fw->fo", rec_obs[:, x.size :], force[..., 0])
            yield (
                sl,
                FRF(
                    f=fb,
                    vehicle=u_v[..., 0],
                    rail=rail[..., 0],
                    contact_force=force[..., 0],
                    dofs=self.vehicle.dofs,
                    receptance=rec,
                    wheels=self.vehicle.wheel_names,
                    rail_observed=observed,
                ),
            )

    def _fused_block(
        self,
        f: NDArray[np.float64],
        x: NDArray[np.float64],
        x_obs: NDArray[np.float64],
        delays: NDArray[np.float64],
        observed_wanted: bool,
        out: tuple[NDArray[Any], ...] | None = None,
    ) -> FRF:
        """One block of :meth:`frf_blocks` on the compiled fused kernel (:func:`fused_points`).

        The frequencies where the kernel's vehicle elimination fails its pivot test are
        solved again by the NumPy path (condensed densely with LAPACK's pivoting). `out`:
        the arrays the responses are written into (:func:`fused_points`), or None.
        """
        rec_obs, scale = _receptance_parts(self.track, f, x, x_obs)
        vehicle = self.vehicle
        u_v, force, rail, rec, observed, bad = fused_points(
            vehicle.elimination_program,
            f,
            vehicle.element_stiffness(f),
            rec_obs,
            scale,
            self.contact_stiffness,
            delays,
            out=out,
        )
        if bad.any():
            cond = vehicle.condensed_to_wheels(f[bad])
            v = excitation_vector(f[bad], delays)[..., None]
            u_b, force_b, rail_b = coupled_response(cond, rec[bad], self.contact_stiffness, v)
            u_v[bad], force[bad], rail[bad] = u_b[..., 0], force_b[..., 0], rail_b[..., 0]
            far = rec_obs[bad, x.size :] * scale
            observed[bad] = np.einsum("fow,fw->fo", far, force_b[..., 0])
        return FRF(
            f=f,
            vehicle=u_v,
            rail=rail,
            contact_force=force,
            dofs=vehicle.dofs,
            receptance=rec,
            wheels=vehicle.wheel_names,
            rail_observed=observed if observed_wanted else None,
        )


def compiled_solve(n_points: int, n_wheels: int, compiled: bool | None = None) -> bool:
    """Whether a coupled solve of `n_points` points runs on :mod:`railvib.coupled_kernel`.

    Parameters
    ----------
    n_points : int
        (case, frequency) points of the solve.
    n_wheels : int
        Wheels of the vehicle (above :data:`DENSE_WHEELS` the solve stays on LAPACK).
    compiled : bool, optional
        Whether compiled kernels are wanted; default: where the compiled wave kernel is
        loaded in this process and serves a stack this size
        (:func:`railvib.track.compiled.use_compiled`, never loading it).

    Returns
    -------
    bool
        True where numba is installed and the solve is wanted compiled.
    """
    if n_wheels > DENSE_WHEELS:
        return False
    wanted = use_compiled(n_points, load=False) if compiled is None else compiled
    return wanted and coupled_kernel() is not None


def _pad_supports(
    tracks: Sequence[PeriodicTrack], f: NDArray[np.float64]
) -> dict[int, NDArray[np.complex128]]:
    """The supports of the tracks whose support is their pad alone, evaluated together.

    Parameters
    ----------
    tracks : sequence of PeriodicTrack
        The tracks of one stack.
    f : numpy.ndarray
        Frequencies in Hz, ``(n_freq,)``.

    Returns
    -------
    dict of int to numpy.ndarray
        By index into `tracks`, ``K*(f)`` in N/m (:func:`railvib.pads.stack.pad_stiffnesses`:
        the pads of one model over arrays of their parameters, bit for bit each
        track's ``support_stiffness``); tracks with layers below the pad are left out.
    """
    plain = [
        i
        for i, track in enumerate(tracks)
        if type(track).support_stiffness is PeriodicTrack.support_stiffness
    ]
    if not plain:
        return {}
    rows = pad_stiffnesses(
        [tracks[i].pad for i in plain], [tracks[i].pad_temperature for i in plain], f
    )
    return dict(zip(plain, rows, strict=True))


def _stackable(track: PeriodicTrack) -> bool:
    """Whether the stacked kernel gives `track`'s receptance: an Euler rail, the wave solver."""
    return type(track).receptance is PeriodicTrack.receptance and not track.rail.is_timoshenko


def _complex_ei(track: PeriodicTrack) -> complex:
    """The rail's ``EI (1 + i eta)`` as the wave solver takes it (vanishing loss floored), N m^2."""
    return track.rail.bending_stiffness * (
        1.0 + 1j * max(track.rail.loss_factor, VANISHING_LOSS_FACTOR)
    )


def track_receptances(
    f: NDArray[np.float64],
    tracks: Sequence[PeriodicTrack],
    positions: Sequence[NDArray[np.float64]],
    compiled: bool | None = None,
) -> NDArray[np.complex128]:
    """Rail receptance between each track's contact points, ``(n_track, n_freq, n_w, n_w)``, m/N.

    The tracks with an Euler rail on the wave solver and the same dimensionless wheel
    positions ``x / d`` are one stack of (track, frequency) points, each point with its
    own ``beta4 = m omega^2 d^4 / EI*``, support ``K*(f, T) d^3 / EI*`` and scale
    ``d^3 / EI*``, solved in blocks of :data:`FREQUENCY_BLOCK` points: by the compiled
    kernel (:mod:`railvib.track.compiled`) where it is available and the stack large
    enough, else by the NumPy kernel (:mod:`railvib.track.stacked`), which also takes the
    points the compiled one leaves to it. Other tracks (a Timoshenko rail) use their own
    :meth:`~railvib.track.PeriodicTrack.receptance`.

    Parameters
    ----------
    f : numpy.ndarray
        Frequencies in Hz, ``(n_freq,)``.
    tracks : sequence of PeriodicTrack
        The tracks.
    positions : sequence of numpy.ndarray
        The contact positions on each track, m, ``(n_w,)`` each.
    compiled : bool, optional
        Whether to use the compiled kernel; default: where
        :func:`railvib.track.compiled.use_compiled` allows it for the whole stack
        (loading it now if the stack is large enough).

    Returns
    -------
    numpy.ndarray
        ``[t, k, i, j]``: displacement at contact ``i`` per unit force at contact ``j``.
    """
    n_w = positions[0].size
    out = np.empty((len(tracks), f.size, n_w, n_w), dtype=np.complex128)
    stacks: dict[tuple[float, ...], list[int]] = {}
    for i, (track, x) in enumerate(zip(tracks, positions, strict=True)):
        if _stackable(track):
            stacks.setdefault(tuple(x / track.sleeper_spacing), []).append(i)
        else:
            out[i] = track.receptance(f, x, x)
    omega = 2.0 * np.pi * f
    for x_d, members in stacks.items():
        n_points = len(members) * f.size
        b4 = np.empty(n_points, dtype=np.complex128)
        k = np.empty(n_points, dtype=np.complex128)
        sc = np.empty(n_points, dtype=np.complex128)
        for i in members:
            tracks[i].check_frequencies(f)
        pad_k = _pad_supports([tracks[i] for i in members], f)
        for row, i in enumerate(members):
            track = tracks[i]
            d, ei = track.sleeper_spacing, _complex_ei(track)
            rows = slice(row * f.size, (row + 1) * f.size)
            # the wave solver's expressions, operation for operation
            b4[rows] = track.rail.mass_per_length * omega**2 * d**4 / ei
            support = pad_k[row] if row in pad_k else track.support_stiffness(f)
            k[rows] = support * d**3 / ei
            sc[rows] = d**3 / ei
        points = np.tile(f, len(members))
        x = np.array(x_d)
        fast = use_compiled(n_points) if compiled is None else compiled
        # each block scaled straight into its place (a view of `out` where the members are
        # its consecutive tracks, as when every track is on the stacked kernel)
        consecutive = members == list(range(members[0], members[0] + len(members)))
        whole = slice(members[0], members[0] + len(members))
        rec = (
            out[whole].reshape(n_points, n_w, n_w)
            if consecutive
            else np.empty((n_points, n_w, n_w), dtype=np.complex128)
        )
        condition = np.empty(n_points)
        left: list[NDArray[np.intp]] = []  # points the compiled kernel leaves to NumPy
        for start in range(0, n_points, FREQUENCY_BLOCK):
            sl = slice(start, start + FREQUENCY_BLOCK)
            if fast:
                block, condition[sl], bad = compiled_receptance(b4[sl], k[sl], x, x)
                left.append(start + np.flatnonzero(bad))
            else:
                block, condition[sl] = _dimensionless(b4[sl], k[sl], x, False)
            np.multiply(block, sc[sl, None, None], out=rec[sl])
        # those of every block in one NumPy call (a call's cost is mostly its fixed part)
        bad_points = np.concatenate(left) if left else np.empty(0, dtype=np.intp)
        for start in range(0, bad_points.size, FREQUENCY_BLOCK):
            idx = bad_points[start : start + FREQUENCY_BLOCK]
            block, condition[idx] = _dimensionless(b4[idx], k[idx], x, False)
            rec[idx] = block * sc[idx, None, None]
        for start in range(0, n_points, FREQUENCY_BLOCK):
            sl = slice(start, start + FREQUENCY_BLOCK)
            warn_if_ill_conditioned(points[sl], condition[sl])
        if not consecutive:
            out[members] = rec.reshape(len(members), f.size, n_w, n_w)
    return out


def _compiled_receptance(
    track: PeriodicTrack, f: NDArray[np.float64], x: NDArray[np.float64], x_obs: NDArray[np.float64]
) -> NDArray[np.complex128]:
    """One track's receptance from contacts `x` to points `x_obs` (m) on the compiled kernel.

    ``(n_freq, n_obs, n_w)``, m/N, from the expressions of :func:`track_receptances`.
    """
    rec, scale = _receptance_parts(track, f, x, x_obs)
    return rec if scale == 1.0 else rec * scale


def _receptance_parts(
    track: PeriodicTrack, f: NDArray[np.float64], x: NDArray[np.float64], x_obs: NDArray[np.float64]
) -> tuple[NDArray[np.complex128], complex]:
    """:func:`_compiled_receptance` as its dimensionless part and its scale ``d^3 / EI*`` (m/N).

    A track off the wave solver (:func:`_stackable`) gives its receptance in m/N, scale 1.
    """
    if not _stackable(track):
        return track.receptance(f, x, x_obs), 1.0
    track.check_frequencies(f)
    omega = 2.0 * np.pi * f
    d, ei = track.sleeper_spacing, _complex_ei(track)
    b4 = np.asarray(track.rail.mass_per_length * omega**2 * d**4 / ei, dtype=np.complex128)
    k = np.asarray(track.support_stiffness(f) * d**3 / ei, dtype=np.complex128)
    rec, condition = _dimensionless(b4, k, x / d, True, x_obs / d)
    warn_if_ill_conditioned(f, condition)
    return rec, d**3 / ei


def _dimensionless(
    beta4: NDArray[np.complex128],
    pad: NDArray[np.complex128],
    x: NDArray[np.float64],
    compiled: bool,
    x_obs: NDArray[np.float64] | None = None,
) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """Dimensionless receptance of a block, and the matching's condition estimate.

    From the loads at `x` to the points `x_obs` (default `x`), dimensionless positions.
    """
    obs = x if x_obs is None else x_obs
    if compiled:
        rec, condition, bad = compiled_receptance(beta4, pad, x, obs)
        if not bad.any():
            return rec, condition
        waves = stacked_waves(beta4[bad], pad[bad])
        rec[bad] = stacked(receptance_entries(waves, x, obs))
        condition[bad] = waves.condition
        return rec, condition
    waves = stacked_waves(beta4, pad)
    return np.asarray(stacked(receptance_entries(waves, x, obs))), np.asarray(waves.condition)


def coupled_response(
    vehicle: WheelCondensation,
    receptance: NDArray[np.complex128],
    contact_stiffness: float,
    excitation: NDArray[np.complex128],
) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]]:
    """Solve the coupled system for any number of excitation vectors at once.

    With ``Q = (R + I/k_H)^-1`` and the vehicle condensed on its wheels (``S``),
    ``(S + Q) u_w = Q r``; multiplied by ``Q^-1`` this is
    ``((R + I/k_H) S + I) u_w = r``, which needs no inverse. The wheels' equation
    ``S u_w = -P`` gives the contact forces without the cancellation of
    ``u_w - r`` at low frequency; then ``u = R_v u_w`` and ``u_rail = R P``.

    Parameters
    ----------
    vehicle : WheelCondensation
        From :meth:`railvib.vehicle.Vehicle.condensed_to_wheels` at the same frequencies.
    receptance : numpy.ndarray
        Rail receptance between the contact points, ``(n_freq, n_wheel, n_wheel)``, m/N.
    contact_stiffness : float
        k_H per contact, N/m.
    excitation : numpy.ndarray
        Irregularity at each wheel, ``(n_freq, n_wheel, n_rhs)``, m.

    Returns
    -------
    vehicle_displacement, contact_force, rail_displacement : numpy.ndarray
        ``(n_freq, n_dof, n_rhs)``, ``(n_freq, n_wheel, n_rhs)``, ``(n_freq, n_wheel, n_rhs)``.
    """
    return _coupled(vehicle, receptance, contact_stiffness, excitation, np)


def _coupled(
    vehicle: WheelCondensation, receptance: Any, contact_stiffness: float, excitation: Any, xp: Any
) -> tuple[Any, Any, Any]:
    """:func:`coupled_response` in the stacked layout, in array namespace `xp`."""
    if len(vehicle.stiffness_entries) > DENSE_WHEELS:
        return _coupled_dense(vehicle, receptance, contact_stiffness, excitation, xp)
    rec = entries(receptance, xp)
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
    rhs = [excitation[:, a, :] for a in range(n)]
    u_w, bad = solve(system, rhs, xp)
    if bool(xp.any(bad)):  # pivots too small for elimination without exchanges: LAPACK
        a_bad = to_numpy(stacked(system, xp))[to_numpy(bad)]
        fixed = np.linalg.solve(a_bad, to_numpy(excitation)[to_numpy(bad)])
        u_w = [put(u_w[a], bad, fixed[:, a, :], xp) for a in range(n)]
    force = [-_apply(s[a], u_w) for a in range(n)]
    vehicle_u = [_apply(row, u_w) for row in vehicle.recovery_entries]
    rail = [_apply(rec[a], force) for a in range(n)]
    return stacked(vehicle_u, xp), stacked(force, xp), stacked(rail, xp)


def _coupled_dense(
    vehicle: WheelCondensation, receptance: Any, contact_stiffness: float, excitation: Any, xp: Any
) -> tuple[Any, Any, Any]:
    """:func:`coupled_response` on ``(N, n, n)`` stacks with LAPACK: a train's many wheels.

    The stacked elimination costs some ``n^3 / 3`` array operations; for the 32 wheels of an
    8-car train that is 10^4 passes over the frequencies, where one batched LAPACK solve
    (partial pivoting) makes one. The vehicle's recovery is applied row by row over the
    wheels each DOF depends on (a train's car body on its own car's wheels only).
    """
    rec = xp.asarray(receptance) if not isinstance(receptance, list) else stacked(receptance, xp)
    n = len(vehicle.stiffness_entries)
    blocks = _wheel_blocks(vehicle)
    entries_s = vehicle.stiffness_entries
    s_blocks = [stacked([[entries_s[a][b] for b in g] for a in g], xp) for g in blocks]
    system = xp.empty_like(rec)
    for g, s_g in zip(blocks, s_blocks, strict=True):
        lo, hi = g[0], g[-1] + 1
        system[:, :, lo:hi] = rec[:, :, lo:hi] @ s_g
        system[:, lo:hi, lo:hi] += s_g * (1.0 / contact_stiffness)
    diag = xp.arange(n)
    system[:, diag, diag] += 1.0
    u_w = xp.linalg.solve(system, excitation)
    force = xp.empty_like(u_w)
    for g, s_g in zip(blocks, s_blocks, strict=True):
        lo, hi = g[0], g[-1] + 1
        force[:, lo:hi] = -(s_g @ u_w[:, lo:hi])
    rail = rec @ force
    columns = [u_w[:, b, :] for b in range(n)]
    zero = xp.zeros_like(columns[0])
    vehicle_u = []
    for row, active in zip(vehicle.recovery_entries, vehicle.active_wheels, strict=True):
        vehicle_u.append(
            dot([row[b][:, None] for b in active], [columns[b] for b in active]) if active else zero
        )
    return xp.stack(vehicle_u, axis=1), force, rail


def _wheel_blocks(vehicle: WheelCondensation) -> list[tuple[int, ...]]:
    """Contiguous groups of wheels with no vehicle stiffness between groups (a train's cars).

    From :attr:`WheelCondensation.recovery_wheels` where given, else one group of all.
    """
    n = len(vehicle.stiffness_entries)
    groups = sorted(set(vehicle.recovery_wheels or ())) or [tuple(range(n))]
    covered = [w for g in groups for w in g]
    contiguous = all(g == tuple(range(g[0], g[-1] + 1)) for g in groups)
    if sorted(covered) != list(range(n)) or not contiguous:
        return [tuple(range(n))]
    return groups


def _apply(row: list[Any], x: list[Any]) -> Any:
    """``sum_b row[b] x[b]`` for entries ``(N,)`` and right-hand sides ``(N, k)``."""
    return dot([r[:, None] for r in row], x)
