"""The fused compiled block of a case (issue 13) against the NumPy condensation and solve.

:func:`railvib.coupled_kernel.fused_points` runs the vehicle's elimination
(:attr:`railvib.vehicle.Vehicle.elimination_program`), the coupled solve and the body
recovery point by point; the reference is :meth:`railvib.vehicle.Vehicle.condensed_to_wheels`
with :func:`railvib.coupling.coupled_response`, given the same rail receptance. Vehicles
with other trees than the default car are checked too: a three-stage car with a Maxwell
element, a two-axle wagon, and the six-car train (24 wheels, block-diagonal ``S``).
"""

import importlib.util

import numpy as np
import pytest

import railvib
from railvib import coupled_kernel, coupling
from railvib.case import build_system
from railvib.coupling import CoupledSystem, coupled_response
from railvib.pem import excitation_vector, wheel_delays
from railvib.track import compiled
from railvib.vehicle import RigidBody, Suspension, Vehicle, Wheel, parse_vehicle
from railvib.vehicle.parts import Attachment

#: reason: the same equations in another order of operations (the coupled solve with
#: partial pivoting where the reference eliminates without exchanges, the bodies
#: back-substituted through the elimination's multipliers where the reference forms the
#: recovery matrix): rounding of some 10^2 operations (~1e-14) times the coupled
#: system's condition over the grid (measured differences 1e-15 to 5e-14); 1e-12 of each
#: response's peak
RTOL = 1e-12

#: numba compiles the fused kernel on its first use (seconds), then loads it from its cache
needs_numba = [
    pytest.mark.slow,
    pytest.mark.skipif(importlib.util.find_spec("numba") is None, reason="needs numba"),
]


def _max_rel(a, b):
    """Largest difference relative to the largest value of each response (PSD notches)."""
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=0, keepdims=True)))


@pytest.fixture(scope="module")
def system():
    return build_system(railvib.load_preset_case())


def _body(name, mass, inertia=None, x=0.0):
    out = {"name": name, "mass_kg": mass, "x_m": x}
    if inertia is not None:
        out["pitch_inertia_kg_m2"] = inertia
    return out


def _spring(upper, lower, k, c=0.0, x=None, **extra):
    out = {"upper": upper, "lower": lower, "stiffness_n_per_m": k, "damping_ns_per_m": c}
    if x is not None:
        out["x_m"] = x
    return {**out, **extra}


def _three_stage_car():
    """Unequal bogies, a car-body spring that is only a Maxwell element (another tree)."""
    bodies = [
        _body("carbody", 3.0e4, 1.5e6),
        _body("bogieA", 3000.0, 2500.0, 6.0),
        _body("bogieB", 2000.0, 1800.0, -7.0),
        _body("w1", 1500.0, x=7.2),
        _body("w2", 1500.0, x=4.8),
        _body("w3", 1400.0, x=-6.0),
        _body("w4", 1400.0, x=-8.0),
    ]
    el = {"model": "generalized_maxwell", "k_inf_n_per_m": 2e5, "k_n_per_m": [1e5], "tau_s": [0.01]}
    susp = [
        _spring("carbody", "bogieA", 3e5, 2e4, x=6.0),
        _spring("carbody", "bogieB", 0.0, 1e4, x=-7.0, element=el),
        _spring("bogieA", "w1", 1e6, 3e3),
        _spring("bogieA", "w2", 1.2e6, 3e3),
        _spring("bogieB", "w3", 9e5, 2e3),
        _spring("bogieB", "w4", 9e5, 2e3),
    ]
    return parse_vehicle(bodies, susp, [{"body": b} for b in ("w1", "w2", "w3", "w4")])


def _two_axle_wagon():
    bodies = [
        _body("carbody", 2.0e4, 5.0e5),
        _body("wheelset1", 1200.0, x=4.5),
        _body("wheelset2", 1200.0, x=-4.5),
    ]
    susp = [_spring("carbody", "wheelset1", 1e6, 2e4), _spring("carbody", "wheelset2", 1e6, 2e4)]
    return parse_vehicle(bodies, susp, [{"body": "wheelset1"}, {"body": "wheelset2"}])


def _undamped_car():
    """No damping: the bogie's bounce pivot ``k - omega^2 m`` is 0 at one frequency."""
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


def _vehicle(name, system):
    if name == "default":
        return system.vehicle
    if name == "train6":
        return build_system(railvib.load_preset_case("wang2017_metro_train6")).vehicle
    return {"three_stage": _three_stage_car, "two_axle": _two_axle_wagon}[name]()


def _reference(vehicle, rec_obs, f, k_h, delays):
    """The NumPy path of :meth:`railvib.coupling.CoupledSystem.frf_blocks`."""
    n = len(vehicle.wheels)
    v = excitation_vector(f, delays)[..., None]
    u, force, rail = coupled_response(vehicle.condensed_to_wheels(f), rec_obs[:, :n], k_h, v)
    observed = np.einsum("fow,fw->fo", rec_obs[:, n:], force[..., 0])
    return u[..., 0], force[..., 0], rail[..., 0], observed


