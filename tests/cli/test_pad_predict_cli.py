"""``railvib pad predict`` end to end, in process, and the user guide's command lines."""

import re
import shlex
from pathlib import Path

import numpy as np
import pytest

from railvib.case import load_case
from railvib.cli.main import main
from railvib.pads import load_pad_toml, wj7_example_csv

ROOT = Path(__file__).resolve().parents[2]
FILES = (
    "pad.toml",
    "case.toml",
    "fig06_hysteresis_loops.png",
    "fig07_temperature_sweep.png",
    "fig08_predicted_stiffness.png",
)


@pytest.mark.slow  # draws three figures: ~1.3 s
def test_pad_predict_writes_a_pad_a_runnable_case_and_three_plots(tmp_path, capsys):
    out = tmp_path / "out"
    data = str(wj7_example_csv())
    assert main(["pad", "predict", data, "--temperature", "-10", "-o", str(out)]) == 0
    for name in FILES:
        assert (out / name).stat().st_size > 0, name
    printed = capsys.readouterr().out
    for step in ("step 2: Tg = ", "step 3: at T0 = -10 degC", "step 5: vertical factor"):
        assert step in printed
    assert f"next: railvib run {out / 'case.toml'}" in printed
    header = (out / "case.toml").read_text().splitlines()
    assert header[0] == f"# railvib pad predict {data} --temperature -10 -o {out}"
    # pad.toml is a case-file fragment: its pad loads, and is shifted by temperature
    pad = load_pad_toml(out / "pad.toml")
    assert pad.storage(5.0, -30.0) > pad.storage(5.0, -10.0) > pad.storage(5.0, 20.0)
    case = load_case(out / "case.toml")
    assert case.track.pad_temperature_c == -10.0
    assert case.title.startswith("wang2017_metro with the pad predicted from")
    assert np.isfinite(pad.stiffness(np.geomspace(1.0, 1000.0, 5), -10.0)).all()


def test_pad_example_points_to_predict(tmp_path, capsys):
    assert main(["pad", "example", "-o", str(tmp_path)]) == 0
    path = tmp_path / "wj7_synthetic_0p3hz.csv"
    assert f"railvib pad predict {path} --temperature -10" in capsys.readouterr().out


@pytest.mark.slow  # runs the whole case: ~4 s
def test_the_user_guides_command_lines_run(tmp_path, monkeypatch, capsys):
    guide = (ROOT / "docs" / "user-guide.md").read_text()
    block = next(b for b in re.findall(r"```bash\n(.*?)```", guide, flags=re.S) if "predict" in b)
    monkeypatch.chdir(tmp_path)
    for line in block.strip().splitlines():
        words = shlex.split(line.split("#")[0])
        assert words[0] == "railvib"
        assert main(words[1:]) == 0, line
    assert (tmp_path / "pad-m10" / "run").is_dir()
    assert any((tmp_path / "pad-m10" / "run").iterdir())
    assert "wheelset2.bounce" in capsys.readouterr().out
