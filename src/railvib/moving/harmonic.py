"""Harmonic balance of the vehicle moving over the periodic track.

Wheel ``i`` runs at ``x_i(t) = x_i + v t`` (``x_i`` its position at ``t = 0``, sleepers at
``j d``). A contact force ``P_i exp(i Omega t)`` moving with it deflects the rail at wheel
``j``, ``r_ji = x_j - x_i`` ahead of it, by (:mod:`railvib.track.moving`, whose load stands
on a sleeper at ``t = 0``; wheel ``i`` passes one at ``-x_i / v``)::

    u_j(t) = P_i exp(i Omega t) sum_n A_n(Omega, r_ji) exp(i n phi_i) exp(i n Omega_s t),
    phi_i = 2 pi x_i / d,   Omega_s = 2 pi v / d.

With the contact forces a harmonic series on ``Omega + m Omega_s`` (``m = -N .. N``), the
rail under the wheels is the same series with the blocks::

    R[q, m]_ji = A_{q-m}(Omega + m Omega_s, r_ji) exp(i (q - m) phi_i),   |q - m| <= N,

and the vehicle (condensed onto its wheels, ``S`` at each ``Omega + m Omega_s``) and the
linear Hertz springs close the system as in the stationary model
(:func:`railvib.coupling.coupled_response`)::

    (I + (R + I / k_H) S) u_w = r + (R + I / k_H)[:, 0] G,   P = G delta_m0 - S u_w,

``r`` the irregularity at the wheels per harmonic and ``G`` the static wheel loads (the
parametric problem, on the constant harmonic ``Omega = 0``). Negative frequencies are
those of the real system: ``A_n(-Omega) = conj A_{-n}(Omega)``, ``S(-Omega) = conj S(Omega)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.coupling import CoupledSystem
from railvib.errors import CaseError
from railvib.track.moving import (
    MAX_HARMONIC_ORDER,
    SPEED_FRACTION,
    critical_speed,
    moving_load_receptance,
)
from railvib.track.moving_interp import interpolated_receptance
from railvib.track.periodic import PeriodicTrack

__all__ = [
    "DEFAULT_ORDER",
    "DEFAULT_TOLERANCE",
    "QUADRATURE_TOLERANCE",
    "HarmonicSystem",
    "LoadReceptances",
    "MovingSettings",
    "check_moving",
    "harmonic_blocks",
    "load_receptances",
]

#: default harmonic order N: the moving-load harmonics ``|n| >= 2`` are below 1e-3 of A_0 on
#: ballasted track away from the split pinned-pinned peaks (docs/moving-load.md)
DEFAULT_ORDER = 3

#: default largest harmonic left out, relative to the largest (dimensionless)
DEFAULT_TOLERANCE = 1e-2

#: frequencies of the order probe run before the whole computation
_PROBE = 12

#: wavenumber-quadrature tolerance of the moving-load receptances between the wheels
#: (``quadrature_tolerance`` of :func:`~railvib.track.moving.moving_load_receptance`,
#: relative to the largest harmonic at each load frequency): the coupled harmonics
#: ``|n| >= 2`` are 1e-2..1e-5 of ``H_0`` and take their accuracy from small ``A_n``
#: between far wheels. At 3e-9 every ``H_n``, ``|n| <= 5``, of the ``wang2017_metro`` preset
#: is within 1e-4 of its own peak of a 1e-9 reference (100 frequencies 0.5-1000 Hz); at the
#: kernel's default 1e-6, 0.15 at ``|n| = 5`` (the rule before the Filon one: 0.49, its far
#: gaps' ``exp(i k r)`` refining more than its tolerance asked, at 2.2 times the cost)
QUADRATURE_TOLERANCE = 3e-9

#: interpolation tolerance of those receptances in the load frequency
#: (:func:`~railvib.track.moving_interp.interpolated_receptance`, relative to the largest
#: harmonic at each point): ten times the quadrature's
INTERPOLATION_TOLERANCE = 3e-8


@dataclass(frozen=True)
class MovingSettings:
    """The ``[moving]`` settings: the harmonic order and the tolerance on its tail.

    Parameters
    ----------
    harmonic_order : int
        N: contact forces at ``f + m v / d``, ``|m| <= N`` (a count, 1 .. 50).
    tolerance : float
        Largest harmonic left out, relative to the largest one (dimensionless, in (0, 1)).
    """

    harmonic_order: int = DEFAULT_ORDER
    tolerance: float = DEFAULT_TOLERANCE

    def __post_init__(self) -> None:
        n = self.harmonic_order
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
            raise CaseError("moving.harmonic_order", n, f"an integer 1..{MAX_HARMONIC_ORDER}")
        if not 1 <= n <= MAX_HARMONIC_ORDER:
            raise CaseError("moving.harmonic_order", n, f"an integer 1..{MAX_HARMONIC_ORDER}")
        tol = self.tolerance
        if isinstance(tol, bool) or not isinstance(tol, (int, float)) or not 0.0 < tol < 1.0:
            raise CaseError("moving.tolerance", tol, "a number between 0 and 1, exclusive (-)")


def check_moving(
    system: CoupledSystem, f_max: float, settings: MovingSettings, f_min: float = 0.0
) -> None:
    """Refuse, before computing, what the moving-vehicle model cannot do, in one line each.

    A track without the moving-load formulation (a slab track), a speed
    above :data:`~railvib.track.moving.SPEED_FRACTION` of the critical speed (the series
    in the sleeper-passing harmonics stops converging towards it), and a harmonic order
    too low for the speed and band: the moving-load receptance is computed at a few
    frequencies up to ``f_max + N v / d`` and the order needed is named.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact and speed (m/s).
    f_max : float
        Highest frequency of the run, Hz.
    f_min : float
        Lowest frequency of the run, Hz (0: the constant load of the parametric problem).
    settings : MovingSettings
        Harmonic order and tolerance.

    Raises
    ------
    CaseError
        ``track.model``, ``speed_kmh`` or ``moving.harmonic_order``.
    """
    track = system.track
    try:
        track.support_stiffness(np.array([1.0]))
    except CaseError:
        raise CaseError(
            "track.model",
            type(track).__name__,
            "a track with independent supports under the rail (rigid_base, ballasted) for "
            "mode = 'moving': the moving-load formulation needs the support of one rail seat",
        ) from None
    bound = SPEED_FRACTION * critical_speed(track)
    if not system.speed <= bound:
        raise CaseError(
            "speed_kmh",
            round(system.speed * 3.6, 6),
            f"at most {bound * 3.6:.4g} km/h for mode = 'moving' ({SPEED_FRACTION:g} x the "
            "track's critical speed: towards it the sleeper-passing series does not converge)",
        )
    n = settings.harmonic_order
    top = float(f_max) + n * system.speed / track.sleeper_spacing
    probe = np.linspace(float(f_min), top, _PROBE)
    moving_load_receptance(track, probe, system.speed, order=n, tolerance=settings.tolerance)


@dataclass(frozen=True, eq=False)
class HarmonicSystem:
    """The harmonic-balance blocks of the moving vehicle at a stack of base frequencies.

    Attributes
    ----------
    f : numpy.ndarray
        Base frequencies, Hz, ``(n_freq,)``; harmonic ``m`` is at ``f + m v / d``.
    passing_hz : float
        Sleeper-passing frequency ``v / d``, Hz.
    orders : numpy.ndarray
        ``-N .. N``.
    receptance : numpy.ndarray
        ``R``, m/N, ``(n_freq, H, n_w, H, n_w)`` (``H = 2 N + 1``): rail displacement at
        wheel ``j``, harmonic ``q``, per contact force at wheel ``i``, harmonic ``m``.
    stiffness : numpy.ndarray
        Vehicle condensed on its wheels at each harmonic, N/m, ``(n_freq, H, n_w, n_w)``.
    recovery : numpy.ndarray
        Vehicle DOFs per wheel displacement at each harmonic, ``(n_freq, H, n_dof, n_w)``.
    contact_stiffness : float
        k_H, N/m.
    """

    f: NDArray[np.float64]
    passing_hz: float
    orders: NDArray[np.int64]
    receptance: NDArray[np.complex128]
    stiffness: NDArray[np.complex128]
    recovery: NDArray[np.complex128]
    contact_stiffness: float

    @property
    def frequencies(self) -> NDArray[np.float64]:
        """``f + m v / d``, Hz, ``(n_freq, H)``."""
        return self.f[:, None] + self.orders[None, :] * self.passing_hz

    def solve(
        self, excitation: NDArray[np.complex128], static_loads: ArrayLike | None = None
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]]:
        """Vehicle, contact-force and rail harmonics for irregularity harmonics at the wheels.

        Parameters
        ----------
        excitation : numpy.ndarray
            Irregularity at each wheel per harmonic, m, ``(n_freq, H, n_w, n_rhs)``.
        static_loads : array_like, optional
            Static wheel loads ``G`` in N, ``(n_w,)``, acting on harmonic 0 (the parametric
            problem, base frequency 0); None: none.

        Returns
        -------
        vehicle, contact_force, rail : numpy.ndarray
            ``(n_freq, H, n_dof, n_rhs)`` (m, rad), ``(n_freq, H, n_w, n_rhs)`` (N),
            ``(n_freq, H, n_w, n_rhs)`` (m).
        """
        n_f, h, n_w = self.stiffness.shape[:3]
        size = h * n_w
        rec = self.receptance.reshape(n_f, size, h, n_w)
        k_h = self.contact_stiffness
        # (R + I / k_H) S: R S per harmonic column block (batched products written straight
        # into the system's layout), then S / k_H on the diagonal blocks and the identity
        system = np.empty((n_f, size, size), dtype=np.complex128)
        columns = system.reshape(n_f, size, h, n_w).transpose(0, 2, 1, 3)  # (n_f, H, size, n_w)
        np.matmul(rec.transpose(0, 2, 1, 3), self.stiffness, out=columns)
        blocks = system.reshape(n_f, h, n_w, h, n_w)
        for c in range(h):
            blocks[:, c, :, c, :] += self.stiffness[:, c] / k_h
        system.reshape(n_f, size * size)[:, :: size + 1] += 1.0  # the diagonal, a strided view
        rhs = excitation.reshape(n_f, size, -1).astype(np.complex128)
        centre = h // 2
        g = None
        if static_loads is not None:
            g = np.asarray(static_loads, dtype=float)
            lift = rec[:, :, centre, :] @ g  # (R + I / k_H)[:, 0] G
            lift[:, centre * n_w : (centre + 1) * n_w] += g / k_h
            rhs = rhs + lift[..., None]
        u_w = np.linalg.solve(system, rhs).reshape(n_f, h, n_w, -1)
        force = -np.matmul(self.stiffness, u_w)
        if g is not None:
            force[:, centre] += g[None, :, None]
        rail = np.matmul(rec.reshape(n_f, size, size), force.reshape(n_f, size, -1))
        vehicle = np.matmul(self.recovery, u_w)
        return vehicle, force, rail.reshape(force.shape)


@dataclass(frozen=True, eq=False)
class LoadReceptances:
    """Moving-load receptances between the wheels at distinct load frequencies.

    Attributes
    ----------
    f : numpy.ndarray
        Sorted distinct load frequencies ``|F|`` (rounded to 1e-9 Hz), Hz, ``(n_load,)``.
    r : numpy.ndarray
        Distinct wheel gaps ``x_j - x_i``, m, ``(n_r,)``.
    amplitudes : numpy.ndarray
        ``A_n(F, r)``, m/N, ``(n_load, n_r, 2 N + 1)`` (:mod:`railvib.track.moving`).
    """

    f: NDArray[np.float64]
    r: NDArray[np.float64]
    amplitudes: NDArray[np.complex128]

    def signed(self, freqs: ArrayLike) -> NDArray[np.complex128]:
        """``A_n(F, r)`` at signed load frequencies, m/N, ``(n, n_r, 2 N + 1)``.

        ``A_n(-F) = conj A_{-n}(F)`` (a real system).

        Parameters
        ----------
        freqs : array_like
            Load frequencies, Hz, ``(n,)`` (any sign); each ``|F|`` must be in :attr:`f`.

        Returns
        -------
        numpy.ndarray
        """
        freqs = np.asarray(freqs, dtype=float)
        mag = np.round(np.abs(freqs), 9)
        idx = np.minimum(np.searchsorted(self.f, mag), self.f.size - 1)
        if not np.array_equal(self.f[idx], mag):
            raise ValueError("load frequencies outside the table (a programming error)")
        amp = np.asarray(self.amplitudes[idx], dtype=np.complex128)  # a copy
        negative = freqs < 0.0
        amp[negative] = np.conj(amp[negative][:, :, ::-1])
        return amp


def load_receptances(
    system: CoupledSystem, f: ArrayLike, settings: MovingSettings
) -> LoadReceptances:
    """The moving-load receptances the harmonic balance needs at base frequencies `f`.

    One call of :func:`~railvib.track.moving.moving_load_receptance` on the sorted,
    distinct ``|f + m v / d|`` (``|m| <= N``) of the whole grid, between every pair of
    wheels: on a uniform grid whose spacing divides ``v / d`` most of them coincide.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle (wheel positions, m), track and speed (m/s).
    f : array_like
        Base frequencies, Hz (any sign).
    settings : MovingSettings
        Harmonic order and tolerance.

    Returns
    -------
    LoadReceptances
    """
    f = np.atleast_1d(np.asarray(f, dtype=float))
    n = settings.harmonic_order
    passing = system.speed / system.track.sleeper_spacing
    freqs = f[:, None] + np.arange(-n, n + 1)[None, :] * passing
    mag = np.unique(np.round(np.abs(freqs), 9))
    r = _wheel_gaps(system)[0]
    res = interpolated_receptance(
        system.track,
        mag,
        system.speed,
        order=n,
        r=r,
        tolerance=settings.tolerance,
        quadrature_tolerance=QUADRATURE_TOLERANCE,
        interpolation_tolerance=INTERPOLATION_TOLERANCE,
    )
    return LoadReceptances(mag, r, np.asarray(res.amplitudes, dtype=np.complex128))


def _wheel_gaps(system: CoupledSystem) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """Distinct gaps ``r_ji = x_j - x_i`` (m) and each pair's index ``(n_w[j], n_w[i])``."""
    x = system.wheel_positions
    r, pair = np.unique(np.round(x[:, None] - x[None, :], 9), return_inverse=True)
    return r, pair.reshape(x.size, x.size)


