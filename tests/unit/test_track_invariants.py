"""Structural invariants of the periodic-track solution (docs/reference-values.md §3.4)."""

import numpy as np
import pytest

from railvib.errors import CaseError, SolverWarning
from railvib.pads import Hysteretic, SpringDamper
from railvib.track import PeriodicTrack, Rail

F = np.array([0.1, 1.0, 37.0, 186.6, 300.0, 800.0, 1300.0, 1441.0, 2000.0, 3000.0, 5000.0])


def doubling(k):
    """Semi-infinite stiffness of a chain of identical cells by cyclic reduction."""
    a, b = k[:, :2, :2].copy(), k[:, :2, 2:].copy()
    c, d = k[:, 2:, :2].copy(), k[:, 2:, 2:].copy()
    for _ in range(60):
        x = np.linalg.inv(d + a)
        a, b, c, d = a - b @ x @ c, -b @ x @ b, -c @ x @ c, d - c @ x @ b
        if np.abs(b).max() < 1e-15 * np.abs(a).max():
            break
    return a


def test_transfer_matrix_is_symplectic(paper_track):
    s = paper_track.transfer_matrix(F)
    j = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.eye(2), np.zeros((2, 2))]])
    # compare in scaled units: T = D^-1 S D with D = diag(1, 1/d, EI/d^3, EI/d^2) is O(1)
    resid = np.einsum("fji,jk,fkl->fil", s, j, s) - j
    scale = np.abs(np.einsum("fji,fjl->fil", np.abs(s), np.abs(s))).max(axis=(1, 2))
    assert np.all(np.abs(resid).max(axis=(1, 2)) <= 1e-12 * scale)


def test_transfer_matrix_equals_paper_eq4_from_cell_stiffness(paper_track):
    # paper Eq. 4: S from the condensed cell stiffness; away from the clamped-bay pole (3268 Hz)
    k = paper_track.cell_dynamic_stiffness(F)
    kaa, kab, kba, kbb = k[:, :2, :2], k[:, :2, 2:], k[:, 2:, :2], k[:, 2:, 2:]
    kab_inv = np.linalg.inv(kab)
    s_eq4 = np.block([[-kab_inv @ kaa, kab_inv], [-kba + kbb @ kab_inv @ kaa, -kbb @ kab_inv]])
    s = paper_track.transfer_matrix(F)
    rel = np.abs(s_eq4 - s) / np.abs(s).max(axis=(1, 2), keepdims=True)
    assert rel.max() < 1e-9


def test_cell_stiffness_is_reciprocal(paper_track):
    k = paper_track.cell_dynamic_stiffness(F)
    np.testing.assert_allclose(k, np.swapaxes(k, 1, 2), rtol=1e-12, atol=0)


@pytest.mark.parametrize("pad", [SpringDamper(5e7, 5e4), Hysteretic(8e7, 0.2)])
def test_semi_infinite_stiffness_properties(pad):
    track = PeriodicTrack(Rail(6.62e6, 60.64), pad, 0.6)
    p_b, p_a = track.semi_infinite_stiffness(F)
    # complex symmetric
    np.testing.assert_allclose(p_b, np.swapaxes(p_b, 1, 2), rtol=1e-9, atol=0)
    # agrees with cyclic reduction of the cell stiffness (an independent route, no eigenvectors)
    ref = doubling(track.cell_dynamic_stiffness(F))
    np.testing.assert_allclose(p_b, ref, rtol=1e-8)
    # solves the discrete Riccati equation P = K_aa - K_ab (K_bb + P)^-1 K_ba
    k = track.cell_dynamic_stiffness(F)
    ric = k[:, :2, :2] - k[:, :2, 2:] @ np.linalg.inv(k[:, 2:, 2:] + p_b) @ k[:, 2:, :2]
    np.testing.assert_allclose(ric, p_b, rtol=1e-8)
    # the left chain seen from just right of a sleeper is the mirror of the right chain plus
    # that sleeper's pad: P_a = J2 P_b J2 + diag(z, 0)
    j2 = np.diag([1.0, -1.0])
    mirror = j2 @ p_b @ j2
    mirror[:, 0, 0] += pad.stiffness(F)
    np.testing.assert_allclose(p_a, mirror, rtol=1e-8)


