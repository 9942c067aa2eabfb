"""``railvib pad fit`` end to end, in process."""

import numpy as np
import pytest

from railvib.cli.main import main
from railvib.pads import load_pad_toml, wj7_example_csv


def test_pad_fit_writes_toml_and_plots(tmp_path, capsys):
    out = tmp_path / "out"
    rc = main(
        ["pad", "fit", str(wj7_example_csv()), "--model", "zener", "--tg", "-40", "-o", str(out)]
    )
    assert rc == 0
    for name in ("pad.toml", "master_curve.png", "stiffness_vs_frequency.png"):
        assert (out / name).stat().st_size > 0
    pad = load_pad_toml(out / "pad.toml")  # loadable by pad_from_dict as a case-file table
    assert pad.storage(5.0, -30.0) > pad.storage(5.0, 20.0)
    assert np.isfinite(pad.stiffness(np.geomspace(1, 1000, 5), -10.0)).all()
    assert "log-linear at 20 degC" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("args", "text"),
    [(["--tg", "-40", "--c1", "8"], "--tg"), (["--model", "rubber", "--tg", "-40"], "model")],
)
def test_pad_fit_errors_are_one_line_exit_2(tmp_path, capsys, args, text):
    rc = main(["pad", "fit", str(wj7_example_csv()), "-o", str(tmp_path), *args])
    assert rc == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ")
    assert text in err
    assert err.count("\n") == 1


def test_header_records_the_whole_command_and_a_parameter_at_a_bound_is_reported(tmp_path, capsys):
    out = tmp_path / "out"
    data = str(wj7_example_csv())
    # the synthetic pad's loss is not viscous: a log-linear law with viscous damping fits
    # its storage stiffness and is pushed to zero damping, the lower search bound
    args = ["--model", "log_linear", "--tg", "-40", "--temperatures", "-20,0,20"]
    assert main(["pad", "fit", data, *args, "--no-vertical-shift", "-o", str(out)]) == 0
    header = (out / "pad.toml").read_text().splitlines()
    assert header[0] == (
        f"# railvib pad fit {data} --model log_linear --tg -40 --no-vertical-shift "
        f"--temperatures -20,0,20 -o {out}"
    )
    note = next(line for line in capsys.readouterr().out.splitlines() if "note" in line)
    assert note.startswith("note: damping_ns_per_m = ")
    assert "N s/m ended at its lower search bound (0 N s/m)" in note
    assert f"# {note}" in header


def test_pad_example_writes_the_shipped_csv_and_says_what_next(tmp_path, capsys):
    assert main(["pad", "example", "-o", str(tmp_path)]) == 0
    path = tmp_path / "wj7_synthetic_0p3hz.csv"
    assert path.read_text() == wj7_example_csv().read_text()
    out = capsys.readouterr().out
    assert f"railvib pad fit {path} --model zener --tg -40" in out
    assert main(["pad", "example", "--multifrequency", "-o", str(tmp_path)]) == 0
    multi = tmp_path / "wj7_synthetic_multifrequency.csv"
    assert multi.read_text() == wj7_example_csv(multi.name).read_text()
