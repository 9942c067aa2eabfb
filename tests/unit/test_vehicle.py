"""The vehicle assembled from parts against hand-derived closed forms."""

import numpy as np
import pytest
from scipy.linalg import eigh

from railvib.errors import CaseError
from railvib.vehicle import RigidBody, Suspension, Vehicle, Wheel
from railvib.vehicle.parts import Attachment
from tests.conftest import PAPER_VEHICLE_PARAMS as P


def _two_dof_frequencies(m1, k11, k12, m2, k22):
    """Natural frequencies (Hz) of [[k11, k12], [k12, k22]] x = w^2 diag(m1, m2) x, closed form."""
    a = m1 * m2
    b = -(k11 * m2 + k22 * m1)
    c = k11 * k22 - k12**2
    disc = np.sqrt(b * b - 4 * a * c)
    w2 = np.array([(-b - disc) / (2 * a), (-b + disc) / (2 * a)])
    return np.sqrt(w2) / (2 * np.pi)


def clamped_wheel_frequencies(vehicle):
    """Natural frequencies (Hz) of the vehicle with its wheelsets held fixed (rigid track)."""
    keep = [i for i, d in enumerate(vehicle.dofs) if not d.startswith("wheelset")]
    k = vehicle.stiffness_matrix[np.ix_(keep, keep)]
    m = vehicle.mass_matrix[np.ix_(keep, keep)]
    return np.sort(np.sqrt(eigh(k, m, eigvals_only=True)) / (2 * np.pi))


def test_rigid_track_frequencies_match_closed_forms(paper_vehicle):
    k1, k2, lc, lt = (
        P.primary_stiffness,
        P.secondary_stiffness,
        P.bogie_half_spacing,
        P.wheelset_half_spacing,
    )
    # bogie pitch: two primary springs at +-l_t, decoupled: w^2 = 2 K1 lt^2 / Jt (twice)
    f_bogie_pitch = np.sqrt(2 * k1 * lt**2 / P.bogie_pitch_inertia) / (2 * np.pi)
    # symmetric bounce, both bogies at zt: Mc zc'' = -2 K2 (zc - zt);
    # 2 Mt zt'' = 2 K2 (zc - zt) - 4 K1 zt
    bounce = _two_dof_frequencies(
        P.carbody_mass, 2 * k2, -2 * k2, 2 * P.bogie_mass, 2 * k2 + 4 * k1
    )
    # antisymmetric, bogies at +-y: Jc th'' = -2 K2 lc (lc th - y);
    # 2 Mt y'' = 2 K2 (lc th - y) - 4 K1 y
    pitch = _two_dof_frequencies(
        P.carbody_pitch_inertia, 2 * k2 * lc**2, -2 * k2 * lc, 2 * P.bogie_mass, 2 * k2 + 4 * k1
    )
    expected = np.sort(np.concatenate([bounce, pitch, [f_bogie_pitch, f_bogie_pitch]]))
    np.testing.assert_allclose(clamped_wheel_frequencies(paper_vehicle), expected, rtol=1e-10)
    # docs/reference-values.md §2 (wheels on k_H rather than clamped): body bounce 0.766,
    # pitch 0.909 Hz
    np.testing.assert_allclose(expected[:2], [0.766, 0.909], atol=2e-3)


def test_static_wheel_loads_share_the_weight(paper_vehicle):
    loads = paper_vehicle.static_wheel_loads(9.81)
    per_wheelset = (P.carbody_mass / 4 + P.bogie_mass / 2 + P.wheelset_mass) * 9.81
    np.testing.assert_allclose(loads, per_wheelset, rtol=1e-12)
    # docs/reference-values.md §1: 40.10 kN per wheel (two wheels per wheelset)
    assert loads[0] / 2 == pytest.approx(40.10e3, rel=1e-3)


def test_matrices_are_symmetric_and_rigid_modes_free(paper_vehicle):
    k = paper_vehicle.stiffness_matrix
    np.testing.assert_array_equal(k, k.T)
    # rigid bounce of everything stretches no spring
    assert np.abs(k @ np.array([1, 0, 1, 0, 1, 0, 1, 1, 1, 1])).max() < 1e-6


def test_wheel_geometry(paper_vehicle):
    np.testing.assert_allclose(paper_vehicle.wheel_offsets, [0.0, 2.2, 12.6, 14.8])


def test_bad_parts_are_rejected_with_field_names():
    with pytest.raises(CaseError, match=r"vehicle\.carbody\.mass = -1\.0: must be > 0 \(kg\)"):
        RigidBody("carbody", -1.0, 10.0)
    body = RigidBody("a", 1.0)
    with pytest.raises(CaseError, match=r"vehicle\.s\.stiffness = 0\.0"):
        Suspension("s", Attachment("a", 0), Attachment("a", 0), 0.0)
    with pytest.raises(CaseError, match="a body among"):
        Vehicle(
            (body,),
            (Suspension("s", Attachment("a", 0), Attachment("zz", 0), 1.0),),
            (Wheel("a", 0.0),),
        )
