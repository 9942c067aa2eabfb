"""The exact non-stationary PEM validated against independent references.

(a) the covariance (Lyapunov) differential equation of a quarter car driven by an
irregularity that is filtered white noise in space, with the speed varying (Hammond
and Harrison 1981): sigma(t) to 1 %; (b) at constant speed, from rest, the stationary
PEM once the start-up transient has decayed; (c) the quasi-stationary estimate and
the exact result converge as the acceleration goes to 0; (d) a time-domain Monte Carlo
with the same profile, within its confidence band.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.coupling import coupled_response
from railvib.nonstationary import (
    RigidTrackVehicle,
    ShapingFilter,
    SpatialBand,
    SpeedProfile,
    covariance_response,
    exact_response,
    quasi_stationary_psd,
)
from railvib.spectra import FRAClass
from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

pytestmark = pytest.mark.slow

#: a road-like quarter car (body 1.46 Hz, wheel 12.2 Hz, body damping ratio 0.19)
QUARTER = Vehicle(
    (RigidBody("carbody", 400.0, None, 0.0), RigidBody("wheelset1", 40.0, None, 0.0)),
    (
        Suspension(
            "primary.1", Attachment("carbody", 0.0), Attachment("wheelset1", 0.0), 4e4, 1.5e3
        ),
    ),
    (Wheel("wheelset1", 0.0),),
)
TYRE = 2e5  # N/m
#: variance 1e-4 m^2 (1 cm RMS), corner 0.5 rad/m (12.6 m)
SHAPING = ShapingFilter.first_order(1e-4, 0.5)
#: wavelengths 0.02-5000 m: the first-order spectrum's tails beyond them hold
#: (2 / pi)(alpha / Omega_max + Omega_min / alpha) = 0.27 % of the variance
BAND = SpatialBand.log_spaced(SHAPING, 0.02, 5000.0, 1500)


@pytest.mark.parametrize(
    "profile",
    [SpeedProfile.uniform(20.0, 0.0, 4.0), SpeedProfile.uniform(0.0, 20.0, 4.0)],
    ids=["braking-to-a-stop", "starting-from-rest"],
)
def test_rms_follows_the_covariance_equation(profile):
    model = RigidTrackVehicle(QUARTER, TYRE)
    hist = exact_response(model, profile, BAND, 2e-3, map_times=2)
    ref = covariance_response(model, SHAPING, profile, hist.t)
    # where v >= 5 m/s: near a stop the accelerations and the contact force are carried by
    # wavelengths shorter than the band's 2 cm (a first-order profile has no finite
    # slope), which the Lyapunov reference includes and the band does not
    moving = profile.speed(hist.t) >= 5.0
    ratio = np.sqrt(hist.variance[moving] / ref[moving])
    # outputs: body, wheel displacement; body, wheel acceleration; contact force
    assert np.abs(ratio - 1).max() <= 0.01
    # the displacements everywhere, the stop included (band truncation 0.27 % of variance)
    ratio_all = np.sqrt(hist.variance[:, :2] / ref[:, :2])
    assert np.abs(ratio_all - 1).max() <= 0.01
    # and the test has teeth: sigma of the body acceleration changes by half over the run
    sd = np.sqrt(ref[moving, 2])
    assert sd.max() > 1.5 * sd.min()


def test_constant_speed_from_rest_reaches_the_stationary_pem(paper_vehicle):
    kh = 1.0e9
    band = SpatialBand.log_spaced(FRAClass(5), 1.0, 100.0, 200)
    model = RigidTrackVehicle(paper_vehicle, kh)
    v, duration = 20.0, 30.0
    hist = exact_response(model, SpeedProfile.constant(v, duration), band, 0.02, initial="rest")
    f = v * band.wavenumber / (2 * np.pi)
    exc = np.exp(-1j * band.wavenumber[:, None] * paper_vehicle.wheel_offsets[None, :])[..., None]
    u, force, _ = coupled_response(
        paper_vehicle.condensed_to_wheels(f), np.zeros((f.size, 4, 4), complex), kh, exc
    )
    acc = -((2 * np.pi * f[:, None]) ** 2) * u[..., 0]
    a2 = band.amplitude[:, None] ** 2
    ref = np.concatenate([(a2 * np.abs(y) ** 2).sum(0) for y in (u[..., 0], acc, force[..., 0])])
    # the transient decays as exp(-d t), d the smallest modal decay rate of the car on its
    # contact springs (from the test's own eigenvalues of its first-order matrix); the
    # pseudo response's error at t is then at most a few times exp(-d t) of its size
    m, c, k = (
        paper_vehicle.mass_matrix,
        paper_vehicle.damping_matrix,
        paper_vehicle.stiffness_matrix,
    )
    w = paper_vehicle.wheel_matrix
    n = m.shape[0]
    a = np.block(
        [
            [np.zeros((n, n)), np.eye(n)],
            [-np.linalg.solve(m, k + kh * w @ w.T), -np.linalg.solve(m, c)],
        ]
    )
    decay = float(np.min(-np.linalg.eigvals(a).real))
    envelope = np.exp(-decay * hist.t)
    err = np.abs(np.sqrt(hist.variance / ref) - 1)
    assert err[0, :10] == pytest.approx(1.0)  # at rest: no displacement at all
    assert err[-1].max() <= max(5 * envelope[-1], 1e-10)  # 1e-10: the round-off floor
    assert envelope[-1] < 1e-3  # long enough for the check to mean something


def test_quasi_stationary_converges_to_exact_as_acceleration_vanishes(paper_vehicle):
    kh = 1.0e9
    band = SpatialBand.log_spaced(FRAClass(5), 1.0, 100.0, 200)
    model = RigidTrackVehicle(paper_vehicle, kh)
    errors = []
    for accel in (1.0, 0.25, 0.0625):
        profile = SpeedProfile.uniform(80 / 3.6, 40 / 3.6, accel)
        hist = exact_response(model, profile, band, 0.02, map_times=2)
        pick = np.linspace(0, hist.t.size - 1, 12).round().astype(int)
        qs = quasi_stationary_psd(model, profile, band, hist.t[pick]).sum(axis=1)
        errors.append(float(np.max(np.abs(np.sqrt(hist.variance[pick] / qs) - 1))))
    # the lag of the response behind the speed is first order in the acceleration: each
    # quartering of it cuts the difference at least in half (about 4 times expected)
    assert errors[1] < errors[0] / 2
    assert errors[2] < errors[1] / 2
    assert errors[2] < 0.01
    assert errors[0] > 0.01  # at 1 m/s^2 the two do differ


def test_monte_carlo_ensemble_rms_within_its_confidence_band():
    # sample profiles r(x) = Re sum_k sqrt(2) a_k exp(i (Omega_k x + theta_k)) with random
    # phases, integrate the quarter car through the same braking profile by the trapezoidal
    # rule (written here, 2 ms: a frequency warp of (pi f h)^2 / 3 = 2e-3 at the 12 Hz wheel
    # mode), and compare the ensemble RMS with the PEM's at 8 instants
    rng = np.random.default_rng(18)
    model = RigidTrackVehicle(QUARTER, TYRE)
    band = SpatialBand.log_spaced(SHAPING, 0.1, 500.0, 200)
    profile = SpeedProfile.uniform(20.0, 0.0, 4.0)
    h, n_real = 2e-3, 1000
    t = np.arange(0.0, profile.duration + h / 2, h)
    x = profile.position(t)
    coeff = np.sqrt(2.0) * band.amplitude[:, None] * np.exp(2j * np.pi * rng.random((200, n_real)))
    r = (np.exp(1j * x[:, None] * band.wavenumber[None, :]) @ coeff).real  # (n_t, n_real)
    m, c, k = QUARTER.mass_matrix, QUARTER.damping_matrix, QUARTER.stiffness_matrix
    w = QUARTER.wheel_matrix
    a = np.block(
        [
            [np.zeros((2, 2)), np.eye(2)],
            [-np.linalg.solve(m, k + TYRE * w @ w.T), -np.linalg.solve(m, c)],
        ]
    )
    b = np.concatenate([np.zeros(2), np.linalg.solve(m, TYRE * w[:, 0])])
    left = np.linalg.inv(np.eye(4) - h / 2 * a)
    step, drive = left @ (np.eye(4) + h / 2 * a), left @ b * (h / 2)
    # steady start: run the first 20 s at 20 m/s on the same samples, extended backwards
    pre = np.arange(-20.0, 0.0, h)
    r_pre = (np.exp(1j * (20.0 * pre)[:, None] * band.wavenumber[None, :]) @ coeff).real
    z = np.zeros((4, n_real))
    for i in range(1, pre.size):
        z = step @ z + np.outer(drive, r_pre[i - 1] + r_pre[i])
    z = step @ z + np.outer(drive, r_pre[-1] + r[0])
    body_acc = np.empty((t.size, n_real))
    body_acc[0] = a[2] @ z
    for i in range(1, t.size):
        z = step @ z + np.outer(drive, r[i - 1] + r[i])
        body_acc[i] = a[2] @ z
    hist = exact_response(model, profile, band, h, map_times=2)
    pick = np.linspace(0, t.size - 1, 8).round().astype(int)
    pem = np.sqrt(hist.variance[pick, 2])
    mc = np.sqrt(np.mean(body_acc[pick] ** 2, axis=1))
    # the sample RMS of n Gaussian values has a relative standard deviation 1/sqrt(2 n)
    # (2.2 % for 1000); 4 of them, plus the trapezoid's warp (< 0.5 %)
    assert np.all(np.abs(mc / pem - 1) <= 4 / np.sqrt(2 * n_real) + 0.005)
