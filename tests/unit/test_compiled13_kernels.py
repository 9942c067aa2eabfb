"""The compiled coupled solve and the leaner wave kernel against their NumPy references (issue 13).

The coupled point kernel (:mod:`railvib.coupled_kernel`) solves the same equations as
:func:`railvib.coupling.coupled_response` point by point, with partial pivoting where the
reference eliminates without exchanges (and leaves weak pivots to LAPACK); the two agree
to rounding. The plain-Python kernels are checked where numba is not installed too.
"""

import numpy as np
import pytest

import railvib
from railvib import coupled_kernel
from railvib.case import build_system, case_from_dict
from railvib.case.load import load_preset_case, merge_case_dicts
from railvib.coupling import compiled_solve, coupled_response
from railvib.pem import excitation_vector, wheel_delays
from railvib.stack import stacked
from railvib.sweep.spec import nested_override
from railvib.sweep.stacked import frf_case_stack
from railvib.track import compiled
from railvib.track.stacked import receptance_entries, stacked_waves

#: reason: the same equations in another order of operations (and another pivot order
#: where the reference's elimination passes its pivot test); 1e-12 of each response's peak
RTOL = 1e-12


def _max_rel(a, b):
    """Largest difference relative to the largest value of each response (last axis)."""
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=-2, keepdims=True)))


@pytest.fixture(scope="module")
def system():
    return build_system(railvib.load_preset_case())


def _inputs(system, f):
    x = system.wheel_positions
    rec = system.track.receptance(f, x, x)
    cond = system.vehicle.condensed_to_wheels(f)
    v = excitation_vector(f, wheel_delays(system.vehicle.wheel_offsets, system.speed))
    return rec, cond, v


def test_uncompiled_coupled_kernel_equals_coupled_response(system):
    f = np.geomspace(0.5, 3000.0, 40)
    rec, cond, v = _inputs(system, f)
    one = np.zeros(1, dtype=np.int64)
    got = coupled_kernel.coupled_points(
        rec[None],
        one,
        cond.stiffness[None],
        cond.recovery[None],
        one,
        np.array([system.contact_stiffness]),
        v[None],
        one,
        run=coupled_kernel._points,
    )
    ref = coupled_response(cond, rec, system.contact_stiffness, v[..., None])
    for g, r in zip(got, ref, strict=True):
        assert _max_rel(g[0], r[..., 0]) < RTOL


def test_coupled_kernel_pivots_where_elimination_without_exchanges_fails():
    # (R + h I) S + I with S = I and R_00 = -1 - h: the first pivot is exactly zero, so the
    # solve must exchange rows; the reference here is LAPACK on the same matrix
    rng = np.random.default_rng(13)
    n, h = 4, 0.5
    rec = rng.normal(size=(3, n, n)) + 1j * rng.normal(size=(3, n, n))
    rec[:, 0, 0] = -1.0 - h
    stiff = np.broadcast_to(np.eye(n, dtype=complex), (3, n, n)).copy()
    recovery = rng.normal(size=(3, 6, n)) + 0j
    r = rng.normal(size=(3, n)) + 1j * rng.normal(size=(3, n))
    one = np.zeros(1, dtype=np.int64)
    args = (rec[None], one, stiff[None], recovery[None], one, np.array([1.0 / h]), r[None], one)
    u_v, force, rail = coupled_kernel.coupled_points(*args, run=coupled_kernel._points)
    system = (rec + h * np.eye(n)) @ stiff + np.eye(n)
    u_w = np.linalg.solve(system, r[..., None])[..., 0]
    # reason: LAPACK's and the kernel's pivoted elimination, rounding of O(cond) x 1e-16
    np.testing.assert_allclose(force[0], -u_w, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(u_v[0], np.einsum("fij,fj->fi", recovery, u_w), rtol=1e-11)
    np.testing.assert_allclose(rail[0], np.einsum("fij,fj->fi", rec, -u_w), rtol=1e-11)


def test_wave_kernel_to_observation_points_off_the_loads_equals_the_numpy_kernel(system):
    # seats (on sleepers, x = 0 exactly), a midspan load (the half bay's own coordinate)
    # and coordinates shared between loads and observation points
    d = system.track.sleeper_spacing
    x = np.array([0.5, -3.5, -0.25, 2.0])
    obs = np.array([0.5, 1.0, -3.0, -0.25, 0.75, 2.0])
    f = np.geomspace(0.5, 3000.0, 30)
    ei = system.track.rail.bending_stiffness * (1 + 1e-12j)
    beta4 = (system.track.rail.mass_per_length * (2 * np.pi * f) ** 2 * d**4 / ei).astype(complex)
    pad = system.track.support_stiffness(f) * d**3 / ei
    rec, condition, bad = compiled.compiled_receptance(beta4, pad, x, obs, kernel=compiled._points)
    waves = stacked_waves(beta4, pad)
    ref = np.asarray(stacked(receptance_entries(waves, x, obs)))
    assert not bad.any()
    scale = np.abs(ref).max(axis=0, keepdims=True)
    # reason: the same formulas, each Krylov series summed once per coordinate
    assert float(np.max(np.abs(rec - ref) / scale)) < RTOL


def _sweep_systems():
    base = load_preset_case().model_dump(exclude_none=True)
    overrides = [
        ("track.pad.stiffness_n_per_m", 2.0e7),
        ("track.pad.stiffness_n_per_m", 1.5e8),
        ("vehicle.carbody_mass", 30000.0),
        ("contact.stiffness", 8.0e8),
        ("speed_kmh", 160.0),
        ("track.sleeper_spacing", 0.65),
    ]
    return [
        build_system(case_from_dict(merge_case_dicts(base, nested_override(k, v))))
        for k, v in overrides
    ]


def test_case_stack_on_the_compiled_solve_equals_the_numpy_path():
    pytest.importorskip("numba")
    f = np.geomspace(0.5, 1000.0, 150)
    systems = _sweep_systems()
    assert compiled_solve(len(systems) * f.size, 4, True)
    fast = frf_case_stack(f, systems, compiled=True)
    slow = frf_case_stack(f, systems, compiled=False)
    for name in ("vehicle", "rail", "contact_force"):
        assert _max_rel(getattr(fast, name), getattr(slow, name)) < RTOL


def test_a_run_with_the_kernels_loaded_equals_the_numpy_run(system, monkeypatch):
    pytest.importorskip("numba")
    compiled.compile_kernel()
    f = np.linspace(0.5, 1000.0, 2 * compiled.LOADED_MIN_POINTS)
    assert compiled_solve(f.size, 4)  # loaded with the wave kernel: the run uses both
    fast = system.frf(f)
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    assert not compiled_solve(f.size, 4)
    slow = system.frf(f)
    for name in ("vehicle", "rail", "contact_force"):
        assert _max_rel(getattr(fast, name), getattr(slow, name)) < RTOL


def test_many_wheels_stay_on_lapack():
    assert not compiled_solve(10**6, 32, True)
