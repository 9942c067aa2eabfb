"""The stacked-layout kernels (issue 13) against dense LAPACK and the per-case solver."""

from dataclasses import replace

import numpy as np
import pytest

import railvib
from railvib.case import build_system
from railvib.errors import CaseError
from railvib.pads import SpringDamper
from railvib.stack import entries, namespace, solve, stacked
from railvib.sweep.stacked import frf_pad_stack, frf_stack
from railvib.track.stacked import receptance_entries, stacked_waves
from railvib.vehicle import RigidBody, Suspension, Vehicle, Wheel
from railvib.vehicle.parts import Attachment


@pytest.fixture(scope="module")
def system():
    return build_system(railvib.load_preset_case())


def _max_rel(a, b):
    """Largest difference relative to the largest value of each response (PSD notches)."""
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=0, keepdims=True)))


def test_solve_equals_lapack_and_flags_the_points_that_need_pivoting():
    rng = np.random.default_rng(0)
    a = rng.normal(size=(50, 4, 4)) + 1j * rng.normal(size=(50, 4, 4)) + 4 * np.eye(4)
    a[7, 0, 0] = 0.0  # elimination without row exchanges cannot use this pivot
    b = rng.normal(size=(50, 4, 3)) + 0j
    x, bad = solve(entries(a), [b[:, i, :] for i in range(4)])  # 3 right-hand sides
    assert bad[7]
    assert bad.sum() <= 5
    ok = ~bad
    # reason: well-conditioned 4x4 systems (diagonal shifted by 4): a few ulp times a
    # condition number of order 10
    np.testing.assert_allclose(stacked(x)[ok], np.linalg.solve(a, b)[ok], rtol=1e-12)


def _undamped_car():
    bodies = (
        RigidBody("body", 2.0e4, 1.0e6, 0.0),
        RigidBody("bogie", 2.0e3, 2.0e3, 5.0),
        RigidBody("wheelset1", 1.5e3, None, 6.0),
        RigidBody("wheelset2", 1.5e3, None, 4.0),
    )
    sus = (
        Suspension("secondary", Attachment("body", 5.0), Attachment("bogie", 5.0), 3.0e5),
        Suspension("primary.1", Attachment("bogie", 6.0), Attachment("wheelset1", 6.0), 1.0e6),
        Suspension("primary.2", Attachment("bogie", 4.0), Attachment("wheelset2", 4.0), 1.0e6),
    )
    return Vehicle(bodies, sus, (Wheel("wheelset1", 6.0), Wheel("wheelset2", 4.0)))


def test_condensation_equals_the_dense_schur_complement_even_at_a_zero_pivot():
    vehicle = _undamped_car()
    # the bogie's bounce with everything else held: its diagonal entry of K - w^2 M is 0
    k_bb = vehicle.stiffness_matrix[2, 2]
    f_zero = np.sqrt(k_bb / 2.0e3) / (2 * np.pi)
    f = np.array([0.3, 1.0, f_zero, 7.0, 40.0, 900.0])
    cond = vehicle.condensed_to_wheels(f)
    d = vehicle.dynamic_stiffness(f)
    w = vehicle.wheel_dofs
    b = np.setdiff1d(np.arange(len(vehicle.dofs)), w)
    x = np.linalg.solve(d[:, b][:, :, b], d[:, b][:, :, w])
    schur = d[:, w][:, :, w] - d[:, w][:, :, b] @ x
    # reason: small well-conditioned systems (but at f_zero, where LAPACK pivots): ulps
    assert _max_rel(cond.stiffness, schur) < 1e-11
    assert _max_rel(cond.recovery[:, b], -x) < 1e-11
    np.testing.assert_array_equal(cond.recovery[:, w], np.broadcast_to(np.eye(2), (f.size, 2, 2)))


def test_stacked_track_kernel_equals_the_periodic_track(system):
    track = system.track
    f = np.geomspace(0.5, 5000.0, 400)
    x = system.wheel_positions
    d, ei = track.sleeper_spacing, track.rail.complex_bending_stiffness
    beta4 = track.rail.mass_per_length * (2 * np.pi * f) ** 2 * d**4 / ei
    pad = track.pad.stiffness(f) * d**3 / ei
    rec = stacked(receptance_entries(stacked_waves(beta4, pad), x / d, x / d)) * d**3 / ei
    # reason: both solve the same waves, each accurate to ~1e-11 of the peak against the
    # independent references (docs/validation.md); they must agree to 1e-10
    ref = track.receptance(f, x, x)
    scale = np.abs(ref).max(axis=(1, 2), keepdims=True)
    assert np.max(np.abs(rec - ref) / scale) < 1e-10


