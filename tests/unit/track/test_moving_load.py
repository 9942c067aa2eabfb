"""The moving harmonic load on the periodic track (railvib.track.moving, issue 17 item 1).

The slow-speed limit is checked against the stationary wave solver
(:meth:`PeriodicTrack.receptance`), an independent code path (Bloch waves of the bay's
transfer matrix; the moving-load code never forms them): as ``v -> 0`` the harmonics
``A_n`` tend to the Fourier coefficients over load position of the stationary receptance.
"""

from __future__ import annotations

import numpy as np
import pytest

import railvib.track.moving as moving
from railvib.errors import CaseError, SolverWarning
from railvib.pads import SpringDamper
from railvib.track import BallastedTrack, PeriodicTrack, Rail
from railvib.track.moving import (
    MAX_HARMONIC_ORDER,
    SPEED_FRACTION,
    critical_speed,
    moving_load_receptance,
)

#: Nordborg's ballasted track (Acta Acustica 84, 1998): EI, m, pad, sleeper, ballast, d
NORDBORG = BallastedTrack(
    Rail(4.725e6, 60.0),
    SpringDamper(300e6, 18e3),
    0.6,
    sleeper_mass=150.0,
    ballast=SpringDamper(150e6, 48e3),
)
#: a rigid-base track with a damped rail and soft pads
RIGID = PeriodicTrack(Rail(6.62e6, 60.64, 0.01), SpringDamper(5e7, 5e4), 0.6)
F = np.array([50.0, 300.0, 800.0, 2000.0])
N_POSITIONS = 64


def _fourier_over_load_position(track, f, r, orders):
    """Fourier coefficients of ``alpha(xi + r, xi, f)`` over xi in one bay (FFT, 64 points).

    ``alpha`` is smooth in xi with a jump in its third derivative at the sleepers, so
    its coefficients fall as n^-4 and the aliasing of 64 samples is < 1e-7 of A_0.
    """
    d = track.sleeper_spacing
    xi = np.arange(N_POSITIONS) / N_POSITIONS * d
    alpha = track.receptance(f, xi, xi + r)  # (n_freq, n_obs, n_load)
    diag = alpha[:, np.arange(N_POSITIONS), np.arange(N_POSITIONS)]
    coef = np.fft.fft(diag, axis=1) / N_POSITIONS  # coefficient of exp(+i 2 pi n xi / d)
    return np.stack([coef[:, n % N_POSITIONS] for n in orders], axis=1)


@pytest.mark.parametrize("track", [NORDBORG, RIGID], ids=["ballasted", "rigid_base"])
@pytest.mark.parametrize("r", [0.0, 0.25])
def test_slow_load_recovers_the_stationary_fourier_coefficients(track, r):
    orders = range(-3, 4)
    ref = _fourier_over_load_position(track, F, r, orders)
    errors = {}
    for v in (1.0, 0.1):
        res = moving_load_receptance(track, F, v, order=3, r=[r])
        errors[v] = np.abs(res.amplitudes[:, 0, :] - ref).max(axis=1) / np.abs(ref[:, 3])
    # the moving load differs from the stationary one by first-order Doppler terms,
    # O(v / c) with c >= 100 m/s the bending phase speed in the band: < 1e-3 at 0.1 m/s
    assert errors[0.1].max() < 1e-3
    # ... and the difference is that first-order term: it falls with v (ten times slower,
    # ten times smaller, measured), down to the floor of the quadrature and of the 64-point
    # FFT (3e-5 of A_0 at 2 kHz, measured: a 9 kHz pinned-pinned wave)
    assert np.all(errors[0.1] < errors[1.0] / 5.0 + 3e-5), errors


def test_mean_is_the_position_average_at_low_speed():
    """A_0 as v -> 0 is the stationary point receptance averaged over the bay."""
    res = moving_load_receptance(RIGID, F, 0.1, order=2)
    ref = _fourier_over_load_position(RIGID, F, 0.0, [0])[:, 0]
    # the same O(v / c) bound as above
    np.testing.assert_allclose(res.mean[:, 0], ref, rtol=1e-3)


@pytest.mark.slow  # 250 frequencies: 4-8 s
def test_pinned_pinned_peak_splits_by_the_sleeper_passing_frequency():
    """The stationary mean peaks at f_pp; the moving one at f_pp -+ v / (2 d)."""
    v, d = 60.0, NORDBORG.sleeper_spacing
    f = np.arange(1100.0, 1350.0, 1.0)
    moving = np.abs(moving_load_receptance(NORDBORG, f, v, order=3).mean[:, 0])
    f_pp = NORDBORG.pinned_pinned_frequencies_hz(2000.0)[0]
    low, high = f < f_pp, f > f_pp
    peak_low, peak_high = f[low][np.argmax(moving[low])], f[high][np.argmax(moving[high])]
    # 1 Hz grid; the band edge of the pinned-pinned wave sits a few Hz from f_pp itself
    assert abs(peak_low - (f_pp - v / (2 * d))) <= 6.0
    assert abs(peak_high - (f_pp + v / (2 * d))) <= 6.0
    # at f_pp itself the moving load meets a trough: 10 dB under the split peaks
    at_pp = moving[np.argmin(np.abs(f - f_pp))]
    assert 20 * np.log10(min(moving[low].max(), moving[high].max()) / at_pp) > 10.0


