"""The Filon rule of the moving-load kernel at observation points ahead of the load.

``moving_load_receptance`` refines its wavenumber panels on the ``r = 0`` integrand only
and integrates ``exp(i k r)`` against the integrand's polynomial interpolant exactly
(:func:`railvib.track.moving_kernel.filon_weights`). Checked here: the weights themselves
against closed-form integrals; the receptance at the gaps of a vehicle's wheels against
an independent adaptive Gauss-Kronrod quadrature that keeps ``exp(i k r)`` inside the
integrand (the method before the Filon rule, written out below from the public
integrand), and against a brute-force trapezoid rule on a fine mapped grid.
"""

from __future__ import annotations

import numpy as np
import pytest

import railvib.track.moving as moving
import railvib.track.moving_kernel as kernel
from railvib.pads import SpringDamper
from railvib.track import BallastedTrack, PeriodicTrack, Rail
from railvib.track.moving import moving_load_receptance
from railvib.track.periodic import VANISHING_LOSS_FACTOR

#: Nordborg's ballasted track (damped pads and ballast)
NORDBORG = BallastedTrack(
    Rail(4.725e6, 60.0),
    SpringDamper(300e6, 18e3),
    0.6,
    sleeper_mass=150.0,
    ballast=SpringDamper(150e6, 48e3),
)
#: the paper's rigid-base track with an undamped rail (the vanishing loss factor)
PAPER = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
#: the wheel gaps of the paper's metro car (bogie 2.2 m, bogie centres 12.6 m) and 0
GAPS = np.array([0.0, 2.2, -2.2, 10.4, -12.6, 14.8])


def _reference(track, f, speed, order, r, tolerance):
    """``A_n(f, r)`` by adaptive Gauss-Kronrod 7-15 with ``exp(i k r)`` in the integrand.

    Every panel is bisected while ``max |Kronrod - Gauss|`` over harmonics and
    observation points exceeds `tolerance` of the largest harmonic at the frequency (the
    oscillation of the far gaps drives the refinement), from the kernel's starting
    panels; NumPy, one frequency at a time.
    """
    orders = np.arange(-order, order + 1)
    rail = track.rail
    d = track.sleeper_spacing
    constants = (
        rail.bending_stiffness,
        rail.mass_per_length,
        max(rail.loss_factor, VANISHING_LOSS_FACTOR),
        d,
    )
    shift = 2.0 * np.pi * orders / d
    a, b = moving._starting_panels(track, f, order)
    omega_load = 2.0 * np.pi * f
    total = np.zeros((r.size, orders.size), dtype=complex)
    scale = None
    for _ in range(40):
        mid, half = 0.5 * (a + b), 0.5 * (b - a)
        k = mid[:, None] + half[:, None] * kernel.NODES
        omega = omega_load - k * speed
        values = kernel.integrand(k, omega, moving._support(track, omega), constants, shift)
        phase = np.exp(1j * k[:, :, None] * r)  # (panel, node, obs)
        kron = np.einsum("pqn,pqo,q,p->pon", values, phase, kernel._KRONROD, half)
        gauss = np.einsum("pqn,pqo,q,p->pon", values, phase, kernel._GAUSS, half)
        if scale is None:
            scale = np.abs(kron.sum(axis=0)).max()
        done = np.abs(kron - gauss).max(axis=(1, 2)) <= tolerance * scale
        total += kron[done].sum(axis=0)
        if np.all(done):
            break
        a, b = a[~done], b[~done]
        c = 0.5 * (a + b)
        a, b = np.concatenate([a, c]), np.concatenate([c, b])
    return total * np.exp(1j * np.outer(r, shift)) / (2.0 * np.pi)


def _brute_force(track, f, speed, order, r, step):
    """``A_n(f, r)`` by the trapezoid rule in ``u``, ``k = c sinh u``, uniform ``u`` step.

    ``c = pi / d``; ``|k|`` up to 2e4 rad/m (the integrand falls as ``k^-4``: the rest is
    < 1e-10 of the result). The map concentrates the nodes in the core, ``dk = c cosh u
    du``; `step` in ``u``.
    """
    orders = np.arange(-order, order + 1)
    rail = track.rail
    d = track.sleeper_spacing
    constants = (
        rail.bending_stiffness,
        rail.mass_per_length,
        max(rail.loss_factor, VANISHING_LOSS_FACTOR),
        d,
    )
    shift = 2.0 * np.pi * orders / d
    c = np.pi / d
    top = np.arcsinh(2e4 / c)
    out = np.zeros((r.size, orders.size), dtype=complex)
    for u in np.array_split(np.arange(-top, top + step / 2, step), 64):
        k = c * np.sinh(u)
        omega = 2.0 * np.pi * f - k * speed
        values = kernel.integrand(k, omega, moving._support(track, omega), constants, shift)
        weight = step * c * np.cosh(u)
        out += np.einsum("qn,qo,q->on", values, np.exp(1j * np.outer(k, r)), weight)
    return out * np.exp(1j * np.outer(r, shift)) / (2.0 * np.pi)


