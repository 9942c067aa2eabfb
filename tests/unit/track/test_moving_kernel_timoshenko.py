"""The moving harmonic load on a Timoshenko rail (railvib.track.moving, issue 17 item 1).

The lattice sum is checked against the direct sum over images, and the slow-load limit
against the stationary Timoshenko wave solver (:meth:`PeriodicTrack.receptance`: the
closed-form span transfer matrices of railvib.track.beam, Bloch waves of the bay), an
independent code path: as ``v -> 0`` the harmonics tend to the Fourier coefficients of
the stationary receptance over load position.
"""

from __future__ import annotations

import numpy as np
import pytest

import railvib.track.moving_kernel as kernel
from railvib.pads import SpringDamper
from railvib.track import BallastedTrack, PeriodicTrack, Rail
from railvib.track.moving import moving_load_receptance

#: CHN60 as a Timoshenko beam (kappa G A, rho I of railvib.track.periodic.Rail's docs)
RAIL = Rail(6.62e6, 60.64, 0.01, shear_stiffness=2.45e8, rotary_inertia=0.2525)
RIGID = PeriodicTrack(RAIL, SpringDamper(5e7, 5e4), 0.6)
BALLASTED = BallastedTrack(
    RAIL, SpringDamper(300e6, 18e3), 0.6, sleeper_mass=150.0, ballast=SpringDamper(150e6, 48e3)
)
F = np.array([50.0, 300.0, 800.0, 2000.0])
#: load positions over a bay: the Timoshenko rail's receptance has a kink under the load
#: (shear), so its coefficients fall as n^-2; 256 samples alias < 1e-5 of A_0 (64: 7e-5)
N_POSITIONS = 256


def test_lattice_sum_against_the_direct_sum():
    rng = np.random.default_rng(3)
    kd = rng.uniform(-3.0, 3.0, 6)
    beta4 = np.concatenate([[1e-12, 1e-6], rng.uniform(0.1, 30.0, 4)]) * (1 + 0.01j)
    eps, rho = 0.05, beta4 * 0.01
    rho_eps = rho * eps
    q, g = rho + eps * beta4, beta4 * (1.0 - rho_eps)
    m_max = 50_000
    x = kd[:, None] + 2.0 * np.pi * np.arange(-m_max, m_max + 1)
    terms = (eps * x**2 + (1.0 - rho_eps)[:, None]) / (x**4 - q[:, None] * x**2 - g[:, None])
    # the terms fall as eps / x^2: the images left out add 2 eps / (4 pi^2 m_max)
    direct = terms.sum(axis=1) + 2.0 * eps / (4.0 * np.pi**2 * m_max)
    closed = kernel.timoshenko_lattice_sum(kd, beta4, eps, rho, rho_eps)
    # 1e5 terms summed in double precision (~1e-12) and the tail's next term, ~eps / m_max^3
    np.testing.assert_allclose(closed, direct, rtol=1e-10)


def test_lattice_sum_euler_limit():
    """eps = rho = 0: the Euler rail's closed form (another formula: sin z/2, sinh z/2)."""
    rng = np.random.default_rng(4)
    kd, beta4 = rng.uniform(-3.0, 3.0, 8), rng.uniform(0.0, 30.0, 8) * (1 + 0.01j)
    zero = np.zeros(8, dtype=complex)
    euler = kernel.lattice_sum(kd, beta4)
    np.testing.assert_allclose(
        kernel.timoshenko_lattice_sum(kd, beta4, 0.0, zero, zero), euler, rtol=1e-13
    )


def _fourier_over_load_position(track, f, r, orders):
    d = track.sleeper_spacing
    xi = np.arange(N_POSITIONS) / N_POSITIONS * d
    alpha = track.receptance(f, xi, xi + r)
    diag = alpha[:, np.arange(N_POSITIONS), np.arange(N_POSITIONS)]
    coef = np.fft.fft(diag, axis=1) / N_POSITIONS
    return np.stack([coef[:, n % N_POSITIONS] for n in orders], axis=1)


def _errors(track, r, speeds, f=F):
    """Largest |A_n - reference| / |A_0| per frequency at each speed."""
    orders = range(-3, 4)
    ref = _fourier_over_load_position(track, f, r, orders)
    errors = {}
    for v in speeds:
        res = moving_load_receptance(track, f, v, order=3, r=[r])
        errors[v] = np.abs(res.amplitudes[:, 0, :] - ref).max(axis=1) / np.abs(ref[:, 3])
    return errors


