"""Property-based: the rigid-base and ballasted tracks alone over random parameter sets.

Euler rails (the rail's own loss left out, so that the supports dissipate everything),
every registered pad model with a plausible range as pad, ballast and subgrade
(``railvib.testing.strategies.pad_tables``), two- and three-layer ballasted tracks,
sleeper spacing 0.5-0.75 m, 0.1 Hz - 5 kHz with points at the pinned-pinned
frequencies (closed form). For a unit force at a random point:

* reciprocity ``alpha(x_i, x_j) = alpha(x_j, x_i)``;
* passivity: the input power ``-omega Im alpha(x_F, x_F) / 2 >= 0``;
* power balance: the input power equals the power dissipated in every layer of every
  rail seat, ``sum omega Im K |compression|^2 / 2`` (``support_response``), once the
  solver's vanishing rail loss is extrapolated away; the seats beyond the 20 nearest on
  each side are summed in closed form from the two Bloch waves (``w_{n+k} = sum_j c_j
  mu_j^k``, a geometric series).
"""

import warnings
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from railvib.errors import SolverWarning
from railvib.pads import PADS
from railvib.testing.strategies import pad_tables
from railvib.track import BallastedTrack, PeriodicTrack, Rail

#: seats summed explicitly on each side of the load's nearest one
N_SEATS = 20


def log_uniform(lo, hi):
    return st.floats(np.log(lo), np.log(hi)).map(np.exp)


@st.composite
def tracks(draw):
    """A rigid-base, two-layer or three-layer ballasted track with an Euler rail."""
    rail = Rail(draw(log_uniform(3e6, 1.2e7)), draw(st.floats(40.0, 80.0)))
    d = draw(st.floats(0.5, 0.75))
    pad = PADS.from_dict(draw(pad_tables()), "pad")
    kind = draw(st.sampled_from(["rigid_base", "ballasted", "three_layer"]))
    if kind == "rigid_base":
        return PeriodicTrack(rail, pad, d, 20.0)
    layers = {
        "sleeper_mass": draw(st.floats(50.0, 300.0)),
        "ballast": PADS.from_dict(draw(pad_tables()), "ballast"),
    }
    if kind == "three_layer":
        layers["ballast_mass"] = draw(st.floats(200.0, 800.0))
        layers["subgrade"] = PADS.from_dict(draw(pad_tables()), "subgrade")
    return BallastedTrack(rail, pad, d, 20.0, **layers)


def pinned_pinned_hz(rail, d, f_max=5000.0):
    """Pinned-pinned frequencies of one bay (Euler rail): (n pi / d)^2 sqrt(EI / m) / 2 pi."""
    f = [(n * np.pi / d) ** 2 * np.sqrt(rail.bending_stiffness / rail.mass_per_length) / (2 * np.pi)
         for n in range(1, 9)]  # fmt: skip
    return [p for p in f if p <= f_max]


def geometric_tail(w0, w1, mu):
    """``sum_{k >= 1} |w_k|^2`` of ``w_k = c_1 mu_1^k + c_2 mu_2^k`` through ``w0, w1``."""
    c2 = (w1 - mu[:, 0] * w0) / (mu[:, 1] - mu[:, 0])
    c = np.stack([w0 - c2, c2], axis=1)
    pair = mu[:, :, None] * np.conj(mu[:, None, :])
    gram = pair / (1.0 - pair)
    return np.real(np.einsum("fj,fjl,fl->f", c, gram, np.conj(c)))


def supports_power(track, f, x_load):
    """Input power and the power the seats' layers dissipate, W per N^2 of force amplitude."""
    omega = 2 * np.pi * f
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SolverWarning)  # flagged at f_pp, as it should be
        driving = track.receptance(f, [x_load], [x_load])[:, 0, 0]
        out = track.support_response(f, x_load, N_SEATS + 1)
        mu = track.propagation_constants(f)
    seat = sum(
        0.5 * omega[:, None] * out.stiffness[name].imag[:, None] * np.abs(c) ** 2
        for name, c in out.compression.items()
    )
    rail = out.displacement["rail"]
    per_w2 = seat[:, N_SEATS] / np.abs(rail[:, N_SEATS]) ** 2  # same factor at every seat
    right = geometric_tail(rail[:, -2], rail[:, -1], mu)  # from the outermost seat on
    left = geometric_tail(rail[:, 1], rail[:, 0], mu)
    return -0.5 * omega * driving.imag, seat[:, 1:-1].sum(axis=1) + per_w2 * (right + left)


