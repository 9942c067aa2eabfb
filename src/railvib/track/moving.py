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

(``G_n`` the Timoshenko rail's free-beam Green's function where the rail has a shear
stiffness, :func:`~railvib.track.moving_kernel.timoshenko_lattice_sum`)

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

from railvib.errors import CaseError, NonFiniteResult, SolverWarning
from railvib.track.moving_kernel import NODES, compiled_available, panel_rules
from railvib.track.periodic import VANISHING_LOSS_FACTOR, PeriodicTrack
from railvib.track.slab import SlabTrack
from railvib.track.timoshenko import wavenumbers

__all__ = [
    "COMPILED_MIN_FREQUENCIES",
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

#: width of the starting panels of the wavenumber quadrature, at most, in units of pi/d
#: (each frequency then bisects its own panels where its integrand needs it; 1 instead
#: of 4 costs 30 % more nodes for the same accuracy, 8 misses features: 8e-6 errors)
_PANEL = 4.0

#: a panel is bisected while its Gauss-Kronrod error estimate exceeds this fraction of the
#: largest harmonic at its frequency (against a 1000 times tighter tolerance the harmonics
#: change by < 2e-6 of the largest, measured on the paper's, a damped rigid-base and
#: Nordborg's track from 0 to 2 kHz)
_PANEL_TOLERANCE = 1e-6

#: most bisections of a starting panel (width 4 pi/d / 2^30 = 3.7e-9 pi/d): enough for
#: the pinned-pinned cusps of an undamped rail; a support without loss has undamped
#: waves at every frequency, whose poles the refinement cannot reach (SolverWarning)
_MAX_LEVELS = 30

#: the remaining error estimate, relative to the largest harmonic, above which a
#: SolverWarning names the frequencies
_WARN_ERROR = 1e-4

#: the integral is carried to this multiple of the core half-width (geometric panels):
#: the integrand falls as k^-4 there, so the tail left out is < 1e-8 of the result; on a
#: Timoshenko rail as 1 / (kappa G A k^2) (shear), hence the longer tail: < 1e-7
_TAIL_FACTOR = 40.0
_TAIL_FACTOR_TIMOSHENKO = 4000.0
_TAIL_RATIO = 4.0

#: frequencies integrated together (each refines its own panels; the batch bounds memory)
_BATCH = 256

#: frequencies from which ``compiled=None`` runs the numba kernel where it is installed
#: (loading it from numba's cache costs 0.3-1 s; it saves ~40 ms a frequency)
COMPILED_MIN_FREQUENCIES = 64


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
    compiled: bool | None = None,
    quadrature_tolerance: float | None = None,
) -> MovingLoadResponse:
    """Rail response to a unit harmonic point load moving at constant speed.

    The load ``exp(i 2 pi f t)`` (N) is at ``x = v t``, on a sleeper at ``t = 0``; the
    response at ``x = v t + r`` is ``exp(i 2 pi f t) sum_n A_n exp(i 2 pi n v t / d)``.
    ``f = 0`` is the constant load: its harmonics ``n != 0`` are the parametric
    (sleeper-passing) lines at ``n v / d``.

    Parameters
    ----------
    track : PeriodicTrack
        Rigid-base or ballasted periodic track, Euler-Bernoulli or Timoshenko rail.
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
    compiled : bool, optional
        Run the wavenumber integral on the numba kernel (True; numba must be installed)
        or on NumPy (False). Default: numba where it is installed, ``RAILVIB_COMPILED`` is
        not ``0`` and there are at least :data:`COMPILED_MIN_FREQUENCIES` frequencies. Both
        give the same harmonics to rounding (the refinement they choose is the same).
    quadrature_tolerance : float, optional
        Gauss-Kronrod error estimate a wavenumber panel may keep, relative to the largest
        harmonic at its frequency (dimensionless, 1e-12 .. 1e-3; default
        :data:`_PANEL_TOLERANCE` = 1e-6). The harmonics' error is about this size; a looser
        one costs fewer nodes (1e-5: about 30 % fewer).

    Returns
    -------
    MovingLoadResponse

    Raises
    ------
    CaseError
        ``moving.speed_m_per_s`` outside its bound, ``moving.harmonic_order`` out of
        range or too low for the speed and band (naming the order needed),
        ``moving.r_m`` or ``frequency`` not finite, ``moving.quadrature_tolerance`` out of
        range, ``moving.compiled`` True without numba, ``track.model`` a slab track.

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
    compiled, quadrature_tolerance = _checked_method(f_arr.size, compiled, quadrature_tolerance)
    amplitudes = _harmonics(
        track, f_arr, v, n_orders, r_arr, (bool(compiled), float(quadrature_tolerance))
    )
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
    if isinstance(track, SlabTrack):
        raise CaseError(
            "track.model",
            type(track).__name__,
            "rigid_base or ballasted: the moving-load formulation needs each rail seat on its "
            "own support, and a slab couples them",
        )
    f_arr = np.atleast_1d(np.asarray(f, dtype=float))
    if f_arr.ndim != 1 or not np.all(np.isfinite(f_arr) & (f_arr >= 0)):
        raise CaseError("frequency", "negative or non-finite values", "finite and >= 0 (Hz)")
    if f_arr.size == 0:
        raise CaseError("frequency", "none", "at least one frequency (Hz)")
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

    `amplitudes` holds :data:`_EXTRA` harmonics more on each side than `order`
    (:func:`check_harmonic_sizes` on their sizes).
    """
    check_harmonic_sizes(f, v, np.abs(amplitudes).max(axis=1), order, tolerance)


