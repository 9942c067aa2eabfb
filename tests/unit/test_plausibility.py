"""Legal but suspicious input warns with one PlausibilityWarning naming the field; huge grids
are refused unless forced (issue 10: a new user's first hour)."""

import pickle
import re
import time
import warnings

import numpy as np
import pytest

import railvib
from railvib.case import case_from_dict, load_case
from railvib.case.plausibility import (
    MAX_FREQUENCIES,
    WARN_FREQUENCIES,
    grid_cost,
    grid_size,
)
from railvib.case.template import render_template
from railvib.errors import CaseError, PlausibilityWarning
from railvib.grid import FrequencyGrid
from railvib.pads import pad_from_dict
from railvib.presets import list_presets

SMALL_GRID = {"f_min": 1.0, "f_max": 50.0, "step": 1.0}
TTS_UNIVERSAL = {
    "model": "fractional_zener",
    "k0_n_per_m": 3.0e7,
    "k_inf_n_per_m": 6.0e8,
    "tau_s": 1.0e-7,
    "alpha": 0.35,
    "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -40.0},
}
TTS_GIVEN = {**TTS_UNIVERSAL, "tts": {"reference_temperature_c": 20.0, "c1": 8.0, "c2_k": 100.0}}


def _case(**overrides):
    return {"preset": "wang2017_metro", "frequency": SMALL_GRID, **overrides}


def _warnings(data, **kw):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        case_from_dict(data, **kw)
    return [w.message for w in seen if issubclass(w.category, PlausibilityWarning)]


def test_the_presets_and_the_template_load_without_warnings(tmp_path):
    # the first thing a new user runs must be quiet
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name in list_presets():
            case_from_dict({"preset": name})
        path = tmp_path / "case.toml"
        path.write_text(render_template())
        load_case(path)


@pytest.mark.parametrize(
    ("speed", "side"), [(5.0, "below"), (9.99, "below"), (451.0, "above"), (500.0, "above")]
)
def test_an_implausible_speed_warns_once_naming_the_field(speed, side):
    (w,) = _warnings(_case(speed_kmh=speed))
    assert str(w).startswith(f"speed_kmh = {speed!r}: {side} 10-450 km/h")
    assert (w.field, w.value) == ("speed_kmh", speed)
    assert "\n" not in str(w)


@pytest.mark.parametrize("speed", [10.0, 80.0, 350.0, 450.0])
def test_a_plausible_speed_is_quiet(speed):
    assert _warnings(_case(speed_kmh=speed)) == []


@pytest.mark.parametrize(
    ("stiffness", "text"),
    [(50.0, "below 1e6 N/m"), (9.9e5, "below 1e6 N/m"), (6e9, "above 5e9 N/m")],
)
def test_an_implausible_pad_stiffness_warns(stiffness, text):
    # 50 N/m: "50 kN/mm" typed without the unit conversion
    pad = {"model": "spring_damper", "stiffness_n_per_m": stiffness, "damping_ns_per_m": 5e4}
    (w,) = _warnings(_case(track={"pad": pad}))
    assert w.field == "track.pad"
    assert text in str(w)
    assert f"= {stiffness:.4g} N/m" in str(w)


def test_pad_stiffness_is_evaluated_on_the_grid():
    # K' = K0 (f / f0)^0.5 with K0 = 1.2 MN/m at 5 Hz: 0.54 MN/m at 1 Hz
    pad = {
        "model": "log_linear",
        "k0_n_per_m": 1.2e6,
        "f0_hz": 5.0,
        "exponent": 0.5,
        "hold_below_f0": False,
    }
    above_f0 = {"f_min": 5.0, "f_max": 50.0, "step": 1.0}
    assert _warnings(_case(frequency=above_f0, track={"pad": pad})) == []
    (w,) = _warnings(_case(track={"pad": pad}))  # from 1 Hz
    assert w.value == "K'(1 Hz) = 5.367e+05 N/m"


