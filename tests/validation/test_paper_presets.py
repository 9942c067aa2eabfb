"""The paper's presets: shared tables stay identical, the pad values are the paper's."""

import pytest

from railvib import load_preset_case
from railvib.pads import pad_from_dict
from railvib.presets import load_preset

BASE = "wang2017_metro"
FREQDEP = ("wang2017_freqdep_20c", "wang2017_temp_m30c", "wang2017_temp_m10c", "wang2017_temp_p20c")
PREDICTED = ("wang2017_predicted_m30c", "wang2017_predicted_m10c", "wang2017_predicted_p20c")


@pytest.mark.parametrize("name", FREQDEP + PREDICTED)
def test_only_pad_title_and_temperature_differ_from_base(name):
    base, other = load_preset(BASE), load_preset(name)
    for d in (base, other):
        d.pop("title")
        d["track"].pop("pad")
        d["track"].pop("pad_temperature_c")
    assert other == base


@pytest.mark.parametrize("name", FREQDEP)
def test_frequency_dependent_pads_are_the_papers_law(name):
    # Section 3.2.3: kappa = 0.07 for WJ-7; f0 = 5 Hz (the upper end of "3-5 Hz");
    # the same viscous damping as Table 2's constant case.
    pad = load_preset_case(name).track.pad
    assert pad["model"] == "log_linear"
    assert pad["exponent"] == 0.07
    assert pad["f0_hz"] == 5.0
    assert pad["damping_ns_per_m"] == load_preset_case(BASE).track.pad["damping_ns_per_m"]


def test_freqdep_20c_equals_constant_case_at_f0():
    # Figs. 9-12 compare at equal stiffness at f0 (K0 = Table 2's 50 kN/mm).
    k_fd = pad_from_dict(load_preset_case("wang2017_freqdep_20c").track.pad).stiffness(5.0)
    k_c = pad_from_dict(load_preset_case(BASE).track.pad).stiffness(5.0)
    assert complex(k_fd) == pytest.approx(complex(k_c), rel=1e-12)


def test_temperature_series_colder_is_stiffer():
    # Section 3.2.3 values 31.0 / 45.2 / 70.8 kN/mm, paired physically: colder is stiffer.
    k0 = {n: load_preset_case(n).track.pad["k0_n_per_m"] for n in FREQDEP[1:]}
    temps = {n: load_preset_case(n).track.pad_temperature_c for n in FREQDEP[1:]}
    assert temps == {
        "wang2017_temp_m30c": -30.0,
        "wang2017_temp_m10c": -10.0,
        "wang2017_temp_p20c": 20.0,
    }
    assert k0 == {
        "wang2017_temp_m30c": 70.8e6,
        "wang2017_temp_m10c": 45.2e6,
        "wang2017_temp_p20c": 31.0e6,
    }
