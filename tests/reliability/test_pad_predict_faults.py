"""``railvib pad predict`` on bad input: one line naming the field, exit 2, nothing written."""

import numpy as np
import pytest

from railvib.cli.main import main
from railvib.pads import wj7_example_csv

HEADER = "temperature_c,frequency_hz,storage_kn_per_mm,loss_factor\n"


def _csv(path, rows):
    path.write_text(HEADER + "".join(f"{t},{f},{k},{e}\n" for t, f, k, e in rows))
    return path


def _monotone_loss(temps):
    # loss factor rising with temperature: the peak lies above the measured range
    return [(t, 0.3, 30.0 * np.exp(-t / 40.0), 0.1 + 0.001 * (t + 60.0)) for t in temps]


CASES = {
    "one temperature": (
        lambda d: _csv(d / "one.csv", [(20.0, 0.3, 31.0, 0.09)]),
        [],
        "data.temperature_c",
        "at least 2 temperatures",
    ),
    "no loss peak in the range": (
        lambda d: _csv(d / "rising.csv", _monotone_loss(np.arange(-60.0, 20.1, 2.5))),
        [],
        "data.loss_factor",
        "Tg cannot be found",
    ),
    "two temperatures, Tg not given": (
        lambda d: _csv(d / "two.csv", [(-10.0, 0.3, 45.0, 0.1), (20.0, 0.3, 31.0, 0.09)]),
        [],
        "data.temperature_c",
        "Tg cannot be found",
    ),
    "several frequencies": (
        lambda d: wj7_example_csv("wj7_synthetic_multifrequency.csv"),
        [],
        "data.frequency_hz",
        "one test frequency",
    ),
    "a frequency not in the data": (
        lambda d: wj7_example_csv(),
        ["--frequency", "1"],
        "frequency_hz",
        "one of the test frequencies 0.3",
    ),
    "below the WLF singularity": (
        lambda d: wj7_example_csv(),
        ["--temperature", "-95", "--tg", "-40"],
        "temperature_c",
        "singular",
    ),
    "unknown preset": (
        lambda d: wj7_example_csv(),
        ["--preset", "wang2017_metr"],
        "pad_predict.preset (--preset)",
        "wang2017_metro",
    ),
    "a case file given as data": (
        lambda d: (d / "case.toml").write_text('preset = "wang2017_metro"\n') and d / "case.toml",
        [],
        "data",
        "not a TOML file",
    ),
}


@pytest.mark.parametrize("name", list(CASES))
def test_bad_input_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys, name):
    make, args, field, text = CASES[name]
    inputs = tmp_path / "in"
    inputs.mkdir()
    data = make(inputs)
    before = set(tmp_path.rglob("*"))
    out = tmp_path / "out"
    rc = main(["pad", "predict", str(data), "-o", str(out), *args])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.count("\n") == 1, err
    assert err.startswith(f"error: {field} = "), err
    assert text in err
    assert "Traceback" not in err
    assert set(tmp_path.rglob("*")) == before  # not even the output folder