def check_harmonic_sizes(
    f: NDArray[np.float64],
    v: float,
    size: NDArray[np.float64],
    order: int,
    tolerance: float,
) -> None:
    """Refuse an order that leaves out harmonics above `tolerance` of the largest one.

    `size` is ``max_r |A_n(f, r)|`` (m/N, ``(n_freq, n_harm)``) of :data:`_EXTRA` harmonics
    more on each side than `order`, at the frequencies `f` (Hz) and speed `v` (m/s). The
    order needed is the lowest whose left-out harmonics are within the tolerance,
    extrapolated beyond those computed as a power law ``|A_n| ~ n^-p`` (the receptance
    over load position has a kink in its third derivative at the sleepers, so ``p`` tends
    to 4).
    """
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
    method: tuple[bool, float],
) -> NDArray[np.complex128]:
    """``A_n(Omega, r)`` by the adaptive wavenumber integral, m/N, ``(n_freq, n_obs, n_harm)``.

    Warns (:func:`warn_unresolved`) where the quadrature could not reach its tolerance.
    """
    out, left = integrated_harmonics(track, f, v, orders, r, method)
    warn_unresolved(f, left, stacklevel=4)
    return out


def integrated_harmonics(
    track: PeriodicTrack,
    f: NDArray[np.float64],
    v: float,
    orders: NDArray[np.int64],
    r: NDArray[np.float64],
    method: tuple[bool, float],
) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """``A_n(Omega, r)`` and the quadrature error estimate each frequency kept.

    Parameters
    ----------
    track : PeriodicTrack
        Rigid-base or ballasted periodic track.
    f : numpy.ndarray
        Load frequencies, Hz, ``(n_freq,)``.
    v : float
        Load speed, m/s.
    orders : numpy.ndarray
        Harmonic orders ``n``, ``(n_harm,)``.
    r : numpy.ndarray
        Observation points ahead of the load, m, ``(n_obs,)``.
    method : tuple
        ``(compiled, quadrature_tolerance)`` (bool, dimensionless).

    Returns
    -------
    amplitudes : numpy.ndarray
        m/N, ``(n_freq, n_obs, n_harm)``.
    left : numpy.ndarray
        The error estimate left, relative to the largest harmonic (dimensionless),
        ``(n_freq,)``.
    """
    out = np.empty((f.size, r.size, orders.size), dtype=np.complex128)
    left = np.zeros(f.size)
    ascending = np.argsort(f, kind="stable")
    for start in range(0, f.size, _BATCH):  # bounds the memory of the panel lists
        batch = ascending[start : start + _BATCH]
        # the core of the panels reaches 4 bending wavenumbers at the batch's top frequency
        panels = _starting_panels(track, float(f[batch[-1]]), int(np.abs(orders).max()))
        out[batch], left[batch] = _integrate(track, f[batch], v, orders, r, panels, method)
    return out, left


def warn_unresolved(f: NDArray[np.float64], left: NDArray[np.float64], stacklevel: int) -> None:
    """One SolverWarning naming the frequencies whose quadrature kept a large error.

    Parameters
    ----------
    f : numpy.ndarray
        Load frequencies integrated, Hz, ``(n_freq,)``.
    left : numpy.ndarray
        Their error estimates left, relative to the largest harmonic (dimensionless).
    stacklevel : int
        Passed to :func:`warnings.warn` (a count of frames).
    """
    if np.any(left > _WARN_ERROR):
        bad = left > _WARN_ERROR
        warnings.warn(
            f"{int(bad.sum())} moving-load frequencies (first {np.sort(f[bad])[0]:.6g} Hz) kept a "
            f"quadrature error estimate up to {left.max():.1e} of the largest harmonic: an "
            "undamped wave travels with the load there (at the split pinned-pinned peaks "
            "f_pp +- v/(2d) of an undamped rail, or anywhere on a support without loss) and "
            f"the response is that of a rail loss factor of {VANISHING_LOSS_FACTOR:g}. Set "
            "track.rail.loss_factor (e.g. 0.01) or damp the support, or move the grid point.",
            SolverWarning,
            stacklevel=stacklevel,
        )


