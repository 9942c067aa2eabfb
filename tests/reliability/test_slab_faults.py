"""Slab tracks on the command line: bad input is one field-named line; run and sweep agree."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from railvib.cli.main import main

GRID = '[frequency]\nspacing = "log"\nf_min = 1.0\nf_max = 200.0\nn = 12\n'
BASE = 'preset = "wang2017_metro"\nrail_model = "rail_pair"\n' + GRID
TRACK = """[track]
model = "{model}"
sleeper_spacing = 0.6
slab_bending_stiffness = 1.2e8
slab_mass_per_length = 1750.0
{extra}
[track.rail]
bending_stiffness = 6.62e6
mass_per_length = 60.64
[track.pad]
model = "hysteretic"
stiffness_n_per_m = 4e7
loss_factor = 0.2
"""
FOUNDATION = (
    '[track.foundation]\nmodel = "hysteretic"\nstiffness_n_per_m = 7e6\nloss_factor = 0.2\n'
)
BEARING = '[track.bearing]\nmodel = "spring_damper"\nstiffness_n_per_m = 7e6\n'
UNIT = "slab_length_m = 4.8\nfasteners_per_slab = 8"

CASES = {
    "no-support": (TRACK.format(model="floating_slab", extra=""), "track.foundation"),
    "two-supports": (
        TRACK.format(model="floating_slab", extra="") + FOUNDATION + BEARING,
        "track.foundation",
    ),
    "no-slab-mass": (
        TRACK.format(model="floating_slab", extra="").replace("slab_mass_per_length = 1750.0\n", "")
        + FOUNDATION,
        "track.slab_mass_per_length",
    ),
    "negative-slab-ei": (
        TRACK.format(model="floating_slab", extra="").replace("= 1.2e8", "= -1.2e8") + FOUNDATION,
        "track.slab_bending_stiffness",
    ),
    "slab-shorter-than-spacing": (
        TRACK.format(model="unit_slab", extra="slab_length_m = 0.5\nfasteners_per_slab = 1")
        + FOUNDATION,
        "track.slab_length_m",
    ),
    "fasteners-do-not-fit": (
        TRACK.format(model="unit_slab", extra="slab_length_m = 4.8\nfasteners_per_slab = 9")
        + FOUNDATION,
        "track.fasteners_per_slab",
    ),
    "fractional-fastener-count": (
        TRACK.format(model="unit_slab", extra="slab_length_m = 4.8\nfasteners_per_slab = 7.5")
        + FOUNDATION,
        "track.fasteners_per_slab",
    ),
    "no-slab-length": (
        TRACK.format(model="unit_slab", extra="fasteners_per_slab = 8") + FOUNDATION,
        "track.slab_length_m",
    ),
    "unit-key-on-floating": (
        TRACK.format(model="floating_slab", extra=UNIT) + FOUNDATION,
        "track.slab_length_m",
    ),
    "bearing-spacing-with-foundation": (
        TRACK.format(model="floating_slab", extra="bearing_spacing_fasteners = 2") + FOUNDATION,
        "track.bearing_spacing_fasteners",
    ),
    "negative-joint": (
        TRACK.format(model="unit_slab", extra=UNIT + "\njoint_shear_stiffness = -1.0") + FOUNDATION,
        "track.joint_shear_stiffness",
    ),
}


def _one_error_line(captured, field):
    lines = [s for s in captured.err.splitlines() if s.strip() and not s.startswith("warning:")]
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("error: "), lines[0]
    assert field in lines[0], lines[0]
    assert "Traceback" not in captured.out + captured.err


@pytest.mark.parametrize(("track", "field"), CASES.values(), ids=CASES)
def test_bad_slab_track_is_one_field_named_line(tmp_path, monkeypatch, capsys, track, field):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(BASE + track, encoding="utf-8")
    before = set(tmp_path.rglob("*"))
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 2
    _one_error_line(capsys.readouterr(), field)
    assert set(tmp_path.rglob("*")) == before


def test_non_passive_foundation_is_refused_before_computing(tmp_path, monkeypatch, capsys):
    # an active foundation (negative viscous damping: Im K < 0) is refused by the pad
    # family's own bound, named under the foundation's table, before any solve
    monkeypatch.chdir(tmp_path)
    active = FOUNDATION.replace('"hysteretic"', '"spring_damper"').replace(
        "loss_factor = 0.2", "damping_ns_per_m = -1e4"
    )
    (tmp_path / "case.toml").write_text(
        BASE + TRACK.format(model="floating_slab", extra="") + active, encoding="utf-8"
    )
    before = set(tmp_path.rglob("*"))
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 2
    _one_error_line(capsys.readouterr(), "track.foundation")
    assert set(tmp_path.rglob("*")) == before


def test_validate_refuses_a_hysteretic_slab_foundation_naming_its_key(
    tmp_path, monkeypatch, capsys
):
    # the reference models of railvib validate have slab DOFs now; a layer without an
    # exact time-domain form is refused by its key before any work (was: track.model)
    monkeypatch.chdir(tmp_path)
    viscous_pad = TRACK.replace(
        'model = "hysteretic"\nstiffness_n_per_m = 4e7\nloss_factor = 0.2',
        'model = "spring_damper"\nstiffness_n_per_m = 4e7\ndamping_ns_per_m = 4e4',
    )
    (tmp_path / "case.toml").write_text(
        BASE + viscous_pad.format(model="floating_slab", extra="") + FOUNDATION, encoding="utf-8"
    )
    before = set(tmp_path.rglob("*"))
    assert main(["validate", "case.toml", "-o", "out"]) == 2
    captured = capsys.readouterr()
    _one_error_line(captured, "track.foundation.model")
    assert "hysteretic" in captured.err
    assert set(tmp_path.rglob("*")) == before


@pytest.mark.slow
def test_sweep_of_a_slab_track_equals_its_cases_run_one_by_one(tmp_path, monkeypatch):
    # the sweep groups cases by structure and stacks pads and speeds over one track
    # solution (sweep.stacked.frf_pad_stack hands the track its pads point by point); each
    # case must equal the same case run alone (rounding of two orderings of the same
    # arithmetic: 1e-9)
    monkeypatch.chdir(tmp_path)
    track = TRACK.format(model="unit_slab", extra=UNIT + "\njoint_shear_stiffness = 1e8")
    (tmp_path / "base.toml").write_text(BASE + track + FOUNDATION, encoding="utf-8")
    (tmp_path / "sweep.toml").write_text(
        'title = "slab"\nmode = "product"\nvariables = ["psd_acceleration"]\nbase = "base.toml"\n'
        '[[axes]]\nfield = "track.pad.stiffness_n_per_m"\nname = "kp"\nvalues = [2e7, 4e7]\n'
        '[[axes]]\nfield = "track.slab_mass_per_length"\nname = "ms"\nvalues = [1200.0, 1750.0]\n'
        '[[axes]]\nfield = "speed_kmh"\nname = "speed"\nvalues = [60.0, 80.0]\n',
        encoding="utf-8",
    )
    assert main(["sweep", "sweep.toml", "-o", "sw"]) == 0
    swept = xr.open_zarr(tmp_path / "sw" / "sweep.zarr")["psd_acceleration"]
    one = (
        BASE.replace('rail_model = "rail_pair"\n', 'rail_model = "rail_pair"\nspeed_kmh = 60.0\n')
        + track.replace("stiffness_n_per_m = 4e7", "stiffness_n_per_m = 2e7").replace(
            "1750.0", "1200.0"
        )
        + FOUNDATION
    )
    (tmp_path / "one.toml").write_text(one, encoding="utf-8")
    assert main(["run", "one.toml", "-o", "one", "--no-plots"]) == 0
    alone = xr.open_dataset(tmp_path / "one" / "results.nc")["psd_acceleration"]
    point = swept.sel(kp=2e7, ms=1200.0, speed=60.0).transpose(*alone.dims)
    np.testing.assert_allclose(point.values, alone.values, rtol=1e-9)
