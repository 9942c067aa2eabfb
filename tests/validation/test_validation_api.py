"""The validation API: one system description, deprecated call forms, datasets with units.

Every reference model takes the ``CoupledSystem`` of the symplectic path; the older
parameter-bundle forms must warn (``RailvibDeprecationWarning``) and give the same
result as the new form, bit for bit (same code path, same seed). The settings are
tiny: these tests check the plumbing, not the accuracy (that is
``test_validation_acceptance.py``).
"""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from railvib.coupling import CoupledSystem
from railvib.errors import RailvibDeprecationWarning
from railvib.pads import SpringDamper
from railvib.results import load_netcdf
from railvib.results.variables import VARIABLES
from railvib.spectra import Combined, FRAClass, ShiTai
from railvib.track import PeriodicTrack, Rail
from railvib.validation import (
    FiniteCoupledSystem,
    MonteCarloSettings,
    ValidationSettings,
    finite_track_frf,
    monte_carlo,
    validate_case,
    validate_to_folder,
    validation_files,
    write_validation,
)
from railvib.validation import report as report_module
from railvib.vehicle import PitchPlaneParameters, pitch_plane_10dof

K_H = 9.873e8
SPEED = 80 / 3.6
SPECTRUM = Combined(FRAClass(5), ShiTai())
TINY_MC = MonteCarloSettings(
    realisations=2,
    record_seconds=1.0,
    discard_seconds=0.5,
    ramp_seconds=0.25,
    segment_seconds=0.5,
    margin_spans=10,
    absorber_spans=5,
    batch=1,
)
TINY = ValidationSettings(
    n_frf=6, frf_margin_spans=10, frf_elements_per_span=4, monte_carlo=TINY_MC
)
F = np.array([3.0, 40.0, 400.0])


@pytest.fixture(scope="module")
def system():
    # the paper's vehicle and track (the values of tests/conftest.py), module-scoped
    p = PitchPlaneParameters(21920, 617310, 2550, 1750, 1420, 1.7e6, 5e3, 2.75e5, 3e4, 6.3, 1.1)
    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    return CoupledSystem(pitch_plane_10dof(p), track, K_H, 0.3, SPEED)


@pytest.fixture(scope="module")
def tiny_result(system):
    return validate_case(system, SPECTRUM, settings=TINY, seed=4)


def _bundle(system):
    t = system.track
    return (system.vehicle, t.rail, t.pad, t.sleeper_spacing, K_H, 0.3, SPEED)


def test_finite_system_from_the_coupled_system(system):
    finite = FiniteCoupledSystem.from_system(system, margin_spans=10, elements_per_span=4)
    assert finite.vehicle is system.vehicle
    assert finite.track.rail is system.track.rail
    assert finite.track.pad is system.track.pad
    assert finite.track.sleeper_spacing == system.track.sleeper_spacing
    assert finite.track.pad_temperature == system.track.pad_temperature
    assert (finite.contact_stiffness, finite.leading_wheel_position, finite.speed) == (
        K_H,
        0.3,
        SPEED,
    )
    np.testing.assert_array_equal(finite.wheel_positions, system.wheel_positions)


def test_deprecated_build_warns_and_equals_from_system(system):
    kw = {"margin_spans": 10, "elements_per_span": 4, "absorber_spans": 3}
    new = FiniteCoupledSystem.from_system(system, absorber_damping=1e5, **kw)
    with pytest.warns(RailvibDeprecationWarning, match="from_system"):
        old = FiniteCoupledSystem.build(*_bundle(system), absorber_damping=1e5, **kw)
    for a, b in zip(old.time_domain_matrices(), new.time_domain_matrices(), strict=True):
        assert (a != b).nnz == 0
    np.testing.assert_array_equal(old.frf(F).displacement, new.frf(F).displacement)


