"""``railvib track`` end to end, in process: the dataset, the decay-rate table, the plots."""

import re
import shlex
from pathlib import Path

import numpy as np
import pytest

from railvib.case import load_case
from railvib.cli.main import main
from railvib.results.dataset import load_netcdf
from railvib.trackrun import TRACK_FILES, _track

FAST = ["--fmin", "50", "--fmax", "1200", "-n", "40", "--tdr-bands", "100,1000"]


def _case(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text('preset = "thompson_ballasted"\n')
    return path


def _run(tmp_path, *args):
    out = tmp_path / "out"
    rc = main(["track", str(_case(tmp_path)), "-o", str(out), *FAST, *args])
    return rc, out


def test_track_writes_the_dataset_and_the_decay_table(tmp_path, capsys):
    rc, out = _run(tmp_path, "--no-plots")
    assert rc == 0
    printed = capsys.readouterr().out
    assert "band (Hz)" in printed
    assert f"written to {out}/" in printed
    assert sorted(p.name for p in out.iterdir()) == ["decay_rate.csv", "track.nc"]
    ds = load_netcdf(out / "track.nc")
    for name, da in {**ds.data_vars, **{k: ds[k] for k in ("frequency", "position")}}.items():
        assert da.attrs.get("units"), name
        assert da.attrs.get("long_name"), name
    # the file holds the model's receptance for one rail (the case is rail_pair: not doubled)
    track = _track(load_case(_case(tmp_path)))
    f = ds["frequency"].values
    np.testing.assert_allclose(f, np.geomspace(50.0, 1200.0, 40))
    x = ds["position"].values
    assert x[0] == pytest.approx(0.3)  # mid-span of the first bay, d = 0.6 m
    want = track.receptance(f, [0.3], x)[:, :, 0]
    np.testing.assert_allclose(ds["receptance"].values, want, rtol=1e-13)
    np.testing.assert_allclose(ds["receptance_magnitude"].values, np.abs(want), rtol=1e-13)
    omega = 2 * np.pi * f[:, None]
    np.testing.assert_allclose(ds["mobility_magnitude"].values, omega * np.abs(want), rtol=1e-13)
    # the layers of a ballasted track: sleeper displacement, pad and ballast forces
    for name in ("sleeper_displacement", "pad_force", "ballast_force", "foundation_force"):
        assert ds[name].dims == ("frequency", "support"), name
    assert ds.sizes["support"] == 21
    np.testing.assert_array_equal(ds["foundation_force"].values, ds["ballast_force"].values)
    # bands 100 Hz - 1 kHz: 11 of them, each a row of the CSV with the same rates
    lines = [s for s in (out / "decay_rate.csv").read_text().splitlines() if s[0] != "#"]
    assert lines[0].startswith("band_nominal_hz,band_centre_hz,decay_rate_db_per_m")
    assert [s.split(",")[0] for s in lines[1:]] == [
        "100", "125", "160", "200", "250", "315", "400", "500", "630", "800", "1000",
    ]  # fmt: skip
    rates = np.array([float(s.split(",")[2]) for s in lines[1:]])
    np.testing.assert_allclose(rates, ds["decay_rate"].values, rtol=1e-5)  # 6 digits written


@pytest.mark.slow  # draws three figures: ~1.5 s
def test_track_draws_three_figures_and_a_later_run_replaces_the_set(tmp_path):
    rc, out = _run(tmp_path)
    assert rc == 0
    assert sorted(p.name for p in out.iterdir()) == sorted(TRACK_FILES)
    for name in TRACK_FILES:
        assert (out / name).stat().st_size > 0
    (out / "notes.txt").write_text("mine")
    rc, out = _run(tmp_path, "--no-plots", "--load", "support")
    assert rc == 0
    # the earlier plots are gone (not this run's), the user's file kept
    assert sorted(p.name for p in out.iterdir()) == ["decay_rate.csv", "notes.txt", "track.nc"]
    assert load_netcdf(out / "track.nc").attrs["load_position_m"] == 0.0


def test_track_help_lists_its_options(capsys):
    assert main(["track", "--help"]) == 0
    text = capsys.readouterr().out
    for option in ("--fmin", "--fmax", "-n", "--load", "--tdr-bands", "--supports", "-o"):
        assert option in text


DOC = Path(__file__).resolve().parents[2] / "docs" / "track-outputs.md"


@pytest.mark.slow  # a Timoshenko rail's TDR over 11 bands: ~1-4 s
def test_the_python_example_of_the_docs_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), flags=re.S)
    assert blocks
    for block in blocks:
        exec(compile(block, str(DOC), "exec"), {})  # noqa: S102


