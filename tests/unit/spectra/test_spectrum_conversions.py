"""Density-transform identities of docs/spectra.md, "Conventions" (closed forms, no numbers)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from railvib.spectra import (
    ChineseHSR,
    Combined,
    FRAClass,
    GermanVertical,
    Sato,
    ShiTai,
    temporal_psd,
)

TWO_PI = 2.0 * np.pi
SPEED = 80.0 / 3.6

SPECTRA = [
    FRAClass(5),
    ShiTai(),
    Sato(),
    GermanVertical("high"),
    ChineseHSR(extrapolate=True),
    Combined(FRAClass(5), ShiTai()),
    Combined(FRAClass(5), ShiTai(), blend_decades=0.5),
]


@pytest.mark.parametrize("spec", SPECTRA, ids=repr)
def test_cycles_equal_two_pi_radians(spec):
    # S(n) = 2 pi S(Omega = 2 pi n); pure float rounding -> rtol 1e-13
    n = np.geomspace(0.01, 50.0, 37)
    np.testing.assert_allclose(spec.psd_cycles(n), TWO_PI * spec.psd(TWO_PI * n), rtol=1e-13)


@pytest.mark.parametrize("spec", SPECTRA, ids=repr)
def test_per_hz_against_per_rad_per_s(spec):
    # S_t(f) = 2 pi S_t(omega), S_t(omega) = S_x(omega / v) / v; float rounding -> rtol 1e-13
    f = np.geomspace(0.5, 1000.0, 29)
    per_rad_s = spec.psd(TWO_PI * f / SPEED) / SPEED
    np.testing.assert_allclose(spec.temporal(f, SPEED), TWO_PI * per_rad_s, rtol=1e-13)
    np.testing.assert_allclose(temporal_psd(spec, f, SPEED), spec.temporal(f, SPEED), rtol=0)


@pytest.mark.parametrize("spec", SPECTRA, ids=repr)
@pytest.mark.parametrize(("f1", "f2"), [(0.5, 10.0), (10.0, 40.0), (40.0, 1000.0)])
def test_variance_conservation(spec, f1, f2):
    # int S_x dOmega over [2 pi f1/v, 2 pi f2/v] equals int S_t df over [f1, f2]. Both are
    # integrated in log variables with epsrel 1e-10, breaking at the 1 m join (f = v / 1 m)
    # where the hard switch jumps; rel 1e-8 leaves room for the quadrature only.
    f_join = SPEED / 1.0
    edges = [f1, *([f_join] if f1 < f_join < f2 else []), f2]

    def integrate(func, a, b):
        total = 0.0
        for lo, hi in zip(a, b, strict=True):
            val, _ = quad(
                lambda u: float(func(np.exp(u))) * np.exp(u),
                np.log(lo),
                np.log(hi),
                epsabs=0.0,
                epsrel=1e-10,
                limit=200,
            )
            total += val
        return total

    lows, highs = edges[:-1], edges[1:]
    var_t = integrate(lambda f: spec.temporal(f, SPEED), lows, highs)
    om_lo = [TWO_PI * f / SPEED for f in lows]
    om_hi = [TWO_PI * f / SPEED for f in highs]
    var_x = integrate(spec.psd, om_lo, om_hi)
    assert var_t == pytest.approx(var_x, rel=1e-8)


def test_scalar_and_array_shapes():
    spec = FRAClass(5)
    assert np.ndim(spec.psd(1.0)) == 0
    assert spec.psd(np.ones((3, 4))).shape == (3, 4)
