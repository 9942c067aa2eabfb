"""The time-domain model with sleeper, ballast-mass and slab DOFs (issue 14, Monte Carlo part).

The Newmark model integrates the real ``(M, C, K)`` of the finite track; for a ballasted
track each sleeper (and ballast mass) is a DOF of its own, for a slab track the slab is a
beam of Hermite elements with its own DOFs (:class:`FiniteTrack`,
:class:`FiniteSlabTrack`): nothing is condensed and nothing comes from the wave solver.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from railvib.coupling import CoupledSystem
from railvib.pads import SpringDamper
from railvib.track import BallastedTrack, FloatingSlabTrack, Rail, UnitSlabTrack
from railvib.validation import (
    FiniteCoupledSystem,
    FiniteTrack,
    newmark_frequency_warp,
    simulate_time_domain,
)
from railvib.validation.finite_slab import FiniteSlabTrack
from railvib.vehicle import pitch_plane_10dof
from tests.conftest import PAPER_VEHICLE_PARAMS

RAIL = Rail(6.42e6, 60.0)
PAD = SpringDamper(3e8, 3e4)
BALLAST = SpringDamper(5e7, 8e4)
SUBGRADE = {"subgrade": SpringDamper(1e8, 1e5), "ballast_mass": 300.0}
FOUNDATION = SpringDamper(7e6, 7e3)
SLAB = {"slab_bending_stiffness": 1.2e8, "slab_mass_per_length": 1750.0}
UNIT = {"slab_length": 4.8, "fasteners_per_slab": 8}
JOINT = {"joint_shear_stiffness": 1e8, "joint_bending_stiffness": 1e6}


def _ballasted(**layers):
    return FiniteTrack.around(
        [0.0, 0.3],
        RAIL,
        PAD,
        0.6,
        margin_spans=6,
        elements_per_span=2,
        absorber_spans=2,
        absorber_damping=2e5,
        ballast=BALLAST,
        sleeper_mass=162.0,
        **layers,
    )


def _slab(**support):
    return FiniteSlabTrack(
        RAIL,
        PAD,
        0.6,
        slab_loss_factor=0.0,
        x_min=-6.0,
        x_max=6.0,
        elements_per_span=2,
        nodes_at=(0.0, 0.3),
        absorber_length=1.2,
        absorber_damping=2e5,
        **SLAB,
        **support,
    )


FINITE = {
    "ballasted": lambda: _ballasted(),
    "three_layer": lambda: _ballasted(**SUBGRADE),
    "floating_slab": lambda: _slab(foundation=FOUNDATION),
    "slab_bearings": lambda: _slab(bearing=SpringDamper(2e7, 2e4), bearing_spacing_fasteners=2),
    "jointed_unit_slab": lambda: _slab(foundation=FOUNDATION, **UNIT, **JOINT),
}


@pytest.mark.parametrize("name", FINITE)
def test_time_domain_matrices_are_the_frequency_domain_dynamic_stiffness(name):
    # K + i omega C - omega^2 M of the real matrices against the complex dynamic stiffness
    # assembled from each layer's K*(f) (two assembly paths of the same springs): round-off,
    # 1e-12 of the largest entry
    track = FINITE[name]()
    m, c, k = track.time_domain_matrices()
    for f in (3.0, 300.0):
        omega = 2 * np.pi * f
        got = (k + 1j * omega * c - omega**2 * m).toarray()
        expected = track.dynamic_stiffness(f).toarray()
        assert np.abs(got - expected).max() <= 1e-12 * np.abs(expected).max()


@pytest.mark.parametrize("name", FINITE)
def test_the_mass_matrix_holds_every_mass_once(name):
    # a unit rigid-body translation (w = 1 at every node and mass DOF, theta = 0) has the
    # kinetic-energy mass u^T M u = rail + sleepers (+ ballast masses), or rail + slab, by
    # hand: exact up to round-off
    track = FINITE[name]()
    m = track.time_domain_matrices()[0]
    u = np.zeros(track.n_dof)
    if isinstance(track, FiniteTrack):
        u[0 : 2 * track.nodes.size : 2] = 1.0
        u[2 * track.nodes.size :] = 1.0
        length = (track.last_sleeper - track.first_sleeper) * 0.6
        n_seats = track.last_sleeper - track.first_sleeper + 1
        per_seat = 162.0 + (300.0 if track.subgrade is not None else 0.0)
        expected = 60.0 * length + n_seats * per_seat
    else:
        u[0::2] = 1.0
        expected = (60.0 + 1750.0) * 12.0
    assert u @ (m @ u) == pytest.approx(expected, rel=1e-12)


def _coupled(track):
    vehicle = pitch_plane_10dof(PAPER_VEHICLE_PARAMS)
    system = CoupledSystem(vehicle, track, 9.873e8, 0.3, 80 / 3.6)
    return FiniteCoupledSystem.from_system(
        system, margin_spans=40, elements_per_span=2, absorber_spans=20, absorber_damping=2e5
    )


TRACKS = {
    "ballasted": lambda: BallastedTrack(RAIL, PAD, 0.6, sleeper_mass=162.0, ballast=BALLAST),
    "three_layer": lambda: BallastedTrack(
        RAIL, PAD, 0.6, sleeper_mass=162.0, ballast=BALLAST, **SUBGRADE
    ),
    "floating_slab": lambda: FloatingSlabTrack(RAIL, PAD, 0.6, foundation=FOUNDATION, **SLAB),
    "jointed_unit_slab": lambda: UnitSlabTrack(
        RAIL, PAD, 0.6, foundation=FOUNDATION, **SLAB, **UNIT, **JOINT
    ),
}


def test_the_coupled_finite_system_has_the_layers_as_dofs():
    # the ballasted track adds one DOF per sleeper (two for three layers) to the rail's; the
    # slab track a second beam: counted from the meshes, not from the solver
    ballasted = _coupled(TRACKS["ballasted"]()).track
    three = _coupled(TRACKS["three_layer"]()).track
    slab = _coupled(TRACKS["floating_slab"]()).track
    n_seats = ballasted.last_sleeper - ballasted.first_sleeper + 1
    assert ballasted.n_dof == 2 * ballasted.nodes.size + n_seats
    assert three.n_dof == 2 * three.nodes.size + 2 * n_seats
    assert isinstance(slab, FiniteSlabTrack)
    assert slab.n_dof == 2 * (slab.rail_nodes.size + sum(x.size for x in slab.slab_nodes))


@pytest.mark.slow  # 1.5 s of Newmark steps per case
@pytest.mark.parametrize("name", TRACKS)
def test_harmonic_steady_state_matches_the_frequency_domain(name):
    # a delayed sinusoidal irregularity at 47 Hz (near the slab's and the bogie's modes):
    # after the transients the Newmark amplitude equals the direct frequency-domain solution
    # of the same finite system at the warped frequency (Newmark is the bilinear map). 0.5 %
    # covers the residual transient and the amplitude read from a finite record (as for the
    # rigid base, tests/validation/test_validation_time_domain.py)
    system = _coupled(TRACKS[name]())
    f0, dt = 47.0, 1e-4
    t = np.arange(int(1.5 / dt) + 1) * dt
    ramp = np.clip(t / 0.2, 0.0, 1.0)
    r = ramp[:, None] * np.sin(2 * np.pi * f0 * (t[:, None] - system.delays[None, :]))
    hist = simulate_time_domain(system, r * 1e-4, dt)
    tail = t > 1.0
    basis = np.exp(2j * np.pi * f0 * t[tail])
    amp_td = 2 * (hist.acceleration[tail, :, 0].T @ basis.conj()) / tail.sum()
    fw = float(newmark_frequency_warp(f0, dt))
    h = replace(system, speed=system.speed * fw / f0).frf([fw])
    frf = np.concatenate([h.vehicle[0], h.rail[0]])
    amp_fd = -((2 * np.pi * fw) ** 2) * frf * 1e-4 / 1j
    big = np.abs(amp_fd) > 1e-3 * np.abs(amp_fd).max()
    np.testing.assert_allclose(np.abs(amp_td[big]), np.abs(amp_fd[big]), rtol=5e-3)