def test_deprecated_finite_track_frf_warns_and_equals_new_form(system):
    new = finite_track_frf(system, F, margin_spans=10, elements_per_span=4)
    with pytest.warns(RailvibDeprecationWarning, match=r"finite_track_frf\(system, f"):
        old = finite_track_frf(*_bundle(system), F, margin_spans=10, elements_per_span=4)
    for name in ("vehicle", "rail", "contact_force"):
        np.testing.assert_array_equal(getattr(old, name), getattr(new, name))
    assert old.labels == new.labels


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_deprecated_monte_carlo_warns_and_equals_new_form(system):
    new = monte_carlo(system, SPECTRUM, settings=TINY_MC, seed=3)
    with pytest.warns(RailvibDeprecationWarning, match=r"monte_carlo\(system, spectrum"):
        old = monte_carlo(*_bundle(system), SPECTRUM, settings=TINY_MC, seed=3)
    np.testing.assert_array_equal(old.estimate.psd, new.estimate.psd)
    assert old.estimate.dof == new.estimate.dof
    assert old.labels == new.labels


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_deprecated_validate_case_warns_and_equals_new_form(system, tiny_result):
    with pytest.warns(RailvibDeprecationWarning, match=r"validate_case\(system, spectrum"):
        old = validate_case(
            system.vehicle, system.track, K_H, 0.3, SPEED, SPECTRUM, settings=TINY, seed=4
        )
    for key in ("frf", "mc", "table"):
        xr.testing.assert_identical(getattr(old, key), getattr(tiny_result, key))


def test_first_argument_must_be_a_system():
    with pytest.raises(TypeError, match="CoupledSystem"):
        finite_track_frf("not a system", F)


def test_every_variable_has_real_units(tiny_result):
    psd = VARIABLES["psd_acceleration"]
    psd_vars = ("pem_psd", "finite_psd", "pem_expected", "mc_psd", "mc_lower", "mc_upper")
    for key in ("frf", "mc", "table"):
        ds = getattr(tiny_result, key)
        for name, da in ds.data_vars.items():
            assert da.attrs["units"] != "see attrs", (key, name)
            assert da.attrs["long_name"], (key, name)
            if name in psd_vars:
                assert da.attrs["units"] == psd.units
                assert da.attrs["note"] == psd.note
            elif da.dtype == bool:
                assert da.attrs["units"] == "1"
    assert tiny_result.mc["inside"].dtype == bool
    labels = list(tiny_result.frf["response"].values)
    units = tiny_result.frf.attrs["psd_units"]
    assert units[labels.index("carbody.pitch")] == "(rad/s^2)^2/Hz"
    assert units[labels.index("carbody.bounce")] == psd.units


@pytest.mark.slow  # ~1.9 s: whole commands with their files, kept out of the fast suite
def test_written_datasets_load_back_identical(tiny_result, tmp_path):
    write_validation(tiny_result, tmp_path, "tiny")
    mc = load_netcdf(tmp_path / "tiny_mc.nc")
    assert mc["inside"].dtype == bool
    for name, da in tiny_result.mc.data_vars.items():
        np.testing.assert_array_equal(mc[name].values, da.values)
        assert mc[name].attrs == da.attrs
    assert mc.attrs["psd_units"] == str(tiny_result.mc.attrs["psd_units"])
    assert mc.attrs["realisations"] == 2
    assert (tmp_path / "tiny_agreement.md").is_file()
    assert not list(tmp_path.glob("*.part"))


@pytest.mark.slow  # ~1.4 s: whole commands with their files, kept out of the fast suite
def test_validate_to_folder_writes_exactly_the_listed_files(
    system, tiny_result, monkeypatch, tmp_path
):
    # validate_case is replaced by the module's tiny result: this tests the file set only
    monkeypatch.setattr(report_module, "validate_case", lambda *a, **k: tiny_result)
    out = tmp_path / "out"
    validate_to_folder(system, SPECTRUM, out, name="tiny")
    assert sorted(p.name for p in out.iterdir()) == sorted(validation_files("tiny"))


@pytest.mark.slow  # ~1.8 s: whole commands with their files, kept out of the fast suite
def test_a_failing_validation_leaves_the_earlier_set_and_the_users_files(
    system, tiny_result, monkeypatch, tmp_path
):
    monkeypatch.setattr(report_module, "validate_case", lambda *a, **k: tiny_result)
    out = tmp_path / "out"
    validate_to_folder(system, SPECTRUM, out, name="tiny")
    (out / "notes.txt").write_text("mine", encoding="utf-8")
    before = {p.name: p.read_bytes() for p in out.iterdir()}

    def fail_after_the_first_file(result, outdir, name):
        (Path(outdir) / f"{name}_agreement.md").write_text("half", encoding="utf-8")
        raise OSError("simulated failure half-way through the writes")

    monkeypatch.setattr(report_module, "write_validation", fail_after_the_first_file)
    with pytest.raises(OSError, match="half-way"):
        validate_to_folder(system, SPECTRUM, out, name="tiny")
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert not list(tmp_path.glob(".*"))  # no staging folder left beside it
