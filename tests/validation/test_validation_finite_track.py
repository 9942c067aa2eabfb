"""Finite Hermite-element track: element accuracy, reciprocity, passivity, no end reflections."""

import numpy as np
import pytest
from scipy.linalg import eigh

from railvib.pads import Hysteretic, SpringDamper
from railvib.track import Rail
from railvib.validation import FiniteTrack, MonteCarloSettings

RAIL = Rail(6.62e6, 60.64)
PAD = SpringDamper(5e7, 5e4)
WHEELS = np.array([0.3, -1.9, -12.3, -14.5])


def test_hermite_elements_give_simply_supported_beam_frequencies():
    # closed form f_n = (n pi / L)^2 sqrt(EI/m) / (2 pi) for a 6 m beam pinned at both ends.
    # Hermite elements converge as h^4; at 0.075 m (8 per 0.6 m bay) the first 5 are < 1e-5
    track = FiniteTrack(RAIL, PAD, 6.0, 0, 1, elements_per_span=80)
    k = track.rail_stiffness_matrix.toarray()
    k[0, 0] += 1e15
    k[-2, -2] += 1e15
    w2 = eigh(k, track.mass_matrix.toarray(), eigvals_only=True)[:5]
    f_fe = np.sqrt(w2) / (2 * np.pi)
    n = np.arange(1, 6)
    f_exact = (n * np.pi / 6.0) ** 2 * np.sqrt(RAIL.bending_stiffness / RAIL.mass_per_length)
    np.testing.assert_allclose(f_fe, f_exact / (2 * np.pi), rtol=1e-5)


def test_nodes_at_wheels_and_mesh_density():
    track = FiniteTrack.around(WHEELS, RAIL, PAD, 0.6, margin_spans=10, elements_per_span=4)
    np.testing.assert_allclose(track.nodes[track.node_index(WHEELS)], WHEELS, atol=1e-12)
    assert np.diff(track.nodes).max() <= 0.15 + 1e-12
    assert track.sleeper_dofs.size == track.last_sleeper - track.first_sleeper + 1


def test_receptance_reciprocal_and_passive():
    track = FiniteTrack.around(WHEELS, RAIL, PAD, 0.6, margin_spans=20, elements_per_span=4)
    r = track.receptance([20.0, 300.0, 900.0], WHEELS, WHEELS)
    np.testing.assert_allclose(r, np.swapaxes(r, 1, 2), rtol=1e-9, atol=1e-20)
    assert np.all(np.imag(np.diagonal(r, axis1=1, axis2=2)) <= 0)


def test_power_balance_at_driving_point():
    # input power -(omega/2) Im(alpha) equals the power dissipated in the pads
    # (sum of (omega^2 c / 2) |w_pad|^2 per unit force): closed-form energy identity
    track = FiniteTrack.around([0.3], RAIL, PAD, 0.6, margin_spans=40, elements_per_span=4)
    from scipy.sparse.linalg import splu

    for f in (50.0, 400.0):
        omega = 2 * np.pi * f
        rhs = np.zeros(track.n_dof, dtype=complex)
        rhs[track.w_dof([0.3])] = 1.0
        u = splu(track.dynamic_stiffness(f)).solve(rhs)
        p_in = -0.5 * omega * np.imag(u[track.w_dof([0.3])][0])
        p_pad = 0.5 * omega**2 * PAD.damping_ns_per_m * np.sum(np.abs(u[track.sleeper_dofs]) ** 2)
        assert p_in == pytest.approx(p_pad, rel=1e-9)


def test_time_domain_track_does_not_reflect():
    # the Monte Carlo track (margin + absorbing layer) against one 4x longer: the
    # receptances between the wheels differ by < 1e-3 up to the top of the input band,
    # so reflections from the ends cannot reach the results
    s = MonteCarloSettings()
    short = FiniteTrack.around(
        WHEELS,
        RAIL,
        PAD,
        0.6,
        margin_spans=s.margin_spans,
        elements_per_span=s.elements_per_span,
        absorber_spans=s.absorber_spans,
        absorber_damping=s.absorber_damping,
    )
    long = FiniteTrack.around(
        WHEELS, RAIL, PAD, 0.6, margin_spans=4 * s.margin_spans, elements_per_span=2
    )
    f = np.linspace(5.0, s.input_band[1], 60)
    a = short.receptance(f, WHEELS, WHEELS)
    b = long.receptance(f, WHEELS, WHEELS)
    err = np.abs(a - b).max(axis=(1, 2)) / np.abs(b).max(axis=(1, 2))
    assert err.max() < 1e-3


def test_time_domain_needs_viscous_pad():
    from railvib.errors import CaseError

    track = FiniteTrack(RAIL, Hysteretic(5e7, 0.2), 0.6, 0, 10)
    with pytest.raises(CaseError, match="spring_damper"):
        track.time_domain_matrices()


def test_timoshenko_rail_is_refused_by_the_euler_reference():
    from railvib.errors import CaseError

    rail = Rail(6.62e6, 60.64, shear_stiffness=2.447e8)
    with pytest.raises(CaseError, match="Euler-Bernoulli rail"):
        FiniteTrack.around([0.3], rail, SpringDamper(5e7, 5e4), 0.6)
