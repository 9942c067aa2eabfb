"""The exact non-stationary PEM against the stationary solver, and its step-size error."""

from __future__ import annotations

import numpy as np

from railvib.coupling import coupled_response
from railvib.nonstationary import (
    RigidTrackVehicle,
    SpatialBand,
    SpeedProfile,
    exact_response,
    phase_error_bound,
    quasi_stationary_psd,
)
from railvib.spectra import FRAClass
from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

KH = 1.0e9  # N/m, about the linearised Hertz stiffness of a 70 kN wheel


def _stationary_variances(vehicle, band, speed):
    """Variances of displacements, accelerations and contact forces by the stationary solver."""
    f = speed * band.wavenumber / (2 * np.pi)
    n_w = vehicle.wheel_offsets.size
    exc = np.exp(-1j * band.wavenumber[:, None] * vehicle.wheel_offsets[None, :])[..., None]
    rigid = np.zeros((f.size, n_w, n_w), dtype=complex)
    u, force, _ = coupled_response(vehicle.condensed_to_wheels(f), rigid, KH, exc)
    acc = -((2 * np.pi * f[:, None]) ** 2) * u[..., 0]
    a2 = band.amplitude[:, None] ** 2
    return np.concatenate([(a2 * np.abs(y) ** 2).sum(0) for y in (u[..., 0], acc, force[..., 0])])


def test_steady_start_at_constant_speed_is_the_stationary_pem(paper_vehicle):
    # two independent routes: modal time stepping vs the frequency-domain condensation;
    # both exact, so they agree to round-off (1e-9 allows the ill-conditioning of the
    # wheelset modes, 1e3 times faster than the car body's)
    band = SpatialBand.log_spaced(FRAClass(5), 1.0, 100.0, 64)
    model = RigidTrackVehicle(paper_vehicle, KH)
    v = 20.0
    hist = exact_response(model, SpeedProfile.constant(v, 2.0), band, 0.01, map_times=2)
    ref = _stationary_variances(paper_vehicle, band, v)
    np.testing.assert_allclose(hist.variance[[0, -1]], np.stack([ref, ref]), rtol=1e-9)
    # the quasi-stationary route at constant speed is the stationary solution too
    qs = quasi_stationary_psd(model, SpeedProfile.constant(v, 2.0), band, [1.0]).sum(axis=1)
    np.testing.assert_allclose(qs[0], ref, rtol=1e-12)


def _quarter_car() -> Vehicle:
    return Vehicle(
        (RigidBody("carbody", 400.0, None, 0.0), RigidBody("wheelset1", 40.0, None, 0.0)),
        (
            Suspension(
                "primary.1", Attachment("carbody", 0.0), Attachment("wheelset1", 0.0), 4e4, 1.5e3
            ),
        ),
        (Wheel("wheelset1", 0.0),),
    )


def test_step_error_is_second_order_in_the_phase_bound():
    # hard braking (8 m/s^2) with short waves; the input phase's chord over a step is off
    # by at most delta = Omega a h^2 / 8, and the integrator takes the first-order term of
    # that parabola exactly, so what is left is of order delta^2 / 2 (a factor 2 allows the
    # response to amplify it near resonance: delta^2 in all)
    model = RigidTrackVehicle(_quarter_car(), 2e5)
    band = SpatialBand.log_spaced(FRAClass(5), 0.5, 50.0, 48)
    profile = SpeedProfile.uniform(16.0, 0.0, 8.0)
    coarse = exact_response(model, profile, band, 0.02, map_times=2)
    fine = exact_response(model, profile, band, 0.0025, map_times=2)
    sub = slice(None, None, 8)  # the coarse steps are every 8th fine one
    np.testing.assert_allclose(fine.t[sub], coarse.t, atol=1e-12)
    # relative to each response's largest RMS (at the stop the accelerations vanish)
    sd_c, sd_f = np.sqrt(coarse.variance), np.sqrt(fine.variance[sub])
    rel = np.abs(sd_c - sd_f) / sd_f.max(axis=0)
    bound = phase_error_bound(band, profile, 0.02)
    assert 1e-6 < bound < 0.05  # a test that can fail: the bound is not vacuous
    assert rel.max() <= bound**2


def test_moments_are_consistent():
    # E[y y'] is half the rate of E[y^2]: checked by differences of the variance history
    model = RigidTrackVehicle(_quarter_car(), 2e5)
    band = SpatialBand.log_spaced(FRAClass(5), 1.0, 50.0, 40)
    hist = exact_response(model, SpeedProfile.uniform(20.0, 2.0, 3.0), band, 0.002, map_times=2)
    rate = np.gradient(hist.variance, hist.t, axis=0)[5:-5]
    # central differences of a smooth history: error ~ h^2 |y'''|, 1e-3 of the scale here
    scale = np.abs(rate).max(axis=0)
    np.testing.assert_allclose(2 * hist.cross[5:-5], rate, atol=2e-3 * scale.max(), rtol=2e-3)