def test_slow_load_on_a_timoshenko_rail():
    errors = _errors(RIGID, 0.0, [0.1], f=F[[1, 3]])
    # first-order Doppler terms, O(v / c) with c >= 100 m/s the bending phase speed
    # (measured 1e-5 and 1.3e-5)
    assert errors[0.1].max() < 1e-3


@pytest.mark.slow  # 8 slow-load runs and 256-position stationary references: 4-8 s
@pytest.mark.parametrize("track", [RIGID, BALLASTED], ids=["rigid_base", "ballasted"])
@pytest.mark.parametrize("r", [0.0, 0.25])
def test_slow_load_recovers_the_stationary_timoshenko_coefficients(track, r):
    errors = _errors(track, r, [0.1, 0.01])
    # first-order Doppler terms, O(v / c) with c >= 100 m/s the bending phase speed
    assert errors[0.1].max() < 1e-3
    assert errors[0.01].max() < 1e-4
    # ... which fall with v, down to the floor of the quadrature and the FFT (~1e-5)
    assert np.all(errors[0.01] < errors[0.1] + 1e-5), errors


def test_compiled_rules_equal_numpy_rules():
    pytest.importorskip("numba")
    if not kernel.compiled_available():
        pytest.skip("RAILVIB_COMPILED=0")
    rng = np.random.default_rng(5)
    n = 100
    mid, half = rng.uniform(-60.0, 60.0, n), rng.uniform(1e-4, 2.0, n)
    omega_load = 2.0 * np.pi * rng.uniform(0.0, 2000.0, n)
    omega_load[:3] = 0.0  # a static load: the series branch of D1 near k = 0
    k = mid[:, None] + half[:, None] * kernel.NODES
    support = 5e7 + 1j * 5e4 * (omega_load[:, None] - k * 30.0)
    rail = (6.62e6, 60.64, 1e-2, 0.6, 2.45e8, 0.2525)
    shift, r = 2.0 * np.pi * np.arange(-3, 4) / 0.6, np.array([0.0, 0.25])
    args = (mid, half, omega_load, support, 30.0, rail, shift, r)
    ref, _ = kernel.panel_rules(*args)
    rule, _ = kernel.panel_rules(*args, compiled=True)
    # the same formulas in another order: rounding (measured 1.2e-12 at worst, next to the
    # free beam's pole at k = omega = 0 of a static load, where S - G_0 cancels: the
    # direct image sum is the Euler rail's only)
    assert np.abs(rule - ref).max() / np.abs(ref).max() < 3e-9


def test_receptance_compiled_equals_numpy():
    pytest.importorskip("numba")
    if not kernel.compiled_available():
        pytest.skip("RAILVIB_COMPILED=0")
    f = np.array([0.0, 300.0, 2000.0])
    ref = moving_load_receptance(RIGID, f, 40.0, order=3, compiled=False).amplitudes
    res = moving_load_receptance(RIGID, f, 40.0, order=3, compiled=True).amplitudes
    # a panel at the tolerance may be bisected on one side only: < 1e-6 of the largest
    assert np.abs(res - ref).max() / np.abs(ref).max() < 1e-8


def test_python_node_loop_equals_numpy_rules():
    """The Timoshenko branch of the source numba compiles, run as plain Python."""
    rng = np.random.default_rng(6)
    n = 5
    mid, half = rng.uniform(-30.0, 30.0, n), rng.uniform(1e-3, 1.0, n)
    omega_load = 2.0 * np.pi * np.array([0.0, 1.0, 200.0, 900.0, 2000.0])
    k = mid[:, None] + half[:, None] * kernel.NODES
    support = 5e7 + 1j * 5e4 * (omega_load[:, None] - k * 30.0)
    rail = (6.62e6, 60.64, 1e-2, 0.6, 2.45e8, 0.2525)
    shift, r = 2.0 * np.pi * np.arange(-2, 3) / 0.6, np.array([0.0, 0.25])
    ref, _ = kernel.panel_rules(mid, half, omega_load, support, 30.0, rail, shift, r)
    rule, error = np.empty_like(ref), np.empty(n)
    kernel._panels(
        mid, half, omega_load, support, 30.0, *rail, shift,
        *kernel._filon_table(half, r), r, True, kernel.NODES,
        kernel._KRONROD, kernel._GAUSS, kernel.OMEGA_FLOOR, kernel._D1_SERIES,
        kernel._CSC2_SERIES, rule, error,
    )  # fmt: skip
    # rounding (the same formulas, scalar): 1e-12 at worst next to a cancellation
    assert np.abs(rule - ref).max() / np.abs(ref).max() < 3e-9
