"""Sweeps over train length on the command line: bad values on one line, a good one runs.

Each bad value is named at load time (exit 2, one ``error:`` line naming the field and the
axis value, no traceback, nothing written); a good sweep over ``train.cars`` writes one
dataset laid out as the longest train.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.cli.main import main
from railvib.sweep import load_sweep_dataset

BASE = (
    'preset = "wang2017_metro"\n[frequency]\nspacing = "log"\nf_min = 1.0\nf_max = 100.0\nn = 8\n'
)


def _sweep(tmp_path, monkeypatch, axis, extra_base=""):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "base.toml").write_text(BASE + extra_base, encoding="utf-8")
    text = f'base = "base.toml"\nvariables = ["psd_force"]\n[[axes]]\n{axis}\n'
    (tmp_path / "sweep.toml").write_text(text, encoding="utf-8")


@pytest.mark.parametrize(
    ("axis", "extra_base", "field", "where"),
    [
        ('field = "train.cars"\nvalues = [1, 0]', "", "train.cars", "axes[0].values[1]"),
        ('field = "train.cars"\nvalues = [2, 51]', "", "train.cars", "axes[0].values[1]"),
        ('field = "train.cars"\nvalues = [1, 2.5]', "", "train.cars", "axes[0].values[1]"),
        (
            'field = "train"\nlabels = ["a", "b"]\n'
            "values = [{ cars = 2 }, { cars = 2, gap_m = -1.0 }]",
            "",
            "train.gap_m",
            "axes[0].values[1]",
        ),
        (
            'field = "train.cars"\nvalues = [2, 1]',
            '[train]\ncars = 2\n[criteria]\ncomfort_body = "car2.carbody"\n',
            "criteria.comfort_body",
            "axes[0].values[1]",
        ),
    ],
    ids=["no-cars", "too-many-cars", "fractional", "negative-gap-in-table", "comfort-body"],
)
def test_bad_train_length_value_is_one_line(
    tmp_path, monkeypatch, capsys, axis, extra_base, field, where
):
    _sweep(tmp_path, monkeypatch, axis, extra_base)
    before = set(tmp_path.rglob("*"))
    assert main(["sweep", "sweep.toml", "-o", "out"]) == 2
    captured = capsys.readouterr()
    lines = [s for s in captured.err.splitlines() if s.strip() and not s.startswith("warning:")]
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("error: "), lines[0]
    assert field in lines[0], lines[0]
    assert where in lines[0], lines[0]
    assert "Traceback" not in captured.out + captured.err
    assert set(tmp_path.rglob("*")) == before


@pytest.mark.slow
def test_a_sweep_over_train_length_runs_and_reads_back(tmp_path, monkeypatch, capsys):
    _sweep(tmp_path, monkeypatch, 'field = "train.cars"\nname = "cars"\nvalues = [1, 2]')
    assert main(["sweep", "sweep.toml", "-o", "out", "-j", "1", "--csv"]) == 0
    ds = load_sweep_dataset(tmp_path / "out")
    assert ds.sizes["wheel"] == 8
    assert ds.train_cars.values.tolist() == [1, 2]
    # the single car has no second car: NaN there, values for its own four wheels
    force = ds.psd_force.sel(cars=1).values
    assert np.isfinite(force[:, :4]).all()
    assert np.isnan(force[:, 4:]).all()
    assert np.isfinite(ds.psd_force.sel(cars=2).values).all()
    rows = (tmp_path / "out" / "summary.csv").read_text(encoding="utf-8").splitlines()
    assert len(rows) == 1 + 14 + 28  # header, the single car's rows, the two cars' rows
