"""`railvib run` with a vehicle file or a vehicle preset."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from railvib.cli.main import main

BASE = (
    'preset = "wang2017_metro"\n[frequency]\nspacing = "log"\nf_min = 1.0\nf_max = 200.0\nn = 12\n'
)
WAGON = """name = "two-axle wagon for the test"
[[bodies]]
name = "carbody"
mass_kg = 20000.0
pitch_inertia_kg_m2 = 5.0e5
[[bodies]]
name = "wheelset1"
mass_kg = 1200.0
x_m = 4.5
[[bodies]]
name = "wheelset2"
mass_kg = 1200.0
x_m = -4.5
[[suspensions]]
upper = "carbody"
lower = "wheelset1"
stiffness_n_per_m = 1.0e6
damping_ns_per_m = 1.0e4
[[suspensions]]
upper = "carbody"
lower = "wheelset2"
stiffness_n_per_m = 1.0e6
damping_ns_per_m = 1.0e4
[[wheels]]
body = "wheelset1"
[[wheels]]
body = "wheelset2"
"""


def test_run_with_a_vehicle_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "cars").mkdir()
    (tmp_path / "cars" / "wagon.toml").write_text(WAGON, encoding="utf-8")
    (tmp_path / "case.toml").write_text(BASE + '[vehicle]\nfile = "cars/wagon.toml"\n', "utf-8")
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 0
    ds = xr.open_dataset(tmp_path / "out" / "results.nc")
    labels = list(ds["response"].values)
    assert labels == [
        "carbody.bounce",
        "carbody.pitch",
        "wheelset1.bounce",
        "wheelset2.bounce",
        "rail@wheel1",
        "rail@wheel2",
    ]
    # the resolved case stored with the results holds the vehicle inline (rerunnable alone)
    assert 'name = "wheelset2"' in ds.attrs["case_toml"]
    # the static load of each wheel: half the body plus its wheelset, 9.81 m/s^2
    load = ds["static_contact_load"].values
    np.testing.assert_allclose(load, 9.81 * (10000.0 + 1200.0), rtol=1e-12)
    ds.close()


@pytest.mark.slow  # two runs, ~1.5 s; the unit test compares the same FRFs in 0.1 s
def test_run_with_the_paper_car_preset_matches_the_default(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.toml").write_text(BASE, encoding="utf-8")
    (tmp_path / "b.toml").write_text(BASE + '[vehicle]\npreset = "wang2017_metro_b"\n', "utf-8")
    assert main(["run", "a.toml", "-o", "a", "--no-plots"]) == 0
    assert main(["run", "b.toml", "-o", "b", "--no-plots"]) == 0
    a = xr.open_dataset(tmp_path / "a" / "results.nc")
    b = xr.open_dataset(tmp_path / "b" / "results.nc")
    # the same car written as a file: equal to 1e-12 of each response's peak
    for name in ("psd_displacement", "psd_force"):
        x, y = a[name].values, b[name].values
        assert np.abs(x - y).max() <= 1e-12 * np.abs(x).max()
    assert list(a["response"].values) == list(b["response"].values)
    a.close()
    b.close()


def test_run_the_train_preset(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    case = 'preset = "wang2017_metro_train6"\n' + BASE.split("\n", 1)[1]
    (tmp_path / "case.toml").write_text(case, encoding="utf-8")
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 0
    ds = xr.open_dataset(tmp_path / "out" / "results.nc")
    labels = [str(r) for r in ds["response"].values]
    # 6 cars of 10 DOFs, then the rail under 24 wheels, each named by its car
    assert len(labels) == 6 * 10 + 24
    assert labels[10] == "car2.carbody.bounce"
    assert "rail@car3.wheel2" in labels
    assert ds.sizes["wheel"] == 24
    ds.close()
    summary = (tmp_path / "out" / "summary.md").read_text()
    section = summary.split("## Per car and for the train", 1)[1].split("\n## ", 1)[0]
    rows = [line.split("|")[1].strip() for line in section.splitlines() if line.startswith("| ")]
    assert rows[1:] == [f"car{i}" for i in range(1, 7)] + ["train"]