@pytest.mark.parametrize("width", [1e-3, 0.5, 3.0])
@pytest.mark.parametrize("r", [0.0, 2.2, -12.6, 400.0])
def test_filon_weights_integrate_an_exponential_times_the_oscillation(width, r):
    """``int exp(alpha k) exp(i k r) dk`` over a panel, against its closed form."""
    alpha, mid = 0.3, 1.7
    half = 0.5 * width
    weights = kernel.filon_weights(np.array([mid]), np.array([half]), np.array([r]))[0, 0]
    k = mid + half * kernel.NODES
    rule = weights @ np.exp(alpha * k)
    s = alpha + 1j * r
    exact = np.exp(s * (mid - half)) * np.expm1(s * width) / s  # no cancellation
    # exp(alpha k) differs from its interpolant of degree 14 by ~(alpha half)^15 / 15! of
    # itself (< 1e-18 here); the rest is rounding in the weights (cond(V) = 6.4, the
    # spherical Bessel functions to ~1e-15), relative to the integral of |exp(alpha k)|
    scale = np.exp(alpha * (mid + half)) * width
    assert abs(rule - exact) < 1e-13 * scale


def test_filon_weights_at_zero_gap_are_the_kronrod_rule():
    mid, half = np.array([-3.0, 40.0]), np.array([0.25, 2.0])
    weights = kernel.filon_weights(mid, half, np.array([0.0, 1e-300]))
    np.testing.assert_array_equal(weights[:, 0], half[:, None] * kernel._KRONROD)
    # a vanishing gap: the interpolatory rule of the 15 nodes is the Kronrod rule (rounding)
    np.testing.assert_allclose(weights[:, 1], half[:, None] * kernel._KRONROD, atol=1e-15)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("track", "speed"),
    [(PAPER, 10.0), (PAPER, 80 / 3.6), (NORDBORG, 40.0)],
    ids=["paper-10", "paper-22", "nordborg-40"],
)
def test_filon_equals_the_adaptive_rule_with_the_oscillation_inside(track, speed):
    """At several gaps and speeds, both at a tight quadrature tolerance (1e-10).

    The reference refines until the far gaps' ``exp(i k r)`` is resolved (~10^4 nodes a
    frequency); the Filon rule refines on the ``r = 0`` integrand only.
    """
    order = 3
    f = np.array([0.0, 37.0, 160.0, 700.0])
    res = moving_load_receptance(
        track, f, speed, order=order, r=GAPS, tolerance=0.5, quadrature_tolerance=1e-10
    )
    default = moving_load_receptance(track, f, speed, order=order, r=GAPS, tolerance=0.5)
    for i, fi in enumerate(f):
        ref = _reference(track, fi, speed, order + 2, GAPS, 1e-10)[:, 2:-2]
        largest = np.abs(ref).max()
        # both refined to 1e-10 of the largest harmonic a panel; they differ by the tail
        # beyond 40 k_core each leaves out (< 1e-8 of the result, moving._TAIL_FACTOR;
        # the two start from different panels): measured <= 8.8e-10, the same at both
        # speeds of the paper's track (the tail's G_n ~ 1 / EI k^4 does not see v)
        assert np.abs(res.amplitudes[i] - ref).max() < 1e-8 * largest
        # the default panel tolerance 1e-6 of the largest harmonic, the error estimate
        # ~1e-6 a panel: measured <= 3.3e-7 here (<= 7.6e-7 on the metro car's 9 gaps at
        # 200 frequencies 0.5-1200 Hz; main's rule with the oscillation inside: 1.05e-5)
        assert np.abs(default.amplitudes[i] - ref).max() < 5e-6 * largest


@pytest.mark.slow
def test_filon_against_a_brute_force_trapezoid_rule():
    """The ballasted track (damped: no pole closer to the real axis than the step can see)."""
    speed, order = 40.0, 2
    f = np.array([37.0, 400.0])
    res = moving_load_receptance(
        NORDBORG, f, speed, order=order, r=GAPS, tolerance=0.5, quadrature_tolerance=1e-10
    )
    for i, fi in enumerate(f):
        fine = _brute_force(NORDBORG, fi, speed, order + 2, GAPS, 2e-5)
        coarse = _brute_force(NORDBORG, fi, speed, order + 2, GAPS, 4e-5)
        largest = np.abs(fine).max()
        # the trapezoid's own error, from doubling its step (measured 4.4e-11): the
        # integrand has a kink (the rail loss's sign at omega = 0), an O(step^2) error
        own = np.abs(fine - coarse).max() / largest
        assert own < 1e-8
        # the kernel refined to 1e-10 a panel, its tail beyond 40 k_core left out (< 1e-8);
        # measured 8.2e-11 and 1.2e-10
        assert np.abs(res.amplitudes[i] - fine[:, 2:-2]).max() < 1e-8 * largest + 3 * own * largest


