"""The moving vehicle's time-averaged contact-force PSD against the vehicle rolling in time.

One 4 s record of the half metro car rolling at 80 km/h through the finite track
(:func:`railvib.validation.moving_vehicle.simulate_moving_vehicle`: the wheels' contact
points travel through the mesh) over an irregularity sampled from the Wang et al. (2017)
spectrum (random phases, :func:`railvib.validation.samples.sample_profile`), its Welch PSD
(0.5 s Hann segments, half overlap: 27 degrees of freedom) against the expectation of that
estimator for the frequency-domain time-averaged PSD of :func:`railvib.moving.moving_frf`
(seen through the Welch window, :func:`railvib.validation.statistics.welch_expectation`).
The issue's criterion: inside the 95 % band in >= 90 % of the bins from 1 to 500 Hz. The bins
within 2.5 Hz of the sleeper-passing lines n v / d (the deterministic part, validated on its
own in test_moving_vehicle_time_domain.py) are left out.

On this soft-pad track the moving and stationary PSDs differ by -5 % .. +12 %, well inside
the statistical band of one record: the test checks the moving model, not that it differs.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.coupling import CoupledSystem
from railvib.moving import MovingSettings, moving_frf
from railvib.pads import SpringDamper
from railvib.spectra import SPECTRA
from railvib.track import BallastedTrack, Rail
from railvib.validation.finite_track import FiniteTrack
from railvib.validation.moving_vehicle import simulate_moving_vehicle
from railvib.validation.samples import sample_profile
from railvib.validation.statistics import welch_expectation, welch_psd
from railvib.vehicle.library import PitchPlaneParameters

RAIL = Rail(6.4e6, 60.0)  # no loss factor: the time-domain model has no hysteretic loss
PAD, BALLAST = SpringDamper(2.0e8, 3.0e4), SpringDamper(1.0e8, 8.0e4)
D, SLEEPER, X0, K_H, SPEED = 0.6, 150.0, 0.3, 1.0e9, 22.2
VEHICLE = (
    PitchPlaneParameters(
        21920.0, 617310.0, 2550.0, 1750.0, 1420.0, 1.7e6, 5.0e3, 2.75e5, 3.0e4, 6.3, 1.1
    )
    .vehicle()
    .scaled(0.5)
)
SPECTRUM = SPECTRA.from_dict(
    {
        "type": "combined",
        "split_wavelength_m": 1.0,
        "long_wave": {"type": "fra", "class_number": 5},
        "short_wave": {"type": "shitai"},
    },
    "irregularity",
)
DT, RECORD, SEGMENT, F_TOP = 1e-4, 4.0, 0.5, 700.0  # s, s, s, Hz (input band top)


@pytest.mark.slow  # 40 000 Newmark steps on 3600 DOFs (~50 s CPU) and 100 moving frequencies
@pytest.mark.validation
def test_time_averaged_psd_matches_the_rolling_vehicle():
    settle = 20  # sleeper periods before the record
    fit = int(np.ceil(RECORD * SPEED / D))
    first = int(np.floor((X0 - VEHICLE.wheel_offsets.max()) / D)) - 40
    last = int(np.ceil((X0 + (settle + fit) * D) / D)) + 40
    track = FiniteTrack(
        RAIL,
        PAD,
        D,
        first,
        last,
        elements_per_span=6,
        absorber_spans=25,
        absorber_damping=1e6,
        ballast=BALLAST,
        sleeper_mass=SLEEPER,
    )
    dx = SPEED * DT / 2.0  # two profile samples per step
    n_points = 2 ** int(np.ceil(np.log2(((last - first) * D + 10.0) / dx)))
    # wavelengths of 1 .. 700 Hz at this speed: the inputs f + n v/d of the outputs to 500 Hz
    x, r = sample_profile(SPECTRUM, n_points * dx, dx, 7, wavelength_range=(SPEED / F_TOP, SPEED))
    sim = simulate_moving_vehicle(
        VEHICLE,
        track,
        K_H,
        SPEED,
        x_start=X0,
        dt=DT,
        settle_periods=settle,
        fit_periods=fit,
        profile=(x + first * D - 5.0, r),
    )
    est = welch_psd(sim.history[:, :1], sim.sample_rate, SEGMENT)

    wave = BallastedTrack(RAIL, PAD, D, sleeper_mass=SLEEPER, ballast=BALLAST)
    f = np.geomspace(1.0, 560.0, 100)  # log-interpolated between (a smooth PSD)
    system = CoupledSystem(VEHICLE, wave, K_H, X0, SPEED)
    _, force = moving_frf(system, f, MovingSettings(2)).averaged_psd(SPECTRUM)
    psd = force[:, 0]

    def model(g: np.ndarray) -> np.ndarray:
        return np.exp(np.interp(np.log(g), np.log(f), np.log(psd)))

    expected = welch_expectation(model, est.f, sim.sample_rate, SEGMENT, (1.0, 560.0))
    lo, hi = est.band(0.95)
    fb = est.f
    lines = np.abs(fb[:, None] - np.arange(1, 20)[None, :] * SPEED / D).min(axis=1) <= 2.5
    keep = (fb >= 1.0) & (fb <= 500.0) & ~lines
    inside = (expected >= lo[:, 0]) & (expected <= hi[:, 0])
    # measured 92.9 % of 184 bins; a fair estimator puts 95 % inside on average
    assert inside[keep].mean() >= 0.9