def _case(system, vehicle, f):
    """The rail receptance from the vehicle's wheels (default track, vehicle's own
    spacing) to the wheels and the rail seats under them, m/N; the k_H and delays."""
    offsets = vehicle.wheel_offsets
    x = 0.2 - offsets
    seats = np.round(x / system.track.sleeper_spacing) * system.track.sleeper_spacing
    rec_obs = system.track.receptance(f, x, np.concatenate([x, seats]))
    return rec_obs, system.contact_stiffness, wheel_delays(offsets, system.speed)


@pytest.mark.parametrize("name", ["default", "three_stage", "two_axle", "train6"])
@needs_numba[0]
@needs_numba[1]
def test_fused_kernel_equals_the_numpy_condensation_and_solve(system, name):
    vehicle = _vehicle(name, system)
    f = np.geomspace(0.5, 1000.0, 300)
    rec_obs, k_h, delays = _case(system, vehicle, f)
    # the receptance in another scale: the kernel multiplies it back (as the wave
    # solver's dimensionless one, d^3 / EI*)
    scale = 2.5e-9 - 1.0e-10j
    u, force, rail, rec, observed, bad = coupled_kernel.fused_points(
        vehicle.elimination_program,
        f,
        vehicle.element_stiffness(f),
        rec_obs / scale,
        scale,
        k_h,
        delays,
    )
    assert not bad.any()
    n = len(vehicle.wheels)
    expected = _reference(vehicle, rec_obs, f, k_h, delays)
    for got, want in zip((u, force, rail, observed), expected, strict=True):
        assert _max_rel(got, want) < RTOL
    # reason: one complex product and division by `scale` each way: a few ulp
    np.testing.assert_allclose(rec, rec_obs[:, :n], rtol=1e-15, atol=0)


@pytest.mark.parametrize("name", ["three_stage", "train6"])
def test_the_plain_python_fused_kernel_equals_the_numpy_path(system, name):
    # without numba too: the kernel's own code, run by the interpreter (few points: slow)
    vehicle = _vehicle(name, system)
    f = np.array([0.7, 9.0, 63.0, 410.0]) if name == "train6" else np.geomspace(0.5, 1e3, 12)
    rec_obs, k_h, delays = _case(system, vehicle, f)
    prog = vehicle.elimination_program
    ke = vehicle.element_stiffness(f)
    run = coupled_kernel._fused
    u, force, rail, _, observed, bad = coupled_kernel.fused_points(
        prog, f, ke, rec_obs, 1.0, k_h, delays, run=run
    )
    assert not bad.any()
    expected = _reference(vehicle, rec_obs, f, k_h, delays)
    for got, want in zip((u, force, rail, observed), expected, strict=True):
        assert _max_rel(got, want) < RTOL


def _zero_pivot_case(system):
    """The undamped car, and a grid with the frequency where its bogie's bounce pivot is 0."""
    vehicle = _undamped_car()
    k_bb = vehicle.stiffness_matrix[2, 2]
    f_zero = np.sqrt(k_bb / 2.0e3) / (2 * np.pi)
    f = np.sort(np.concatenate([np.linspace(0.5, 400.0, compiled.LOADED_MIN_POINTS), [f_zero]]))
    return vehicle, f_zero, f


def test_a_zero_pivot_is_flagged(system):
    vehicle, f_zero, _ = _zero_pivot_case(system)
    few = np.array([50.0, f_zero, 400.0])  # every other pivot passes the test there
    rec, k_h, delays = _case(system, vehicle, few)
    out = coupled_kernel.fused_points(
        vehicle.elimination_program, few, vehicle.element_stiffness(few), rec, 1.0, k_h, delays,
        run=coupled_kernel._fused,
    )  # fmt: skip
    np.testing.assert_array_equal(out[-1], [False, True, False])
    # the receptance is given at a flagged point too (the caller solves it again with it)
    np.testing.assert_array_equal(out[3][1], rec[1, :2])


@needs_numba[0]
@needs_numba[1]
def test_the_flagged_points_of_a_fused_block_are_solved_by_the_numpy_path(system, monkeypatch):
    # a run's blocks with the kernels loaded against the NumPy path, with the zero pivot and
    # the points near the undamped car's body resonances its pivot test flags
    vehicle, f_zero, f = _zero_pivot_case(system)
    at = int(np.flatnonzero(f == f_zero)[0])
    assert compiled.compile_kernel()
    case = CoupledSystem(vehicle, system.track, system.contact_stiffness, 0.2, system.speed)
    seats = np.array([0.0, -1.2])

    def blocks():
        return [b for _, b in case.frf_blocks(f, observe=seats)]

    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    numpy_path = blocks()
    monkeypatch.setenv("RAILVIB_COMPILED", "1")
    calls = []

    def spy(*args, **kwargs):
        calls.append(1)
        return coupled_kernel.fused_points(*args, **kwargs)

    monkeypatch.setattr(coupling, "fused_points", spy)
    fused_path = blocks()
    assert calls  # the blocks went through the fused kernel
    for key in ("vehicle", "contact_force", "rail", "rail_observed"):
        got = np.concatenate([getattr(b, key) for b in fused_path])
        want = np.concatenate([getattr(b, key) for b in numpy_path])
        assert np.all(np.isfinite(got[at]))
        # reason: the fused kernel against the NumPy path, the wave kernel's receptance
        # against the NumPy one's included (measured differences ~1e-14; see RTOL)
        assert _max_rel(got, want) < RTOL
