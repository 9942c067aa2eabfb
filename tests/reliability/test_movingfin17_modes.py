"""A moving (or non-stationary) case where only the stationary model runs: refused, one line.

Before issue 17's follow-up, ``railvib.run`` / ``run_to_folder``, ``railvib sweep`` and
``railvib validate`` ran such a case silently with the vehicle standing still (the moving
settings ignored), and ``railvib run --strict`` ignored ``--strict``. Each now names the
field (``mode``, ``case.mode`` or the sweep axis) in one line, exit 2, before anything is
computed or written.
"""

from __future__ import annotations

import pytest

from railvib.case import load_case
from railvib.cli.main import main
from railvib.errors import CaseError
from railvib.solve import run, run_to_folder

GRID = '[frequency]\nspacing = "log"\nf_min = 5.0\nf_max = 200.0\nn = 12\n'
MOVING = 'preset = "wang2017_metro"\nmode = "moving"\n' + GRID
NONSTATIONARY = (
    'preset = "wang2017_metro"\nmode = "nonstationary"\n'
    '[speed_profile]\nkind = "uniform"\nv_start_kmh = 30.0\nv_end_kmh = 60.0\n'
    "acceleration_ms2 = 1.0\n"
)


def _files(root):
    return set(root.rglob("*"))


@pytest.mark.parametrize(
    ("text", "mode"),
    [(MOVING, "moving"), (NONSTATIONARY, "nonstationary")],
    ids=["moving", "nonstationary"],
)
@pytest.mark.parametrize("call", ["run", "run_to_folder"])
def test_library_run_refuses_other_modes(tmp_path, text, mode, call):
    (tmp_path / "case.toml").write_text(text, encoding="utf-8")
    before = _files(tmp_path)
    case = load_case(tmp_path / "case.toml")
    calls = {
        "run": lambda: run(case),
        "run_to_folder": lambda: run_to_folder(case, tmp_path / "out"),
    }
    with pytest.raises(CaseError) as err:
        calls[call]()
    assert err.value.field == "mode"
    assert mode in str(err.value)
    assert "\n" not in str(err.value)
    assert _files(tmp_path) == before  # no output folder made


def _cli_refuses(tmp_path, capsys, args, field):
    before = _files(tmp_path)
    assert main(args) == 2
    captured = capsys.readouterr()
    lines = [s for s in captured.err.splitlines() if s.strip()]
    assert len(lines) == 1, captured.err
    assert lines[0].startswith(f"error: {field} = "), lines[0]
    assert "Traceback" not in captured.out + captured.err
    assert _files(tmp_path) == before


SWEEPS = {
    "moving-base-file": ('base = "case.toml"\n', "case.mode"),
    "moving-inline": (
        "[case]\n"
        + MOVING.replace("[frequency]", "[case.frequency]")
        + '[[axes]]\nfield = "speed_kmh"\nvalues = [60.0, 80.0]\n',
        "case.mode",
    ),
    "mode-axis": (
        '[case]\npreset = "wang2017_metro"\n'
        + GRID.replace("[frequency]", "[case.frequency]")
        + '[[axes]]\nfield = "mode"\nvalues = ["stationary", "moving"]\n',
        "axes[0].field",
    ),
    "moving-section-axis": (
        '[case]\npreset = "wang2017_metro"\n'
        + GRID.replace("[frequency]", "[case.frequency]")
        + '[[axes]]\nfield = "moving.harmonic_order"\nvalues = [2, 3]\n',
        "axes[0].field",
    ),
}


@pytest.mark.parametrize(("sweep", "field"), SWEEPS.values(), ids=list(SWEEPS))
def test_sweep_refuses_a_moving_case(tmp_path, monkeypatch, capsys, sweep, field):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(MOVING, encoding="utf-8")
    if sweep.startswith("base"):
        sweep += '[[axes]]\nfield = "speed_kmh"\nvalues = [60.0, 80.0]\n'
    (tmp_path / "sweep.toml").write_text(sweep, encoding="utf-8")
    _cli_refuses(tmp_path, capsys, ["sweep", "run", "sweep.toml", "-o", "out"], field)


@pytest.mark.parametrize("text", [MOVING, NONSTATIONARY], ids=["moving", "nonstationary"])
def test_validate_refuses_other_modes(tmp_path, monkeypatch, capsys, text):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(text, encoding="utf-8")
    _cli_refuses(tmp_path, capsys, ["validate", "case.toml", "--quick", "-o", "out"], "mode")


@pytest.mark.parametrize("text", [MOVING, NONSTATIONARY], ids=["moving", "nonstationary"])
def test_strict_refused_for_other_modes(tmp_path, monkeypatch, capsys, text):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(text, encoding="utf-8")
    _cli_refuses(tmp_path, capsys, ["run", "case.toml", "-o", "out", "--strict"], "mode")
