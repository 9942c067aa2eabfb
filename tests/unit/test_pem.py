"""Pseudo-excitation method: delays, excitation vector, PSD helpers and the PEM identity.

The identity test checks the module's one-line pseudo-excitation result against the
full cross-spectral formula ``S_yy = H S_rr H^H`` with ``S_rr = S v v^H``, built in the
test by explicit matrix products from an independently computed ``v``.
"""

import math

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.pem import acceleration_psd, excitation_vector, response_psd, wheel_delays

EPS = np.finfo(float).eps

# ----------------------------------------------------------------------- wheel_delays


def test_wheel_delays_are_offset_over_speed_exact_for_power_of_two_speed():
    # dividing by 16 only shifts exponents: the quotients are exact
    t = wheel_delays([0.0, 2.5, 12.5, 15.0], 16.0)
    np.testing.assert_array_equal(t, [0.0, 0.15625, 0.78125, 0.9375])


def test_wheel_delays_general_speed():
    s = np.array([0.0, 2.2, 12.6, 14.8])
    v = 80.0 / 3.6
    t = wheel_delays(s, v)
    # one correctly rounded division each side of the comparison: 2 eps relative
    np.testing.assert_allclose(t * v, s, rtol=2 * EPS, atol=0)
    assert t.shape == (4,)


@pytest.mark.parametrize("speed", [0.0, -10.0, np.nan, np.inf])
def test_wheel_delays_rejects_bad_speed(speed):
    with pytest.raises(CaseError) as info:
        wheel_delays([0.0, 2.5], speed)
    assert info.value.field == "speed"
    assert "\n" not in str(info.value)


# ------------------------------------------------------------------ excitation_vector


def test_excitation_vector_shape_and_unit_modulus():
    f = np.linspace(0.0, 200.0, 37)
    t = np.array([0.0, 0.099, 0.567, 0.666])
    v = excitation_vector(f, t)
    assert v.shape == (37, 4)
    assert v.dtype == np.complex128
    # |cos + i sin| differs from 1 only by the rounding of cos and sin: a few eps
    np.testing.assert_allclose(np.abs(v), 1.0, rtol=0, atol=4 * EPS)
    # zero delay: exp(0) is exactly 1 at every frequency
    np.testing.assert_array_equal(v[:, 0], 1.0)


def test_excitation_vector_exact_phase_at_quarter_periods():
    # f t = 1/8, 1/4, 1/2, 1, 5/2 -> v = exp(-i 2 pi f t) known exactly
    f = np.array([1.0, 2.0, 4.0, 8.0, 20.0])
    t = np.array([0.125])
    v = excitation_vector(f, t)[:, 0]
    expected = np.array([(1 - 1j) / math.sqrt(2), -1j, -1.0, 1.0, -1.0])
    # the argument 2 pi f t carries pi's rounding (<= 0.5 ulp of 2 pi f t <= 16 ~ 1.8e-15);
    # sin/cos pass that on as an absolute error: 1e-14 is ample
    np.testing.assert_allclose(v, expected, rtol=0, atol=1e-14)


def test_excitation_vector_phase_is_minus_two_pi_f_t():
    f = np.linspace(0.0, 50.0, 2001)  # fine enough that the phase steps are < pi
    t = np.array([0.0, 0.1, 0.63, 0.74])
    v = excitation_vector(f, t)
    phase = np.unwrap(np.angle(v), axis=0)
    # angle() of a rounded unit phasor: ~eps absolute per sample; unwrap adds exact 2 pi
    # multiples whose own rounding grows with |phase| <= 2 pi * 50 * 0.74 ~ 232: 1e-12 abs
    np.testing.assert_allclose(phase, -2 * np.pi * f[:, None] * t[None, :], rtol=0, atol=1e-12)


# ---------------------------------------------------------------------- response_psd


def test_response_psd_1d_hand_values():
    h = np.array([3 + 4j, 1j, 2.0, 0.0])
    s = np.array([2.0, 5.0, 0.25, 7.0])
    # |3+4i|^2 * 2 = 50, |i|^2 * 5 = 5, 4 * 0.25 = 1, 0: all exact in binary
    np.testing.assert_array_equal(response_psd(h, s), [50.0, 5.0, 1.0, 0.0])


@pytest.mark.parametrize(
    "shape",
    [
        pytest.param((6, 3), id="2-D"),
        pytest.param((6, 6), id="2-D-square"),  # catches S broadcast along the last axis
        pytest.param((6, 2, 6), id="3-D"),
    ],
)
def test_response_psd_broadcasts_over_trailing_axes(shape):
    rng = np.random.default_rng(17)
    h = rng.normal(size=shape) + 1j * rng.normal(size=shape)
    s = rng.uniform(0.5, 2.0, size=shape[0])
    out = response_psd(h, s)
    assert out.shape == shape
    expected = np.empty(shape)
    for k in range(shape[0]):  # frequency by frequency: the definition, no broadcasting
        expected[k] = (h[k].real ** 2 + h[k].imag ** 2) * s[k]
    # abs()**2 (hypot, then square) vs re^2 + im^2: a few roundings each, ~4 eps relative
    np.testing.assert_allclose(out, expected, rtol=8 * EPS, atol=0)


