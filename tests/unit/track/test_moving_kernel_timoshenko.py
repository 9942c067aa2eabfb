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
from railvib.errors import CaseError
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


def test_compiled_refused_for_a_timoshenko_rail():
    with pytest.raises(CaseError) as err:
        moving_load_receptance(RIGID, [100.0], 30.0, compiled=True)
    assert err.value.field == "moving.compiled"
    assert "Timoshenko" in str(err.value)
    assert "\n" not in str(err.value)