def _checked_method(
    n_freq: int, compiled: bool | None, quadrature_tolerance: float | None
) -> tuple[bool, float]:
    """The quadrature's kernel and tolerance, defaults filled in and checked.

    Parameters
    ----------
    n_freq : int
        Number of load frequencies (a count): the compiled kernel is the default from
        :data:`COMPILED_MIN_FREQUENCIES` on, where numba is available.
    compiled : bool or None
        The caller's choice of kernel; None: the default.
    quadrature_tolerance : float or None
        The panels' relative tolerance (-); None: the default.

    Returns
    -------
    tuple of (bool, float)
        Whether the compiled kernel runs, and the tolerance.

    Raises
    ------
    CaseError
        ``moving.compiled`` True without numba; ``moving.quadrature_tolerance`` outside
        1e-12 .. 1e-3.
    """
    if compiled is None:
        compiled = n_freq >= COMPILED_MIN_FREQUENCIES and compiled_available()
    elif compiled and not compiled_available():
        raise CaseError(
            "moving.compiled", compiled, "False where numba is not installed or RAILVIB_COMPILED=0"
        )
    if quadrature_tolerance is None:
        quadrature_tolerance = _PANEL_TOLERANCE
    if not (np.isfinite(quadrature_tolerance) and 1e-12 <= quadrature_tolerance <= 1e-3):
        raise CaseError(
            "moving.quadrature_tolerance", quadrature_tolerance, "between 1e-12 and 1e-3 (-)"
        )
    return bool(compiled), float(quadrature_tolerance)


def _require_finite(
    rule: NDArray[np.complex128], error: NDArray[np.float64], f_panel: NDArray[np.float64]
) -> None:
    """Refuse NaN or infinite panel rules before they are bisected.

    A non-finite rule makes every panel's error test fail, so without this check each of
    its panels would be halved at all :data:`_MAX_LEVELS` levels (``2^30``-fold growth of
    the work and memory) instead of stopping.

    Parameters
    ----------
    rule, error : ndarray
        The panels' rules ``(n_panel, n_out)`` and their error estimates ``(n_panel,)``.
    f_panel : ndarray
        The load frequency of each panel, Hz.

    Raises
    ------
    NonFiniteResult
        Naming how many load frequencies are affected and the first of them.
    """
    bad = ~(np.isfinite(rule).all(axis=1) & np.isfinite(error))
    if np.any(bad):
        hit = np.unique(f_panel[bad])
        raise NonFiniteResult(
            f"moving-load receptance: the wavenumber integrand is NaN or infinite at "
            f"{hit.size} load frequencies (first {hit[0]:.6g} Hz): the track's values are "
            "beyond what the solver resolves in floating point"
        )


def _integrate(
    track: PeriodicTrack,
    f: NDArray[np.float64],
    v: float,
    orders: NDArray[np.int64],
    r: NDArray[np.float64],
    panels: tuple[NDArray[np.float64], NDArray[np.float64]],
    method: tuple[bool, float],
) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """Adaptive Gauss-Kronrod integral, each frequency refining its own panels.

    Every frequency starts from the shared `panels` ``(a, b)``; each panel is integrated
    by the 15-point Kronrod rule (Filon's rule on its nodes where ``r != 0``: the
    oscillating ``exp(i k r)`` integrated exactly) with the embedded 7-point Gauss rule on
    the ``r = 0`` integrand as its error estimate
    (:func:`~railvib.track.moving_kernel.panel_rules`, compiled or not: ``method =
    (compiled, tolerance)``), and a panel whose estimate exceeds `tolerance` of the largest
    harmonic at its own frequency is bisected, up to :data:`_MAX_LEVELS` times: every
    observation point costs the nodes of ``r = 0``. Returns the harmonics and the error
    estimate left (relative, per frequency).
    """
    compiled, tolerance = method
    rail = track.rail
    d = track.sleeper_spacing
    constants: tuple[float, ...] = (
        rail.bending_stiffness,
        rail.mass_per_length,
        max(rail.loss_factor, VANISHING_LOSS_FACTOR),
        d,
    )
    if rail.shear_stiffness is not None:
        constants += (rail.shear_stiffness, rail.rotary_inertia)
    shift = np.asarray(2.0 * np.pi * orders / d, dtype=np.float64)
    n_f, n_out = f.size, r.size * orders.size
    which = np.repeat(np.arange(n_f), panels[0].size)  # the frequency of each panel
    a, b = np.tile(panels[0], n_f), np.tile(panels[1], n_f)
    omega_load = 2.0 * np.pi * f
    total = np.zeros((n_f, n_out), dtype=np.complex128)
    left = np.zeros(n_f)
    scale = None
    for level in range(_MAX_LEVELS + 1):
        mid, half = 0.5 * (a + b), 0.5 * (b - a)
        omega = omega_load[which][:, None] - (mid[:, None] + half[:, None] * NODES) * v
        rule, error = panel_rules(
            mid,
            half,
            omega_load[which],
            _support(track, omega),
            v,
            constants,
            shift,
            r,
            compiled=compiled,
        )
        rule = rule.reshape(mid.size, n_out)
        _require_finite(rule, error, f[which])
        if scale is None:  # the largest harmonic per frequency, from the starting panels
            scale = np.maximum(np.abs(_sum_by(which, rule, n_f)).max(axis=1), np.finfo(float).tiny)
        relative = error / scale[which]
        done = relative <= tolerance
        if level == _MAX_LEVELS:
            left = _sum_by(which[~done], relative[~done, None], n_f)[:, 0].real
            done[:] = True
        total += _sum_by(which[done], rule[done], n_f)
        if np.all(done):
            break
        # bisect the others, each half next to the other: `which` stays sorted
        which, a, b = np.repeat(which[~done], 2), a[~done], b[~done]
        centre = 0.5 * (a + b)
        a = np.stack([a, centre], axis=1).ravel()
        b = np.stack([centre, b], axis=1).ravel()
    phase_n = np.exp(1j * np.outer(r, shift)).ravel()  # (n_obs * n_harm,)
    result = total * phase_n / (2.0 * np.pi)
    return result.reshape(n_f, r.size, orders.size), left


