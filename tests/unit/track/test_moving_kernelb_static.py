"""The constant load (Omega = 0) at walking speeds: the mean deflection is the static bowl.

Independent reference: as ``v -> 0`` a constant load passes the sleepers so slowly that
the rail follows its static deflection at each load position, so the mean harmonic
``A_0(0, r)`` tends to the stationary receptance (:meth:`PeriodicTrack.receptance`, the
Bloch-wave solver of the bay: another code path) at a quasi-static frequency, averaged
over the load position in a bay. The corrections are inertial, ``O((v / c)^2)`` with ``c
>= 100 m/s`` the bending phase speeds of these tracks: < 4e-4 at 2 m/s.

Issue 17: before the cancellation-free ``G_0 (d + K S') / (d + K S)`` this mean was
2.0e-6 m/N at 0.5 m/s against 6.5e-9 static (with a SolverWarning); on a Timoshenko rail
the closed-form ``S - G_0`` kept the cancellation next to the pole of ``G_0`` at ``k = 0``,
and quadrature tolerances <= 1e-9 chased it (A_0 wrong by a factor of 17 to 550).
"""

from __future__ import annotations

import numpy as np
import pytest

import railvib.track.moving_kernel as kernel
from railvib.pads import Hysteretic, SpringDamper
from railvib.track import BallastedTrack, PeriodicTrack, Rail
from railvib.track.moving import moving_load_receptance

D = 0.6
#: the moving-vehicle tests' ballasted metro track (issue 17's report), rail loss 0 and 0.01
BALLASTED = {
    eta: BallastedTrack(
        Rail(6.4e6, 60.0, loss_factor=eta),
        SpringDamper(2.0e8, 3.0e4),
        D,
        sleeper_mass=150.0,
        ballast=SpringDamper(1.0e8, 8.0e4),
    )
    for eta in (0.0, 0.01)
}
#: CHN60 as a Timoshenko beam (kappa G A, rho I of railvib.track.periodic.Rail's docs)
TIMOSHENKO = Rail(6.62e6, 60.64, 0.01, shear_stiffness=2.45e8, rotary_inertia=0.2525)
TIMOSHENKO_TRACKS = {
    "rigid_base": PeriodicTrack(TIMOSHENKO, SpringDamper(5e7, 5e4), D),
    "ballasted": BallastedTrack(
        TIMOSHENKO,
        SpringDamper(300e6, 18e3),
        D,
        sleeper_mass=150.0,
        ballast=SpringDamper(150e6, 48e3),
    ),
}
SPEEDS = (0.1, 0.5, 1.0, 2.0)
#: load positions over a bay: the Timoshenko receptance's coefficients fall as n^-2, so
#: 256 samples of the periodic bowl leave < 1e-5 of its mean (the n = 256 alias); an Euler
#: rail's as n^-4: 64 leave < 1e-6
N_POSITIONS = {"euler": 64, "timoshenko": 256}
#: "quasi-static" frequency of the reference, Hz: its dynamic part is (f / 40 Hz)^2 ~ 1e-15
F_STATIC = 1e-6


def _static_bowl_mean(track: PeriodicTrack, r: float) -> complex:
    """``(1/d) int alpha(xi, xi + r) dxi`` over the load position in a bay, m/N.

    The real part: a hysteretic loss gives the stationary receptance an imaginary part
    ``-i eta sign(f)`` that does not vanish as ``f -> 0+``; a constant load sees both signs
    of the fixed-frame frequency ``omega = -k v`` alike, and its response is real.
    """
    n = N_POSITIONS["euler" if track.rail.shear_stiffness is None else "timoshenko"]
    xi = np.arange(n) / n * D
    alpha = track.receptance([F_STATIC], xi, xi + r)[0]
    return complex(np.mean(np.diag(alpha)).real)


@pytest.mark.filterwarnings("error::railvib.errors.SolverWarning")
@pytest.mark.parametrize("eta", [0.0, 0.01], ids=["no_rail_loss", "rail_loss_0.01"])
def test_constant_slow_load_mean_is_the_static_bowl(eta):
    track = BALLASTED[eta]
    # under the load, and under the wheels a bogie's 2.2 m ahead and behind
    r = np.array([0.0, 2.2, -2.2])
    ref = np.array([_static_bowl_mean(track, x) for x in r])
    for v in SPEEDS:
        res = moving_load_receptance(track, [0.0], v, order=2, r=r)
        a = res.mean[0]
        # under the load: inertial corrections O((v/c)^2) < 4e-4 at 2 m/s (measured
        # <= 6e-6); main before the fix: 2.0e-6 m/N at 0.5 m/s, 300 times the static 6.5e-9
        np.testing.assert_allclose(a[0], ref[0], rtol=4e-4, err_msg=f"v = {v}")
        # ahead and behind, the viscous damping tilts the bowl by O(v) (odd in r): their
        # mean is the static bowl to O(v^2), relative to the deflection under the load
        np.testing.assert_allclose(
            0.5 * (a[1] + a[2]), ref[1], rtol=0.0, atol=4e-4 * abs(ref[0]), err_msg=f"v = {v}"
        )
        # the tilt itself: first order in v from the viscous dampers (measured 1.1e-4 of
        # the peak deflection per m/s), plus a speed-independent part from a hysteretic
        # rail loss (rate-independent: measured 1e-3 at eta = 0.01)
        assert abs(a[1] - a[2]) < (1e-3 * v + 0.5 * eta) * abs(ref[0])