# ------------------------------------------------------------------ acceleration_psd


def test_acceleration_psd_is_omega_to_the_fourth_times_s():
    f = np.array([0.0, 0.5, 1.0, 2.0])
    s = np.array([3.0, 1.0, 1.0, 2.0])
    p4 = math.pi**4
    # (2 pi f)^4 for f = 0.5, 1, 2: pi^4, 16 pi^4, 256 pi^4 (powers of two exact); pow()
    # of 2 pi f vs pi**4 differ by a few roundings: 1e-15 relative
    np.testing.assert_allclose(
        acceleration_psd(f, s), [0.0, p4, 16 * p4, 512 * p4], rtol=1e-15, atol=0
    )


def test_acceleration_psd_broadcasts_over_trailing_axes():
    f = np.array([0.5, 1.0, 2.0])
    s = np.arange(12.0).reshape(3, 4) + 1.0
    out = acceleration_psd(f, s)
    assert out.shape == (3, 4)
    factor = np.array([1.0, 16.0, 256.0]) * math.pi**4
    # same roundings as above, 1e-15 relative
    np.testing.assert_allclose(out, factor[:, None] * s, rtol=1e-15, atol=0)


def test_acceleration_of_a_harmonic_displacement():
    # a displacement of PSD S at f has acceleration PSD omega^4 S: at f = 1/(2 pi) Hz,
    # omega = 1 rad/s and the PSD is unchanged
    f = np.array([1.0 / (2.0 * math.pi)])
    # 2 pi * (1/(2 pi)) rounds to 1 within 1 ulp; to the 4th power: 4 ulp
    np.testing.assert_allclose(acceleration_psd(f, np.array([2.5])), [2.5], rtol=8 * EPS)


# ---------------------------------------------------------------- the PEM identity


def _sdof_receptance(f, k, m, c):
    w = 2 * np.pi * f
    return 1.0 / (k - m * w**2 + 1j * w * c)


def test_pseudo_excitation_equals_full_cross_spectral_formula():
    f = np.linspace(0.2, 30.0, 600)
    # two wheels with different single-DOF transfer functions to the one output
    h = np.stack(
        [
            _sdof_receptance(f, k=4.0e5, m=1.0e3, c=2.0e3),  # ~3.2 Hz, lightly damped
            _sdof_receptance(f, k=9.0e6, m=1.5e3, c=8.0e3),  # ~12.3 Hz
        ],
        axis=1,
    )  # (n_freq, n_wheel)
    s_r = 1e-6 / (1.0 + (f / 5.0) ** 2)  # any positive input PSD, m^2/Hz
    t = wheel_delays([0.0, 2.5], 20.0)

    # module route: one pseudo excitation, |sum_j H_j v_j|^2 S
    v = excitation_vector(f, t)
    pem = response_psd(np.sum(h * v, axis=1), s_r)

    # independent route: v from cos/sin, S_rr = S v v^H, S_yy = H S_rr H^H
    phase = 2 * np.pi * f[:, None] * t[None, :]
    v_ref = np.cos(phase) - 1j * np.sin(phase)
    s_rr = s_r[:, None, None] * (v_ref[:, :, None] @ v_ref.conj()[:, None, :])
    h_row = h[:, None, :]  # (n_freq, 1, n_wheel)
    full = (h_row @ s_rr @ h_row.conj().transpose(0, 2, 1))[:, 0, 0]

    # rounding in each term is ~eps of its size; the terms are bounded by
    # (sum_j |H_j|)^2 S, and cancellation makes the result smaller than that: compare on
    # that scale, with 1e-14 (~50 eps) for the handful of products and sums
    scale = np.sum(np.abs(h), axis=1) ** 2 * s_r
    assert np.all(np.abs(full.imag) <= 1e-14 * scale)  # Hermitian form: real
    assert np.all(np.abs(pem - full.real) <= 1e-14 * scale)
    # the two wheels really interfere: the response is not the incoherent sum
    incoherent = np.sum(np.abs(h) ** 2, axis=1) * s_r
    assert np.max(np.abs(pem - incoherent) / incoherent) > 0.5


def test_two_equal_wheels_give_the_cos_squared_filter():
    # equal H at both wheels, delay t: |H (1 + e^{-i w t})|^2 S = 4 cos^2(w t / 2) |H|^2 S
    f = np.linspace(0.5, 40.0, 400)
    h1 = _sdof_receptance(f, k=4.0e5, m=1.0e3, c=2.0e3)
    s_r = np.full_like(f, 2e-7)
    t = wheel_delays([0.0, 2.5], 20.0)
    v = excitation_vector(f, t)
    pem = response_psd(h1 * (v[:, 0] + v[:, 1]), s_r)
    closed = 4 * np.cos(np.pi * f * t[1]) ** 2 * np.abs(h1) ** 2 * s_r
    # near the zeros of cos the sum 1 + e^{-iwt} cancels: compare on the scale
    # 4 |H|^2 S (the largest value), 1e-14 for a few roundings
    assert np.all(np.abs(pem - closed) <= 1e-14 * 4 * np.abs(h1) ** 2 * s_r)
