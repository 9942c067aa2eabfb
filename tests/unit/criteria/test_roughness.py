"""Roughness levels in one-third-octave wavelength bands <-> railvib's wavenumber PSD."""

import numpy as np
import pytest

import railvib
from railvib.errors import CaseError
from railvib.spectra import SPECTRA, Combined, ISO3095Limit, RoughnessLevels, Sato
from railvib.spectra.roughness import (
    ISO3095_LIMIT,
    band_width_rad_per_m,
    contact_filter,
    level_to_psd,
    psd_to_level,
)

#: ISO 3095:2013, Figure 2: the levels printed beside its points, dB re 1 um, 40 cm to 0.315 cm
FIGURE_2_CM = [
    40, 31.5, 25, 20, 16, 12.5, 10, 8, 6.3, 5, 4, 3.15, 2.5, 2, 1.6, 1.25, 1, 0.8, 0.63, 0.5,
    0.4, 0.315,
]  # fmt: skip
FIGURE_2_DB = [
    17.1, 15.0, 13.0, 11.0, 9.0, 7.0, 4.9, 2.9, 0.9, -1.1, -3.2, -5.0, -5.6, -6.2, -6.8, -7.4,
    -8.0, -8.6, -9.2, -9.8, -10.4, -11.0,
]  # fmt: skip


def test_round_trip_level_psd_level():
    rng = np.random.default_rng(3095)
    lam = 10.0 ** rng.uniform(-3, 0, 50)
    level = rng.uniform(-30.0, 30.0, 50)
    back = psd_to_level(lam, level_to_psd(lam, level))
    assert np.max(np.abs(back - level)) < 1e-12  # dB: rounding of log10/10** only


def test_a_band_of_constant_psd_holds_the_level():
    # S constant across the band: r_rms^2 = S * width; 0 dB re 1 um means r_rms = 1 um
    lam = 0.05
    s = level_to_psd([lam], [0.0])[0]
    om_c = 2 * np.pi / lam
    width = om_c * (10**0.05 - 10**-0.05)
    assert s * width == pytest.approx(1e-12, rel=1e-13)
    assert band_width_rad_per_m([lam])[0] == pytest.approx(width, rel=1e-15)


def test_iso_3095_limit_values_as_printed():
    assert [round(100 * w, 3) for w, _ in ISO3095_LIMIT] == FIGURE_2_CM
    assert [lv for _, lv in ISO3095_LIMIT] == FIGURE_2_DB


def test_iso_3095_limit_spectrum_gives_the_printed_levels_at_the_band_centres():
    spectrum = SPECTRA.get("iso3095_limit").build()
    lam = np.array(FIGURE_2_CM) / 100.0
    levels = psd_to_level(lam, spectrum.psd(2 * np.pi / lam))
    assert levels == pytest.approx(FIGURE_2_DB, abs=1e-9)  # interpolation at its nodes


def test_roughness_table_is_zero_outside_its_bands_and_serves_as_the_short_wave_part():
    measured = RoughnessLevels(wavelength_m=(0.1, 0.01, 0.001), level_db=(5.0, -5.0, -15.0))
    om = 2 * np.pi / np.array([1.0, 0.1, 0.01, 0.001, 1e-4])
    s = measured.psd(om)
    assert s[0] == 0.0
    assert s[-1] == 0.0
    assert psd_to_level([0.1, 0.01, 0.001], s[1:4]) == pytest.approx([5.0, -5.0, -15.0], abs=1e-9)
    combined = Combined(long_wave=Sato(), short_wave=measured, split_wavelength_m=0.1)
    assert combined.psd(om[2:4]) == pytest.approx(s[2:4], rel=1e-14)  # below the split: the table
    assert combined.psd(om[:1]) == pytest.approx(Sato().psd(om[:1]), rel=1e-14)


def test_contact_filter_closed_form():
    a = 5e-3
    assert contact_filter([1e-3], a)[0] == pytest.approx(1.0, abs=1e-9)  # long waves pass
    # first zero where Omega a = pi: the wavelength equals the contact length 2a
    assert contact_filter([np.pi / a], a)[0] == pytest.approx(0.0, abs=1e-30)
    x = 1.3
    assert contact_filter([x / a], a)[0] == pytest.approx((np.sin(x) / x) ** 2, rel=1e-14)
    filtered = ISO3095Limit(contact_half_length_m=a)
    om = np.array([2 * np.pi / 0.05])
    assert filtered.psd(om) == pytest.approx(ISO3095Limit().psd(om) * contact_filter(om, a))


def test_mismatched_table_is_refused_with_the_field():
    with pytest.raises(CaseError, match="level_db"):
        RoughnessLevels(wavelength_m=(0.1, 0.01), level_db=(1.0,))


def test_case_file_can_name_the_limit_spectrum():
    case = railvib.case_from_dict(
        {
            "preset": "wang2017_metro",
            "irregularity": {
                "type": "combined",
                "long_wave": {"type": "sato"},
                "short_wave": {"type": "iso3095_limit"},
                "split_wavelength_m": 0.4,
            },
        }
    )
    spectrum = railvib.case.build_spectrum(case)
    assert isinstance(spectrum.short_wave, ISO3095Limit)
