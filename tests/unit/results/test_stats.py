"""Summary statistics of one-sided PSDs against closed forms.

RMS = sqrt(integral of the PSD over f). The trapezoidal rule is exact for PSDs that are
piecewise linear between grid points (constants, ramps, hats with grid-point corners),
so the expected values below are exact integrals and only rounding separates them.
"""

import math

import numpy as np
import pytest
import xarray as xr

from railvib.results import band_rms, dominant_frequency, peak, summary

EPS = np.finfo(float).eps


def _psd(f, columns, labels=None, units="(m/s^2)^2/Hz"):
    """A (frequency, response) DataArray from a list of 1-D columns."""
    labels = labels or [f"r{i}" for i in range(len(columns))]
    return xr.DataArray(
        np.stack(columns, axis=1),
        dims=("frequency", "response"),
        coords={"frequency": np.asarray(f, dtype=float), "response": labels},
        attrs={"units": units, "long_name": "test PSD"},
    )


# ------------------------------------------------------------------------- band RMS


def test_flat_psd_rms_is_sqrt_s0_times_bandwidth():
    f1, f2 = 2.0, 10.0
    f = f1 + 0.125 * np.arange(65)  # 2 ... 10, binary-exact nodes
    s0, s1 = 3.0e-3, 0.5
    psd = _psd(f, [np.full_like(f, s0), np.full_like(f, s1)])
    rms = band_rms(psd)
    assert rms.dims == ("response",)
    # trapezoid of a constant is exact; 64 rounded additions: ~64 eps worst, 1e-14
    np.testing.assert_allclose(
        rms.values, [math.sqrt(s0 * (f2 - f1)), math.sqrt(s1 * (f2 - f1))], rtol=1e-14, atol=0
    )


def test_flat_psd_rms_over_a_sub_band_on_grid_points():
    f = 2.0 + 0.125 * np.arange(65)
    s0 = 3.0e-3
    psd = _psd(f, [np.full_like(f, s0)])
    # [4, 6] are grid points: the in-band trapezoid spans exactly 2 Hz; rounding, 1e-14
    np.testing.assert_allclose(
        band_rms(psd, (4.0, 6.0)).values, [math.sqrt(2.0 * s0)], rtol=1e-14, atol=0
    )


def test_linear_psd_variance_is_a_f_max_squared_over_two():
    a, f_max = 0.7, 20.0
    f = np.linspace(0.0, f_max, 1001)
    psd = _psd(f, [a * f])
    # the trapezoid rule is exact for a linear integrand; the 1000-term sum and the
    # rounded linspace nodes leave ~1e-15, 1e-13 keeps a wide margin
    np.testing.assert_allclose(band_rms(psd).values ** 2, [a * f_max**2 / 2.0], rtol=1e-13, atol=0)


def test_linear_psd_over_a_band_not_starting_at_zero():
    a = 2.0
    f = 0.25 * np.arange(81)  # 0 ... 20, binary exact
    psd = _psd(f, [a * f])
    lo, hi = 5.0, 12.5
    # integral of a f over [lo, hi] = a (hi^2 - lo^2) / 2, exact for the trapezoid;
    # 30 rounded additions: 1e-14
    np.testing.assert_allclose(
        band_rms(psd, (lo, hi)).values ** 2, [a * (hi**2 - lo**2) / 2.0], rtol=1e-14, atol=0
    )


def test_band_rms_of_a_psd_vanishing_outside_the_band_equals_whole_grid_rms():
    f = 0.5 * np.arange(1, 81)  # 0.5 ... 40
    lo, hi, apex, height = 10.0, 20.0, 14.0, 6.0
    # a hat that is zero at and outside lo and hi, with its corners on grid points
    hat = np.where(
        f <= apex, height * (f - lo) / (apex - lo), height * (hi - f) / (hi - apex)
    ).clip(min=0.0)
    psd = _psd(f, [hat, 3.0 * hat])
    whole = band_rms(psd).values
    band = band_rms(psd, (lo, hi)).values
    # the same nonzero trapezoids, summed in a different (pairwise) order: 1e-15
    np.testing.assert_allclose(band, whole, rtol=1e-15, atol=0)
    # and both equal the hat's area height*(hi - lo)/2 (exact for the trapezoid): 1e-14
    area = height * (hi - lo) / 2.0
    np.testing.assert_allclose(whole, np.sqrt([area, 3.0 * area]), rtol=1e-14, atol=0)


