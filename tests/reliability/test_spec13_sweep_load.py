"""Issue 13: a bad axis value deep in a long axis is one line at load time, nothing written."""

from pathlib import Path

import tomli_w

from railvib.cli.main import main
from tests.unit.sweep.sweep_cases import small_sweep


def _long_axis_sweep(bad):
    values = [2.0e7 + 1.0e4 * i for i in range(1000)]
    values[537] = bad
    d = small_sweep(
        axes=[
            {"field": "track.pad_temperature_c", "values": [-30.0, 0.0]},
            {"field": "track.pad.k0_n_per_m", "values": values},
        ]
    )
    d["case"]["frequency"]["n"] = 20
    return d


def test_bad_pad_stiffness_at_537_of_1000_is_one_line(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(tomli_w.dumps(_long_axis_sweep(-1.0)))
    before = sorted(Path(tmp_path).rglob("*"))
    assert main(["sweep", str(path), "-o", str(tmp_path / "out"), "--no-progress"]) == 2
    captured = capsys.readouterr()
    lines = [line for line in captured.err.splitlines() if line.strip()]
    assert "Traceback" not in captured.err
    assert len(lines) == 1, captured.err
    assert "track.pad.k0_n_per_m" in lines[0]
    assert "axes[1].values[537]" in lines[0]
    assert sorted(Path(tmp_path).rglob("*")) == before


def test_pad_stiffness_above_k_inf_at_537_is_one_line(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(tomli_w.dumps(_long_axis_sweep(3.0e8)))  # k0 above k_inf = 2e8
    assert main(["sweep", str(path), "-o", str(tmp_path / "out"), "--no-progress"]) == 2
    captured = capsys.readouterr()
    lines = [line for line in captured.err.splitlines() if line.strip()]
    assert "Traceback" not in captured.err
    assert len(lines) == 1, captured.err
    assert "axes[1].values[537]" in lines[0]
    assert not (tmp_path / "out").exists()
