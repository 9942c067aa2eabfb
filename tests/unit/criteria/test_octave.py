"""One-third-octave bands (IEC 61260-1:2014) and band mean squares of PSDs."""

import numpy as np
import pytest

from railvib.outputs.octave import (
    BAND_EDGE_RATIO,
    band_mean_square,
    level_db,
    third_octave_bands,
)

#: IEC 61260-1:2014, Annex E, Table E.1: nominal mid-band frequencies of the one-third-octave
#: bands from 25 Hz to 20 kHz, Hz, as printed
TABLE_E1_NOMINAL = [
    25, 31.5, 40, 50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800, 1000,
    1250, 1600, 2000, 2500, 3150, 4000, 5000, 6300, 8000, 10000, 12500, 16000, 20000,
]  # fmt: skip


def test_nominal_centres_are_the_printed_table():
    bands = third_octave_bands(22.0, 23000.0)
    assert bands.nominal.tolist() == pytest.approx(TABLE_E1_NOMINAL, rel=1e-12)  # rounding only


def test_exact_centres_and_edges_follow_the_base_ten_definition():
    bands = third_octave_bands(0.5, 1000.0)
    g = 10.0 ** (3.0 / 10.0)  # IEC 61260-1:2014, 5.2: octave ratio, base 10
    x = bands.index
    assert bands.exact == pytest.approx(1000.0 * g ** (x / 3.0), rel=1e-13)  # rounding only
    assert bands.upper == pytest.approx(bands.exact * g ** (1 / 6), rel=1e-13)
    assert bands.lower == pytest.approx(bands.exact * g ** (-1 / 6), rel=1e-13)
    # consecutive bands share an edge, and every band lies inside the range asked for
    assert bands.upper[:-1] == pytest.approx(bands.lower[1:], rel=1e-13)
    assert bands.lower[0] >= 0.5
    assert bands.upper[-1] <= 1000.0
    assert bands.nominal[0] == 0.63
    assert bands.nominal[-1] == 800.0


def test_nominal_centres_within_the_tolerance_of_the_exact_ones():
    # the nominal value rounds the exact one; rounding to 3 significant digits is within 2 %
    bands = third_octave_bands(0.1, 20000.0)
    assert np.all(np.abs(bands.nominal / bands.exact - 1.0) < 0.02)


def test_white_psd_gives_the_closed_form_in_each_band():
    f = np.linspace(1.0, 1000.0, 997)
    s0 = 3.7e-4
    bands = third_octave_bands(f[0], f[-1])
    ms = band_mean_square(f, np.full_like(f, s0), bands.lower, bands.upper)
    expected = s0 * bands.exact * (10 ** (1 / 20) - 10 ** (-1 / 20))
    assert ms == pytest.approx(expected, rel=1e-12)  # linear interpolation is exact for a constant


def _power_law_band(a, lo, hi):
    return a * (1.0 / lo - 1.0 / hi)  # integral of A f^-2 from lo to hi


def test_power_law_f_minus_two_on_a_fine_grid_against_the_closed_form():
    a = 2.0e-3
    f = np.linspace(2.0, 500.0, 200_001)
    bands = third_octave_bands(f[0], f[-1])
    ms = band_mean_square(f, a * f**-2, bands.lower, bands.upper)
    expected = _power_law_band(a, bands.lower, bands.upper)
    # trapezoid error of a piece: h^2/12 * max|S''|/S * width, here h = 2.5e-3 Hz at f >= 2 Hz:
    # (2.5e-3)^2 / 12 * 6 / 2^2 = 8e-7 relative at most
    assert ms == pytest.approx(expected, rel=1e-6)


def test_coarse_grid_against_a_fine_one():
    a = 2.0e-3
    fine = np.linspace(2.0, 500.0, 100_001)
    coarse = np.linspace(2.0, 500.0, 2_001)  # 0.25 Hz step
    bands = third_octave_bands(10.0, 500.0)
    ms_fine = band_mean_square(fine, a * fine**-2, bands.lower, bands.upper)
    ms_coarse = band_mean_square(coarse, a * coarse**-2, bands.lower, bands.upper)
    # the coarse grid's trapezoid error at f >= 10 Hz: 0.25^2/12 * 6/10^2 = 3e-4 relative at most
    assert ms_coarse == pytest.approx(ms_fine, rel=3.2e-4)
    assert not np.allclose(ms_coarse, ms_fine, rtol=1e-8, atol=0)  # the grids do differ


def test_band_edges_between_grid_points_interpolate_not_sum_bins():
    # PSD 1 on [0, 10] Hz with a step of 1 Hz; a "band" 2.25-3.75 Hz holds 1.5, not 1 or 2 bins
    f = np.arange(1.0, 11.0)
    ms = band_mean_square(f, np.ones_like(f), np.array([2.25]), np.array([3.75]))
    assert ms == pytest.approx([1.5], rel=1e-14)
    # a linear PSD y = f: integral of f from 2.25 to 3.75 = (3.75^2 - 2.25^2)/2 = 4.5
    ms = band_mean_square(f, f, np.array([2.25]), np.array([3.75]))
    assert ms == pytest.approx([4.5], rel=1e-14)


def test_consecutive_bands_add_up_to_the_trapezoid_over_their_union():
    rng = np.random.default_rng(16)
    f = np.sort(rng.uniform(1.0, 200.0, 500))
    y = rng.uniform(0.0, 1.0, (500, 3))
    bands = third_octave_bands(f[0], f[-1])
    ms = band_mean_square(f, y, bands.lower, bands.upper, axis=0)
    union = band_mean_square(f, y, bands.lower[:1], bands.upper[-1:], axis=0)
    assert ms.sum(axis=0) == pytest.approx(union[0], rel=1e-12)  # summation rounding only


def test_band_outside_the_grid_is_refused():
    f = np.linspace(1.0, 100.0, 100)
    with pytest.raises(ValueError, match="outside the grid"):
        band_mean_square(f, np.ones_like(f), np.array([0.8]), np.array([1.2]))


def test_levels_use_their_reference():
    assert level_db(1e-12, 1e-6) == pytest.approx(0.0, abs=1e-12)
    assert level_db(1.0, 1e-6) == pytest.approx(120.0, rel=1e-14)
    assert level_db(0.0, 1.0) == -np.inf


def test_band_edge_ratio():
    assert BAND_EDGE_RATIO**2 == pytest.approx(10**0.1, rel=1e-15)
