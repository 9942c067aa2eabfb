"""Case files: every rejection names the field, the value and what is allowed."""

import re

import pytest

import railvib
from railvib.case import case_from_dict, load_case
from railvib.case.template import render_template
from railvib.errors import CaseError


def _case(**overrides):
    return {"preset": "wang2017_metro", **overrides}


def test_preset_loads_and_template_round_trips(tmp_path):
    case = railvib.load_preset_case()
    assert case.vehicle.carbody_mass == 21920.0
    path = tmp_path / "t.toml"
    path.write_text(render_template())
    assert load_case(path) == case


@pytest.mark.parametrize(
    ("overrides", "message"),
    [
        ({"vehicle": {"carbody_mass": -1.0}}, "vehicle.carbody_mass = -1.0: must be > 0.0 (kg)"),
        ({"vehicle": {"bogie_mass": 0}}, "vehicle.bogie_mass = 0: must be > 0.0 (kg)"),
        ({"speed_kmh": 0.0}, "speed_kmh = 0.0: must be > 0.0 (km/h)"),
        ({"speed_kmh": "fast"}, "speed_kmh = 'fast': must be a number (km/h)"),
        ({"track": {"sleeper_spacing": -0.6}}, "track.sleeper_spacing = -0.6: must be > 0.0 (m)"),
        (
            {"track": {"rail": {"bending_stiffness": 0.0}}},
            "track.rail.bending_stiffness = 0.0: must be > 0.0 (N m^2)",
        ),
        (
            {"track": {"pad": {"stiffness_n_per_m": -5e7}}},
            "track.pad.stiffness_n_per_m = -50000000.0",
        ),
        ({"vehicle": {"wheel_mass": 3.0}}, "vehicle.wheel_mass = 3.0: unknown key; allowed here:"),
        ({"colour": "red"}, "colour = 'red': unknown key"),
        ({"frequency": {"f_min": 10.0, "f_max": 5.0}}, "frequency.f_max = 5.0: must be > f_min"),
        ({"frequency": {"f_min": -1.0}}, "frequency.f_min = -1.0: must be > 0.0 (Hz)"),
        ({"frequency": {"spacing": "log", "step": None}}, "frequency.n = None: required"),
        ({"rail_model": "three_rails"}, "rail_model = 'three_rails': must be one of"),
        (
            {"contact": {"leading_wheel_position": -0.1}},
            "contact.leading_wheel_position = -0.1: must be >= 0.0 (m)",
        ),
        ({"irregularity": {"type": "fra", "class_number": 9}}, "irregularity.class_number = 9"),
        ({"track": {"pad": {"model": "rubber_duck"}}}, "track.pad.model = 'rubber_duck'"),
        (
            {"vehicle": {"wheelset_half_spacing": 7.0}},
            "vehicle.wheelset_half_spacing = 7.0: must be < bogie_half_spacing = 6.3 (m)",
        ),
    ],
)
def test_rejections_name_field_value_and_allowed(overrides, message):
    with pytest.raises(CaseError, match=re.escape(message)):
        case_from_dict(_case(**overrides))


def test_missing_value_is_rejected():
    data = railvib.presets.load_preset("wang2017_metro")
    del data["vehicle"]["wheelset_mass"]
    with pytest.raises(
        CaseError, match=re.escape("vehicle.wheelset_mass = '<missing>': required (kg)")
    ):
        case_from_dict(data)


def test_leading_wheel_beyond_spacing_is_rejected():
    case = case_from_dict(_case(contact={"leading_wheel_position": 0.6}))
    with pytest.raises(
        CaseError, match=re.escape("contact.leading_wheel_position = 0.6: must be in [0, 0.6) (m)")
    ):
        railvib.build_system(case)


def test_bad_toml_and_missing_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("speed_kmh = = 3")
    with pytest.raises(CaseError, match="valid TOML"):
        load_case(bad)
    with pytest.raises(CaseError, match="readable TOML case file"):
        load_case(tmp_path / "nope.toml")


def test_rail_pair_mode_doubles_beam_pads_and_contact():
    single = railvib.build_system(railvib.load_preset_case())
    pair = railvib.build_system(case_from_dict(_case(rail_model="rail_pair")))
    assert pair.track.rail.bending_stiffness == 2 * single.track.rail.bending_stiffness
    assert pair.track.rail.mass_per_length == 2 * single.track.rail.mass_per_length
    assert pair.contact_stiffness == pytest.approx(2 * single.contact_stiffness)
    k1 = single.track.pad.stiffness([10.0])
    k2 = pair.track.pad.stiffness([10.0])
    assert k2[0] == pytest.approx(2 * k1[0])
    # docs/reference-values.md §1: k_H at the 40.10 kN wheel load is 9.873e8 N/m
    assert single.contact_stiffness == pytest.approx(9.873e8, rel=1e-3)


def test_presets_nest_and_cycles_are_refused(monkeypatch):
    import railvib.presets as presets

    texts = {
        "a": 'preset = "b"\ntitle = "A"\n',
        "b": 'preset = "wang2017_metro"\nspeed_kmh = 60.0\n',
        "c": 'preset = "d"\n',
        "d": 'preset = "c"\n',
        "wang2017_metro": presets.preset_text("wang2017_metro"),
    }
    monkeypatch.setattr(presets, "preset_text", lambda name: texts[name])
    data = presets.load_preset("a")
    assert (data["title"], data["speed_kmh"]) == ("A", 60.0)
    assert data["vehicle"]["carbody_mass"] == 21920.0
    with pytest.raises(
        CaseError, match=re.escape("preset = 'c': no cycle of presets (c -> d -> c)")
    ):
        presets.load_preset("c")


def test_timoshenko_rail_from_case_file():
    rail = {"shear_stiffness": 2.447e8, "rotary_inertia": 0.2525}
    case = case_from_dict(_case(track={"rail": rail}))
    track = railvib.build_system(case).track
    assert track.rail.is_timoshenko
    assert (track.rail.shear_stiffness, track.rail.rotary_inertia) == (2.447e8, 0.2525)
    pair = railvib.build_system(case_from_dict(_case(rail_model="rail_pair", track={"rail": rail})))
    assert pair.track.rail.shear_stiffness == 2 * 2.447e8
    assert pair.track.rail.rotary_inertia == 2 * 0.2525
    with pytest.raises(
        CaseError, match=re.escape("track.rail.shear_stiffness = 0.0: must be > 0.0 (N)")
    ):
        case_from_dict(_case(track={"rail": {"shear_stiffness": 0.0}}))
