"""Property-based: the solver over random physical parameter sets (issue 11, part C).

Euler and Timoshenko rails, undamped or damped; every registered pad model with a
plausible range (``railvib.testing.strategies``) and lossless pads (no damping at all),
with and without a WLF temperature shift; 20-400 km/h; sleeper spacing 0.5-0.75 m;
0.1 Hz - 5 kHz with dense points at the pinned-pinned frequencies (closed form), where
an undamped rail has a double Bloch eigenvalue.
"""

import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import railvib
from railvib.case import build_spectrum
from railvib.errors import SolverWarning
from railvib.testing.strategies import case_overrides, pad_tables

#: distances of the extra grid points from each pinned-pinned frequency (relative)
NEAR_PP = np.concatenate([[0.0], np.geomspace(1e-15, 1e-3, 5)])


def log_uniform(lo, hi):
    return st.floats(np.log(lo), np.log(hi)).map(np.exp)


LOSSLESS_PADS = st.one_of(
    st.fixed_dictionaries(
        {"model": st.just("spring_damper"), "stiffness_n_per_m": log_uniform(1e7, 1e9)}
    ),
    st.fixed_dictionaries(
        {
            "model": st.just("hysteretic"),
            "stiffness_n_per_m": log_uniform(1e7, 1e9),
            "loss_factor": st.just(0.0),
        }
    ),
)

#: WLF shift: glass transition well below the pad temperature (the law's singularity at
#: T = Tg - 51.6 K is another item of issue 11)
TTS = st.fixed_dictionaries(
    {"reference_temperature_c": st.just(20.0), "glass_transition_c": st.floats(-60.0, -30.0)}
)


@st.composite
def solver_cases(draw):
    """Case overrides of the default preset spanning the solver's inputs."""
    overrides = draw(case_overrides())
    track = overrides["track"]
    pad = dict(draw(st.one_of(pad_tables(), LOSSLESS_PADS)))
    if draw(st.booleans()):
        pad["tts"] = draw(TTS)
        track["pad_temperature_c"] = draw(st.floats(-20.0, 40.0))
    track["pad"] = pad
    if draw(st.booleans()):  # Timoshenko: CHN60's kappa G A and rho I, halved to doubled
        track["rail"]["shear_stiffness"] = draw(log_uniform(1.2e8, 5e8))
        track["rail"]["rotary_inertia"] = draw(st.floats(0.12, 0.5))
    overrides["speed_kmh"] = draw(st.floats(20.0, 400.0))
    return overrides


def pinned_pinned_hz(rail, d, f_max=5000.0):
    """Pinned-pinned frequencies of one bay below `f_max` (closed forms; Rao Eq. 11.83)."""
    ei, m = rail.bending_stiffness, rail.mass_per_length
    out = []
    for n in range(1, 9):
        k = n * np.pi / d
        if rail.shear_stiffness is None:
            w2 = ei * k**4 / m
        else:
            kga, rho_i = rail.shear_stiffness, rail.rotary_inertia
            a, b = rho_i * m / kga, -((ei * m / kga + rho_i) * k**2 + m)
            w2 = (-b - np.sqrt(b * b - 4 * a * ei * k**4)) / (2 * a)
        out.append(np.sqrt(w2) / (2 * np.pi))
    return [f for f in out if f <= f_max]


