"""The Timoshenko bay's closed forms (railvib.track.timoshenko) against the bay's matrix.

The reference is the bay's transfer matrix ``T = P exp(A)`` evaluated independently in
extended precision (x87 long double, eps = 1.1e-19: Taylor series with scaling and
squaring), from which ``tr T``, the sum of its principal 2x2 minors and ``T y`` are
formed. The trace route loses ``cosh^2 b`` to cancellation; over these rails
``|b| < 3`` (``cosh^2 b < 110``), so the reference holds 1e-17 of the terms.
"""

import numpy as np
import pytest

from railvib.pads import Hysteretic, SpringDamper
from railvib.track import PeriodicTrack, Rail, periodic
from railvib.track.timoshenko import bay_characteristic, bay_waves, span_terms

pytestmark = pytest.mark.skipif(
    np.finfo(np.longdouble).eps > 1e-18, reason="needs an extended-precision long double"
)

#: CHN60 (cut-off 4958 Hz), a soft undamped rail on a lossless pad (cut-off 3008 Hz,
#: both wave pairs propagate above it), a damped soft rail on 0.75 m bays
TRACKS = {
    "chn60": PeriodicTrack(
        Rail(6.62e6, 60.64, shear_stiffness=2.45e8, rotary_inertia=0.2525),
        SpringDamper(5e7, 5e4),
        0.6,
    ),
    "soft_lossless": PeriodicTrack(
        Rail(3.1e6, 45.0, shear_stiffness=1.5e8, rotary_inertia=0.42), SpringDamper(3e8, 0.0), 0.5
    ),
    "soft_damped": PeriodicTrack(
        Rail(3.0e6, 80.0, loss_factor=0.02, shear_stiffness=1.2e8, rotary_inertia=0.5),
        Hysteretic(1e9, 0.3),
        0.75,
    ),
}


def frequencies(track):
    """100 Hz - 5 kHz, and points at the cut-off (b = 0) and 1e-9 and 1e-4 from it."""
    f_c = track.rail.cut_off_frequency_hz
    near = f_c * (1.0 + np.array([-1e-4, -1e-9, 0.0, 1e-9, 1e-4]))
    f = np.concatenate([np.geomspace(100.0, 5000.0, 40), near[near < 5000.0]])
    return np.sort(f)


def extended_bay(track, f, with_pad=True):
    """``T = P exp(A)`` (or the span's ``exp(A)``) in long double, ``(n_freq, 4, 4)``."""
    beta4, eps, rho, _ = track._timoshenko_terms(f)
    pad = track._pad_hat(f)
    a = np.zeros((f.size, 4, 4), dtype=np.clongdouble)
    a[:, 0, 1] = a[:, 1, 2] = a[:, 2, 3] = 1
    a[:, 0, 3] = -np.clongdouble(eps)
    a[:, 2, 1] = -rho.astype(np.clongdouble)
    a[:, 3, 0] = beta4.astype(np.clongdouble)
    squarings = 8  # |A| / 256 < 0.3 here: 40 Taylor terms are far below the long double eps
    term = a / np.longdouble(2.0) ** squarings
    total = np.broadcast_to(np.eye(4, dtype=np.clongdouble), a.shape).copy()
    power = total.copy()
    for k in range(1, 40):
        power = power @ term / k
        total = total + power
    for _ in range(squarings):
        total = total @ total
    if with_pad:
        total[:, 3, :] -= pad.astype(np.clongdouble)[:, None] * total[:, 0, :]
    return total


@pytest.mark.parametrize("name", sorted(TRACKS))
def test_characteristic_coefficients_match_the_extended_bay(name):
    track = TRACKS[name]
    f = frequencies(track)
    span = span_terms(*track._timoshenko_terms(f))
    pad = track._pad_hat(f)
    c1, c2m2, disc = bay_characteristic(span, pad)
    t = extended_bay(track, f)
    ref_c1 = np.einsum("fii->f", t)
    ref_c2m2 = 0.5 * (ref_c1**2 - np.einsum("fij,fji->f", t, t)) - 2
    # the closed form's terms (X, Y, pad B14): c1 and lambda = mu + 1/mu are needed to a
    # few ulp of them; 20 eps allows the rounding of a, b and of about ten operations
    terms = np.abs(span.x) + np.abs(span.y) + np.abs(pad * (span.alpha_sin + span.gamma_sinh))
    used = np.abs(span.r) >= periodic.SMALL_WAVENUMBERS  # where the solver uses the forms
    assert used.sum() > 25
    eps = np.finfo(float).eps
    assert np.all(np.abs(c1 - ref_c1)[used] <= 20 * eps * terms[used])
    assert np.all(np.abs(c2m2 - ref_c2m2)[used] <= 20 * eps * terms[used] ** 2)
    ref_disc = ref_c1**2 - 4 * ref_c2m2
    assert np.all(np.abs(disc - ref_disc)[used] <= 100 * eps * terms[used] ** 2)