def test_whole_grid_trapezoid_includes_the_ramps_at_the_band_edges():
    # a flat S0 on [lo, hi] and zero elsewhere: the whole-grid trapezoid adds two
    # half-cells S0*df/2 (ramps from 0 to S0), the in-band one does not
    df, s0 = 0.5, 4.0
    f = df * np.arange(1, 81)
    lo, hi = 10.0, 20.0
    psd = _psd(f, [np.where((f >= lo) & (f <= hi), s0, 0.0)])
    # all numbers are binary exact and the sums short: 1e-14
    np.testing.assert_allclose(
        band_rms(psd, (lo, hi)).values ** 2, [s0 * (hi - lo)], rtol=1e-14, atol=0
    )
    np.testing.assert_allclose(
        band_rms(psd).values ** 2, [s0 * (hi - lo) + s0 * df], rtol=1e-14, atol=0
    )


def test_band_rms_keeps_non_frequency_coordinates():
    f = np.arange(1.0, 11.0)
    psd = _psd(f, [np.ones(10), np.ones(10)], labels=["carbody.bounce", "rail@wheel1"])
    psd = psd.assign_coords(displacement_unit=("response", ["m", "m"]))
    rms = band_rms(psd)
    assert list(rms["response"].values) == ["carbody.bounce", "rail@wheel1"]
    assert list(rms["displacement_unit"].values) == ["m", "m"]
    assert "frequency" not in rms.coords


# -------------------------------------------------------- peak, dominant frequency


def _two_peaks():
    f = 0.5 * np.arange(1, 101)  # 0.5 ... 50
    g1, g2 = 0.75, 2.0
    # Lorentzians 1/((f - f0)^2 + g^2): maximum 1/g^2 exactly at f0 (a grid point)
    col_a = 1.0 / ((f - 5.0) ** 2 + g1**2) + 0.25 / ((f - 30.0) ** 2 + g2**2)
    col_b = 0.1 / ((f - 5.0) ** 2 + g1**2) + 1.0 / ((f - 30.0) ** 2 + g2**2)
    return f, col_a, col_b


def test_peak_and_dominant_frequency_of_known_maxima():
    f, col_a, col_b = _two_peaks()
    psd = _psd(f, [col_a, col_b], labels=["a", "b"])
    pk = peak(psd)
    fd = dominant_frequency(psd)
    assert pk.dims == ("response",)
    assert fd.dims == ("response",)
    assert "frequency" not in fd.coords
    np.testing.assert_array_equal(fd.values, [5.0, 30.0])
    # the peak is the input value at f0 (index 9 is 5 Hz, 59 is 30 Hz): exact, no arithmetic
    np.testing.assert_array_equal(pk.values, [col_a[9], col_b[59]])
    # and close to the Lorentzian maximum 1/g1^2 = 1.78: the other peak's tail there,
    # 0.25/(25^2 + 4) ~ 4e-4, is 2.2e-4 relative, inside 1e-3
    assert pk.values[0] == pytest.approx(1.0 / 0.75**2, rel=1e-3)


def test_peak_and_dominant_frequency_within_a_band():
    f, col_a, col_b = _two_peaks()
    psd = _psd(f, [col_a, col_b], labels=["a", "b"])
    band = (20.0, 40.0)  # excludes the 5 Hz peak of response a
    np.testing.assert_array_equal(dominant_frequency(psd, band).values, [30.0, 30.0])
    np.testing.assert_array_equal(peak(psd, band).values, [col_a[59], col_b[59]])


def test_band_edges_are_inclusive():
    f = np.arange(1.0, 11.0)
    s = np.zeros(10)
    s[3] = 2.0  # 4 Hz
    psd = _psd(f, [s])
    np.testing.assert_array_equal(dominant_frequency(psd, (4.0, 6.0)).values, [4.0])
    np.testing.assert_array_equal(peak(psd, (2.0, 4.0)).values, [2.0])


