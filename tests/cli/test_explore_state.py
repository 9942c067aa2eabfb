"""The explorer's state (railvib.explore.state): controls -> case -> run -> what the page draws.

No web library needed. Expected values are closed forms: the default preset's pad is a
spring and dashpot, K*(f) = k + i c 2 pi f with k = 50 kN/mm and c = 5e4 N s/m
(Wang et al. 2017, Table 1, as the wang2017_metro preset reads it), so K' = k and
K''/K' = 2 pi f c / k; a stiffness factor multiplies k and leaves c.
"""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import railvib
from railvib.case import load_case
from railvib.errors import CaseError
from railvib.explore import AS_CASE, Explorer, controls_from_values
from railvib.presets import load_vehicle_preset

K_PAD = 5.0e7  # N/m, the preset's pad stiffness
C_PAD = 5.0e4  # N s/m, its damping


@pytest.fixture(scope="module")
def explorer():
    return Explorer(railvib.load_preset_case())


def test_the_controls_start_at_the_case(explorer):
    start = explorer.initial()
    assert (start.speed_kmh, start.pad_temperature_c, start.fra_class) == (80.0, 20.0, 5)
    assert start.track == start.pad == start.vehicle == AS_CASE
    assert explorer.fra_classes == [1, 2, 3, 4, 5, 6]  # the FRA family's choices


def test_the_choices_come_from_the_registries_through_the_presets(explorer):
    from railvib.pads import PADS
    from railvib.track import TRACKS

    models = {label.split(" ")[0] for label in explorer.tracks if label != AS_CASE}
    assert models <= set(TRACKS.names())
    assert {"ballasted", "floating_slab"} <= models
    pads = {label.split(" ")[0] for label in explorer.pads if label != AS_CASE}
    assert pads <= set(PADS.names())
    assert {"spring_damper", "hysteretic", "tabulated"} <= pads


def test_the_table_carries_each_control(explorer):
    start = explorer.initial()
    table = explorer.table(replace(start, speed_kmh=120.0, pad_factor=2.0, fra_class=3))
    assert table["speed_kmh"] == 120.0
    pad = table["track"]["pad"]
    assert pad["stiffness_n_per_m"] == 2 * K_PAD  # N/m parameters scaled
    assert pad["damping_ns_per_m"] == C_PAD  # N s/m left alone
    assert table["irregularity"]["long_wave"]["class_number"] == 3  # nested FRA spectrum
    ballasted = next(label for label in explorer.tracks if label.startswith("ballasted"))
    table = explorer.table(replace(start, track=ballasted))
    assert table["track"]["model"] == "ballasted"
    assert table["rail_model"] == "rail_pair"  # the preset's rail model with its track


def test_a_vehicle_preset_replaces_the_vehicle(explorer):
    case, _ = explorer.case(replace(explorer.initial(), vehicle="wu_yang2003_shinkansen_300"))
    preset = load_vehicle_preset("wu_yang2003_shinkansen_300")
    masses = [b["mass_kg"] for b in preset["bodies"]]
    got = [b["mass_kg"] for b in case.model_dump()["vehicle"]["bodies"]]
    assert got == masses


def test_a_choice_not_offered_is_refused(explorer):
    with pytest.raises(CaseError, match="explore.track = 'slab': one of"):
        explorer.table(replace(explorer.initial(), track="slab"))


@pytest.mark.slow  # a run of 9,996 frequencies: 0.2-2 s
def test_the_frame_holds_the_pad_in_closed_form(explorer):
    frame = explorer.frame(replace(explorer.initial(), pad_factor=2.0))
    f = frame.frequency
    np.testing.assert_allclose(frame.pad_storage_kn_per_mm, 2 * K_PAD / 1e6, rtol=1e-12)
    np.testing.assert_allclose(
        frame.pad_loss_factor, 2 * np.pi * f * C_PAD / (2 * K_PAD), rtol=1e-12
    )
    assert list(frame.psd) == ["carbody.bounce", "bogie1.bounce", "wheelset1.bounce", "rail@wheel1"]
    assert frame.psd_units["carbody.bounce"] == "(m/s^2)^2/Hz"
    assert frame.band_nominal[0] == pytest.approx(0.63)  # the first band inside 0.5-1000 Hz
    assert any(n.startswith("loss of contact:") for n in frame.notes)
    rows = {r["response"]: r for r in frame.summary_rows}
    assert rows["carbody.pitch"]["rms_unit"] == "rad/s^2"


@pytest.mark.slow  # two runs
def test_a_faster_run_shakes_more(explorer):
    # the temporal irregularity PSD at a fixed frequency grows with speed for these spectra
    slow = explorer.frame(replace(explorer.initial(), speed_kmh=40.0))
    fast = explorer.frame(replace(explorer.initial(), speed_kmh=160.0))
    rms = {r["response"]: r["rms"] for r in fast.summary_rows}
    rms_slow = {r["response"]: r["rms"] for r in slow.summary_rows}
    assert rms["wheelset1.bounce"] > rms_slow["wheelset1.bounce"]


def test_save_writes_a_case_file_railvib_runs(explorer, tmp_path):
    path = explorer.save(
        replace(explorer.initial(), speed_kmh=120.0, fra_class=4), tmp_path / "c.toml"
    )
    case = load_case(path)
    assert case.speed_kmh == 120.0
    assert case.title.endswith("[explored: speed_kmh 120, fra_class 4]")  # not "80 km/h" alone
    assert case.irregularity["long_wave"]["class_number"] == 4
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.toml"]  # no temporary left


def test_save_of_a_refused_case_writes_nothing(explorer, tmp_path):
    with pytest.raises(CaseError, match="speed_kmh"):
        explorer.save(replace(explorer.initial(), speed_kmh=-5.0), tmp_path / "c.toml")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("values", "field"),
    [
        ({"speed_kmh": float("nan")}, "speed_kmh"),
        ({"pad_factor": -1.0}, "track.pad.stiffness_n_per_m"),
        ({"pad_temperature_c": 1e9}, "track.pad_temperature_c"),
        ({"fra_class": "9"}, "irregularity.long_wave.class_number"),
        ({"fra_class": "worst"}, "explore.fra_class"),
        ({"speed_kmh": "fast"}, "explore.speed_kmh"),
        ({"vehicle": "../../etc/passwd"}, "explore.vehicle"),
        ({"pad": "tabulated (/tmp/pad.csv)"}, "explore.pad"),
        ({"output": "/tmp/x.toml"}, "explore"),
    ],
)
def test_values_a_crafted_message_could_send_are_refused(explorer, tmp_path, values, field):
    # the page offers none of these; a websocket message could send them
    with pytest.raises(CaseError, match=f"^{field} = "):
        explorer.save(controls_from_values(explorer.initial(), values), tmp_path / "c.toml")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow  # a run
def test_a_nonstationary_case_is_said_to_be_shown_stationary():
    root = Path(__file__).resolve().parents[2]
    explorer = Explorer(load_case(root / "docs" / "examples" / "braking.toml"))
    frame = explorer.frame(explorer.initial())
    assert frame.notes[0].startswith(
        "note: mode = 'nonstationary' in the case: shown is the stationary"
    )
