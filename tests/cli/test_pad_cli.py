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
