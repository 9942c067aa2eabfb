"""``mode = "moving"`` on the command line: bad input is one field-named line, exit 2, no output.

And a small good run writes the sleeper-passing lines and the random PSDs as separate
variables, with the summary's moving-against-stationary table.
"""

from __future__ import annotations

import warnings

import pytest

from railvib.case import case_from_dict
from railvib.cli.main import main
from railvib.errors import PlausibilityWarning
from railvib.movingrun import run_moving_to_folder
from railvib.results.dataset import load_netcdf

GRID = '[frequency]\nspacing = "log"\nf_min = 5.0\nf_max = {f_max}\nn = {n}\n'
METRO = 'preset = "wang2017_metro"\nmode = "moving"\n' + GRID.format(f_max=200.0, n=12)

CASES = {
    # near the split pinned-pinned peaks harmonic n = 1 is as large as n = 0: order 1 with a
    # tight tolerance is too low, and the message names the order needed
    "order-too-low": (
        'preset = "wang2017_metro"\nmode = "moving"\nspeed_kmh = 216.0\n'
        "[moving]\nharmonic_order = 1\ntolerance = 1e-4\n" + GRID.format(f_max=1500.0, n=12),
        "moving.harmonic_order = 1: at least",
    ),
    "order-zero": (METRO + "[moving]\nharmonic_order = 0\n", "moving.harmonic_order"),
    "order-not-integer": (METRO + "[moving]\nharmonic_order = 2.5\n", "moving.harmonic_order"),
    "tolerance-one": (METRO + "[moving]\ntolerance = 1.0\n", "moving.tolerance"),
    "moving-without-mode": (
        'preset = "wang2017_metro"\n[moving]\nharmonic_order = 2\n' + GRID.format(f_max=200, n=12),
        "moving",
    ),
    # a soft pad: the critical speed (4 EI s / m^2)^(1/4) is 331 m/s, the bound half of it
    "speed-beyond-convergence": (
        METRO.replace('mode = "moving"', 'mode = "moving"\nspeed_kmh = 700.0')
        + '[track.pad]\nmodel = "spring_damper"\nstiffness_n_per_m = 1e6\ndamping_ns_per_m = 5e4\n',
        "speed_kmh = 700",
    ),
    "slab-track": (
        'preset = "floating_slab_metro"\nmode = "moving"\n' + GRID.format(f_max=200, n=12),
        "track.model",
    ),
}


#: the order probe computes the moving-load receptance up to 1.6 kHz: ~3 s
SLOW = {"order-too-low"}


@pytest.mark.parametrize(
    ("case", "field"),
    [
        pytest.param(*v, id=k, marks=[pytest.mark.slow] if k in SLOW else [])
        for k, v in CASES.items()
    ],
)
def test_bad_moving_input_is_one_field_named_line(tmp_path, monkeypatch, capsys, case, field):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(case, encoding="utf-8")
    before = set(tmp_path.rglob("*"))
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 2
    captured = capsys.readouterr()
    lines = [s for s in captured.err.splitlines() if s.strip() and not s.startswith("warning:")]
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("error: "), lines[0]
    assert field in lines[0], lines[0]
    assert "Traceback" not in captured.out + captured.err
    assert set(tmp_path.rglob("*")) == before


@pytest.mark.slow  # the moving-load receptance at 12 x 5 load frequencies, 9 wheel gaps: ~10 s
def test_moving_run_writes_lines_and_psds_apart(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(METRO + "[moving]\nharmonic_order = 2\n", "utf-8")
    assert main(["run", "case.toml", "-o", "out"]) == 0
    out = capsys.readouterr().out
    assert "sleeper-passing frequency v/d = 37.04 Hz" in out
    assert "| contact force wheel 1 |" in out
    names = {p.name for p in (tmp_path / "out").iterdir()}
    assert {"results.nc", "lines.csv", "bands.csv", "summary.md", "moving_psd.png"} <= names
    ds = load_netcdf(tmp_path / "out" / "results.nc")
    assert ds.contact_force_line_amplitude.dims == ("line", "wheel")
    assert ds.contact_force_psd.dims == ("frequency", "wheel")
    assert ds.psd_over_period.dims == ("phase", "frequency", "response")
    assert ds.line_frequency.values.tolist() == pytest.approx([37.037, 74.074], rel=1e-4)


def test_a_costly_grid_warns_before_computing(tmp_path):
    # 30 000 frequencies x 7 harmonics = 210 000 moving-load frequencies (a table of some
    # 0.5 GB): a
    # one-line PlausibilityWarning naming the field, before anything is computed; escalated
    # to an error (as -W error does) it leaves nothing behind
    case = case_from_dict(
        {
            "preset": "wang2017_metro",
            "mode": "moving",
            "frequency": {"spacing": "log", "f_min": 5.0, "f_max": 200.0, "n": 30000},
        }
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        with pytest.raises(PlausibilityWarning, match=r"^frequency = '30000 frequencies': x 7"):
            run_moving_to_folder(case, tmp_path / "out")
    assert not (tmp_path / "out").exists()
