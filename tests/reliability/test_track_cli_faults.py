"""``railvib track`` on bad input: one line naming the field, exit 2, nothing written."""

import pytest

from railvib.cli.main import main

CASE = 'preset = "thompson_ballasted"\n'

#: name -> (extra case text, options, field named, text of the allowed values)
CASES = {
    "negative --fmin": ("", ["--fmin", "-1"], "--fmin", "> 0"),
    "--fmax below the lowest frequency": (
        "",
        ["--fmin", "100", "--fmax", "50"],
        "--fmax",
        "> the lowest",
    ),
    "-n of one frequency": ("", ["-n", "1"], "-n", ">= 2"),
    "grid below every TDR band": (
        "",
        ["--fmin", "1", "--fmax", "50", "-n", "20"],
        "frequency",
        "one-third octave band of 100 Hz - 5 kHz",
    ),
    "--tdr-bands beyond the grid": (
        "",
        ["--tdr-bands", "100,5000"],
        "--tdr-bands",
        "within the frequency grid",
    ),
    "--tdr-bands not two numbers": ("", ["--tdr-bands", "100"], "--tdr-bands", "LOW,HIGH"),
    "--tdr-bands reversed": ("", ["--tdr-bands", "1000,100"], "--tdr-bands", "low <= high"),
    "--tdr-bands above the solver's range": (
        # a 4.9 t/m rail at 2.9 m is solved up to 1096 Hz: the 1 kHz band reaches 1122 Hz
        "[track]\nsleeper_spacing = 2.9\n[track.rail]\nmass_per_length = 4900.0\n"
        "[frequency]\nf_max = 1050.0\n",
        ["--tdr-bands", "100,1000"],
        "--tdr-bands",
        "highest frequency this rail",
    ),
    "negative --supports": ("", ["--supports", "-1"], "--supports", ">= 0"),
    "a bad track value": ("[track]\nsleeper_mass_kg = -5.0\n", [], "track.sleeper_mass_kg", "0"),
    "an unknown track key": ("[track]\nsleeper_mas_kg = 150.0\n", [], "track.sleeper_mas_kg", ""),
}


@pytest.mark.parametrize("name", list(CASES))
def test_bad_input_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys, name):
    extra, args, field, text = CASES[name]
    case = tmp_path / "case.toml"
    case.write_text(CASE + extra)
    before = set(tmp_path.rglob("*"))
    out = tmp_path / "out"
    rc = main(["track", str(case), "-o", str(out), *args])
    err = capsys.readouterr().err
    assert rc == 2
    lines = [s for s in err.splitlines() if s.strip() and not s.startswith("warning: ")]
    assert len(lines) == 1, err
    assert lines[0].startswith(f"error: {field}"), err
    assert text in lines[0]
    assert "Traceback" not in err
    assert set(tmp_path.rglob("*")) == before  # not even the output folder


def test_a_missing_case_file_is_named(tmp_path, capsys):
    rc = main(["track", str(tmp_path / "nope.toml"), "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.count("\n") == 1, err
    assert "nope.toml" in err
    assert "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_an_output_path_that_is_a_file_is_refused_before_writing(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    target = tmp_path / "taken"
    target.write_text("mine")
    rc = main(["track", str(case), "-o", str(target), "--no-plots", "--fmin", "90", "-n", "10"])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.startswith("error: "), err
    assert "--output" in err
    assert err.count("\n") == 1, err
    assert target.read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml", "taken"]
