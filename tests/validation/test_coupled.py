"""The coupled vehicle-track PSDs against independent assemblies and references.

The reference here does not condense the contact onto the vehicle: it solves the
saddle-point system [[D_v, B], [B^T, -(R + I/k_H)]] [u_v; P] = [0; r] per wheel,
then forms PSDs by the CQC double sum over the four delayed, fully coherent inputs.

The rail receptance of the finite-track comparison comes from
:class:`railvib.validation.FiniteTrack`, a long finite rail of Hermite elements on
discrete pads solved by one sparse LU per frequency. It is independent of the
symplectic solver: it shares no code with :mod:`railvib.track` or
:mod:`railvib.coupling`, only the parameter records (`Rail`, the pad's
``stiffness(f)``), and its own checks are against closed forms and identities
(``test_validation_finite_track.py``). The mesh is the one of the test-only model it
replaces (see ``test_track_periodic.py``): sleepers -300 to +300, 12 elements per bay,
100-bay absorbing ends reaching 2e6 N s/m, every wheel position a node. Measured worst
PSD differences from the symplectic path, 7.4e-4 (x0 = 0.3 m) and 5.9e-4 (x0 = 0), are
the same with the replaced model to the digits shown.
"""

import numpy as np
import pytest

from railvib.coupling import CoupledSystem
from railvib.grid import FrequencyGrid
from railvib.pads import SpringDamper
from railvib.solve import run_system
from railvib.spectra import Combined, FRAClass, ShiTai
from railvib.track import Rail
from railvib.validation import FiniteTrack

K_H = 9.873e8
SPEED = 80 / 3.6
SPECTRUM = Combined(FRAClass(5), ShiTai(), 1.0)


def saddle_point_frfs(vehicle, receptance, f, k_h):
    """Per-wheel FRFs: vehicle DOFs (n_f, n_dof, n_w) and contact forces (n_f, n_w, n_w)."""
    b = vehicle.wheel_matrix
    n, m = b.shape
    out_u = np.empty((f.size, n, m), dtype=complex)
    out_p = np.empty((f.size, m, m), dtype=complex)
    dv = vehicle.dynamic_stiffness(f)
    for i in range(f.size):
        a = np.block([[dv[i], b], [b.T, -(receptance[i] + np.eye(m) / k_h)]])
        rhs = np.vstack([np.zeros((n, m)), np.eye(m)])
        sol = np.linalg.solve(a, rhs)
        out_u[i], out_p[i] = sol[:n], sol[n:]
    return out_u, out_p


def cqc_psd(h, f, delays, s_r):
    """S_y = S_r sum_jk H_j conj(H_k) exp(-i w (t_j - t_k)) for h of shape (n_f, n_y, n_w)."""
    w = 2 * np.pi * f
    phase = np.exp(-1j * w[:, None, None] * (delays[:, None] - delays[None, :]))
    s = np.einsum("fyj,fyk,fjk->fy", h, h.conj(), phase)
    return s.real * s_r[:, None]


@pytest.fixture
def system(paper_vehicle, paper_track):
    return CoupledSystem(paper_vehicle, paper_track, K_H, 0.3, SPEED)


def test_pem_equals_cqc_of_independent_assembly(system):
    f = np.geomspace(0.5, 2000.0, 150)
    ds = run_system(system, FrequencyGrid.from_array(f), SPECTRUM)
    x = system.wheel_positions
    rec = system.track.receptance(f, x, x)
    h_u, h_p = saddle_point_frfs(system.vehicle, rec, f, K_H)
    h_rail = np.einsum("fij,fjk->fik", rec, h_p)
    delays = system.vehicle.wheel_offsets / SPEED
    s_r = SPECTRUM.temporal(f, SPEED)
    expected = np.concatenate([cqc_psd(h_u, f, delays, s_r), cqc_psd(h_rail, f, delays, s_r)], 1)
    # 1e-7: the CQC sum cancels four coherent terms; at 2 kHz the car-body pitch PSD
    # (4.6e-43) is 1e-38 of the terms it is formed from, so round-off reaches 2.5e-8
    np.testing.assert_allclose(ds.psd_displacement.values, expected, rtol=1e-7)
    np.testing.assert_allclose(ds.psd_force.values, cqc_psd(h_p, f, delays, s_r), rtol=1e-9)
    # acceleration = w^4 displacement
    w4 = (2 * np.pi * f[:, None]) ** 4
    np.testing.assert_allclose(ds.psd_acceleration.values, w4 * expected, rtol=1e-7)