def _block_layout(
    n: int, pair: NDArray[np.intp], n_r: int, phi: NDArray[np.float64]
) -> tuple[NDArray[np.intp], NDArray[np.complex128]]:
    """Where each entry of ``R`` is in a frequency's table row, and its phase factor.

    Parameters
    ----------
    n : int
        Harmonic order N.
    pair : numpy.ndarray
        Gap index of each wheel pair, ``(n_w[j], n_w[i])``.
    n_r : int
        Number of distinct gaps.
    phi : numpy.ndarray
        Sleeper-period phase of each wheel at ``t = 0``, ``2 pi x_i / d``, rad, ``(n_w,)``.

    Returns
    -------
    index : numpy.ndarray
        ``R[q, j, m, i]``'s flat position in the row ``A[m, r_ji, q - m + N]`` of shape
        ``(2 N + 1, n_r, 2 N + 1)``, ``((2 N + 1) n_w)**2`` flattened (any valid entry
        outside the band ``|q - m| <= N``).
    phase : numpy.ndarray
        ``exp(i (q - m) phi_i)`` inside the band, 0 outside, flattened as `index`.
    """
    h, n_w = 2 * n + 1, phi.size
    q, j, m, i = np.meshgrid(
        np.arange(h), np.arange(n_w), np.arange(h), np.arange(n_w), indexing="ij"
    )
    k = q - m + n
    band = np.abs(q - m) <= n
    k = np.where(band, k, 0)
    index = (m * n_r + pair[j, i]) * h + k
    phase = np.where(band, np.exp(1j * ((k - n) * phi[i])), 0.0)
    return index.ravel(), phase.ravel()