@pytest.mark.parametrize("name", sorted(TRACKS))
def test_span_displacement_per_shear_is_alpha_sin_plus_gamma_sinh(name):
    # the derivation's B14(1), the span's displacement per unit v: w(x) = alpha sin(a x) +
    # gamma sinh(b x) with w(0) = w''(0) = 0, w'(0) = -eps, w'''(0) = 1 + eps^2 beta4
    track = TRACKS[name]
    f = frequencies(track)
    span = span_terms(*track._timoshenko_terms(f))
    b14 = extended_bay(track, f, with_pad=False)[:, 0, 3].astype(complex)
    used = np.abs(span.r) >= periodic.SMALL_WAVENUMBERS
    # 20 eps of the two terms and of alpha a, gamma b: a and b carry their rounding
    # (relative eps), which moves alpha sin a by alpha a cos a times eps a / a (and near
    # a = n pi sin a is small); the reference is exact for the same rounded inputs
    _, eps, _, rho_eps = track._timoshenko_terms(f)
    alpha_a = np.abs(1 + eps * span.eb_b2) / np.abs(span.r)
    gamma_b = np.abs((1 - rho_eps) * span.rho_b2 / (span.a2 * span.r))
    scale = np.abs(span.alpha_sin) + np.abs(span.gamma_sinh) + alpha_a + gamma_b
    closed = span.alpha_sin + span.gamma_sinh
    assert np.all(np.abs(closed - b14)[used] <= 20 * np.finfo(float).eps * scale[used])


@pytest.mark.parametrize("name", sorted(TRACKS))
def test_bloch_waves_are_eigenvectors_of_the_extended_bay(name):
    track = TRACKS[name]
    f = frequencies(track)
    span = span_terms(*track._timoshenko_terms(f))
    used = np.abs(span.r) >= periodic.SMALL_WAVENUMBERS
    f, span = f[used], span_terms(*track._timoshenko_terms(f[used]))
    mu, vec = bay_waves(span, track._pad_hat(f))
    assert np.all(np.abs(mu) <= 1.0 + 1e-15)
    t = extended_bay(track, f)
    residual = np.einsum("fij,fjk->fik", t, vec.astype(np.clongdouble)) - mu[:, None, :] * vec
    norm_t = np.abs(t).max(axis=(1, 2)).astype(float)
    # a backward-stable eigenpair: T y - mu y of the order of eps |T| (unit y); 50 eps for
    # the rounding of the closed form's terms
    assert np.all(
        np.abs(residual).max(axis=1).astype(float) <= 50 * np.finfo(float).eps * norm_t[:, None]
    )


def test_euler_limit_matches_the_euler_closed_form():
    # kGA -> infinity, rho I = 0: eps = EI / (kGA d^2) = 1.8e-13, so the Timoshenko
    # coefficients differ from the Euler ones by O(eps beta4) <= 2e-10 (beta4 <= 1200)
    track = PeriodicTrack(Rail(6.62e6, 60.64, shear_stiffness=1e20), SpringDamper(5e7, 5e4), 0.6)
    f = np.geomspace(300.0, 5000.0, 40)
    terms = track._timoshenko_terms(f)
    span = span_terms(*terms)
    assert np.all(np.abs(span.r) >= periodic.SMALL_WAVENUMBERS)
    pad = track._pad_hat(f)
    c1, c2m2, _ = bay_characteristic(span, pad)
    e1, e2m2 = periodic._euler_characteristic(terms[0], pad)
    np.testing.assert_allclose(c1, e1, rtol=1e-9)
    np.testing.assert_allclose(c2m2, e2m2, rtol=1e-9)