def test_low_frequency_limit_vehicle_follows_profile(system):
    # as f -> 0 every bounce DOF follows the irregularity (|H| -> 1), pitch and rail -> 0
    frf = system.frf(np.array([1e-3]))
    bounce = [i for i, d in enumerate(system.vehicle.dofs) if d.endswith("bounce")]
    np.testing.assert_allclose(np.abs(frf.vehicle[0, bounce]), 1.0, atol=1e-5)
    assert np.abs(frf.rail).max() < 1e-3
    assert np.abs(frf.contact_force).max() < 1e-3 * K_H


@pytest.mark.validation
@pytest.mark.slow
@pytest.mark.parametrize("x0", [0.3, 0.0], ids=["wheel-mid-span", "wheel-above-sleeper"])
def test_coupled_psds_match_finite_track(paper_vehicle, paper_track, x0):
    # within 1 % from 1 Hz to 2 kHz (frequencies within 3 % of the pinned-pinned
    # frequency excluded, where the finite model's answer depends on its length)
    system = CoupledSystem(paper_vehicle, paper_track, K_H, x0, SPEED)
    f = np.concatenate([np.geomspace(1.0, 1400.0, 40), np.geomspace(1480.0, 2000.0, 4)])
    ds = run_system(system, FrequencyGrid.from_array(f), SPECTRUM)
    x = system.wheel_positions
    finite = FiniteTrack(
        Rail(6.62e6, 60.64),
        SpringDamper(5.0e7, 5.0e4),
        0.6,
        -300,
        300,
        elements_per_span=12,
        nodes_at=tuple(x),
        absorber_spans=100,
        absorber_damping=40.0 * 5.0e4,
    )
    rec = finite.receptance(f, x, x)
    h_u, h_p = saddle_point_frfs(paper_vehicle, rec, f, K_H)
    h_rail = np.einsum("fij,fjk->fik", rec, h_p)
    delays = paper_vehicle.wheel_offsets / SPEED
    s_r = SPECTRUM.temporal(f, SPEED)
    ref = np.concatenate([cqc_psd(h_u, f, delays, s_r), cqc_psd(h_rail, f, delays, s_r)], 1)
    got = ds.psd_displacement.values
    # compare each response relative to its own level (pitch and bounce are never zero here)
    rel = np.abs(got - ref) / ref
    worst = rel.max()
    assert worst < 1e-2, f"worst relative PSD difference {worst:.2e}"


def test_contact_linearity_check():
    from scipy.stats import norm

    import railvib

    ds = railvib.run(railvib.load_preset_case())
    p0 = (21920 / 4 + 2550 / 2 + 1420) * 9.81  # per wheelset contact on the one-rail beam
    np.testing.assert_allclose(ds.static_contact_load, p0, rtol=1e-12)
    sigma = np.sqrt(np.trapezoid(ds.psd_force.values, ds.frequency.values, axis=0))
    np.testing.assert_allclose(ds.contact_force_rms, sigma, rtol=1e-3)
    assert np.all(ds.loss_of_contact_probability < 0.01)
    np.testing.assert_allclose(ds.loss_of_contact_probability, norm.cdf(-p0 / sigma), rtol=1e-2)
    # a poor track (FRA class 1) at 160 km/h lifts the wheels: flagged
    rough = railvib.case_from_dict(
        {
            "preset": "wang2017_metro",
            "speed_kmh": 160.0,
            "irregularity": {
                "type": "combined",
                "long_wave": {"type": "fra", "class_number": 1},
                "short_wave": {"type": "sato", "coefficient": 5e-7},
            },
        }
    )
    assert float(railvib.run(rough).loss_of_contact_probability.max()) > 0.01


def test_deprecated_contact_check_gives_the_run_values():
    import railvib
    from railvib.errors import RailvibDeprecationWarning
    from railvib.solve import contact_check

    case = railvib.load_preset_case()
    ds = railvib.run(case)
    system = railvib.build_system(case)
    with pytest.warns(RailvibDeprecationWarning, match="ContactCheck"):
        old = contact_check(
            system, ds.frequency.values, ds.frf_force.values, ds.irregularity_psd.values
        )
    for name in ("contact_force_rms", "static_contact_load", "loss_of_contact_probability"):
        np.testing.assert_array_equal(old[name].values, ds[name].values)  # the same arithmetic