def check_track(track, x_load, n_freq):
    d = track.sleeper_spacing
    near = [p * (1 + s * e) for p in pinned_pinned_hz(track.rail, d) for s in (-1, 1)
            for e in (1e-6, 1e-3)]  # fmt: skip
    f = np.unique(np.concatenate([np.geomspace(0.1, 5000.0, n_freq), near]))
    x = np.array([x_load, 0.0, 0.5 * d, 0.29 * d, -3.7 * d, 2.2 * d])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SolverWarning)
        rec = track.receptance(f, x, x)
    assert np.all(np.isfinite(rec))

    # reciprocity, relative to the geometric mean of the two driving points: 1e-9 for an
    # Euler rail (the solver's bound, tests/property/test_property_solver.py)
    driving = np.diagonal(rec, axis1=1, axis2=2)
    scale = np.sqrt(np.abs(driving[:, :, None] * driving[:, None, :]))
    assert np.all(np.abs(rec - np.swapaxes(rec, 1, 2)) / scale <= 1e-9)

    # passivity: every driving point takes power in (Im alpha <= 0)
    assert np.all(driving.imag <= 0)

    # power balance: input = seats' layers + the rail's own loss. The solver's rail has a
    # loss factor of at least 1e-12 (VANISHING_LOSS_FACTOR), which takes ~1e-12 / eta_support
    # of the input (1e-8 at 0.1 Hz on a spring-damper pad) and up to 1e-6 within 1e-6 of a
    # pinned-pinned frequency, where the rail hardly moves the seats (its share there is
    # not quite linear in eta_r: 4.01x for 4x). Measured at eta_r = 1, 2 and 4 x 1e-12 and
    # extrapolated to eta_r = 0 (quadratic: (8 D_1 - 6 D_2 + D_4) / 3), the seats must
    # account for all of the input, to 1e-8; or, where the layers barely dissipate, to the
    # round-off of Im alpha: ~100 eps |alpha| (measured 40 eps: 1.1e-8 at 0.1 Hz with a
    # spring-damper loss of 9e-7), relative to Im alpha, times the extrapolation's 5. Within
    # 1e-5 of a pinned-pinned frequency (a nearly double Bloch root) the solver holds alpha
    # to ~1e-9 |alpha| (reciprocity above) while Im alpha is down to 1e-2 |alpha|, and the
    # rail's share is no longer smooth enough to extrapolate (measured: 1.3e-7 left of a
    # 6e-7 share, soft spring-damper pad at 2.96 kHz): 1e-6 there
    deficit = []
    for eta in (1e-12, 2e-12, 4e-12):
        lossy = replace(track, rail=replace(track.rail, loss_factor=eta))
        p_in, p_seats = supports_power(lossy, f, x_load)
        assert np.all(p_in > 0)
        deficit.append((p_in - p_seats) / p_in)
    at_zero = (8 * deficit[0] - 6 * deficit[1] + deficit[2]) / 3
    round_off = 5 * 100 * np.finfo(float).eps * np.abs(driving[:, 0]) / -driving[:, 0].imag
    f_pp = np.array(pinned_pinned_hz(track.rail, d) or [np.inf])
    at_pp = np.min(np.abs(f[:, None] / f_pp[None, :] - 1), axis=1) < 1e-5
    bound = np.maximum(np.where(at_pp, 1e-6, 1e-8), round_off)
    assert np.all(np.abs(at_zero) <= bound)


# derandomize: the same examples on every run, so CI is reproducible
@pytest.mark.property
@settings(
    max_examples=4, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow]
)
@given(track=tracks(), x_frac=st.floats(0.0, 0.999))
def test_tracks_are_reciprocal_passive_and_balance_power(track, x_frac):
    check_track(track, x_frac * track.sleeper_spacing, n_freq=40)


@pytest.mark.property
@pytest.mark.slow
@settings(
    max_examples=80, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow]
)
@given(track=tracks(), x_frac=st.floats(0.0, 0.999))
def test_tracks_are_reciprocal_passive_and_balance_power_many_cases(track, x_frac):
    check_track(track, x_frac * track.sleeper_spacing, n_freq=200)