def _sum_by(
    which: NDArray[np.int64], values: NDArray[np.complex128], n: int
) -> NDArray[np.complex128]:
    """Sum the rows of `values` ``(n_rows, n_col)`` into `n` groups by sorted `which`."""
    out = np.zeros((n, values.shape[1]), dtype=np.complex128)
    if which.size:
        starts = np.flatnonzero(np.concatenate([[True], which[1:] != which[:-1]]))
        out[which[starts]] = np.add.reduceat(values, starts, axis=0)
    return out


def _support(track: PeriodicTrack, omega: NDArray[np.float64]) -> NDArray[np.complex128]:
    """``K(omega)`` at signed fixed-frame frequencies: ``K(-omega) = conj K(omega)``."""
    f_abs = np.abs(omega).ravel() / (2.0 * np.pi)
    np.maximum(f_abs, 1e-9, out=f_abs)  # a real system at f -> 0
    k = np.array(track.support_stiffness(f_abs), dtype=np.complex128).reshape(omega.shape)
    k.imag[omega < 0.0] *= -1.0
    return k


def _starting_panels(
    track: PeriodicTrack, f_max: float, order: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Starting panels ``[a, b]`` of the wavenumber integral, rad/m, shared by all frequencies.

    At most ``4 pi/d`` wide over the core ``|k| <= k_core``, which covers the harmonic shifts
    ``2 pi (N + 1) / d`` and four free bending wavenumbers at `f_max`, then growing
    geometrically (ratio 4) to at least ``40 k_core`` (the integrand falls as ``k^-4``;
    ``4000 k_core`` on a Timoshenko rail, where it falls as ``k^-2``).
    """
    d = track.sleeper_spacing
    unit = np.pi / d
    rail = track.rail
    k_bend = (rail.mass_per_length * (2.0 * np.pi * f_max) ** 2 / rail.bending_stiffness) ** 0.25
    tail_factor = _TAIL_FACTOR
    if rail.shear_stiffness is not None:
        tail_factor = _TAIL_FACTOR_TIMOSHENKO
    if rail.shear_stiffness is not None and f_max > 0.0:  # shear: a softer rail, larger k
        omega2 = (2.0 * np.pi * f_max) ** 2
        beta4 = np.array([rail.mass_per_length * omega2 * d**4 / rail.bending_stiffness + 0j])
        rho_eps = np.array([rail.rotary_inertia * omega2 / rail.shear_stiffness + 0j])
        eps = rail.bending_stiffness / (rail.shear_stiffness * d**2)
        rho = np.asarray(rho_eps / eps, dtype=np.complex128)
        a2 = wavenumbers(beta4, eps, rho, rho_eps)[0]
        k_bend = max(k_bend, float(np.abs(np.sqrt(a2[0]))) / d)
    n_units = 2 * (order + 1) + int(np.ceil(4.0 * k_bend / unit)) + 1
    n_panels = int(np.ceil(n_units / _PANEL))
    k_core = n_units * unit
    core = np.linspace(-k_core, k_core, 2 * n_panels + 1)
    n_tail = int(np.ceil(np.log(tail_factor) / np.log(_TAIL_RATIO)))
    tail = k_core * _TAIL_RATIO ** np.arange(1, 1 + n_tail)
    edges = np.concatenate([-tail[::-1], core, tail])
    return edges[:-1], edges[1:]
