"""Every command against the usual wrong inputs: one line, exit 2, nothing written (issue 10).

A new user passes a result where a case is expected, a PNG, a CSV, an empty or binary
file, a path that does not exist or a folder, values out of range and misspelt keys.
Each command must answer with exactly one line ``error: ...`` on stderr that names
the file or the field, exit with code 2, show no traceback (in process, any other
exception would escape :func:`railvib.cli.main.main` and fail the test) and leave
its output folder as it was: nothing is computed before the input is checked.
"""

import pytest
import tomli_w

from railvib.cli.main import main
from tests.unit.sweep.sweep_cases import small_sweep

HDF5 = b"\x89HDF\r\n\x1a\n" + bytes(range(256)) * 4  # how every netCDF-4 file starts
PNG = b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR" + bytes(200)
GARBAGE = bytes(range(256)) * 8
MEASUREMENTS = "temperature_c,frequency_hz,storage_kn_per_mm,loss_factor\n20,1,31,0.1\n"
CASE = 'preset = "wang2017_metro"\n'

#: wrong files, the same for every command: name -> (file name, bytes or None for a folder)
FILES = {
    "netcdf": ("results.nc", HDF5),
    "png": ("figure.png", PNG),
    "empty": ("empty.toml", b""),
    "garbage": ("garbage.bin", GARBAGE),
    "missing": ("missing.toml", None),
    "directory": ("a_folder", None),
}

#: per kind of input a command takes, the wrong files of that kind: name -> (file, text)
CASE_FILES = {
    "csv_as_toml": ("data.csv", MEASUREMENTS),
    "out_of_range": ("range.toml", CASE + "speed_kmh = -5.0\n"),
    "unknown_key": ("typo.toml", CASE + "speed_kmhh = 80.0\n"),
    "bad_band": ("band.toml", CASE + "[output]\nrms_bands = [[1500.0, 2000.0]]\n"),
    "bad_model": ("model.toml", CASE + '[track.pad]\nmodel = "rubber"\n'),
}
SWEEP_FILES = {
    "csv_as_toml": ("data.csv", MEASUREMENTS),
    "a_case_file": ("case.toml", CASE),
    "out_of_range": (
        "range.toml",
        tomli_w.dumps(small_sweep(axes=[{"field": "speed_kmh", "values": [40.0, -1.0]}])),
    ),
    "unknown_key": ("typo.toml", tomli_w.dumps(small_sweep(chunk_sise=4))),
    "unknown_field": (
        "field.toml",
        tomli_w.dumps(small_sweep(axes=[{"field": "speed_kmhh", "values": [40.0]}])),
    ),
}
CSV_FILES = {
    "a_case_file": ("case.toml", CASE),
    "out_of_range": (
        "range.csv",
        "temperature_c,frequency_hz,storage_kn_per_mm,loss_factor\n20,1,-31,0.1\n20,2,31,0.1\n",
    ),
    "unknown_column": ("column.csv", "temperature_c,frequency_hz,stiffness,loss_factor\n1,2,3,4\n"),
    "not_numbers": (
        "text.csv",
        "temperature_c,frequency_hz,storage_kn_per_mm,loss_factor\nwarm,1,31,0.1\n",
    ),
}
RESULT_FILES = {
    "a_case_file": ("case.toml", CASE),
    "a_csv": ("data.csv", MEASUREMENTS),
    "run_folder": ("run", {"results.nc": HDF5, "summary.md": b"|"}),
    "unfinished_sweep": ("unfinished", {"manifest.json": b"{}"}),
    "empty_folder": ("empty_folder", {}),
}


def _make(tmp_path, name, content):
    path = tmp_path / name
    if isinstance(content, dict) or (content is None and name == "a_folder"):
        path.mkdir()
        for inner, data in (content or {}).items():
            (path / inner).write_bytes(data)
    elif isinstance(content, bytes):
        path.write_bytes(content)
    elif isinstance(content, str):
        path.write_text(content, encoding="utf-8")
    return path


def _cases(specific):
    return [*FILES.items(), *specific.items()]


COMMANDS = {
    "run": (lambda f, out: ["run", f, "-o", out], CASE_FILES),
    "validate": (lambda f, out: ["validate", f, "--quick", "-o", out], CASE_FILES),
    "sweep": (lambda f, out: ["sweep", f, "-o", out, "--no-progress", "-j", "1"], SWEEP_FILES),
    "sweep run": (lambda f, out: ["sweep", "run", f, "-o", out, "--no-progress"], SWEEP_FILES),
    "sweep plot": (lambda f, out: ["sweep", "plot", f, "-o", out], RESULT_FILES),
    "plot": (lambda f, out: ["plot", f, "-o", out], RESULT_FILES),
    "sweep export": (
        lambda f, out: ["sweep", "export", f, "--csv", f"{out}/s.csv", "--netcdf", f"{out}/s.nc"],
        RESULT_FILES,
    ),
    "pad fit": (lambda f, out: ["pad", "fit", f, "-o", out, "--tg", "-40"], CSV_FILES),
}

