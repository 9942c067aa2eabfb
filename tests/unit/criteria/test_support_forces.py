"""Forces through the rail seat under each wheel against the finite track's explicit DOFs.

The finite model (:class:`railvib.validation.FiniteTrack`) is solved directly under the
contact forces at the wheels; its pad force is ``K_p (w_rail - w_sleeper)`` and its ballast
force ``K_b w_sleeper`` at the seat, from its own sleeper DOFs: it never uses the wave
solver's receptance or the condensed seat relations that ``support_force_variables`` uses.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from scipy.sparse.linalg import splu

import railvib
from railvib.case import build_system, case_from_dict
from railvib.outputs import criteria_lines
from railvib.outputs.supports import seat_positions, support_force_variables
from railvib.pads import Hysteretic
from railvib.pads.scaled import ScaledPad
from railvib.track import BallastedTrack, FloatingSlabTrack, PeriodicTrack, Rail
from railvib.validation.finite_track import FiniteTrack

RAIL = Rail(6.42e6, 60.0, 0.02)  # a small rail loss, so the waves die out in the finite model
PAD, BALLAST = Hysteretic(3e8, 0.25), Hysteretic(5e7, 1.0)
D = 0.6
WHEELS = np.array([0.3, -2.1, -12.3, -14.7])  # four wheels at mid-span (m)
F = np.geomspace(1.0, 500.0, 5)
#: below 500 Hz, 16 Hermite elements per bay and 40 bays of margin put the finite model
#: within 1e-6 of the exact track (tests/validation/test_ballasted_finite_track.py)
RTOL = 1e-6


def _dataset(seed: int = 1) -> xr.Dataset:
    rng = np.random.default_rng(seed)
    forces = rng.normal(size=(F.size, WHEELS.size)) + 1j * rng.normal(size=(F.size, WHEELS.size))
    return xr.Dataset(
        {
            "frf_force": (("frequency", "wheel"), forces),
            "irregularity_psd": (("frequency",), np.ones(F.size)),
        },
        coords={"frequency": F},
    )


def _finite_seat_forces(ballast: bool, ds: xr.Dataset) -> dict[str, np.ndarray]:
    seats = seat_positions(WHEELS, D)
    layers = {"ballast": BALLAST, "sleeper_mass": 162.0} if ballast else {}
    finite = FiniteTrack.around(
        np.concatenate([WHEELS, seats]),
        RAIL,
        PAD,
        D,
        margin_spans=40,
        elements_per_span=16,
        absorber_spans=10,
        absorber_damping=2e5,
        **layers,
    )
    sleeper = 2 * finite.nodes.size + (np.rint(seats / D).astype(int) - finite.first_sleeper)
    out = {"pad": np.empty((F.size, WHEELS.size), complex)}
    if ballast:
        out["ballast"] = np.empty_like(out["pad"])
    for k, f in enumerate(F):
        load = np.zeros(finite.n_dof, dtype=complex)
        load[finite.w_dof(WHEELS)] = ds["frf_force"].values[k]
        u = splu(finite.dynamic_stiffness(f)).solve(load)
        rail = u[finite.w_dof(seats)]
        below = u[sleeper] if ballast else 0.0
        out["pad"][k] = PAD.stiffness(f) * (rail - below)
        if ballast:
            out["ballast"][k] = BALLAST.stiffness(f) * below
    return out


@pytest.mark.parametrize("ballast", [False, True], ids=["rigid base", "ballasted"])
def test_seat_forces_equal_the_finite_tracks_explicit_dofs(ballast):
    track = (
        BallastedTrack(RAIL, PAD, D, sleeper_mass=162.0, ballast=BALLAST)
        if ballast
        else PeriodicTrack(RAIL, PAD, D)
    )
    ds = _dataset()
    got = support_force_variables(SimpleNamespace(track=track, wheel_positions=WHEELS), ds)
    want = _finite_seat_forces(ballast, ds)
    assert list(got["psd_support_force"]["layer"].values) == list(want)
    for j, layer in enumerate(want):
        amplitude = np.sqrt(got["psd_support_force"].values[:, :, j])
        np.testing.assert_allclose(amplitude, np.abs(want[layer]), rtol=RTOL, err_msg=layer)
    # the seat nearest each wheel; all four wheels are at mid-span: the seat ahead
    positions = got["psd_support_force"]["support_position"].values
    np.testing.assert_allclose(positions, [0.6, -1.8, -12.0, -14.4], rtol=0, atol=1e-12)


def test_a_rail_pair_reports_one_rails_seat():
    # the rail pair's seat stands for both rails' seats: the same track for one rail with
    # the pad doubled carries twice the force; per rail seat it is the same
    ds = _dataset()
    one = PeriodicTrack(Rail(2 * 6.42e6, 2 * 60.0, 0.02), ScaledPad(PAD, 2.0), D)
    single = support_force_variables(SimpleNamespace(track=one, wheel_positions=WHEELS), ds)
    whole = np.abs(_finite_seat_forces(False, ds * 0.5)["pad"]) ** 2  # half the load per rail
    np.testing.assert_allclose(single["psd_support_force"].values[:, :, 0], whole, rtol=2 * RTOL)


def test_a_slab_track_gives_its_bearing_forces_or_its_foundation_bay_forces():
    # the bearings' forces come from the slab under all wheels together (checked against
    # the finite slab track in tests/validation/test_track14_slab_supports.py); a
    # continuous foundation's per bay (tests/validation/test_slab14b_foundation_forces.py)
    slab = build_system(case_from_dict({"preset": "floating_slab_metro"}))
    got = support_force_variables(slab, _dataset())
    assert list(got["psd_support_force"]["layer"].values) == ["pad", "bearing"]
    continuous = FloatingSlabTrack(
        Rail(6.42e6, 60.0),
        PAD,
        D,
        slab_bending_stiffness=1.2e8,
        slab_mass_per_length=1750.0,
        foundation=Hysteretic(7e6, 0.2),
    )
    system = SimpleNamespace(track=continuous, wheel_positions=WHEELS)
    got = support_force_variables(system, _dataset())
    assert list(got["psd_support_force"]["layer"].values) == ["foundation"]


def test_a_run_holds_the_seat_forces_their_levels_and_a_summary_line():
    case = case_from_dict(
        {
            "preset": "thompson_ballasted",
            "frequency": {"spacing": "log", "f_min": 1.0, "f_max": 500.0, "n": 200},
        }
    )
    ds = railvib.run(case)
    assert list(ds["layer"].values) == ["pad", "ballast"]
    assert ds["psd_support_force"].attrs["units"] == "N^2/Hz"
    assert ds["octave_level_support_force"].dims == ("band", "wheel", "layer")
    # the RMS is the integral of the PSD it comes from (trapezoid on the run's grid)
    psd = ds["psd_support_force"].values
    f = ds["frequency"].values
    rms = np.sqrt(np.sum(np.diff(f)[:, None, None] * (psd[1:] + psd[:-1]) / 2, axis=0))
    np.testing.assert_allclose(ds["support_force_rms"].values, rms, rtol=1e-12)
    line = next(s for s in criteria_lines(ds) if s.startswith("rail-seat forces"))
    assert "pad" in line
    assert "ballast" in line
