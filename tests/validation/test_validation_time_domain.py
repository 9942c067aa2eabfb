"""Newmark integration of the vehicle on the finite track against its own frequency response."""

from dataclasses import replace

import numpy as np
import pytest

from railvib.coupling import CoupledSystem
from railvib.pads import SpringDamper
from railvib.track import PeriodicTrack, Rail
from railvib.validation import (
    FiniteCoupledSystem,
    MonteCarloSettings,
    newmark_frequency_warp,
    simulate_time_domain,
)
from railvib.validation.time_domain import output_dofs

K_H = 9.873e8
SPEED = 80 / 3.6
MC = MonteCarloSettings()


@pytest.fixture(scope="module")
def system():
    from railvib.vehicle import PitchPlaneParameters, pitch_plane_10dof

    p = PitchPlaneParameters(21920, 617310, 2550, 1750, 1420, 1.7e6, 5e3, 2.75e5, 3e4, 6.3, 1.1)
    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    return FiniteCoupledSystem.from_system(
        CoupledSystem(pitch_plane_10dof(p), track, K_H, 0.3, SPEED),
        margin_spans=MC.margin_spans,
        elements_per_span=MC.elements_per_span,
        absorber_spans=MC.absorber_spans,
        absorber_damping=MC.absorber_damping,
    )


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
@pytest.mark.parametrize("f0", [47.0, 300.0])
def test_harmonic_steady_state_matches_frequency_domain(system, f0):
    # a delayed sinusoidal irregularity: after the transients the Newmark amplitude equals
    # the direct frequency-domain solution of the same matrices at the warped frequency
    # (Newmark = bilinear map). 0.5 % covers the residual transient and the amplitude
    # read from a finite record.
    dt = 1e-4
    t = np.arange(int(1.5 / dt) + 1) * dt
    ramp = np.clip(t / 0.2, 0.0, 1.0)
    r = ramp[:, None] * np.sin(2 * np.pi * f0 * (t[:, None] - system.delays[None, :]))
    hist = simulate_time_domain(system, r * 1e-4, dt)
    tail = t > 1.0
    basis = np.exp(2j * np.pi * f0 * t[tail])
    amp_td = 2 * (hist.acceleration[tail, :, 0].T @ basis.conj()) / tail.sum()
    fw = float(newmark_frequency_warp(f0, dt))
    # delays act on the true frequency: same phase lag at fw with the speed scaled by fw/f0
    h = replace(system, speed=system.speed * fw / f0).frf([fw])
    dofs, _ = output_dofs(system)
    frf = np.concatenate([h.vehicle[0], h.rail[0]])
    # acceleration of the discrete scheme: -(omega_w)^2 scaling on the warped frequency
    amp_fd = -((2 * np.pi * fw) ** 2) * frf * 1e-4 / 1j
    big = np.abs(amp_fd) > 1e-3 * np.abs(amp_fd).max()
    np.testing.assert_allclose(np.abs(amp_td[big]), np.abs(amp_fd[big]), rtol=5e-3)


def test_pulse_does_not_come_back_from_the_ends(system):
    # a short force pulse on the rail at the leading wheel: the response there on the
    # Monte Carlo track equals that on a 4x longer track (no reflection) to 1e-3 of the peak
    from railvib.validation.time_domain import simulate_time_domain as sim

    track = PeriodicTrack(system.track.rail, system.track.pad, 0.6)
    long = FiniteCoupledSystem.from_system(
        CoupledSystem(system.vehicle, track, K_H, 0.3, SPEED), margin_spans=120, elements_per_span=2
    )
    dt = 1e-4
    n = 3000
    t = np.arange(n + 1) * dt
    pulse = np.where(t < 4e-3, np.sin(np.pi * t / 4e-3) ** 2, 0.0)
    r = np.zeros((n + 1, 4))
    r[:, 0] = (
        1e-5 * pulse
    )  # a 4 ms dip (content below ~500 Hz, as the MC input) under the leading wheel only
    a = sim(system, r, dt).acceleration[:, -4, 0]
    b = sim(long, r, dt).acceleration[:, -4, 0]
    assert np.abs(a - b).max() < 1e-3 * np.abs(b).max()