def test_pad_stiffness_is_evaluated_at_the_temperature():
    # a soft master curve: plausible at 20 degC, below 1 MN/m at 1 Hz when shifted to 60 degC
    soft = {**TTS_UNIVERSAL, "k0_n_per_m": 2.0e5}
    f = FrequencyGrid.linear(**SMALL_GRID).f
    assert pad_from_dict(soft).storage(f, 20.0).min() > 1e6
    assert pad_from_dict(soft).storage(f, 60.0).min() < 1e6
    assert _warnings(_case(track={"pad": soft, "pad_temperature_c": 20.0})) == []
    (w,) = _warnings(_case(track={"pad": soft, "pad_temperature_c": 60.0}))
    assert w.field == "track.pad"
    assert str(w.value).startswith("K'(1 Hz) = ")
    assert str(w.value).endswith(" N/m at 60 degC")


def test_a_temperature_the_pad_ignores_warns():
    (w,) = _warnings(_case(track={"pad_temperature_c": -30.0}))
    assert str(w).startswith(
        "track.pad_temperature_c = -30.0: ignored: pad model 'spring_damper' does not depend "
        "on temperature"
    )
    assert "[track.pad.tts]" in str(w)


def test_a_temperature_recorded_by_a_preset_or_at_room_temperature_is_quiet():
    # wang2017_temp_m30c records -30 degC for its log_linear pad (the temperature is in K0)
    assert _warnings({"preset": "wang2017_temp_m30c"}) == []
    assert _warnings(_case(track={"pad_temperature_c": 23.0})) == []


@pytest.mark.parametrize(
    ("pad", "temperature", "window"),
    [
        (TTS_UNIVERSAL, 400.0, "-40 to 60 degC"),  # Tg + 100 K
        (TTS_UNIVERSAL, 61.0, "-40 to 60 degC"),
        (TTS_UNIVERSAL, -45.0, "-40 to 60 degC"),  # glassy: below Tg
        (TTS_GIVEN, 400.0, "-60 to 100 degC"),  # T_ref +- 80 K, Tg unknown
        (TTS_GIVEN, -61.0, "-60 to 100 degC"),
    ],
)
def test_a_temperature_outside_the_wlf_range_warns(pad, temperature, window):
    found = _warnings(_case(track={"pad": pad, "pad_temperature_c": temperature}))
    (w,) = [w for w in found if w.field == "track.pad_temperature_c"]
    assert str(w).startswith(f"track.pad_temperature_c = {temperature!r}: outside {window}")


@pytest.mark.parametrize(
    ("pad", "temperature"),
    [(TTS_UNIVERSAL, -40.0), (TTS_UNIVERSAL, 60.0), (TTS_GIVEN, -60.0), (TTS_GIVEN, 100.0)],
)
def test_a_temperature_inside_the_wlf_range_is_quiet(pad, temperature):
    assert _warnings(_case(track={"pad": pad, "pad_temperature_c": temperature})) == []


def test_the_wlf_range_follows_the_rule():
    assert pad_from_dict(TTS_UNIVERSAL).temperature_range_c == (-40.0, 60.0)
    assert pad_from_dict(TTS_GIVEN).temperature_range_c == (-60.0, 100.0)
    assert (
        pad_from_dict({"model": "spring_damper", "stiffness_n_per_m": 5e7}).temperature_range_c
        is None
    )


def test_a_huge_grid_is_refused_before_it_is_built():
    # step = 1e-9 Hz would be 1e12 frequencies (8 TB to build): refused from the
    # declarations in no time, naming the step, the size, the cost and the way out
    start = time.perf_counter()
    with pytest.raises(CaseError) as err:
        case_from_dict(_case(frequency={"f_min": 0.5, "f_max": 1000.0, "step": 1e-9}))
    assert time.perf_counter() - start < 5.0  # a margin: the check is arithmetic
    text = str(err.value)
    assert text.startswith("frequency.step = 1e-09: a grid of at most 2,000,000 frequencies")
    assert "this one has 999,500,000,000 (about 2 PB of memory and " in text
    assert "railvib run --force" in text


