"""``railvib sweep``: run, resume, errors on one line, plots and exports."""

import pytest
import tomli_w
import xarray as xr

from railvib.cli.main import main
from railvib.plot.sweep import plot_sweep
from railvib.sweep import load_sweep_dataset
from tests.unit.sweep.sweep_cases import small_sweep


def _write(tmp_path, d, name="s.toml"):
    path = tmp_path / name
    path.write_text(tomli_w.dumps(d))
    return path


@pytest.mark.slow  # ~2.3 s: whole commands with their files, kept out of the fast suite
def test_run_plot_csv_netcdf_then_resume(tmp_path, capsys):
    f = _write(tmp_path, small_sweep())
    out = tmp_path / "out"
    args = ["sweep", str(f), "-o", str(out), "-j", "1", "--no-progress"]
    assert main([*args, "--plot", "--csv", "--netcdf"]) == 0
    err = capsys.readouterr().err
    assert "12 cases (3 x 4 over track.pad_temperature_c, speed_kmh) in 3 chunks" in err
    for name in ("sweep.zarr", "sweep.nc", "summary.csv", "manifest.json"):
        assert (out / name).exists(), name
    pngs = sorted(p.name for p in (out / "plots").glob("*.png"))
    assert "sweep_peak_wheelset1_bounce.png" in pngs
    assert "sweep_dominant_frequency_wheelset1_bounce.png" in pngs
    first = load_sweep_dataset(out)
    assert main(args) == 0  # everything done: nothing recomputed, same result
    xr.testing.assert_identical(load_sweep_dataset(out), first)


def test_changed_sweep_file_is_refused_exit_2(tmp_path, capsys):
    out = tmp_path / "out"
    f = _write(tmp_path, small_sweep())
    assert main(["sweep", "run", str(f), "-o", str(out), "-j", "1", "--no-progress"]) == 0
    changed = small_sweep(chunk_size=2)
    f2 = _write(tmp_path, changed, "s2.toml")
    capsys.readouterr()
    assert main(["sweep", str(f2), "-o", str(out), "-j", "1", "--no-progress"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("error: sweep output ")
    assert "different sweep (changed: chunk_size)" in err[-1]
    assert "--overwrite" in err[-1]
    assert not any("Traceback" in line for line in err)


def test_bad_sweep_file_one_line_exit_2(tmp_path, capsys):
    bad = small_sweep(axes=[{"field": "speed_kmh", "values": [40.0, 0.0]}])
    assert main(["sweep", str(_write(tmp_path, bad)), "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: speed_kmh = 0.0: must be > 0")
    assert "axes[0].values[1]" in err
    assert "Traceback" not in err


@pytest.mark.slow  # ~1.0 s: whole commands with their files, kept out of the fast suite
def test_plot_and_export_commands(tmp_path, capsys):
    out = tmp_path / "out"
    f = _write(tmp_path, small_sweep())
    assert main(["sweep", str(f), "-o", str(out), "-j", "1", "--no-progress"]) == 0
    assert (
        main(
            [
                "sweep",
                "plot",
                str(out),
                "-r",
                "rail@wheel2",
                "-v",
                "rms",
                "--x",
                "speed_kmh",
                "-o",
                str(tmp_path / "p"),
            ]
        )
        == 0
    )
    assert (tmp_path / "p" / "sweep_rms_rail_at_wheel2.png").stat().st_size > 0
    assert (
        main(
            [
                "sweep",
                "export",
                str(out),
                "--csv",
                str(tmp_path / "t.csv"),
                "--netcdf",
                str(tmp_path / "t.nc"),
            ]
        )
        == 0
    )
    assert (tmp_path / "t.csv").exists()
    assert (tmp_path / "t.nc").exists()


def test_plot_sweep_lines_and_heatmap(tmp_path):
    out = tmp_path / "out"
    f = _write(tmp_path, small_sweep())
    assert main(["sweep", str(f), "-o", str(out), "-j", "1", "--no-progress"]) == 0
    ds = load_sweep_dataset(out)
    ax = plot_sweep(
        ds,
        "peak",
        ["wheelset1.bounce", "wheelset4.bounce"],
        kind="lines",
        x="speed_kmh",
        sel={"track.pad_temperature_c": 2},
    )
    assert len(ax.lines) == 2
    assert "track.pad_temperature_c=30.0" in ax.get_title()
    ax = plot_sweep(ds, "dominant_frequency", "wheelset1.bounce")
    assert len(ax.collections) == 1  # a heat map over the two axes


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_plot_commands_default_to_the_sweep_folder(tmp_path, capsys):
    f = tmp_path / "s.toml"
    f.write_text(tomli_w.dumps(small_sweep()))
    out = tmp_path / "out"
    assert main(["sweep", str(f), "-o", str(out), "-j", "1", "--no-progress"]) == 0
    capsys.readouterr()
    assert main(["sweep", "plot", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert f"written {out / 'plots' / 'sweep_peak_wheelset1_bounce.png'}" in lines
    assert len(lines) == 6
    # the top-level alias, on the store itself, with the axes swapped
    args = ["plot", str(out / "sweep.zarr"), "-v", "peak", "-r", "carbody.bounce"]
    assert main([*args, "--x", "track.pad_temperature_c", "--y", "speed_kmh"]) == 0
    assert capsys.readouterr().out.splitlines() == [
        f"written {out / 'plots' / 'sweep_peak_carbody_bounce.png'}"
    ]
    assert main(["plot", str(out), "--x", "temperature"]) == 2
    assert "x = 'temperature'" in capsys.readouterr().err