# ---------------------------------------------------------------------------- summary


def test_summary_variables_names_units_and_values():
    f = 2.0 + 0.125 * np.arange(65)  # 2 ... 10
    s0 = 3.0e-3
    ramp = 0.01 * f
    ds = xr.Dataset({"psd_acceleration": _psd(f, [np.full_like(f, s0), ramp], ["a", "b"])})
    out = summary(ds, bands=[(4.0, 6.0), (2.5, 8.0)])
    assert set(out.data_vars) == {"peak", "dominant_frequency", "rms", "rms_4_6_hz", "rms_2.5_8_hz"}
    for name, var in out.data_vars.items():
        assert var.dims == ("response",), name
        assert var.attrs.get("long_name"), name
    assert out["peak"].attrs["units"] == "(m/s^2)^2/Hz"
    assert out["dominant_frequency"].attrs["units"] == "Hz"
    for name in ("rms", "rms_4_6_hz", "rms_2.5_8_hz"):
        # sqrt of (m/s^2)^2/Hz * Hz
        assert out[name].attrs["units"] == "m/s^2"
    # peak and dominant frequency: the flat column ties, the first grid point wins
    # (argmax); the ramp peaks at its top end
    np.testing.assert_array_equal(out["peak"].values, [s0, 0.01 * 10.0])
    np.testing.assert_array_equal(out["dominant_frequency"].values, [2.0, 10.0])
    # closed forms (trapezoid exact for constants and ramps), rounding 1e-14
    np.testing.assert_allclose(
        out["rms"].values,
        [math.sqrt(s0 * 8.0), math.sqrt(0.01 * (10.0**2 - 2.0**2) / 2)],
        rtol=1e-14,
        atol=0,
    )
    np.testing.assert_allclose(
        out["rms_4_6_hz"].values,
        [math.sqrt(s0 * 2.0), math.sqrt(0.01 * (6.0**2 - 4.0**2) / 2)],
        rtol=1e-14,
        atol=0,
    )
    np.testing.assert_allclose(
        out["rms_2.5_8_hz"].values,
        [math.sqrt(s0 * 5.5), math.sqrt(0.01 * (8.0**2 - 2.5**2) / 2)],
        rtol=1e-14,
        atol=0,
    )


def test_summary_of_another_variable_has_units():
    f = np.arange(1.0, 11.0)
    ds = xr.Dataset({"psd_displacement": _psd(f, [np.ones(10)], units="m^2/Hz")})
    out = summary(ds, variable="psd_displacement", bands=[(1.0, 5.0)])
    assert out["peak"].attrs["units"] == "m^2/Hz"
    assert out["rms"].attrs["units"]  # some unit string for the RMS
    assert out["rms_1_5_hz"].attrs["units"] == out["rms"].attrs["units"]
    # flat 1 m^2/Hz over 9 Hz: sqrt(9) = 3 exactly (nine exact unit trapezoids)
    np.testing.assert_array_equal(out["rms"].values, [3.0])


# ------------------------------------------------------------------------ rejections


@pytest.mark.parametrize(
    "band",
    [
        pytest.param((10.2, 10.4), id="between-grid-points"),
        pytest.param((100.0, 200.0), id="above-grid"),
        pytest.param((0.01, 0.5), id="below-grid"),
        pytest.param((8.0, 2.0), id="reversed"),
    ],
)
@pytest.mark.parametrize("stat", [peak, dominant_frequency, band_rms])
def test_band_without_grid_points_raises(stat, band):
    psd = _psd(np.arange(1.0, 21.0), [np.ones(20)])
    with pytest.raises(ValueError, match="no grid frequency"):
        stat(psd, band)


def test_summary_with_an_empty_band_raises():
    ds = xr.Dataset({"psd_acceleration": _psd(np.arange(1.0, 21.0), [np.ones(20)])})
    with pytest.raises(ValueError, match="no grid frequency"):
        summary(ds, bands=[(2.0, 4.0), (10.2, 10.4)])