def check_solver(overrides, n_freq):
    case = railvib.case_from_dict({"preset": "wang2017_metro", **overrides}, warn=False)
    system = railvib.build_system(case)
    track = system.track
    f_pp = pinned_pinned_hz(track.rail, track.sleeper_spacing)
    rail = track.rail
    if rail.shear_stiffness is not None and rail.rotary_inertia > 0:  # and at the cut-off
        f_pp = [*f_pp, np.sqrt(rail.shear_stiffness / rail.rotary_inertia) / (2 * np.pi)]
    near = [p * (1 + s * NEAR_PP) for p in f_pp for s in (-1.0, 1.0)]
    f = np.unique(np.concatenate([np.geomspace(0.1, 5000.0, n_freq), *near]))
    f = f[f <= 5000.0]
    with warnings.catch_warnings():
        # flagged at the pinned-pinned frequencies, as it should be
        warnings.simplefilter("ignore", SolverWarning)
        ds = railvib.run_system(system, railvib.FrequencyGrid.from_array(f), build_spectrum(case))
        x_wheel = system.wheel_positions
        d = track.sleeper_spacing
        x = np.concatenate([x_wheel, [0.0, 0.5 * d, 0.29 * d, -3.7 * d]])
        rec = track.receptance(f, x, x)
        frf = system.frf(f)
        low = system.frf(np.array([1e-3, 1e-2]))

    # no NaN or inf; PSDs >= 0
    for name in ("psd_acceleration", "psd_displacement", "psd_force", "frf_displacement"):
        assert np.all(np.isfinite(ds[name].values)), name
    for name in ("psd_acceleration", "psd_displacement", "psd_force"):
        assert np.all(ds[name].values >= 0), name
    assert np.all(np.isfinite(rec))

    # passivity of the track: every driving point absorbs power. Strictly: the solver's
    # rail always dissipates (loss factor >= 1e-12), ~1e-13 |alpha| where nothing else does,
    # 30x the round-off of the imaginary part
    driving = np.diagonal(rec, axis1=1, axis2=2)
    assert np.all(driving.imag < 0)

    # reciprocity, relative to the geometric mean of the two driving points: 1e-9, the
    # issue's target (measured at most 1.4e-10 for Timoshenko rails, at the cut-off
    # meeting a pinned-pinned frequency, docs/design/0002-track-solver.md; about 1e-11 for
    # Euler rails)
    scale = np.sqrt(np.abs(driving[:, :, None] * driving[:, None, :]))
    error = (np.abs(rec - np.swapaxes(rec, 1, 2)) / scale).max(axis=(1, 2))
    bound = 1e-9
    assert np.all(error <= bound)

    # the coupled system seen at the wheels, G = (S + Q)^-1 = (C S + I)^-1 C with
    # C = R + I / k_H (track and contact) and S the vehicle condensed on its wheels:
    # passive and reciprocal too. Its imaginary part can be as small as the track's
    # (1e-13 |G|) and is formed through a solve of condition ~1e3: 1e-12 |G| of round-off
    c = frf.receptance + np.eye(x_wheel.size) / system.contact_stiffness
    s = system.vehicle.condensed_to_wheels(f).stiffness
    g = np.linalg.solve(c @ s + np.eye(x_wheel.size), c)
    g_driving = np.diagonal(g, axis1=1, axis2=2)
    assert np.all(g_driving.imag <= 1e-12 * np.abs(g_driving))
    g_scale = np.sqrt(np.abs(g_driving[:, :, None] * g_driving[:, None, :]))
    # The same bound as the track's (G inherits its precision), or the
    # round-off of the solve forming G, 100 eps cond(C S + I), where that is larger (at
    # f_pp of an undamped rail the wheels hold the rail and the condition reaches ~3e7)
    g_error = (np.abs(g - np.swapaxes(g, 1, 2)) / g_scale).max(axis=(1, 2))
    solve_round_off = 100 * np.finfo(float).eps * np.linalg.cond(c @ s + np.eye(x_wheel.size))
    assert np.all(g_error <= np.maximum(bound, solve_round_off))

    # |H_wheelset| -> 1 as f -> 0: below every suspension mode the vehicle moves as a
    # rigid body, so each wheel carries about its share M/n of the inertia force and
    # u_w - r = (R + I/k_H) P with P ~ omega^2 (M/n) u_w. Hence
    # |H - 1| <= 2 omega^2 (M/n) (max row sum |R| + 1/k_H) (2: the share and the modes'
    # amplification, 1.0001 at 0.01 Hz for a 1 Hz carbody mode, are estimates)
    omega = 2 * np.pi * low.f
    total_mass = sum(body.mass for body in system.vehicle.bodies)
    share = total_mass / x_wheel.size
    flexibility = np.abs(low.receptance).sum(axis=2).max(axis=1) + 1 / system.contact_stiffness
    bound = 2 * omega**2 * share * flexibility
    wheelsets = [i for i, name in enumerate(low.dofs) if name.startswith("wheelset")]
    h = low.vehicle[:, wheelsets]
    assert np.all(np.abs(np.abs(h) - 1.0) <= bound[:, None] + 1e-12)


# derandomize: the same examples on every run, so CI is reproducible (random exploration:
# `pytest --hypothesis-seed=<n>`)
@pytest.mark.property
@settings(
    max_examples=4, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow]
)
@given(overrides=solver_cases())
def test_solver_is_finite_passive_reciprocal(overrides):
    check_solver(overrides, n_freq=150)


@pytest.mark.property
@pytest.mark.slow
@settings(
    max_examples=100, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow]
)
@given(overrides=solver_cases())
def test_solver_is_finite_passive_reciprocal_many_cases(overrides):
    check_solver(overrides, n_freq=600)