def harmonic_blocks(
    system: CoupledSystem,
    f: ArrayLike,
    settings: MovingSettings,
    receptances: LoadReceptances | None = None,
) -> HarmonicSystem:
    """The harmonic-balance blocks at base frequencies `f` (Hz).

    Takes the moving-load receptance at every ``|f + m v / d|`` between every pair of
    wheels from `receptances` (computed here when not given), and the vehicle's condensed
    stiffness there.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact stiffness (N/m), leading wheel position (m) and speed (m/s).
    f : array_like
        Base frequencies, Hz, ``(n_freq,)`` (any sign).
    settings : MovingSettings
        Harmonic order and tolerance.
    receptances : LoadReceptances, optional
        From :func:`load_receptances` for these (or more) base frequencies: one table for a
        whole grid solved in blocks.

    Returns
    -------
    HarmonicSystem
    """
    f = np.atleast_1d(np.asarray(f, dtype=float))
    track: PeriodicTrack = system.track
    n = settings.harmonic_order
    orders = np.arange(-n, n + 1)
    h = orders.size
    passing = system.speed / track.sleeper_spacing
    freqs = f[:, None] + orders[None, :] * passing  # (n_f, H) signed load frequencies
    x = system.wheel_positions
    n_w = x.size
    r, pair = _wheel_gaps(system)
    if receptances is None:
        receptances = load_receptances(system, f, settings)
    amp = receptances.signed(freqs.ravel()).reshape(f.size, h, r.size, h)  # [k, m, r, n + N]
    index, phase = _block_layout(n, pair, r.size, 2.0 * np.pi * x / track.sleeper_spacing)
    # R at once in its layout: one gather along each frequency's table row, then the phases
    # (np.take: a C-ordered result; amp[:, index] would be Fortran-ordered, slowing solve)
    rec = np.take(amp.reshape(f.size, -1), index, axis=1)
    rec *= phase
    cond = system.vehicle.condensed_to_wheels(np.abs(freqs.ravel()))
    negative = freqs.ravel() < 0.0
    stiffness, recovery = np.array(cond.stiffness), np.array(cond.recovery)
    stiffness[negative] = np.conj(stiffness[negative])
    recovery[negative] = np.conj(recovery[negative])
    n_dof = recovery.shape[1]
    return HarmonicSystem(
        f,
        passing,
        orders,
        rec.reshape(f.size, h, n_w, h, n_w),
        stiffness.reshape(f.size, h, n_w, n_w),
        recovery.reshape(f.size, h, n_dof, n_w),
        system.contact_stiffness,
    )
