"""Combined spectrum: hard switch at the split, and the optional log-space blend."""

from __future__ import annotations

import numpy as np
import pytest

from railvib.spectra import ChineseHSR, Combined, FRAClass, Sato, ShiTai

TWO_PI = 2.0 * np.pi


def test_hard_switch_picks_branches():
    spec = Combined(FRAClass(5), ShiTai(), split_wavelength_m=1.0)
    lam = np.array([50.0, 2.0, 1.0 + 1e-6, 1.0, 0.5, 0.02])
    om = TWO_PI / lam
    expected = np.where(lam > 1.0, FRAClass(5).psd(om), ShiTai().psd(om))
    # exact selection of one branch or the other -> compared bit for bit
    np.testing.assert_array_equal(spec.psd(om), expected)


def test_exactly_at_split_uses_short_wave():
    # documented choice: at the split wavelength itself the short-wave spectrum applies
    spec = Combined(FRAClass(5), ShiTai(), split_wavelength_m=1.0)
    assert spec.psd(TWO_PI) == ShiTai().psd(TWO_PI)
    spec2 = Combined(FRAClass(5), Sato(), split_wavelength_m=0.8)
    om = TWO_PI / 0.8
    assert spec2.psd(om) == Sato().psd(om)


def test_blend_limits_and_midpoint():
    long, short = FRAClass(5), ShiTai()
    spec = Combined(long, short, split_wavelength_m=1.0, blend_decades=0.4)
    om_s = TWO_PI
    # outside +-0.2 decades the blend weight is exactly 0 or 1
    far = np.array([om_s * 10**-0.25, om_s * 10**0.25])
    np.testing.assert_allclose(spec.psd(far[:1]), long.psd(far[:1]), rtol=1e-14)
    np.testing.assert_allclose(spec.psd(far[1:]), short.psd(far[1:]), rtol=1e-14)
    # at the split the smoothstep weight is 1/2: the geometric mean of the two branches
    geo = np.sqrt(long.psd(om_s) * short.psd(om_s))
    assert spec.psd(om_s) == pytest.approx(geo, rel=1e-13)


def test_blend_is_continuous_and_between_branches():
    long, short = FRAClass(5), ShiTai()
    spec = Combined(long, short, blend_decades=0.5)
    om = TWO_PI * np.geomspace(10**-0.3, 10**0.3, 2001)
    s = spec.psd(om)
    lo = np.minimum(long.psd(om), short.psd(om))
    hi = np.maximum(long.psd(om), short.psd(om))
    assert np.all(s >= lo * (1 - 1e-13))
    assert np.all(s <= hi * (1 + 1e-13))
    # no jump: adjacent samples (0.0003 decades apart) differ by far less than the 2.55x step
    assert np.max(np.abs(np.diff(np.log(s)))) < 0.01


def test_blend_with_zero_branch_is_arithmetic():
    # ChineseHSR is zero below 2 m wavelength; the blend falls back to (1 - w) S_long + w S_short
    spec = Combined(ChineseHSR(), ShiTai(), split_wavelength_m=1.0, blend_decades=0.2)
    om = TWO_PI
    assert spec.psd(om) == pytest.approx(0.5 * ShiTai().psd(om), rel=1e-13)
    assert spec.short_wave_weight(om) == pytest.approx(0.5, rel=1e-15)