def test_reciprocity_between_arbitrary_points(paper_track):
    x = np.array([-3.77, -0.6, 0.0, 0.13, 0.3, 2.2, 11.95])
    f = np.geomspace(0.1, 5000.0, 120)
    a = paper_track.receptance(f, x, x)
    np.testing.assert_allclose(a, np.swapaxes(a, 1, 2), rtol=1e-9, atol=1e-25)


@pytest.mark.parametrize("x0", [0.0, 0.1, 0.3, 0.45])
def test_point_receptance_is_passive(paper_track, x0):
    # a damped track absorbs power: Im(alpha) < 0 at the driving point (exp(+i w t))
    f = np.geomspace(0.1, 5000.0, 400)
    a = paper_track.receptance(f, [x0], [x0])[:, 0, 0]
    assert np.all(np.isfinite(a))
    assert np.all(a.imag < 0)


def test_power_balance_input_equals_pad_dissipation(paper_track):
    # -(w/2) Im alpha(x0) = sum over pads of (w^2 c / 2) |w_n|^2 (rail undamped, viscous pads)
    f = np.array([5.0, 60.0, 250.0, 700.0, 1800.0])
    sleepers = 0.6 * np.arange(-400, 401)
    x0 = 0.21
    a0 = paper_track.receptance(f, [x0], [x0])[:, 0, 0]
    wn = paper_track.receptance(f, [x0], sleepers)[:, :, 0]
    w = 2 * np.pi * f
    p_in = -0.5 * w * a0.imag
    p_pad = 0.5 * w**2 * 5.0e4 * np.sum(np.abs(wn) ** 2, axis=1)
    np.testing.assert_allclose(p_in, p_pad, rtol=1e-8)


def test_far_field_is_finite_and_decays(paper_track):
    # 2 km away the response has underflowed harmlessly: no overflow, no NaN
    f = np.geomspace(0.1, 5000.0, 50)
    a = paper_track.receptance(f, [0.3], [0.3, 2000.3, -2000.0])[:, :, 0]
    assert np.all(np.isfinite(a))
    assert np.all(np.abs(a[:, 1:]) <= 1e-3 * np.abs(a[:, :1]))


def test_propagation_constants_decay(paper_track):
    w = paper_track.waves(np.geomspace(0.1, 5000.0, 300))
    assert np.all(np.abs(w.mu) <= 1.0)


def test_invalid_track_inputs_are_named():
    with pytest.raises(
        CaseError, match=r"track\.sleeper_spacing = -0\.6: must be > 0\.0 and <= 3\.0 \(m\)"
    ):
        PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7), -0.6)
    with pytest.raises(CaseError, match=r"track\.rail\.mass_per_length = 0\.0"):
        Rail(6.62e6, 0.0)
    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7), 0.6)
    with pytest.raises(CaseError, match="frequency"):
        track.receptance([0.0, 1.0], [0.0], [0.0])


def test_pinned_pinned_frequency_is_finite_and_flagged(paper_track):
    # f_pp = (pi/d)^2 sqrt(EI/m) / 2 pi = 1441.67 Hz (docs/reference-values.md §3.3)
    f_pp = (np.pi / 0.6) ** 2 * np.sqrt(6.62e6 / 60.64) / (2 * np.pi)
    with pytest.warns(SolverWarning, match="pinned-pinned"):
        a = paper_track.receptance([f_pp], [0.3], [0.3])
    assert np.all(np.isfinite(a))
    # close to it the mid-span receptance grows as |f - f_pp|^(-1/2): 1e-3 -> 1e-5 is 10x
    near = paper_track.receptance(f_pp * np.array([1 - 1e-3, 1 - 1e-5]), [0.3], [0.3])
    ratio = np.abs(near[1, 0, 0]) / np.abs(near[0, 0, 0])
    assert ratio == pytest.approx(10.0, rel=0.05)
    # a small rail loss factor regularises it (no warning)
    damped = PeriodicTrack(Rail(6.62e6, 60.64, 0.01), SpringDamper(5e7, 5e4), 0.6)
    assert np.abs(damped.receptance([f_pp], [0.3], [0.3])).max() < 1e-8