PARAMS = [
    pytest.param(command, name, content, id=f"{command}-{kind}")
    for command, (_, specific) in COMMANDS.items()
    for kind, (name, content) in _cases(specific)
]


def _assert_one_line(capsys, *names):
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    line = lines[0]
    assert line.startswith("error: "), line
    assert "Traceback" not in captured.err + captured.out
    assert any(name in line for name in names), f"{line!r} names none of {names}"
    return line


#: the field each content-level mistake is about (named in the message)
FIELDS = {
    "range.toml": ("speed_kmh", "values[1]"),
    "typo.toml": ("speed_kmhh", "chunk_sise"),
    "band.toml": ("output.rms_bands[0]",),
    "model.toml": ("track.pad.model",),
    "field.toml": ("speed_kmhh",),
    "range.csv": ("measurements.storage_n_per_m[0]",),
    "column.csv": ("data.stiffness",),
    "text.csv": ("data.temperature_c",),
}


@pytest.mark.parametrize(("command", "name", "content"), PARAMS)
def test_bad_input_is_one_line_exit_2_and_writes_nothing(command, name, content, tmp_path, capsys):
    path = _make(tmp_path, name, content)
    out = tmp_path / "out"
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    args, _ = COMMANDS[command]
    assert main(args(str(path), str(out))) == 2
    _assert_one_line(capsys, str(path), *FIELDS.get(name, ()))
    assert not out.exists(), sorted(out.rglob("*"))
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before


@pytest.fixture(scope="module")
def sweep_result(tmp_path_factory):
    """A finished two-case sweep on a coarse grid."""
    from railvib.sweep import run_sweep, sweep_from_dict

    d = small_sweep(axes=[{"field": "speed_kmh", "name": "speed", "values": [40.0, 80.0]}])
    d["case"]["frequency"]["n"] = 20
    out = tmp_path_factory.mktemp("sweep") / "s.sweep"
    run_sweep(sweep_from_dict(d), out, workers=1, progress=False)
    return out


@pytest.mark.parametrize(
    ("options", "field"),
    [
        (["-v", "bogus"], "variable"),
        (["-v", "peak,rms_20_100"], "variable"),
        (["-r", "wheelset9.bounce"], "response"),
        (["-r", "carbody.bounce,rail@wheel"], "response"),
        (["--x", "temperature"], "x"),
        (["--x", "speed", "--y", "speed"], "y"),
        (["--y", "nope"], "y"),
    ],
)
@pytest.mark.parametrize("command", [["sweep", "plot"], ["plot"]])
def test_bad_plot_options_are_one_line_and_draw_nothing(
    sweep_result, command, options, field, tmp_path, capsys
):
    out = tmp_path / "plots"
    assert main([*command, str(sweep_result), *options, "-o", str(out)]) == 2
    line = _assert_one_line(capsys, f"{field} = ")
    assert line.startswith(f"error: {field} = ")
    assert not out.exists()


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["template", "--preset", "wang2017_metr"], "preset"),
        (["template", "--preset", "my_case.toml"], "preset"),
        (["models", "pads"], "family"),
        (["models", "wheels"], "family"),
        (["run"], "CASE_FILE"),
        (["run", "x.toml", "--bogus"], "--bogus"),
        (["validate", "x.toml", "--realisations", "0"], "--realisations"),
        (["sweep", "export", "x"], "'RESULT'"),
        (["pad", "fit", "x.csv", "--temperatures", "cold"], "--temperatures"),
        (["pad", "fit", "x.csv", "--model", "rubber"], "model"),
        (["nonsense"], "nonsense"),
    ],
)
def test_bad_arguments_are_one_line_exit_2(args, field, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.csv").write_text(MEASUREMENTS)
    (tmp_path / "x.toml").write_text(CASE)
    assert main(args) == 2
    _assert_one_line(capsys, field)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.csv", "x.toml"]


def test_output_folder_that_is_a_file_is_one_line(tmp_path, capsys):
    taken = tmp_path / "taken"
    taken.write_text("a file")
    assert main(["pad", "example", "-o", str(taken)]) == 2
    _assert_one_line(capsys, str(taken), "'taken'")
    assert taken.read_text() == "a file"