def test_the_template_step_of_0_0001_is_refused():
    with pytest.raises(CaseError, match=r"^frequency\.step = 0\.0001: .* 9,995,001 \(about"):
        case_from_dict({"preset": "wang2017_metro", "frequency": {"step": 0.0001}})


def test_a_huge_log_grid_is_refused_naming_n():
    grid = {"spacing": "log", "f_min": 1.0, "f_max": 100.0, "n": 3_000_000, "step": None}
    with pytest.raises(CaseError, match=r"^frequency\.n = 3000000: a grid of at most"):
        case_from_dict(_case(frequency=grid))


def test_a_large_grid_warns_and_a_forced_huge_one_loads():
    step = 99.0 / (MAX_FREQUENCIES + 10)  # just above the limit
    grid = {"f_min": 1.0, "f_max": 100.0, "step": step}
    with pytest.raises(CaseError):
        case_from_dict(_case(frequency=grid))
    (w,) = _warnings(_case(frequency=grid), force=True)
    assert w.field == "frequency.step"
    assert re.search(r"gives 2,000,01\d frequencies, more than 1,000,000: about", str(w))
    grid = {"f_min": 1.0, "f_max": 100.0, "step": 99.0 / (WARN_FREQUENCIES + 10)}
    (w,) = _warnings(_case(frequency=grid))  # warned, not refused
    assert "more than 1,000,000" in str(w)


def test_run_and_run_to_folder_take_force(tmp_path):
    path = tmp_path / "huge.toml"
    path.write_text('preset = "wang2017_metro"\n[frequency]\nstep = 0.0001\n')
    with pytest.raises(CaseError, match="force=True"):
        railvib.run(path)
    with pytest.raises(CaseError, match="force=True"):
        railvib.solve.run_to_folder(path, tmp_path / "out")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("f_min", "f_max", "step"), [(0.5, 1000.0, 0.1), (1.0, 2.0, 0.3), (1.0, 1.0 + 1e-6, 1e-7)]
)
def test_grid_size_is_the_length_of_the_grid(f_min, f_max, step):
    case = case_from_dict(_case(frequency={"f_min": f_min, "f_max": f_max, "step": step}))
    assert grid_size(case) == len(FrequencyGrid.linear(f_min, f_max, step))


def test_grid_cost_scales_with_the_grid():
    # BYTES_PER_FREQUENCY = 2000 B, SECONDS_PER_FREQUENCY = 30 us (measured)
    assert grid_cost(10_000_000) == "about 20 GB of memory and 5 min per case"
    assert grid_cost(1000) == "about 2 MB of memory and 0.03 s per case"


def test_the_warning_pickles_and_has_the_case_error_form():
    w = PlausibilityWarning("speed_kmh", 500.0, "above 10-450 km/h")
    back = pickle.loads(pickle.dumps(w))
    assert (back.field, back.value, back.note, str(back)) == (
        "speed_kmh",
        500.0,
        "above 10-450 km/h",
        "speed_kmh = 500.0: above 10-450 km/h",
    )
    assert issubclass(PlausibilityWarning, UserWarning)


def test_a_warned_case_runs_as_given():
    with pytest.warns(PlausibilityWarning, match="speed_kmh = 500.0"):
        fast = case_from_dict(_case(speed_kmh=500.0))
    ds = railvib.run(fast)
    assert np.all(np.isfinite(ds.psd_acceleration.values))


def test_a_sweep_warns_for_an_implausible_axis_value_when_it_loads():
    from railvib.sweep import sweep_from_dict

    spec = {
        "case": {"preset": "wang2017_metro", "frequency": SMALL_GRID},
        "axes": [{"field": "speed_kmh", "values": [5.0, 80.0]}],
    }
    with pytest.warns(PlausibilityWarning, match=r"^speed_kmh = 5\.0: below") as seen:
        sweep_from_dict(spec)
    assert len([w for w in seen if issubclass(w.category, PlausibilityWarning)]) == 1