@pytest.mark.filterwarnings("error::railvib.errors.SolverWarning")
def test_constant_slow_load_on_hysteretic_supports():
    # the supports' loss changes sign with the fixed-frame frequency omega = -k v at k = 0,
    # a jump in the integrand right at G_0's pole (the moving-vehicle helper saw a
    # SolverWarning there at 1 m/s with the first version of this module)
    track = BallastedTrack(
        Rail(6.4e6, 60.0, loss_factor=0.01),
        Hysteretic(2e8, 0.25),
        D,
        sleeper_mass=150.0,
        ballast=Hysteretic(1e8, 1.0),
    )
    ref = _static_bowl_mean(track, 0.0)
    for v in SPEEDS:
        res = moving_load_receptance(track, [0.0], v, order=2)
        # as above (measured <= 3e-6)
        np.testing.assert_allclose(res.mean[0, 0], ref, rtol=4e-4, err_msg=f"v = {v}")


@pytest.mark.filterwarnings("error::railvib.errors.SolverWarning")
@pytest.mark.parametrize("name", list(TIMOSHENKO_TRACKS))
@pytest.mark.parametrize("quadrature_tolerance", [1e-6, 1e-10])
def test_constant_slow_load_on_a_timoshenko_rail(name, quadrature_tolerance):
    track = TIMOSHENKO_TRACKS[name]
    ref = _static_bowl_mean(track, 0.0)
    for v in (0.1, 0.5, 2.0):
        res = moving_load_receptance(
            track, [0.0], v, order=2, quadrature_tolerance=quadrature_tolerance
        )
        # as above (measured <= 2e-6); before the fix at 1e-10: 17 to 550 times too large
        np.testing.assert_allclose(res.mean[0, 0], ref, rtol=4e-4, err_msg=f"v = {v}")


def test_timoshenko_images_against_the_direct_sum():
    """The direct image sum next to G_0's pole against 2 x 10^5 images summed by brute force."""
    kd = np.array([0.0, 1e-9, 1e-4, 0.3, 0.49, 0.51, 2.0])
    eps = 0.0306  # CHN60 on 0.6 m: EI / (kappa G A d^2)
    beta4 = np.full(kd.shape, 1e-10 * (1 + 0.01j))
    rho_eps = beta4 * 1e-3
    q, g = rho_eps / eps + eps * beta4, beta4 * (1.0 - rho_eps)
    n0 = 1.0 - rho_eps
    m_max = 100_000
    x = kd[:, None] + 2.0 * np.pi * np.concatenate(
        [-np.arange(m_max, 0, -1), np.arange(1, m_max + 1)]
    )
    terms = (eps * x**2 + n0[:, None]) / (x**4 - q[:, None] * x**2 - g[:, None])
    # the terms beyond fall as eps / x^2: 2 eps / (4 pi^2 m_max) left out, added back
    direct = terms.sum(axis=1) + 2.0 * eps / (4.0 * np.pi**2 * m_max)
    got = kernel._timoshenko_images(kd, eps, q, g, n0)
    # the brute force's own error: the next tail term ~ eps / m_max^2 and rounding of 2e5
    # terms (measured 6e-13 absolute against a sum ~ 2.6e-3): 1e-9 relative
    np.testing.assert_allclose(got, direct, rtol=1e-9)
    # away from G_0's poles it is the closed form minus G_0 (no cancellation at kd = 2)
    closed = kernel.timoshenko_lattice_sum(
        kd[-1:], beta4[-1:], eps, q[-1:] - eps * beta4[-1:], rho_eps[-1:]
    )
    g0 = (eps * kd[-1] ** 2 + n0[-1]) / (kd[-1] ** 4 - q[-1] * kd[-1] ** 2 - g[-1])
    np.testing.assert_allclose(got[-1], closed[0] - g0, rtol=1e-9)


def test_timoshenko_static_rules_compiled_equal_numpy():
    """The numba branch of the direct image sum (a static load, nodes around k = 0)."""
    pytest.importorskip("numba")
    if not kernel.compiled_available():
        pytest.skip("RAILVIB_COMPILED=0")
    mid = np.array([0.0, 1e-6, -3e-4, 0.2, 5.0])
    half = np.array([1e-3, 1e-6, 1e-4, 0.2, 1.0])
    omega_load = np.zeros(5)
    speed = 0.5
    k = mid[:, None] + half[:, None] * kernel.NODES
    support = 5e7 + 1j * 5e4 * (omega_load[:, None] - k * speed)
    rail = (6.62e6, 60.64, 1e-2, D, 2.45e8, 0.2525)
    shift, r = 2.0 * np.pi * np.arange(-2, 3) / D, np.array([0.0, 0.25])
    args = (mid, half, omega_load, support, speed, rail, shift, r)
    ref, _ = kernel.panel_rules(*args)
    rule, _ = kernel.panel_rules(*args, compiled=True)
    # the same formulas node by node: rounding (measured ~1e-15 of the largest)
    assert np.abs(rule - ref).max() / np.abs(ref).max() < 1e-12
