"""The rail under a harmonic point load moving at constant speed along the periodic track.

A load ``F exp(i Omega t)`` at ``x = v t`` on a rail on discrete supports at ``x = j d``
gives, in steady state, a rail response that is periodic in the moving frame with the
sleeper-passing period ``d / v``::

    u(v t + r, t) = F exp(i Omega t) sum_n A_n(Omega, r) exp(i n Omega_s t),
    Omega_s = 2 pi v / d,

so harmonic ``n`` is heard at ``Omega + n Omega_s`` by an observer moving with the load
(``r`` is the distance ahead of the load). The amplitudes follow from the wavenumber
integral of the periodic track's travelling-wave response (Floquet coupling ``k -> k +
2 pi n / d``), at the Doppler-shifted frequency ``omega = Omega - k v`` of the fixed
frame::

    A_n = (1 / 2 pi) int dk exp(i k_n r) G_n (delta_n0 - K w_0 / d),
    k_n = k + 2 pi n / d,   G_n = 1 / (EI* k_n^4 - m omega^2),
    w_0 = G_0 / (1 + K S / d),   S = sum_m G_m (closed form),

with ``K = K(omega)`` the support the rail sees at each seat
(:meth:`~railvib.track.periodic.PeriodicTrack.support_stiffness`: the pad on a rigid base, or
the pad-sleeper-ballast chain of :class:`~railvib.track.ballasted.BallastedTrack`). The
derivation, the quadrature and the checks are in ``docs/moving-load.md``. Time dependence
``exp(+i omega t)``; displacements and forces positive downward.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError, SolverWarning
from railvib.track.periodic import VANISHING_LOSS_FACTOR, PeriodicTrack

__all__ = [
    "MAX_HARMONIC_ORDER",
    "SPEED_FRACTION",
    "MovingLoadResponse",
    "critical_speed",
    "moving_load_receptance",
]

#: the speed bound as a fraction of the track's critical speed (:func:`critical_speed`):
#: trains run at under 0.3 of it on ballasted track; towards it the load sheds waves whose
#: group velocity is its own speed, the steady state is reached ever more slowly and the
#: wavenumber refinement grows without bound
SPEED_FRACTION = 0.5

#: most harmonics either side of the load frequency (the cost grows about linearly with
#: the order: benchmarks/bench_moving.py)
MAX_HARMONIC_ORDER = 50

#: harmonics computed beyond the order asked for, to estimate what it leaves out
_EXTRA = 2

#: width of the starting panels of the wavenumber quadrature, in units of pi/d
_PANEL = 1.0 / 20.0

#: a panel is bisected while its Gauss-Kronrod error estimate exceeds this fraction of the
#: largest harmonic at any frequency of the batch (the estimate |K15 - G7| is far above
#: the error of K15 for a smooth integrand: measured totals ~1e-6 of |A_0|)
_PANEL_TOLERANCE = 1e-7

#: most bisections of a starting panel (width pi/d / 20 / 2^24 = 1.6e-8 pi/d): enough for
#: the pinned-pinned cusps of an undamped rail; a support without loss has undamped
#: waves at every frequency, whose poles the refinement cannot reach (SolverWarning)
_MAX_LEVELS = 24

#: the remaining error estimate, relative to the largest harmonic, above which a
#: SolverWarning names the frequencies
_WARN_ERROR = 1e-4

#: the integral is carried to this multiple of the core half-width (geometric panels):
#: the integrand falls as k^-4 there, so the tail left out is < 1e-8 of the result
_TAIL_FACTOR = 40.0
_TAIL_RATIO = 1.2

#: frequencies integrated together (they share the refined panels)
_BATCH = 16

#: Gauss-Kronrod 7-15 nodes on [0, 1] of the half panel and weights (QUADPACK qk15)
_XGK = np.array(
    [
        0.991455371120812639206854697526329,
        0.949107912342758524526189684047851,
        0.864864423359769072789712788640926,
        0.741531185599394439863864773280788,
        0.586087235467691130294144845693013,
        0.405845151377397166906606412076961,
        0.207784955007898467600689403773245,
        0.0,
    ]
)
_WGK = np.array(
    [
        0.022935322010529224963732008058970,
        0.063092092629978553290700663189204,
        0.104790010322250183839876322541518,
        0.140653259715525918745189590510238,
        0.169004726639267902826583426598550,
        0.190350578064785409913256402421014,
        0.204432940075298892414161999234649,
        0.209482141084727828012999174891714,
    ]
)
#: the embedded 7-point Gauss weights at the same nodes (0 at the Kronrod-only ones)
_WG = np.array(
    [
        0.0,
        0.129484966168869693270611432679082,
        0.0,
        0.279705391489276667901467771423780,
        0.0,
        0.381830050505118944950369775488975,
        0.0,
        0.417959183673469387755102040816327,
    ]
)
#: the 15 nodes on [-1, 1] and their Kronrod and Gauss weights
_NODES = np.concatenate([-_XGK[:-1], _XGK[::-1]])
_KRONROD = np.concatenate([_WGK[:-1], _WGK[::-1]])
_GAUSS = np.concatenate([_WG[:-1], _WG[::-1]])


@dataclass(frozen=True)
class MovingLoadResponse:
    """Harmonics of the rail response to a moving harmonic point load.

    Attributes
    ----------
    f : numpy.ndarray
        Load frequencies ``Omega / 2 pi``, Hz, ``(n_freq,)``.
    speed : float
        Load speed v, m/s.
    sleeper_spacing : float
        d, m.
    r : numpy.ndarray
        Distances of the observation points ahead of the load, m, ``(n_obs,)``.
    orders : numpy.ndarray
        Harmonic orders ``-N .. N``, ``(2 N + 1,)``.
    amplitudes : numpy.ndarray
        ``A_n(Omega, r)``, complex, m/N, ``(n_freq, n_obs, 2 N + 1)``.
    """

    f: NDArray[np.float64]
    speed: float
    sleeper_spacing: float
    r: NDArray[np.float64]
    orders: NDArray[np.int64]
    amplitudes: NDArray[np.complex128]

    @property
    def sleeper_passing_frequency_hz(self) -> float:
        """``v / d``, Hz."""
        return self.speed / self.sleeper_spacing

    @property
    def response_frequencies_hz(self) -> NDArray[np.float64]:
        """Frequency of each harmonic in the moving frame, ``f + n v / d``, Hz, ``(n_freq, 2N+1)``.

        Returns
        -------
        numpy.ndarray
            Hz.
        """
        return self.f[:, None] + self.orders[None, :] * self.sleeper_passing_frequency_hz

    @property
    def mean(self) -> NDArray[np.complex128]:
        """``A_0``: the receptance at the load frequency, m/N, ``(n_freq, n_obs)``."""
        return self.amplitudes[:, :, self.orders.size // 2]

    @property
    def tail(self) -> NDArray[np.float64]:
        """``max(|A_N|, |A_-N|) / max_n |A_n|`` per frequency (dimensionless), ``(n_freq,)``.

        The size of the outermost harmonics kept, relative to the largest: an estimate of
        what the harmonics left out carry.
        """
        size = np.abs(self.amplitudes).max(axis=1)  # (n_freq, n_harm)
        edge = np.maximum(size[:, 0], size[:, -1])
        return np.asarray(edge / np.maximum(size.max(axis=1), np.finfo(float).tiny))


def critical_speed(track: PeriodicTrack) -> float:
    """Critical speed of the track, m/s: ``(4 EI s / m^2)^(1/4)``, ``s = Re K(f_0) / d``.

    The lowest phase speed of bending waves on the rail smeared onto a Winkler foundation
    of the supports' stiffness per length, ``s``, at ``f_0 = 1 Hz`` (quasi-static). Below
    it, a load moving at constant speed radiates no free bending wave of its own.

    Parameters
    ----------
    track : PeriodicTrack
        Any periodic track (rigid base or ballasted).

    Returns
    -------
    float
        The critical speed, m/s.
    """
    k_static = float(np.real(track.support_stiffness(np.array([1.0]))[0]))
    s = max(k_static, 0.0) / track.sleeper_spacing
    rail = track.rail
    return float((4.0 * rail.bending_stiffness * s / rail.mass_per_length**2) ** 0.25)


def moving_load_receptance(
    track: PeriodicTrack,
    f: ArrayLike,
    speed: float,
    *,
    order: int = 5,
    r: ArrayLike = (0.0,),
    tolerance: float = 1e-2,
) -> MovingLoadResponse:
    """Rail response to a unit harmonic point load moving at constant speed.

    The load ``exp(i 2 pi f t)`` (N) is at ``x = v t``, on a sleeper at ``t = 0``; the
    response at ``x = v t + r`` is ``exp(i 2 pi f t) sum_n A_n exp(i 2 pi n v t / d)``.
    ``f = 0`` is the constant load: its harmonics ``n != 0`` are the parametric
    (sleeper-passing) lines at ``n v / d``.

    Parameters
    ----------
    track : PeriodicTrack
        Rigid-base or ballasted periodic track with an Euler-Bernoulli rail.
    f : array_like
        Load frequencies in Hz (>= 0), ``(n_freq,)``.
    speed : float
        Load speed v in m/s, ``0 < v <= SPEED_FRACTION x critical_speed(track)``.
    order : int
        Highest harmonic order N kept (a count, 0 .. MAX_HARMONIC_ORDER).
    r : array_like
        Distances of the observation points ahead of the load, m (0: under the load).
    tolerance : float
        Largest harmonic left out (``|n| = N + 1, N + 2``, computed to check), relative to
        the largest one, for ``N >= 1`` (dimensionless).

    Returns
    -------
    MovingLoadResponse

    Raises
    ------
    CaseError
        ``track.rail.shear_stiffness`` for a Timoshenko rail (no moving-load formulation
        yet), ``moving.speed_m_per_s`` outside its bound, ``moving.harmonic_order`` out of
        range or too low for the speed and band (naming the order needed),
        ``moving.r_m`` or ``frequency`` not finite.

    Examples
    --------
    >>> from railvib.pads import SpringDamper
    >>> from railvib.track import Rail, PeriodicTrack
    >>> track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    >>> res = moving_load_receptance(track, [100.0, 500.0], 30.0, order=3)
    >>> res.amplitudes.shape
    (2, 1, 7)
    """
    f_arr, v, r_arr = _checked(track, f, speed, order, r, tolerance)
    # two harmonics more than asked for, to measure what the order leaves out
    n_orders = np.arange(-order - _EXTRA, order + _EXTRA + 1)
    amplitudes = _harmonics(track, f_arr, v, n_orders, r_arr)
    if order >= 1:
        _check_order(f_arr, v, amplitudes, order, tolerance)
    kept = amplitudes[:, :, _EXTRA : amplitudes.shape[2] - _EXTRA]
    return MovingLoadResponse(
        f_arr, v, track.sleeper_spacing, r_arr, n_orders[_EXTRA:-_EXTRA], kept
    )


def _checked(
    track: PeriodicTrack,
    f: ArrayLike,
    speed: float,
    order: int,
    r: ArrayLike,
    tolerance: float,
) -> tuple[NDArray[np.float64], float, NDArray[np.float64]]:
    """The inputs, checked before anything is computed."""
    if not isinstance(track, PeriodicTrack):
        raise CaseError("track", type(track).__name__, "a PeriodicTrack (rigid_base or ballasted)")
    if track.rail.is_timoshenko:
        raise CaseError(
            "track.rail.shear_stiffness",
            track.rail.shear_stiffness,
            "omitted (an Euler-Bernoulli rail): the moving-load formulation uses the "
            "Euler rail's free-beam Green's function (N)",
        )
    f_arr = np.atleast_1d(np.asarray(f, dtype=float))
    if f_arr.ndim != 1 or not np.all(np.isfinite(f_arr) & (f_arr >= 0)):
        raise CaseError("frequency", "negative or non-finite values", "finite and >= 0 (Hz)")
    try:
        v = float(speed)
    except (TypeError, ValueError):
        raise CaseError("moving.speed_m_per_s", speed, "a number > 0 (m/s)") from None
    bound = SPEED_FRACTION * critical_speed(track)
    if not (np.isfinite(v) and 0.0 < v <= bound):
        raise CaseError(
            "moving.speed_m_per_s",
            speed,
            f"> 0 and at most {bound:.4g} m/s ({SPEED_FRACTION:g} x this track's critical "
            "speed, railvib.track.moving.critical_speed) (m/s)",
        )
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)):
        raise CaseError("moving.harmonic_order", order, f"an integer 0..{MAX_HARMONIC_ORDER}")
    if not 0 <= order <= MAX_HARMONIC_ORDER:
        raise CaseError("moving.harmonic_order", order, f"an integer 0..{MAX_HARMONIC_ORDER}")
    if not (np.isfinite(tolerance) and 0.0 < tolerance < 1.0):
        raise CaseError("moving.tolerance", tolerance, "between 0 and 1, exclusive (-)")
    r_arr = np.atleast_1d(np.asarray(r, dtype=float))
    if r_arr.ndim != 1 or not np.all(np.isfinite(r_arr)):
        raise CaseError("moving.r_m", r, "finite distances ahead of the load (m)")
    return f_arr, v, r_arr


def _check_order(
    f: NDArray[np.float64],
    v: float,
    amplitudes: NDArray[np.complex128],
    order: int,
    tolerance: float,
) -> None:
    """Refuse an order that leaves out harmonics above `tolerance` of the largest one.

    `amplitudes` holds :data:`_EXTRA` harmonics more on each side than `order`. The order
    needed is the lowest whose left-out harmonics are within the tolerance, extrapolated
    beyond those computed as a power law ``|A_n| ~ n^-p`` (the receptance over load
    position has a kink in its third derivative at the sleepers, so ``p`` tends to 4).
    """
    size = np.abs(amplitudes).max(axis=1)  # (n_freq, n_harm)
    size = size / np.maximum(size.max(axis=1, keepdims=True), np.finfo(float).tiny)
    centre = size.shape[1] // 2
    # the largest harmonic of order |n| >= j, for each j
    beyond = [
        np.maximum(size[:, : centre - j + 1].max(axis=1), size[:, centre + j :].max(axis=1))
        for j in range(1, centre + 1)
    ]
    left_out = beyond[order]  # |n| > order
    worst = int(np.argmax(left_out))
    if left_out[worst] <= tolerance:
        return
    needed = next((j for j in range(order + 1, centre) if beyond[j][worst] <= tolerance), None)
    if needed is None:
        outer, inner = beyond[centre - 1][worst], beyond[centre - 2][worst]
        p = np.log(inner / outer) / np.log(centre / (centre - 1)) if outer < inner else 1.0
        p = max(float(p), 1.0)
        needed = int(np.ceil(centre * (outer / tolerance) ** (1.0 / p)))
    raise CaseError(
        "moving.harmonic_order",
        order,
        f"at least {needed} for v = {v:g} m/s and {float(f.min()):g}-{float(f.max()):g} Hz: "
        f"the harmonics left out reach {left_out[worst]:.2g} of the largest at "
        f"{f[worst]:g} Hz, above the tolerance {tolerance:g}",
    )


def _harmonics(
    track: PeriodicTrack,
    f: NDArray[np.float64],
    v: float,
    orders: NDArray[np.int64],
    r: NDArray[np.float64],
) -> NDArray[np.complex128]:
    """``A_n(Omega, r)`` by the adaptive wavenumber integral, m/N, ``(n_freq, n_obs, n_harm)``."""
    a, b = _starting_panels(track, float(f.max(initial=0.0)), int(np.abs(orders).max()))
    out = np.empty((f.size, r.size, orders.size), dtype=np.complex128)
    left = np.zeros(f.size)
    for start in range(0, f.size, _BATCH):  # batches of frequencies, vectorised inside
        stop = min(start + _BATCH, f.size)
        out[start:stop], left[start:stop] = _integrate(track, f[start:stop], v, orders, r, a, b)
    if np.any(left > _WARN_ERROR):
        bad = left > _WARN_ERROR
        warnings.warn(
            f"{int(bad.sum())} moving-load frequencies (first {f[bad][0]:.6g} Hz) kept a "
            f"quadrature error estimate up to {left.max():.1e} of the largest harmonic: an "
            "undamped wave travels with the load there (at the split pinned-pinned peaks "
            "f_pp +- v/(2d) of an undamped rail, or anywhere on a support without loss) and "
            f"the response is that of a rail loss factor of {VANISHING_LOSS_FACTOR:g}. Set "
            "track.rail.loss_factor (e.g. 0.01) or damp the support, or move the grid point.",
            SolverWarning,
            stacklevel=3,
        )
    return out


def _integrate(
    track: PeriodicTrack,
    f: NDArray[np.float64],
    v: float,
    orders: NDArray[np.int64],
    r: NDArray[np.float64],
    a: NDArray[np.float64],
    b: NDArray[np.float64],
) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """Adaptive Gauss-Kronrod integral over the panels ``[a, b]`` for a batch of frequencies.

    Every panel is integrated by the 15-point Kronrod rule with the embedded 7-point Gauss
    rule as its error estimate; the panels whose estimate exceeds :data:`_PANEL_TOLERANCE`
    of the largest harmonic at any frequency of the batch are bisected, up to
    :data:`_MAX_LEVELS` times. Returns the harmonics and the error estimate left
    (relative, per frequency).
    """
    shift = np.asarray(2.0 * np.pi * orders / track.sleeper_spacing, dtype=np.float64)
    phase_n = np.exp(1j * np.outer(r, shift))  # (n_obs, n_harm)
    total = np.zeros((f.size, r.size, orders.size), dtype=np.complex128)
    scale = None
    for _level in range(_MAX_LEVELS + 1):
        mid, half = 0.5 * (a + b), 0.5 * (b - a)
        k = (mid[:, None] + half[:, None] * _NODES[None, :]).ravel()
        w = _integrand(track, f, v, k, shift)  # (n_f, n_nodes, n_harm)
        w = w.reshape(f.size, a.size, _NODES.size, orders.size)
        phase = np.exp(1j * k[:, None] * r[None, :]).reshape(a.size, _NODES.size, r.size)
        weights = np.stack([_KRONROD, _GAUSS]) * half[:, None, None]  # (n_panel, 2, 15)
        rules = np.einsum("fpqn,pqr,psq->sfprn", w, phase, weights, optimize=True)
        kronrod, gauss = rules[0], rules[1]
        if scale is None:
            size = np.abs(kronrod.sum(axis=1)).max(axis=(1, 2))
            scale = np.maximum(size, np.finfo(float).tiny)  # largest harmonic per frequency
        error = np.abs(kronrod - gauss).max(axis=(2, 3)) / scale[:, None]  # (n_f, n_panel)
        done = error.max(axis=0) <= _PANEL_TOLERANCE
        total += kronrod[:, done].sum(axis=1)
        if np.all(done) or _level == _MAX_LEVELS:
            total += kronrod[:, ~done].sum(axis=1)
            left = error[:, ~done].sum(axis=1)
            break
        a, b = a[~done], b[~done]
        centre = 0.5 * (a + b)
        a = np.asarray(np.concatenate([a, centre]), dtype=np.float64)
        b = np.asarray(np.concatenate([centre, b]), dtype=np.float64)
    return total * phase_n[None, :, :] / (2.0 * np.pi), left


def _integrand(
    track: PeriodicTrack,
    f: NDArray[np.float64],
    v: float,
    k: NDArray[np.float64],
    shift: NDArray[np.float64],
) -> NDArray[np.complex128]:
    """``G_n (delta_n0 - K w_0 / d)`` at wavenumbers `k` (rad/m), m^2/N, ``(n_f, n_k, n_harm)``."""
    d = track.sleeper_spacing
    rail = track.rail
    m = rail.mass_per_length
    ei, eta = rail.bending_stiffness, max(rail.loss_factor, VANISHING_LOSS_FACTOR)
    omega = 2.0 * np.pi * f[:, None] - k[None, :] * v  # the fixed frame's frequency
    sign = np.where(omega < 0.0, -1.0, 1.0)
    ei_c = ei * (1.0 + 1j * eta * sign)  # hysteretic: EI (1 - i eta) at omega < 0
    support = _support(track, omega)
    lattice = _lattice_sum(k[None, :] * d, m * omega**2 * d**4 / ei_c) * d**4 / ei_c
    mass = m * omega**2
    g0 = 1.0 / (ei_c * k[None, :] ** 4 - mass)
    reaction = support * g0 / (d + support * lattice)  # K w_0 / d
    kn = k[None, :, None] + shift[None, None, :]
    gn = 1.0 / (ei_c[..., None] * kn**4 - mass[..., None])
    return gn * ((shift == 0)[None, None, :] - reaction[..., None])


def _support(track: PeriodicTrack, omega: NDArray[np.float64]) -> NDArray[np.complex128]:
    """``K(omega)`` at signed fixed-frame frequencies: ``K(-omega) = conj K(omega)``."""
    f_abs = np.maximum(np.abs(omega) / (2.0 * np.pi), 1e-9)  # a real system at f -> 0
    k = track.support_stiffness(f_abs.ravel()).reshape(omega.shape)
    return np.where(omega < 0.0, np.conj(k), k)


def _lattice_sum(kd: NDArray[np.float64], beta4: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """``sum_m 1 / ((kd + 2 pi m)^4 - beta4)`` in closed form, without cancellation.

    With ``z^4 = beta4``, ``a = sin^2(kd/2)``: the partial fractions of ``1/(x^4 - z^4)``
    and ``sum_m 1/((kd + 2 pi m)^2 - b^2) = sin b / (2 b (cos b - cos kd))`` give
    ``[ -2 a s3 + (sinhc^2(z/2) sinc z + sinc^2(z/2) sinhc z) / 4 ] / (8 D)``, ``s3 = (sinh z
    - sin z) / (2 z^3)``, ``D = (a - sin^2(z/2)) (a + sinh^2(z/2))``. Every term is even in
    ``z`` and in ``i z``, so no fourth root has to be chosen, and ``z -> 0`` loses no digits
    (``s3`` by its series below ``|z| = 1``).
    """
    z = beta4**0.25
    sin_h, sinh_h = np.sin(0.5 * z), np.sinh(0.5 * z)
    small = np.abs(beta4) < 1.0
    zeta = np.where(small, beta4, 0.0)  # the series: sum zeta^k / (4k+3)!, |zeta| < 1
    series = 1.0 / 6.0 + zeta * (1.0 / 5040.0 + zeta * (1.0 / 39916800.0 + zeta / 1.307674368e12))
    cube = np.where(small, 1.0, z * z * z)
    s3 = np.where(small, series, (np.sinh(z) - np.sin(z)) / (2.0 * cube))
    a = np.sin(0.5 * kd) ** 2
    p, q = sin_h * sin_h, sinh_h * sinh_h
    # (q sin z + p sinh z) / z^3 as products of sin x / x and sinh x / x: exact at z = 0
    mixed = 0.25 * (_sinc(1j * 0.5 * z) ** 2 * _sinc(z) + _sinc(0.5 * z) ** 2 * _sinc(1j * z))
    numerator = -2.0 * a * s3 + mixed
    return np.asarray(numerator / (8.0 * (a - p) * (a + q)), dtype=np.complex128)


def _sinc(z: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """``sin z / z`` (1 at 0; no cancellation anywhere); ``_sinc(i z) = sinh z / z``."""
    zero = z == 0
    safe = np.where(zero, 1.0, z)
    return np.asarray(np.where(zero, 1.0, np.sin(safe) / safe), dtype=np.complex128)


def _starting_panels(
    track: PeriodicTrack, f_max: float, order: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Starting panels ``[a, b]`` of the wavenumber integral, rad/m, shared by all frequencies.

    ``pi/d / 20`` wide over the core ``|k| <= k_core``, which covers the harmonic shifts
    ``2 pi (N + 1) / d`` and four free bending wavenumbers at `f_max`, then growing
    geometrically to ``40 k_core`` (the integrand falls as ``k^-4``).
    """
    d = track.sleeper_spacing
    unit = np.pi / d
    rail = track.rail
    k_bend = (rail.mass_per_length * (2.0 * np.pi * f_max) ** 2 / rail.bending_stiffness) ** 0.25
    n_units = 2 * (order + 1) + int(np.ceil(4.0 * k_bend / unit)) + 1
    n_panels = int(np.ceil(n_units / _PANEL))
    k_core = n_units * unit
    core = np.linspace(-k_core, k_core, 2 * n_panels + 1)
    n_tail = int(np.ceil(np.log(_TAIL_FACTOR) / np.log(_TAIL_RATIO)))
    tail = k_core * _TAIL_RATIO ** np.arange(1, 1 + n_tail)
    edges = np.concatenate([-tail[::-1], core, tail])
    return edges[:-1], edges[1:]
