"""pad_from_dict: every model from a plain dict, and one-line rejections naming the field."""

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.pads import (
    WLF,
    FractionalZener,
    GeneralizedMaxwell,
    SpringDamper,
    TemperatureShifted,
    load_pad_toml,
    pad_from_dict,
    pad_toml,
)


def test_spring_damper_from_dict():
    pad = pad_from_dict(
        {"model": "spring_damper", "stiffness_n_per_m": 5e7, "damping_ns_per_m": 5e4}
    )
    assert pad == SpringDamper(5e7, 5e4)


def test_aliases_and_tts_with_glass_transition():
    d = {
        "model": "zener",
        "k0_n_per_m": 3e7,
        "k_inf_n_per_m": 3e8,
        "tau_s": 1e-6,
        "alpha": 0.4,
        "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -40.0},
    }
    pad = pad_from_dict(d)
    assert isinstance(pad, TemperatureShifted)
    assert isinstance(pad.base, FractionalZener)
    assert pad.wlf.c1 == 17.44
    assert pad.wlf.reference_temperature_c == -40.0
    assert pad.vertical_shift is True
    assert pad.storage(10.0, -30.0) > pad.storage(10.0, 20.0)
    prony = pad_from_dict(
        {"model": "prony", "k_inf_n_per_m": 1e7, "k_n_per_m": [1e7, 2], "tau_s": [1, 2]}
    )
    assert isinstance(prony, GeneralizedMaxwell)
    assert prony.tau_s == (1.0, 2.0)


@pytest.mark.parametrize(
    ("d", "field", "text"),
    [
        ({"model": "rubber"}, "track.pad.model", "one of spring_damper"),
        ({"stiffness_n_per_m": 1.0}, "track.pad.model", "missing"),
        ({"model": "log_linear"}, "track.pad.k0_n_per_m", "missing"),
        ({"model": "log_linear", "k0_n_per_m": 3e7, "k0": 1}, "track.pad.k0", "unknown key"),
        ({"model": "log_linear", "k0_n_per_m": "3e7"}, "track.pad.k0_n_per_m", "finite number"),
        ({"model": "log_linear", "k0_n_per_m": True}, "track.pad.k0_n_per_m", "finite number"),
        ({"model": "log_linear", "k0_n_per_m": -3e7}, "track.pad.k0_n_per_m", "must be > 0"),
        (
            {"model": "log_linear", "k0_n_per_m": 3e7, "hold_below_f0": 1},
            "track.pad.hold_below_f0",
            "true or false",
        ),
        (
            {"model": "spring_damper", "stiffness_n_per_m": 5e7, "damping_ns_per_m": -1.0},
            "track.pad.damping_ns_per_m",
            ">= 0",
        ),
        (
            {"model": "hysteretic", "stiffness_n_per_m": 5e7, "loss_factor": -0.1},
            "track.pad.loss_factor",
            ">= 0",
        ),
        (
            {
                "model": "fractional_zener",
                "k0_n_per_m": 3e8,
                "k_inf_n_per_m": 3e7,
                "tau_s": 1e-3,
                "alpha": 0.5,
            },
            "track.pad.k_inf_n_per_m",
            "loss factor is negative",
        ),
        (
            {
                "model": "fractional_zener",
                "k0_n_per_m": 3e7,
                "k_inf_n_per_m": 3e8,
                "tau_s": 1e-3,
                "alpha": 1.5,
            },
            "track.pad.alpha",
            "(0, 1]",
        ),
        (
            {
                "model": "generalized_maxwell",
                "k_inf_n_per_m": 3e7,
                "k_n_per_m": [1e7, -1e6],
                "tau_s": [1e-3, 1e-4],
            },
            "track.pad.k_n_per_m[1]",
            ">= 0",
        ),
        (
            {
                "model": "generalized_maxwell",
                "k_inf_n_per_m": 3e7,
                "k_n_per_m": [1e7],
                "tau_s": [1e-3, 1e-4],
            },
            "track.pad.tau_s",
            "one relaxation time per branch",
        ),
        (
            {
                "model": "spring_damper",
                "stiffness_n_per_m": 5e7,
                "tts": {"glass_transition_c": -40},
            },
            "track.pad.tts.reference_temperature_c",
            "missing",
        ),
        (
            {
                "model": "spring_damper",
                "stiffness_n_per_m": 5e7,
                "tts": {"reference_temperature_c": 20.0},
            },
            "track.pad.tts",
            "either glass_transition_c",
        ),
        (
            {
                "model": "spring_damper",
                "stiffness_n_per_m": 5e7,
                "tts": {"reference_temperature_c": 20.0, "c1": 8.0},
            },
            "track.pad.tts.c2_k",
            "missing",
        ),
        (
            {
                "model": "spring_damper",
                "stiffness_n_per_m": 5e7,
                "tts": {"reference_temperature_c": 20.0, "c1": -8.0, "c2_k": 100.0},
            },
            "track.pad.tts.c1",
            "> 0",
        ),
        (
            {
                "model": "spring_damper",
                "stiffness_n_per_m": 5e7,
                "tts": {"reference_temperature_c": -100.0, "glass_transition_c": -40.0},
            },
            "track.pad.tts.reference_temperature_c",
            "singular",
        ),
        (
            {
                "model": "spring_damper",
                "stiffness_n_per_m": 5e7,
                "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -40.0, "tg": 1},
            },
            "track.pad.tts.tg",
            "unknown key",
        ),
    ],
)
def test_rejections_name_the_field(d, field, text):
    with pytest.raises(CaseError) as err:
        pad_from_dict(d)
    assert err.value.field == field
    assert text in str(err.value)
    assert "\n" not in str(err.value)


def test_custom_field_prefix():
    with pytest.raises(CaseError) as err:
        pad_from_dict({"model": "fractional_zener"}, field="sweep.pad")
    assert err.value.field == "sweep.pad.k0_n_per_m"


def test_toml_round_trip(tmp_path):
    base = GeneralizedMaxwell(3e7, (1e7, 5e7), (1e-2, 1e-5))
    pad = TemperatureShifted(base, WLF(17.44, 51.6, -45.0), 20.0)
    path = tmp_path / "pad.toml"
    path.write_text(pad_toml(pad, header="fitted\nby hand"))
    text = path.read_text()
    assert text.startswith("# fitted\n# by hand\n[track.pad]")
    again = load_pad_toml(path)
    f = np.geomspace(1, 1000, 7)
    assert np.allclose(again.stiffness(f, -20.0), pad.stiffness(f, -20.0), rtol=1e-14)