@pytest.mark.parametrize("track", [NORDBORG, RIGID], ids=["ballasted", "rigid_base"])
def test_quadrature_converged(track, monkeypatch):
    """A 1000 times tighter panel tolerance changes A_n by < 1e-4 of the largest harmonic."""
    f = np.array([300.0, 1170.0, 1280.0, 1500.0])  # near the split peaks of both tracks
    coarse = moving_load_receptance(track, f, 60.0, order=2).amplitudes
    monkeypatch.setattr(moving, "_PANEL_TOLERANCE", moving._PANEL_TOLERANCE / 1000)
    fine = moving_load_receptance(track, f, 60.0, order=2).amplitudes
    scale = np.abs(fine).max(axis=2, keepdims=True)
    # the Kronrod error estimate is far above the error (measured change 2e-5 at most,
    # on pads down to a loss factor of 0.01)
    assert np.max(np.abs(coarse - fine) / scale) < 1e-4


def test_undamped_wave_travelling_with_the_load_is_flagged():
    """At the split peak of an undamped rail the result is that of the vanishing loss."""
    f_pp = NORDBORG.pinned_pinned_frequencies_hz(2000.0)[0]
    with pytest.warns(SolverWarning, match="undamped wave travels with the load"):
        moving_load_receptance(NORDBORG, [f_pp - 60.0 / 1.2], 60.0, order=2)


def test_response_frequencies_and_tail():
    res = moving_load_receptance(NORDBORG, [300.0], 60.0, order=4)
    np.testing.assert_allclose(res.response_frequencies_hz[0], 300.0 + 100.0 * np.arange(-4, 5))
    assert res.sleeper_passing_frequency_hz == pytest.approx(100.0)
    # the harmonics fall off (|A_4| is ~1e-4 of A_0 at 300 Hz)
    assert res.tail[0] < 1e-3


def test_critical_speed_closed_form():
    """(4 EI s / m^2)^(1/4) with s the static support per length: pad and ballast in series."""
    k = 300e6 * 150e6 / 450e6  # N/m at f -> 0 (the sleeper mass does not count)
    expected = (4 * 4.725e6 * (k / 0.6) / 60.0**2) ** 0.25
    # evaluated at 1 Hz, where the sleeper mass takes m_s omega^2 / K_b = 4e-5 off the
    # ballast, 1e-5 off the speed (a quarter power)
    assert critical_speed(NORDBORG) == pytest.approx(expected, rel=2e-5)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"speed": 0.0}, "moving.speed_m_per_s"),
        ({"speed": -5.0}, "moving.speed_m_per_s"),
        ({"speed": float("nan")}, "moving.speed_m_per_s"),
        ({"speed": "fast"}, "moving.speed_m_per_s"),
        ({"speed": 600.0}, "moving.speed_m_per_s"),
        ({"order": -1}, "moving.harmonic_order"),
        ({"order": 2.5}, "moving.harmonic_order"),
        ({"order": MAX_HARMONIC_ORDER + 1}, "moving.harmonic_order"),
        ({"r": [float("inf")]}, "moving.r_m"),
        ({"f": [-1.0]}, "frequency"),
        ({"tolerance": 0.0}, "moving.tolerance"),
    ],
)
def test_bad_input_names_the_field(kwargs, field):
    args = {"f": [100.0], "speed": 30.0, "order": 2, **kwargs}
    f, speed = args.pop("f"), args.pop("speed")
    with pytest.raises(CaseError) as err:
        moving_load_receptance(NORDBORG, f, speed, **args)
    assert err.value.field == field
    assert "\n" not in str(err.value)


def test_speed_bound_is_stated():
    bound = SPEED_FRACTION * critical_speed(NORDBORG)
    with pytest.raises(CaseError, match=f"at most {bound:.4g} m/s"):
        moving_load_receptance(NORDBORG, [100.0], bound * 1.01)


def test_order_too_low_says_the_order_needed():
    """At the split peak |A_2| is 3e-4 of |A_0|: order 1 is refused for a 1e-4 tolerance."""
    with pytest.raises(CaseError) as err:
        moving_load_receptance(NORDBORG, [1175.0], 60.0, order=1, tolerance=1e-4)
    assert err.value.field == "moving.harmonic_order"
    assert "\n" not in str(err.value)
    needed = int(str(err.value).split("at least ")[1].split()[0])
    # the order it names is accepted, and the one below it is not
    moving_load_receptance(NORDBORG, [1175.0], 60.0, order=needed, tolerance=1e-4)
    if needed > 2:
        with pytest.raises(CaseError):
            moving_load_receptance(NORDBORG, [1175.0], 60.0, order=needed - 1, tolerance=1e-4)
