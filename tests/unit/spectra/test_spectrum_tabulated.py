"""Tabulated spectrum: log-log interpolation, CSV reading and unit conversion."""

from __future__ import annotations

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.spectra import FRAClass, Tabulated

TWO_PI = 2.0 * np.pi

# FRA class 5 written out from its closed form (docs/spectra.md), in m^2/(rad/m).
A_V5, OMEGA_C = 0.2095, 0.8245


def fra5(om):
    return 1e-4 * 0.25 * A_V5 * OMEGA_C**2 / (om**2 * (om**2 + OMEGA_C**2))


# 50 samples per decade. Linear interpolation of g(x) = ln S(e^x) errs by at most
# h^2/8 max|g''|; for the FRA form g'' = -4 c^2 e^{2x} / (e^{2x} + c^2)^2, |g''| <= 1, so
# with h = ln(10)/50 the relative error is <= 2.7e-4 -> rtol 3e-4.
PER_DECADE = 50
RTOL_INTERP = 3e-4


def test_round_trip_from_fra_class5():
    om_tab = np.geomspace(0.02, 20.0, 3 * PER_DECADE + 1)
    tab = Tabulated(om_tab, fra5(om_tab))
    mid = np.sqrt(om_tab[:-1] * om_tab[1:])  # worst case: halfway between samples
    np.testing.assert_allclose(tab.psd(mid), FRAClass(5).psd(mid), rtol=RTOL_INTERP)
    # at the nodes the table is reproduced up to exp(log()) rounding
    np.testing.assert_allclose(tab.psd(om_tab), fra5(om_tab), rtol=1e-13)


def test_exact_for_power_law():
    # a pure power law is a straight line in log-log: interpolation exact to rounding
    om = np.array([1.0, 10.0, 100.0])
    tab = Tabulated(om, 3e-9 * om**-3.0)
    q = np.geomspace(1.0, 100.0, 17)
    np.testing.assert_allclose(tab.psd(q), 3e-9 * q**-3.0, rtol=1e-12)


def test_zero_outside_table():
    tab = Tabulated([1.0, 10.0], [1e-8, 1e-10])
    np.testing.assert_array_equal(tab.psd([0.999, 10.001, 1e3]), 0.0)
    assert tab.psd(1.0) == pytest.approx(1e-8, rel=1e-14)
    assert tab.psd(10.0) == pytest.approx(1e-10, rel=1e-14)


def test_unsorted_input_is_sorted():
    tab = Tabulated([10.0, 1.0], [1e-10, 1e-8])
    np.testing.assert_array_equal(tab.wavenumber_rad_per_m, [1.0, 10.0])
    np.testing.assert_array_equal(tab.psd_m2_per_rad_per_m, [1e-8, 1e-10])


def _write(path, header, rows):
    lines = [",".join(header)] + [",".join(repr(float(v)) for v in r) for r in rows]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_csv_wavelength_and_per_cycle(tmp_path):
    # wavelength column + per-cycle PSD: S(n) = 2 pi S(Omega) with n = 1 / lambda
    lam = np.geomspace(300.0, 0.3, 3 * PER_DECADE + 1)
    om = TWO_PI / lam
    p = _write(
        tmp_path / "t.csv",
        ["wavelength_m", "psd_m2_per_cycle_per_m"],
        zip(lam, TWO_PI * fra5(om), strict=True),
    )
    tab = Tabulated.from_csv(p)
    np.testing.assert_allclose(tab.psd(om), fra5(om), rtol=1e-13)
    mid = np.sqrt(om[:-1] * om[1:])
    np.testing.assert_allclose(tab.psd(mid), fra5(mid), rtol=RTOL_INTERP)


@pytest.mark.parametrize(
    ("x_col", "to_x"),
    [
        ("spatial_frequency_cycle_per_m", lambda om: om / TWO_PI),
        ("wavenumber_rad_per_m", lambda om: om),
    ],
)
def test_csv_other_abscissae(tmp_path, x_col, to_x):
    om = np.array([0.1, 1.0, 10.0])
    p = _write(
        tmp_path / "t.csv", [x_col, "psd_m2_per_rad_per_m"], zip(to_x(om), fra5(om), strict=True)
    )
    np.testing.assert_allclose(Tabulated.from_csv(p).psd(om), fra5(om), rtol=1e-13)


def test_csv_column_order_whitespace_and_delimiter(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text(" psd_m2_per_rad_per_m ; wavenumber_rad_per_m\n1e-8;1\n1e-10;10\n")
    tab = Tabulated.from_csv(p, delimiter=";")
    assert tab.psd(1.0) == pytest.approx(1e-8, rel=1e-14)


# --- rejections -----------------------------------------------------------------------


def test_reject_unknown_column(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("wavelength_m,psd_mm2\n1,1\n2,2\n")
    with pytest.raises(CaseError, match="psd_mm2"):
        Tabulated.from_csv(p)


def test_reject_missing_psd_column(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("wavelength_m\n1\n2\n")
    with pytest.raises(CaseError, match="psd_m2_per_cycle_per_m"):
        Tabulated.from_csv(p)


def test_reject_two_abscissae(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("wavelength_m,wavenumber_rad_per_m,psd_m2_per_rad_per_m\n1,6,1\n2,3,2\n")
    with pytest.raises(CaseError, match="exactly one of"):
        Tabulated.from_csv(p)


def test_reject_one_row(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("wavelength_m,psd_m2_per_rad_per_m\n1,1e-8\n")
    with pytest.raises(CaseError, match=">= 2"):
        Tabulated.from_csv(p)


@pytest.mark.parametrize(
    ("row", "match"),
    [
        ("0,1e-8", "wavelength_m = 0.0"),
        ("-1,1e-8", "wavelength_m = -1.0"),
        ("nan,1e-8", "wavelength_m = nan"),
        ("2,0", "psd_m2_per_rad_per_m = 0.0"),
        ("2,inf", "psd_m2_per_rad_per_m = inf"),
        ("2,abc", "numbers only"),
    ],
)
def test_reject_bad_cells(tmp_path, row, match):
    p = tmp_path / "t.csv"
    p.write_text(f"wavelength_m,psd_m2_per_rad_per_m\n1,1e-8\n{row}\n")
    with pytest.raises(CaseError, match=match):
        Tabulated.from_csv(p)


def test_reject_missing_file(tmp_path):
    with pytest.raises(CaseError, match="path = .*nope.csv"):
        Tabulated.from_csv(tmp_path / "nope.csv")


@pytest.mark.parametrize(
    ("om", "s", "match"),
    [
        ([1.0], [1e-8], "wavenumber_rad_per_m = .*>= 2 rows"),
        ([1.0, 2.0], [1e-8], "psd_m2_per_rad_per_m = .*shape"),
        ([1.0, 1.0], [1e-8, 1e-9], "distinct"),
        ([1.0, -2.0], [1e-8, 1e-9], r"wavenumber_rad_per_m = -2\.0"),
        ([1.0, 2.0], [1e-8, np.nan], "psd_m2_per_rad_per_m = nan"),
        ([1.0, 2.0], [1e-8, -1e-9], "psd_m2_per_rad_per_m = -1e-09"),
    ],
)
def test_reject_bad_arrays(om, s, match):
    with pytest.raises(CaseError, match=match):
        Tabulated(om, s)