def test_frf_stack_and_pad_stack_equal_the_cases_one_by_one(system):
    f = np.geomspace(0.5, 1000.0, 120)
    k = np.array([2.0e7, 6.0e7, 1.5e8])
    c = np.array([1.0e4, 5.0e4, 9.0e4])
    v = np.array([12.0, 25.0, 44.0])
    pads = [SpringDamper(float(ki), float(ci)) for ki, ci in zip(k, c, strict=True)]
    u, rail, force = frf_stack(
        system, f, k[:, None] + 2j * np.pi * f[None, :] * c[:, None], v, block=200
    )
    batch = frf_pad_stack(system, f, [pads[0], pads[1], pads[1]], [None] * 3, v)
    for i in range(3):
        one = replace(system, track=replace(system.track, pad=pads[i]), speed=v[i]).frf(f)
        # reason: the kernels reorder floating-point operations only (1e-10: the two
        # wave solutions above)
        assert _max_rel(u[i], one.vehicle) < 1e-10
        assert _max_rel(rail[i], one.rail) < 1e-10
        assert _max_rel(force[i], one.contact_force) < 1e-10
    one = replace(system, track=replace(system.track, pad=pads[1]), speed=v[2]).frf(f)
    # the same track solution and the same elementwise operations: identical
    np.testing.assert_array_equal(batch.vehicle[2], one.vehicle)


def test_frequency_blocks_give_the_same_numbers(system):
    f = np.geomspace(0.5, 1000.0, 50)
    whole = system.frf(f)
    parts = list(system.frf_blocks(f, block=7))
    assert [sl.start for sl, _ in parts] == list(range(0, 50, 7))
    # every kernel is elementwise over frequency: blocks change nothing
    np.testing.assert_array_equal(np.concatenate([p.vehicle for _, p in parts]), whole.vehicle)
    np.testing.assert_array_equal(
        np.concatenate([p.receptance for _, p in parts]), whole.receptance
    )


def test_backends_are_named_and_missing_ones_refused():
    assert namespace("numpy") is np
    with pytest.raises(CaseError, match="one of numpy, cupy, jax"):
        namespace("torch")
    try:
        import cupy  # noqa: F401
    except ImportError:
        with pytest.raises(CaseError, match="not installed"):
            namespace("cupy")


@pytest.mark.slow
def test_gpu_benchmark_runs_its_numpy_path_and_meets_the_accuracy_goal(capsys):
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "benchmarks" / "bench_gpu.py"
    spec = importlib.util.spec_from_file_location("bench_gpu", path)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    assert bench.main(["--quick", "--backend", "numpy", "--repeat", "1"]) == 0
    out = capsys.readouterr().out
    assert "backend numpy (on the CPU" in out
    assert "goal: max rel diff <= 1e-10: PASS" in out


def test_pad_stack_evaluates_every_layer_at_its_cases_temperature():
    # a ballasted track whose ballast depends on temperature (a viscous ballast under
    # WLF): the stacked sweep must evaluate it at each case's pad temperature, as the
    # case-by-case solver does
    from railvib.pads.tts import WLF, TemperatureShifted

    base = build_system(railvib.load_preset_case("thompson_ballasted"))
    ballast = TemperatureShifted(SpringDamper(5.0e7, 4.0e4), WLF.universal(-40.0), 20.0)
    system = replace(base, track=replace(base.track, ballast=ballast))
    f = np.geomspace(1.0, 2000.0, 60)
    pads = [SpringDamper(3.0e8, 2.0e4), SpringDamper(2.0e8, 2.0e4)]
    temperatures = [-20.0, 20.0, -20.0]
    chosen = [pads[0], pads[0], pads[1]]
    v = np.array([20.0, 20.0, 30.0])
    batch = frf_pad_stack(system, f, chosen, temperatures, v)
    cold, warm = (ballast.stiffness(f, t) for t in (-20.0, 20.0))
    assert np.max(np.abs(cold / warm - 1)) > 0.1  # the temperature matters here
    for i in range(3):
        track = replace(system.track, pad=chosen[i], pad_temperature=temperatures[i])
        one = replace(system, track=track, speed=v[i]).frf(f)
        # reason: the kernels reorder floating-point operations only (as above)
        assert _max_rel(batch.vehicle[i], one.vehicle) < 1e-10
        assert _max_rel(batch.rail[i], one.rail) < 1e-10
