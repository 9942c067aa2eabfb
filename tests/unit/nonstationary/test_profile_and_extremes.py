"""Speed profiles against the kinematics of uniform acceleration; crossing rates against Rice."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate
from scipy.special import erfc

from railvib.case.profile import (
    NonstationarySection,
    SpeedProfileSection,
    check_time_step,
    knots,
)
from railvib.nonstationary import SpeedProfile, first_passage_probability, upcrossing_rate
from railvib.nonstationary.quasi import validity_parameter


def test_uniform_braking_follows_the_closed_form():
    v0, a = 22.0, 1.1
    p = SpeedProfile.uniform(v0, 0.0, a)
    t = np.linspace(0.0, v0 / a, 37)
    assert p.duration == pytest.approx(v0 / a, rel=1e-15)
    np.testing.assert_allclose(p.speed(t), v0 - a * t, atol=1e-12)
    np.testing.assert_allclose(p.position(t), v0 * t - 0.5 * a * t**2, atol=1e-11)
    np.testing.assert_allclose(p.acceleration(t), -a)


def test_position_table_of_a_uniform_acceleration_gives_its_times():
    # v^2 = v0^2 + 2 a x: knots on that curve are joined exactly by constant acceleration,
    # so t = (v - v0) / a at every knot
    v0, a = 5.0, 0.8
    x = np.array([0.0, 10.0, 40.0, 100.0, 250.0])
    v = np.sqrt(v0**2 + 2 * a * x)
    section = SpeedProfileSection(kind="table", position_m=list(x), speeds_kmh=list(3.6 * v))
    t, xk, vk = knots(section, 50.0)
    np.testing.assert_allclose(t, (v - v0) / a, rtol=1e-12)
    np.testing.assert_allclose(xk, x)
    p = SpeedProfile(t, xk, vk)
    tt = np.linspace(0, t[-1], 50)
    np.testing.assert_allclose(p.position(tt), v0 * tt + 0.5 * a * tt**2, rtol=1e-12, atol=1e-12)


def test_time_table_integrates_position_segment_by_segment():
    # accelerate 0 -> 10 m/s in 5 s, hold 10 s, brake to 4 m/s in 3 s
    section = SpeedProfileSection(
        kind="table", time_s=[0.0, 5.0, 15.0, 18.0], speeds_kmh=[0.0, 36.0, 36.0, 14.4]
    )
    t, x, v = knots(section, 50.0)
    np.testing.assert_allclose(x, [0.0, 25.0, 125.0, 125.0 + 21.0], rtol=1e-12)
    p = SpeedProfile(t, x, v)
    assert float(p.position(16.0)) == pytest.approx(125.0 + 10.0 - 1.0, rel=1e-12)  # a = -2


def test_default_time_step_is_half_the_nyquist_step():
    section = SpeedProfileSection(
        kind="uniform", v_start_kmh=72.0, v_end_kmh=0.0, acceleration_ms2=1.0
    )
    settings = NonstationarySection(wavelength_min_m=2.0)

    # f_top = 20 m/s / 2 m = 10 Hz: Nyquist step 0.05 s, half of it 0.025 s
    assert check_time_step(section, settings, 72.0) == pytest.approx(0.025)


def test_validity_parameter_of_uniform_braking():
    p = SpeedProfile.uniform(20.0, 0.0, 2.0)
    t = np.array([0.0, 5.0, 9.0, 10.0])
    eps = validity_parameter(p, t, 0.5)
    np.testing.assert_allclose(eps[:3], 2.0 / ((20.0 - 2.0 * t[:3]) * 0.5))
    assert np.isinf(eps[3])  # at the stop
    assert validity_parameter(SpeedProfile.constant(10.0, 3.0), t[:2], 0.5).tolist() == [0, 0]


def test_stationary_rice_rate():
    # uncorrelated y, y': nu+ = sqrt(l2 / l0) / (2 pi) exp(-b^2 / (2 l0)) (Rice 1944)
    l0, l2, b = 2.0, 50.0, 3.0
    rate = upcrossing_rate(b, l0, l2, 0.0)
    assert float(rate) == pytest.approx(np.sqrt(l2 / l0) / (2 * np.pi) * np.exp(-(b**2) / (2 * l0)))


def test_nonstationary_rice_rate_against_the_joint_density():
    # nu+ = int_0^inf z p(b, z) dz with (y, y') jointly Gaussian, correlated
    l0, l2, c, b = 1.5, 9.0, 1.2, 2.0
    cov = np.array([[l0, c], [c, l2]])
    inv, det = np.linalg.inv(cov), np.linalg.det(cov)

    def density(z: float) -> float:
        x = np.array([b, z])
        return float(np.exp(-0.5 * x @ inv @ x) / (2 * np.pi * np.sqrt(det)))

    expected, _ = integrate.quad(lambda z: z * density(z), 0.0, np.inf, epsabs=1e-13)
    assert float(upcrossing_rate(b, l0, l2, c)) == pytest.approx(expected, rel=1e-8)


def test_poisson_first_passage_of_a_stationary_process():
    t = np.linspace(0.0, 10.0, 11)
    l0, l2, b = 1.0, 4.0, 3.0
    ones = np.ones((t.size, 1))
    nu = np.sqrt(l2 / l0) / (2 * np.pi) * np.exp(-(b**2) / 2)
    p0 = erfc(b / np.sqrt(2))
    got = first_passage_probability(t, [b], l0 * ones, l2 * ones, 0 * ones, 0 * ones)
    assert float(got[0]) == pytest.approx(1 - (1 - p0) * np.exp(-2 * nu * 10.0), rel=1e-12)
    # Vanmarcke, narrow band q = 0.3 (l1^2 = (1 - q^2) l0 l2): fewer, clumped crossings
    q = 0.3
    l1 = np.sqrt((1 - q**2) * l0 * l2)
    van = first_passage_probability(t, [b], l0 * ones, l2 * ones, 0 * ones, l1 * ones, "vanmarcke")
    factor = (1 - np.exp(-np.sqrt(np.pi / 2) * q**1.2 * b)) / (1 - np.exp(-(b**2) / 2))
    assert float(van[0]) == pytest.approx(1 - (1 - p0) * np.exp(-2 * nu * factor * 10.0), rel=1e-12)


def test_frequency_map_of_a_flat_wavenumber_spectrum():
    from railvib.nonstationary import frequency_map

    # S = 1 per rad/m over 1..10 rad/m at 2 pi m/s: f = Omega, S_f = 2 pi / v = 1 per Hz
    om = np.geomspace(1.0, 10.0, 50)
    psd = np.ones((2, om.size, 1))
    f = np.array([0.5, 2.0, 5.0, 20.0])
    out = frequency_map(psd, om, np.array([2 * np.pi, 0.0]), f)
    np.testing.assert_allclose(out[0, :, 0], [0.0, 1.0, 1.0, 0.0])
    assert not out[1].any()  # at rest everything is at 0 Hz