@pytest.mark.slow
def test_default_car_gaps_share_the_gap_zero_nodes():
    """Nodes a frequency for the 9 gaps of the metro car: those of gap 0 (the cost)."""
    f = np.geomspace(0.5, 1200.0, 64)
    gaps = np.array([-14.8, -12.6, -10.4, -2.2, 0.0, 2.2, 10.4, 12.6, 14.8])
    counts = {}
    original = moving.panel_rules
    for name, r in (("zero", gaps[4:5]), ("car", gaps)):
        counted = []

        def counting(mid, *args, counted=counted, **kwargs):
            counted.append(mid.size)
            return original(mid, *args, **kwargs)

        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(moving, "panel_rules", counting)
            moving_load_receptance(PAPER, f, 80 / 3.6, order=5, r=r, tolerance=0.5)
        counts[name] = 15 * sum(counted) / f.size
    # the first-moment estimate (needed where r != 0) adds a few panels: measured +0.2 %
    # (888 -> 890 a frequency on 200 frequencies); the rule with the oscillation inside
    # took 3600 (4 times as many)
    assert counts["car"] < 1.05 * counts["zero"]


def _random_panels(n, seed):
    """Panels over |k| < 60 rad/m, widths 1e-4..2 rad/m, load frequencies 0-2 kHz."""
    rng = np.random.default_rng(seed)
    mid, half = rng.uniform(-60.0, 60.0, n), rng.uniform(1e-4, 2.0, n)
    half[: n // 2] = half[0]  # shared widths, as the bisection makes them
    omega_load = 2.0 * np.pi * rng.uniform(0.0, 2000.0, n)
    k = mid[:, None] + half[:, None] * kernel.NODES
    support = 5e7 + 1j * 5e4 * (omega_load[:, None] - k * 30.0)
    return mid, half, omega_load, support


RAIL = (6.62e6, 60.64, 1e-2, 0.6)
SHIFT = 2.0 * np.pi * np.arange(-3, 4) / 0.6


def test_python_node_loop_at_the_gaps_equals_numpy_rules():
    """The source numba compiles (table of weights per width, phase per panel), as Python."""
    mid, half, omega_load, support = _random_panels(6, seed=3)
    ref, ref_error = kernel.panel_rules(mid, half, omega_load, support, 30.0, RAIL, SHIFT, GAPS)
    rule, error = np.empty_like(ref), np.empty_like(ref_error)
    kernel._panels(
        mid, half, omega_load, support, 30.0, *RAIL, 0.0, 0.0, SHIFT,
        *kernel._filon_table(half, GAPS), GAPS, True, kernel.NODES, kernel._KRONROD, kernel._GAUSS,
        kernel.OMEGA_FLOOR, kernel._D1_SERIES, kernel._CSC2_SERIES, rule, error,
    )  # fmt: skip
    # the same formulas, sums in another order (rounding; the NumPy rules' own checks in
    # test_moving_kernel.py allow 1e-11 for the lattice sum's near-singular denominators)
    assert np.abs(rule - ref).max() < 1e-11 * np.abs(ref).max()
    np.testing.assert_allclose(error, ref_error, rtol=1e-6, atol=1e-11 * np.abs(ref).max())


def test_compiled_rules_at_the_gaps_equal_numpy_rules():
    pytest.importorskip("numba")
    if not kernel.compiled_available():
        pytest.skip("RAILVIB_COMPILED=0")
    mid, half, omega_load, support = _random_panels(200, seed=4)
    args = (mid, half, omega_load, support, 30.0, RAIL, SHIFT, GAPS)
    ref, ref_error = kernel.panel_rules(*args)
    rule, error = kernel.panel_rules(*args, compiled=True)
    # rounding, reassociated by fast-math (as above)
    assert np.abs(rule - ref).max() < 1e-11 * np.abs(ref).max()
    np.testing.assert_allclose(error, ref_error, rtol=1e-6, atol=1e-11 * np.abs(ref).max())


@pytest.mark.slow
def test_compiled_receptance_at_the_gaps_equals_the_adaptive_rule():
    """The numba kernel (from 64 frequencies) at the car's gaps, against the reference."""
    pytest.importorskip("numba")
    if not kernel.compiled_available():
        pytest.skip("RAILVIB_COMPILED=0")
    f = np.linspace(0.0, 1200.0, 64)
    res = moving_load_receptance(
        NORDBORG, f, 40.0, order=3, r=GAPS, tolerance=0.5, quadrature_tolerance=1e-10
    )
    for i in (0, 9, 40, 63):
        ref = _reference(NORDBORG, f[i], 40.0, 5, GAPS, 1e-10)[:, 2:-2]
        # as test_filon_equals_the_adaptive_rule_with_the_oscillation_inside
        assert np.abs(res.amplitudes[i] - ref).max() < 1e-8 * np.abs(ref).max()
