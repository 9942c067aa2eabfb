"""The compiled wave kernel (numba) against the NumPy stacked kernel, its reference (issue 13).

The point kernel is plain Python that numba compiles; run uncompiled on a few points it
is checked where numba is not installed too. Both evaluate the same formulas point by
point instead of entry array by entry array, so they agree to rounding: 1e-12 of each
receptance entry's peak over the stack (the NumPy kernel agrees with the reference wave
solver, ``PeriodicTrack.waves``, to 3e-15; the compiled one compares magnitudes squared
and takes its own Krylov term count per point, changing the last digits only).
"""

from dataclasses import replace

import numpy as np
import pytest

import railvib
from railvib.case import build_system
from railvib.coupling import track_receptances
from railvib.stack import stacked
from railvib.track import compiled
from railvib.track.stacked import receptance_entries, stacked_waves

#: reason: the same formulas in another order of operations (see the module doc)
RTOL = 1e-12


@pytest.fixture(scope="module")
def system():
    return build_system(railvib.load_preset_case())


def _points(system, f):
    track = system.track
    ei = track.rail.bending_stiffness * (1 + 1e-12j)  # the solver's vanishing-loss floor
    d = track.sleeper_spacing
    beta4 = track.rail.mass_per_length * (2 * np.pi * f) ** 2 * d**4 / ei
    return beta4.astype(complex), track.support_stiffness(f) * d**3 / ei


def _reference(beta4, pad, x):
    waves = stacked_waves(beta4, pad)
    return np.asarray(stacked(receptance_entries(waves, x, x))), waves.condition


def _max_rel(a, b):
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=0, keepdims=True)))


#: wheel positions / d: the default car's, and loads left and right of their sleeper
POSITIONS = [
    None,
    np.array([3.7, 1.2, -0.4, -7.9]),
    np.array([0.0, -0.5, -2.25]),
]


@pytest.mark.parametrize("x", POSITIONS, ids=["car", "mixed", "sleeper_and_midspan"])
def test_uncompiled_point_kernel_equals_the_numpy_kernel(system, x):
    x = system.wheel_positions / system.track.sleeper_spacing if x is None else x
    f = np.geomspace(0.5, 3000.0, 25)
    beta4, pad = _points(system, f)
    rec, condition, bad = compiled.compiled_receptance(beta4, pad, x, x, kernel=compiled._points)
    ref, ref_condition = _reference(beta4, pad, x)
    assert not bad.any()
    assert _max_rel(rec, ref) < RTOL
    # reason: the same estimate from magnitudes squared (a few ulp)
    np.testing.assert_allclose(condition, ref_condition, rtol=1e-12)


def test_points_the_numpy_kernel_solves_densely_are_left_to_it(system):
    # a lossless rail on a lossless pad: band edges, where the Bloch vector needs an SVD
    track = replace(system.track, pad=railvib.pads.SpringDamper(5.0e7, 0.0))
    f = np.linspace(200.0, 1500.0, 400)
    d = track.sleeper_spacing
    ei = track.rail.bending_stiffness * (1 + 1e-12j)
    beta4 = (track.rail.mass_per_length * (2 * np.pi * f) ** 2 * d**4 / ei).astype(complex)
    pad = track.support_stiffness(f) * d**3 / ei
    x = np.array([0.3, -1.7])
    _, _, bad = compiled.compiled_receptance(beta4, pad, x, x, kernel=compiled._points)
    weak = stacked_waves(beta4, pad)
    # the flagged points are those of a weak cross product or pivot in the NumPy kernel
    assert bad.any()
    assert bad.sum() < f.size // 4
    assert np.all(np.isfinite(weak.condition))


@pytest.mark.slow  # numba compiles the kernel on its first use (seconds), then caches it
def test_compiled_kernel_equals_the_numpy_kernel_on_a_large_stack(system):
    pytest.importorskip("numba")
    f = np.geomspace(0.5, 3000.0, 20000)
    beta4, pad = _points(system, f)
    x = system.wheel_positions / system.track.sleeper_spacing
    rec, condition, bad = compiled.compiled_receptance(beta4, pad, x, x)
    ref, _ = _reference(beta4, pad, x)
    ok = ~bad
    assert bad.sum() < f.size // 1000  # weak pivots near 3 kHz: left to the NumPy kernel
    assert _max_rel(rec[ok], ref[ok]) < RTOL


@pytest.mark.slow  # as above
def test_track_receptances_agree_compiled_or_not(system, monkeypatch):
    pytest.importorskip("numba")
    f = np.geomspace(0.5, 3000.0, 20000)
    lossless = replace(system.track, pad=railvib.pads.SpringDamper(5.0e7, 0.0))
    tracks = [system.track, lossless]
    x = [system.wheel_positions] * 2
    fast = track_receptances(f, tracks, x, compiled=True)
    slow = track_receptances(f, tracks, x, compiled=False)
    # every point, those left to the NumPy kernel included
    assert _max_rel(fast[0], slow[0]) < RTOL
    # reason: without loss the wave matching's condition number reaches ~1e4 near the band
    # edges, and two evaluations of equal quality differ by about condition x 1e-16
    assert _max_rel(fast[1], slow[1]) < 1e-10
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    assert not compiled.use_compiled(10 * compiled.COMPILED_MIN_POINTS)


def test_small_stacks_and_small_work_stay_on_numpy():
    assert not compiled.use_compiled(compiled.LOADED_MIN_POINTS - 1)
    if not compiled._KERNEL:  # nothing loaded yet in this process: the work decides
        assert not compiled.use_compiled(10_000, work=compiled.COMPILED_MIN_POINTS - 1)
        assert not compiled._KERNEL


def test_a_run_below_the_threshold_is_the_numpy_kernel_exactly(system):
    f = np.geomspace(0.5, 1000.0, 300)
    x = system.wheel_positions
    rec = system.frf(f).receptance
    # the run path calls the track's own solver there: the same numbers, bit for bit
    np.testing.assert_array_equal(rec, system.track.receptance(f, x, x))