@pytest.mark.slow  # the documented command: 400 frequencies and three figures, ~5 s
def test_the_documented_command_prints_the_documented_rates(tmp_path, monkeypatch, capsys):
    root = DOC.parents[1]
    line = re.findall(r"```bash\n(railvib track .*?)\n```", DOC.read_text(), flags=re.S)[0]
    args = shlex.split(line)[1:]
    args[1] = str(root / args[1])
    monkeypatch.chdir(tmp_path)
    assert main(args) == 0
    printed = {s.split()[0]: s.split()[1:3] for s in capsys.readouterr().out.splitlines()[1:-1]}
    # the table of the docs, "band | TDR | wave 1", as printed (3 significant digits)
    rows = re.findall(r"^\| (TDR \(dB/m\)|wave 1 \(dB/m\)) \| (.*) \|$", DOC.read_text(), re.M)
    bands = re.findall(r"^\| band \(Hz\) \| (.*) \|$", DOC.read_text(), re.M)[0].split(" | ")
    for (name, values), column in zip(rows, (0, 1), strict=True):
        for band, value in zip(bands, values.split(" | "), strict=True):
            assert printed[band][column] == value.rstrip("*"), (name, band)


def test_a_slab_track_gets_its_receptance_waves_decay_and_bearing_forces(tmp_path):
    # receptance, waves and decay need only receptance and propagation_constants; the
    # support forces are the bearings' (was: left out for every slab track)
    case = tmp_path / "slab.toml"
    case.write_text('preset = "floating_slab_metro"\n')
    out = tmp_path / "out"
    assert main(["track", str(case), "-o", str(out), *FAST, "--no-plots"]) == 0
    ds = load_netcdf(out / "track.nc")
    track = _track(load_case(case))
    f = ds["frequency"].values
    want = track.receptance(f, [ds.attrs["load_position_m"]], ds["position"].values)[:, :, 0]
    np.testing.assert_allclose(ds["receptance"].values, want, rtol=1e-13)
    for name in ("foundation_force", "bearing_force", "pad_force", "slab_displacement"):
        assert name in ds, name
    # the preset's bearings lie under every second fastener (1.2 m apart)
    np.testing.assert_allclose(np.diff(ds["support"].values), 1.2, rtol=1e-12)
    assert np.isfinite(ds["decay_rate"].values).all()
    assert ds.sizes["wave"] == track.propagation_constants(f[:1]).shape[1]


def test_a_slab_on_a_continuous_foundation_gets_its_bay_forces(tmp_path):
    # the foundation force per slab bay (fastener spacing), at the bay centres (was: no
    # support variables); its values: tests/validation/test_slab14b_foundation_forces.py
    case = tmp_path / "slab.toml"
    case.write_text(
        'preset = "wang2017_metro"\n[track]\nmodel = "floating_slab"\nsleeper_spacing = 0.6\n'
        "slab_bending_stiffness = 1.2e8\nslab_mass_per_length = 1750.0\n"
        "[track.rail]\nbending_stiffness = 6.62e6\nmass_per_length = 60.64\n"
        '[track.pad]\nmodel = "hysteretic"\nstiffness_n_per_m = 4e7\nloss_factor = 0.2\n'
        '[track.foundation]\nmodel = "hysteretic"\nstiffness_n_per_m = 7e6\nloss_factor = 0.2\n'
    )
    out = tmp_path / "out"
    assert main(["track", str(case), "-o", str(out), *FAST, "--no-plots"]) == 0
    ds = load_netcdf(out / "track.nc")
    np.testing.assert_allclose(np.diff(ds["support"].values), 0.6, rtol=1e-12)
    assert np.allclose(ds["support"].values % 0.6, 0.3)
    assert ds["foundation_force"].attrs["units"] == "N/N"
    assert "slab_displacement" in ds
    assert "bearing_force" not in ds
    assert np.isfinite(ds["decay_rate"].values).all()
