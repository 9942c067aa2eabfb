"""Bad ``[criteria]`` input on the command line: one field-named line, exit 2, no output.

A criterion asked for what it does not apply to (comfort on a rail response, a floor
point outside the car body), a band outside the computed grid, a weighting band
outside the standard's range: refused before anything is solved or written.
"""

from __future__ import annotations

import pytest

from railvib.cli.main import main

#: a quick case: 40 log-spaced frequencies from 0.5 Hz to 200 Hz
BASE = (
    'preset = "wang2017_metro"\n'
    '[frequency]\nspacing = "log"\nf_min = 0.5\nf_max = 200.0\nn = 40\n[criteria]\n'
)

CASES = {
    "comfort-on-a-rail-response": ('comfort_body = "rail@wheel1"', "criteria.comfort_body"),
    "comfort-on-a-wheelset": ('comfort_body = "wheelset1"', "criteria.comfort_body"),
    "floor-beyond-the-car-body": (
        "floor_positions_m = [0.0, 20.0]",
        "criteria.floor_positions_m[1]",
    ),
    "weighting-band-below-iso-2631": ("comfort_band_hz = [0.1, 80.0]", "criteria.comfort_band_hz"),
    "weighting-band-above-iso-2631": ("comfort_band_hz = [1.0, 100.0]", "criteria.comfort_band_hz"),
    "comfort-band-beyond-the-grid": ("comfort_band_hz = [0.5, 80.0]", "criteria.comfort_band_hz"),
    "octave-range-beyond-the-grid": ("octave_band_hz = [0.1, 100.0]", "criteria.octave_band_hz"),
    "octave-range-holding-no-band": ("octave_band_hz = [10.0, 11.0]", "criteria.octave_band_hz"),
    "horizontal-weighting": ('comfort_weighting = "Wd"', "criteria.comfort_weighting"),
    "misspelt-key": ("flor_positions_m = [1.0]", "criteria.flor_positions_m"),
}


@pytest.mark.parametrize(("extra", "field"), CASES.values(), ids=CASES)
def test_bad_criteria_are_one_field_named_line(tmp_path, monkeypatch, capsys, extra, field):
    monkeypatch.chdir(tmp_path)
    text = BASE + extra + "\n"
    if extra.startswith(("comfort_band_hz = [0.5, 80.0]", "octave_band_hz = [0.1")):
        text = text.replace("f_min = 0.5", "f_min = 1.0")  # a grid from 1 Hz
    (tmp_path / "case.toml").write_text(text, encoding="utf-8")
    before = set(tmp_path.rglob("*"))
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 2
    captured = capsys.readouterr()
    lines = [s for s in captured.err.splitlines() if s.strip() and not s.startswith("warning:")]
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("error: "), lines[0]
    assert field in lines[0], lines[0]
    assert "Traceback" not in captured.out + captured.err
    assert set(tmp_path.rglob("*")) == before  # nothing written, not even the folder
