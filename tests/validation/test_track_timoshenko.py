"""The Timoshenko rail option against closed forms and the Euler limit.

Reference for the pinned-pinned frequency: the frequency equation of a simply supported
Timoshenko beam (Timoshenko 1921; e.g. Rao, Vibration of Continuous Systems, Eq. 11.83),
for the first mode k = pi / d:
  EI k^4 - (EI m / kGA + rho_I) w^2 k^2 - m w^2 + (rho_I m / kGA) w^4 = 0.
At that frequency the rail's mode has nodes at the (undamped-rail) pads, so the
propagating wave of the periodic track does not decay: |mu| = 1.
"""

import warnings

import numpy as np
import pytest

from railvib.errors import CaseError, SolverWarning
from railvib.pads import SpringDamper
from railvib.track import PeriodicTrack, Rail

EI, M, D = 6.62e6, 60.64, 0.6
KGA = 0.4 * 7.9e10 * 7.745e-3  # CHN60, docs/reference-values.md §3.3
RHO_I = 7850.0 * 3.217e-5
PAD = SpringDamper(5e7, 5e4)


def pinned_pinned_timoshenko_hz():
    k = np.pi / D
    a = RHO_I * M / KGA
    b = -((EI * M / KGA + RHO_I) * k**2 + M)
    c = EI * k**4
    w2 = (-b - np.sqrt(b * b - 4 * a * c)) / (2 * a)
    return np.sqrt(w2) / (2 * np.pi)


def test_closed_form_matches_the_reference_value():
    # docs/reference-values.md §3.3: a Timoshenko CHN60 rail gives f_pp of about 1071 Hz
    # (vs 1441.7 Euler)
    assert pinned_pinned_timoshenko_hz() == pytest.approx(1071.0, rel=0.01)


def test_pinned_pinned_frequency_of_timoshenko_track():
    track = PeriodicTrack(Rail(EI, M, shear_stiffness=KGA, rotary_inertia=RHO_I), PAD, D)
    f_pp = pinned_pinned_timoshenko_hz()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SolverWarning)  # flagged there, as it should be
        mu = track.waves(f_pp * np.array([1.0 - 1e-3, 1.0, 1.0 + 1e-3])).mu
    loss = 1.0 - np.abs(mu).max(axis=1)
    # 1 - |mu| grows as 0.65 sqrt(|f/f_pp - 1|) around f_pp: 2e-5 already at 1e-9 off, 2e-6
    # at 1e-11. At f_pp itself the solver's vanishing rail loss (eta = 1e-12, the limit
    # eta -> 0+) acts as a detuning of about 1e-12: 1 - |mu| <= 0.65 sqrt(1e-12) = 6.5e-7.
    # So 1e-6 pins the model's f_pp to the closed form to better than 1e-11
    assert loss[1] < 1e-6
    assert loss[0] > 1e-2
    assert loss[2] > 1e-2


def test_euler_limit():
    # very stiff in shear and no rotary inertia: the Euler rail, to about
    # EI / (kGA d^2) = 8e-11 here (times the growth of the evanescent waves)
    f = np.geomspace(0.1, 5000.0, 60)
    x = [0.3, -1.9, 0.0]
    euler = PeriodicTrack(Rail(EI, M), PAD, D).receptance(f, x, x)
    stiff = PeriodicTrack(Rail(EI, M, shear_stiffness=KGA * 1e9), PAD, D).receptance(f, x, x)
    np.testing.assert_allclose(stiff, euler, rtol=1e-7)


def test_timoshenko_track_invariants():
    track = PeriodicTrack(Rail(EI, M, shear_stiffness=KGA, rotary_inertia=RHO_I), PAD, D)
    f = np.geomspace(0.1, 5000.0, 80)
    x = np.array([-2.2, 0.0, 0.3, 1.1])
    a = track.receptance(f, x, x)
    assert np.all(np.isfinite(a))
    np.testing.assert_allclose(a, np.swapaxes(a, 1, 2), rtol=1e-8, atol=1e-25)
    assert np.all(np.diagonal(a, axis1=1, axis2=2).imag < 0)
    # input power = pad dissipation (rail undamped, viscous pads)
    fp = np.array([60.0, 700.0, 2500.0])
    sleepers = D * np.arange(-400, 401)
    a0 = track.receptance(fp, [0.21], [0.21])[:, 0, 0]
    wn = track.receptance(fp, [0.21], sleepers)[:, :, 0]
    w = 2 * np.pi * fp
    np.testing.assert_allclose(
        -0.5 * w * a0.imag, 0.5 * w**2 * 5e4 * np.sum(np.abs(wn) ** 2, axis=1), rtol=1e-7
    )
    # Timoshenko is softer than Euler: lower stiffness above a few hundred Hz
    euler = PeriodicTrack(Rail(EI, M), PAD, D).receptance([1000.0], [0.3], [0.3])[0, 0, 0]
    timo = track.receptance([1000.0], [0.3], [0.3])[0, 0, 0]
    assert abs(timo) > abs(euler)


def test_timoshenko_inputs_validated():
    with pytest.raises(CaseError, match=r"track\.rail\.shear_stiffness = -1\.0"):
        Rail(EI, M, shear_stiffness=-1.0)
    with pytest.raises(CaseError, match="needs shear_stiffness too"):
        Rail(EI, M, rotary_inertia=0.25)
