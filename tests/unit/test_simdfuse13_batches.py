"""The fused kernel in batches of points (issue 13): batch edges and the input phasors.

:func:`railvib.coupled_kernel.fused_points` solves its points ``coupled_kernel._B`` at a
time, structure of arrays, and forms the wheels' inputs ``exp(-i 2 pi f t_j)`` from its own
vectorised cos and sin (a reduction by pi/2, fdlibm's polynomial kernels) up to a phase of
``coupled_kernel._SINCOS_MAX``, the library's beyond. The reference is the NumPy path
(:meth:`railvib.vehicle.Vehicle.condensed_to_wheels`, :func:`railvib.coupling.coupled_response`
and :func:`railvib.pem.excitation_vector`) given the same rail receptance.
"""

import importlib.util

import numpy as np
import pytest

import railvib
from railvib import coupled_kernel
from railvib.case import build_system
from railvib.coupling import coupled_response
from railvib.pem import excitation_vector, wheel_delays

#: reason: the same equations in another order of operations (partial pivoting where the
#: reference eliminates without exchanges, the bodies back-substituted through the
#: elimination's multipliers, FMA contraction in the compiled kernel, the phasors within
#: one ulp of the library's): rounding of some 10^2 operations times the coupled system's
#: condition; 1e-12 of each response's peak
RTOL = 1e-12

#: numba compiles the fused kernel on its first use (seconds), then loads it from its cache
needs_numba = [
    pytest.mark.slow,
    pytest.mark.skipif(importlib.util.find_spec("numba") is None, reason="needs numba"),
]


@pytest.fixture(scope="module")
def system():
    return build_system(railvib.load_preset_case())


def _max_rel(a, b):
    """Largest difference relative to the largest value of each response."""
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=0, keepdims=True)))


def _solve(system, f, delays, run):
    """The fused kernel's and the NumPy path's responses of the default car at `f`."""
    vehicle = system.vehicle
    n = len(vehicle.wheels)
    x = 0.2 - vehicle.wheel_offsets
    seats = np.round(x / system.track.sleeper_spacing) * system.track.sleeper_spacing
    rec_obs = system.track.receptance(f, x, np.concatenate([x, seats]))
    k_h = system.contact_stiffness
    *got, bad = coupled_kernel.fused_points(
        vehicle.elimination_program, f, vehicle.element_stiffness(f), rec_obs, 1.0, k_h,
        delays, run=run,
    )  # fmt: skip
    v = excitation_vector(f, delays)[..., None]
    u, force, rail = coupled_response(vehicle.condensed_to_wheels(f), rec_obs[:, :n], k_h, v)
    observed = np.einsum("fow,fw->fo", rec_obs[:, n:], force[..., 0])
    want = (u[..., 0], force[..., 0], rail[..., 0], rec_obs[:, :n], observed)
    return got, want, bad


def _check(got, want, bad):
    assert not bad.any()
    for a, b in zip(got, want, strict=True):
        assert _max_rel(a, b) < RTOL


def test_a_full_batch_and_a_partial_one_equal_the_numpy_path(system):
    # plain Python (no numba needed): one whole batch, then a remainder of 3 points
    f = np.geomspace(0.5, 1e3, coupled_kernel._B + 3)
    delays = wheel_delays(system.vehicle.wheel_offsets, system.speed)
    _check(*_solve(system, f, delays, coupled_kernel._fused))


def test_the_input_phasors_in_every_quadrant_and_beyond_the_reduction(system):
    # delays that put the phases 2 pi f t_j in all four quadrants of many turns, and, for
    # the last wheel at the higher frequencies, beyond the reduction (the library's there)
    f = np.linspace(3.0, 997.0, 11)
    delays = np.array([0.0, 0.137, 7.31, 400.0])
    phase = 2 * np.pi * f[:, None] * delays
    assert (phase[:, 3] > coupled_kernel._SINCOS_MAX).any()
    assert (phase[:, 3] < coupled_kernel._SINCOS_MAX).any()
    assert set(np.floor(phase[:, 2] / (np.pi / 2)).astype(int) % 4) == {0, 1, 2, 3}
    _check(*_solve(system, f, delays, coupled_kernel._fused))


@needs_numba[0]
@needs_numba[1]
def test_the_compiled_batches_equal_the_numpy_path(system):
    # several batches and a remainder, phases beyond the reduction in some batches only
    f = np.linspace(0.5, 1e3, 5 * coupled_kernel._B + 17)
    delays = np.array([0.0, 0.137, 7.31, 300.0])
    assert (2 * np.pi * f * delays[3] > coupled_kernel._SINCOS_MAX).any()
    _check(*_solve(system, f, delays, coupled_kernel.fused_kernel()))
