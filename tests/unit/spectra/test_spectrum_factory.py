"""spectrum_from_dict, PAPER_SPECTRUM_DICT, and the parameter validation of every class."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.spectra import (
    PAPER_SPECTRUM_DICT,
    ChineseHSR,
    Combined,
    FRAClass,
    GermanVertical,
    Sato,
    ShiTai,
    Tabulated,
    spectrum_from_dict,
)

TWO_PI = 2.0 * np.pi


def test_paper_dict_builds_the_paper_recipe():
    spec = spectrum_from_dict(PAPER_SPECTRUM_DICT)
    assert spec == Combined(FRAClass(5), ShiTai(), split_wavelength_m=1.0)
    assert PAPER_SPECTRUM_DICT == {
        "type": "combined",
        "long_wave": {"type": "fra", "class_number": 5},
        "short_wave": {"type": "shitai"},
        "split_wavelength_m": 1.0,
    }


@pytest.mark.parametrize(
    ("d", "expected"),
    [
        ({"type": "fra", "class_number": 3}, FRAClass(3)),
        ({"type": "shitai"}, ShiTai()),
        ({"type": "shitai", "coefficient": 0.05, "exponent": 3.0}, ShiTai(0.05, 3.0)),
        ({"type": "sato", "coefficient": 5e-7}, Sato(5e-7)),
        ({"type": "sato"}, Sato()),
        ({"type": "german", "level": "low"}, GermanVertical("low")),
        ({"type": "chinese_hsr"}, ChineseHSR()),
        ({"type": "chinese_hsr", "extrapolate": True}, ChineseHSR(extrapolate=True)),
        (
            {
                "type": "combined",
                "long_wave": {"type": "german", "level": "high"},
                "short_wave": {"type": "sato"},
                "split_wavelength_m": 2,
                "blend_decades": 0.3,
            },
            Combined(GermanVertical("high"), Sato(), 2.0, 0.3),
        ),
    ],
)
def test_builds_each_type(d, expected):
    assert spectrum_from_dict(d) == expected


def test_tabulated_from_path_and_arrays(tmp_path):
    p = tmp_path / "x.csv"
    p.write_text("wavenumber_rad_per_m,psd_m2_per_rad_per_m\n1,1e-8\n10,1e-11\n")
    for spec in (
        spectrum_from_dict({"type": "tabulated", "path": str(p)}),
        spectrum_from_dict(
            {
                "type": "tabulated",
                "wavenumber_rad_per_m": [1, 10],
                "psd_m2_per_rad_per_m": [1e-8, 1e-11],
            }
        ),
    ):
        assert isinstance(spec, Tabulated)
        # power law 1e-8 Omega^-3 between the nodes -> exact up to rounding
        assert spec.psd(TWO_PI) == pytest.approx(1e-8 * TWO_PI**-3, rel=1e-12)


def test_input_dict_not_mutated():
    d = copy.deepcopy(PAPER_SPECTRUM_DICT)
    spectrum_from_dict(d)
    assert d == PAPER_SPECTRUM_DICT


@pytest.mark.parametrize(
    ("d", "match"),
    [
        ({"type": "fft"}, r"irregularity\.type = 'fft'"),
        ({"class_number": 5}, r"irregularity\.type = None: required"),
        ([1, 2], r"irregularity = \[1, 2\]"),
        ({"type": "fra"}, r"irregularity\.class_number = None: required"),
        ({"type": "fra", "class_number": 5, "grade": 1}, r"irregularity\.grade = 1: unknown key"),
        ({"type": "fra", "class_number": 7}, r"irregularity\.class_number = 7"),
        (
            {
                "type": "combined",
                "long_wave": {"type": "fra", "class_number": 0},
                "short_wave": {"type": "shitai"},
            },
            r"irregularity\.long_wave\.class_number = 0",
        ),
        (
            {
                "type": "combined",
                "long_wave": {"type": "fra", "class_number": 5},
                "short_wave": {"type": "shitai", "exponent": -1},
            },
            r"irregularity\.short_wave\.exponent = -1",
        ),
        (
            {"type": "combined", "long_wave": {"type": "fra", "class_number": 5}},
            r"irregularity\.short_wave = None: required",
        ),
        (
            {
                "type": "combined",
                "long_wave": {"type": "fra", "class_number": 5},
                "short_wave": {"type": "shitai"},
                "split_wavelength_m": 0.0,
            },
            r"irregularity\.split_wavelength_m = 0\.0",
        ),
        ({"type": "german", "level": "medium"}, r"irregularity\.level = 'medium'"),
        ({"type": "tabulated"}, r"irregularity = \[\]: either 'path'"),
        ({"type": "tabulated", "path": "/nonexistent/x.csv"}, r"irregularity\.path"),
        (
            {"type": "tabulated", "wavenumber_rad_per_m": [1.0, 2.0]},
            r"irregularity\.psd_m2_per_rad_per_m = None",
        ),
    ],
)
def test_from_dict_rejections(d, match):
    with pytest.raises(CaseError, match=match):
        spectrum_from_dict(d)


def test_field_prefix_is_used():
    with pytest.raises(CaseError, match=r"case\.track\.profile\.class_number = 9"):
        spectrum_from_dict({"type": "fra", "class_number": 9}, field="case.track.profile")


def test_unknown_csv_column_named_through_dict(tmp_path):
    p = tmp_path / "x.csv"
    p.write_text("wavelength_m,psd_cm2\n1,1\n2,1\n")
    with pytest.raises(CaseError, match=r"irregularity\.column = 'psd_cm2'"):
        spectrum_from_dict({"type": "tabulated", "path": str(p)})


# --- direct constructor rejections -------------------------------------------------------


@pytest.mark.parametrize("bad", [0, 7, -1, 5.0, True, "5", None])
def test_fra_rejects_class(bad):
    with pytest.raises(CaseError, match=r"class_number = .*1, 2, 3, 4, 5 or 6"):
        FRAClass(bad)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"coefficient": 0.0}, r"coefficient = 0\.0: a finite number > 0"),
        ({"coefficient": -0.036}, r"coefficient = -0\.036"),
        ({"exponent": float("nan")}, r"exponent = nan"),
        ({"exponent": "3.15"}, r"exponent = '3\.15'"),
    ],
)
def test_shitai_rejects(kwargs, match):
    with pytest.raises(CaseError, match=match):
        ShiTai(**kwargs)


@pytest.mark.parametrize("bad", [0.0, -4.15e-8, float("inf"), None])
def test_sato_rejects(bad):
    with pytest.raises(CaseError, match=r"coefficient = .*> 0"):
        Sato(bad)


@pytest.mark.parametrize("bad", ["medium", "LOW", 1, None])
def test_german_rejects(bad):
    with pytest.raises(CaseError, match=r"level = .*'low' or 'high'"):
        GermanVertical(bad)


def test_chinese_rejects_non_bool():
    with pytest.raises(CaseError, match=r"extrapolate = 'yes'"):
        ChineseHSR(extrapolate="yes")


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"split_wavelength_m": 0.0}, r"split_wavelength_m = 0\.0"),
        ({"split_wavelength_m": float("nan")}, r"split_wavelength_m = nan"),
        ({"blend_decades": -0.1}, r"blend_decades = -0\.1: a finite number >= 0"),
        ({"blend_decades": float("inf")}, r"blend_decades = inf"),
    ],
)
def test_combined_rejects_numbers(kwargs, match):
    with pytest.raises(CaseError, match=match):
        Combined(FRAClass(5), ShiTai(), **kwargs)


def test_combined_rejects_non_spectrum():
    with pytest.raises(CaseError, match=r"long_wave = .*SpatialSpectrum"):
        Combined({"type": "fra"}, ShiTai())
    with pytest.raises(CaseError, match=r"short_wave = 3"):
        Combined(FRAClass(5), 3)


@pytest.mark.parametrize("bad", [0.0, -1.0, np.nan, np.inf])
def test_psd_rejects_non_positive_wavenumber(bad):
    for spec in (
        FRAClass(5),
        ShiTai(),
        Sato(),
        GermanVertical("low"),
        ChineseHSR(),
        Combined(FRAClass(5), ShiTai()),
        Tabulated([1.0, 2.0], [1e-8, 1e-9]),
    ):
        with pytest.raises(CaseError, match=r"wavenumber = .*> 0 \(rad/m\)"):
            spec.psd(np.array([1.0, bad]))


@pytest.mark.parametrize("bad", [0.0, -22.2, np.nan])
def test_temporal_rejects_bad_speed(bad):
    with pytest.raises(CaseError, match=r"speed = "):
        FRAClass(5).temporal(10.0, bad)


def test_frozen():
    spec = FRAClass(5)
    with pytest.raises(AttributeError):
        spec.class_number = 4  # type: ignore[misc]
