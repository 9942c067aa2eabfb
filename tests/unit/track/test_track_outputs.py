"""The track alone (railvib.track.outputs): FRFs, support forces, waves, EN 15461 decay rate.

Expected values come from closed forms: the infinite Euler beam on a continuous
(Winkler) foundation, a single decaying wave, the pinned-pinned frequency, the
equations of motion of the sleeper and of the rail, and the values printed in
EN 15461 and IEC 61260-1.
"""

import numpy as np
import pytest

from railvib.case import build_track, load_preset_case
from railvib.errors import CaseError
from railvib.pads import Hysteretic
from railvib.track import BallastedTrack, PeriodicTrack, Rail
from railvib.track.outputs import (
    EN15461_GRID_BAYS,
    band_edges,
    en15461_positions,
    en15461_weights,
    frf,
    third_octave_centres,
    track_decay_rate,
    wave_decay,
)

UIC60 = Rail(6.42e6, 60.0)
D = 0.6
#: Thompson (2009) ch. 3 ballasted track (the thompson_ballasted preset, one rail)
THOMPSON = BallastedTrack(
    UIC60, Hysteretic(3e8, 0.25), D, sleeper_mass=162.0, ballast=Hysteretic(5e7, 1.0)
)


class WinklerBeam:
    """Infinite Euler beam on a continuous foundation k_f (1 + i eta), closed form.

    ``EI w'''' - m omega^2 w + k_f* w = F delta(x)``; with ``lambda^4 = (m omega^2 -
    k_f*) / EI`` (the root with Re > 0, Im < 0: both terms decay),
    ``w(x) = -F / (4 EI lambda^3) (i e^{-i lambda |x|} + e^{-lambda |x|})``
    (Thompson 2009, ch. 3; Graff, Wave Motion in Elastic Solids, 1975, 1.5).
    """

    def __init__(self, ei, m, k_f, eta, sleeper_spacing=D):
        self.ei, self.m, self.kf = ei, m, k_f * (1 + 1j * eta)
        self.sleeper_spacing = sleeper_spacing
        self.period = sleeper_spacing

    def lam(self, f):
        omega = 2 * np.pi * np.asarray(f, dtype=float)
        lam = ((self.m * omega**2 - self.kf) / self.ei + 0j) ** 0.25
        assert np.all((lam.real > 0) & (lam.imag < 0))
        return lam

    def receptance(self, f, x_load, x_obs):
        lam = self.lam(f)[:, None, None]
        r = np.abs(np.subtract.outer(np.atleast_1d(x_obs), np.atleast_1d(x_load)))[None]
        return -(1j * np.exp(-1j * lam * r) + np.exp(-lam * r)) / (4 * self.ei * lam**3)

    def propagation_constants(self, f):
        lam = self.lam(f)
        mu = np.stack([np.exp(-1j * lam * self.period), np.exp(-lam * self.period)], axis=1)
        return np.take_along_axis(mu, np.argsort(-np.abs(mu), axis=1), axis=1)


class OneWave:
    """A rail carrying one wave ``exp(-(beta + i k) |x|)`` from the load, nothing else."""

    def __init__(self, beta, k, sleeper_spacing=D):
        self.beta, self.k = beta, k
        self.sleeper_spacing = self.period = sleeper_spacing

    def receptance(self, f, x_load, x_obs):
        r = np.abs(np.subtract.outer(np.atleast_1d(x_obs), np.atleast_1d(x_load)))
        return np.broadcast_to(np.exp(-(self.beta + 1j * self.k) * r), (np.size(f), *r.shape))

    def propagation_constants(self, f):
        mu = np.exp(-(self.beta + 1j * self.k) * self.period)
        return np.full((np.size(f), 1), mu)


# -- the standard's grid, bands and formula ---------------------------------------------
def test_en15461_grid_is_the_29_positions_of_figure_2():
    # 6.7 / Figure 2: every quarter bay to 2.5, every half bay to 4, every bay to 8, then
    # 10, 12, 16, 20, 24, 30, 36, 42, 48, 54, 66
    expected = [0, 0.25, 0.5, 0.75, 1, 1.25, 1.5, 1.75, 2, 2.25, 2.5, 3, 3.5, 4, 5, 6, 7, 8]
    expected += [10, 12, 16, 20, 24, 30, 36, 42, 48, 54, 66]
    assert list(EN15461_GRID_BAYS) == expected
    np.testing.assert_allclose(en15461_positions(0.6)[-1], 39.6, rtol=1e-15)


def test_en15461_weights_are_the_half_distances_of_annex_a():
    # A.2: the direct point stands for 0 to halfway; the last is symmetric about itself
    w = en15461_weights(en15461_positions(1.0))
    assert w[0] == 0.125
    assert w[1] == 0.25
    assert w[10] == 0.375  # from 2.375 to 2.75
    assert w[-1] == 12.0  # 60 to 72 (symmetric about 66)
    assert np.sum(w) == 72.0


def test_third_octave_bands_are_iec_61260_base_10():
    centres, nominal = third_octave_centres(100.0, 5000.0)
    assert nominal == [
        "100", "125", "160", "200", "250", "315", "400", "500", "630", "800",
        "1000", "1250", "1600", "2000", "2500", "3150", "4000", "5000",
    ]  # fmt: skip
    # exact centres 1000 x 10^(x/10): 100 Hz and 1 kHz exactly, 5 kHz is 5011.87 Hz
    np.testing.assert_allclose(centres[[0, 10, 17]], [100.0, 1000.0, 5011.872336], rtol=1e-9)
    lower, upper = band_edges(centres)
    np.testing.assert_allclose(upper[:-1], lower[1:], rtol=1e-14)  # contiguous bands


def test_bad_tdr_arguments_are_named():
    with pytest.raises(CaseError, match="method"):
        track_decay_rate(THOMPSON, method="mean")
    with pytest.raises(CaseError, match="tdr bands"):
        track_decay_rate(THOMPSON, 500.0, 100.0)
    with pytest.raises(CaseError, match="positions"):
        en15461_weights([0.5, 1.0])


# -- closed forms -------------------------------------------------------------------------
WINKLER = WinklerBeam(6.42e6, 60.0, 5e7 / D, 1.0)


def _expected_tdr(track, f, power):
    """Formula 1 evaluated on the closed-form receptance, weights written out from A.2."""
    x = np.asarray(EN15461_GRID_BAYS) * D
    edges = np.concatenate([[0.0], (x[1:] + x[:-1]) / 2, [x[-1] + (x[-1] - x[-2]) / 2]])
    a = track.receptance(f, [0.3], 0.3 + x)[:, :, 0] * (2 * np.pi * f[:, None]) ** power
    return np.abs(a) ** 2, np.diff(edges)


def test_tdr_of_the_winkler_beam_at_band_centres_is_formula_1_of_its_closed_form():
    out = track_decay_rate(WINKLER, 100.0, 5000.0, method="centre")
    a2, dx = _expected_tdr(WINKLER, out.centres, 0)
    expected = 4.343 / np.sum(a2 / a2[:, :1] * dx, axis=1)
    # 4.343 is Formula 1's rounding of 10 lg e = 4.342945: 1.3e-5 relative
    np.testing.assert_allclose(out.rate, expected, rtol=2e-5)
    # the least-attenuated wave is the propagating e^{-i lambda x}: 20 lg e |Im lambda|
    lam = WINKLER.lam(out.centres)
    np.testing.assert_allclose(out.wave, 8.685889638 * np.abs(lam.imag), rtol=1e-9)


def test_band_averaged_tdr_of_the_winkler_beam_averages_the_accelerance_over_the_band():
    out = track_decay_rate(WINKLER, 200.0, 2000.0, method="band", points_per_band=5)
    lower, upper = band_edges(out.centres)
    step = (upper - lower) / 5
    f = (lower[:, None] + (np.arange(5) + 0.5) * step[:, None]).ravel()
    a2, dx = _expected_tdr(WINKLER, f, 2)
    band = a2.reshape(out.centres.size, 5, -1).mean(axis=1)
    expected = 4.342944819 / np.sum(band / band[:, :1] * dx, axis=1)
    np.testing.assert_allclose(out.rate, expected, rtol=1e-10)  # round-off of the sums


def test_tdr_of_a_single_wave_is_its_decay_within_the_grid_quadrature_bound():
    # |A|^2 = exp(-2 beta x): DR = 20 lg e beta exactly for the integral (A.1); the grid
    # sums a decreasing function at one point of each cell [a_n, b_n], so it lies within
    # sum (g(a_n) - g(b_n)) dx_n of the integral over [0, b_N], and the tail beyond b_N
    # is exp(-2 beta b_N) / 2 beta
    for db_per_m in (0.5, 2.0, 10.0):
        beta = db_per_m / 8.685889638
        out = track_decay_rate(OneWave(beta, 3.0), 1000.0, 1000.0, method="centre")
        x = en15461_positions(D)
        edges = np.concatenate([[0.0], (x[1:] + x[:-1]) / 2, [x[-1] + (x[-1] - x[-2]) / 2]])
        g = np.exp(-2 * beta * edges)
        total = np.sum(np.exp(-2 * beta * x) * np.diff(edges))
        bound = np.sum((g[:-1] - g[1:]) * np.diff(edges)) + g[-1] / (2 * beta)
        assert abs(out.rate[0] / db_per_m * (4.342944819 / 4.343) - 1) <= bound / total
        assert abs(out.rate[0] / db_per_m - 1) < 0.15  # the bound is small: a real check
        # -20 lg|exp(-beta d)| / d: round-off of log and exp over beta d ~ 0.01-1
        np.testing.assert_allclose(out.wave[0], db_per_m, rtol=1e-10)


def test_periodic_track_with_dense_supports_tends_to_the_winkler_beam():
    # K = k_f d at spacing d: the discrete supports sample the continuous foundation; the
    # fields differ by O((|lambda| d)^2) (the midpoint rule of the support's integral),
    # here below 1e-3 at 100 - 1000 Hz for d = 0.6 / 40
    d = D / 40
    k_f, eta = 5e7 / D, 1.0
    track = PeriodicTrack(UIC60, Hysteretic(k_f * d, eta), d)
    f = np.array([100.0, 300.0, 1000.0])
    lam = WINKLER.lam(f)
    tol = 2 * np.max(np.abs(lam) * d) ** 2
    assert tol < 1e-2
    x = np.array([0.0, 0.37, 1.2, 3.0])
    got = track.receptance(f, [0.0], x)
    want = WINKLER.receptance(f, [0.0], x)
    np.testing.assert_allclose(got, want, rtol=tol, atol=tol * np.abs(want).max())
    decay, _ = wave_decay(track.propagation_constants(f)[:, 0], d)
    np.testing.assert_allclose(decay, 8.685889638 * np.abs(lam.imag), rtol=tol)


def test_pass_and_stop_bands_of_the_undamped_rail_meet_at_the_pinned_pinned_frequency():
    # rigid base, lossless pad: |mu| = 1 in a pass band; the first pinned-pinned
    # frequency (pi / d)^2 sqrt(EI / m) / 2 pi (1427 Hz) starts a stop band, where
    # mu = -1 (half a wavelength per bay)
    track = PeriodicTrack(UIC60, Hysteretic(3e8, 0.0), D)
    f_pp = (np.pi / D) ** 2 * np.sqrt(6.42e6 / 60.0) / (2 * np.pi)
    mu = track.propagation_constants([0.97 * f_pp, 1.01 * f_pp])
    decay, propagates = wave_decay(mu, D)
    assert propagates[0, 0]
    assert not propagates[1, 0]
    assert abs(abs(mu[0, 0]) - 1) < 1e-9  # the solver's vanishing rail loss, 1e-12
    assert abs(mu[1, 0].real + abs(mu[1, 0])) < 1e-9 * abs(mu[1, 0])  # negative real
    assert not propagates[:, 1].any()  # the second wave is evanescent (decays > 30 dB/m)
    assert decay[:, 1].min() > 30


def test_mobility_and_accelerance_are_i_omega_and_minus_omega_squared_receptance():
    f = np.array([10.0, 500.0])
    alpha = THOMPSON.receptance(f, [0.3], [0.3, 1.1])
    omega = 2 * np.pi * f[:, None, None]
    np.testing.assert_allclose(frf(THOMPSON, f, [0.3], [0.3, 1.1], "mobility"), 1j * omega * alpha)
    np.testing.assert_allclose(
        frf(THOMPSON, f, [0.3], [0.3, 1.1], "accelerance"), -(omega**2) * alpha
    )
    with pytest.raises(CaseError, match="quantity"):
        frf(THOMPSON, f, [0.3], [0.3], "velocity")


# -- support forces ------------------------------------------------------------------------
THREE_LAYER = BallastedTrack(
    UIC60,
    Hysteretic(3e8, 0.25),
    D,
    sleeper_mass=162.0,
    ballast=Hysteretic(1.2e8, 0.5),
    ballast_mass=400.0,
    subgrade=Hysteretic(6e7, 0.8),
)


@pytest.mark.parametrize("track", [THOMPSON, THREE_LAYER], ids=["two layers", "three layers"])
def test_each_mass_below_the_rail_obeys_newton(track):
    # m (-omega^2) w = force from above - force from below, per mass, at every seat
    f = np.array([20.0, 150.0, 800.0])
    out = track.support_response(f, 0.3, 5)
    omega2 = (2 * np.pi * f[:, None]) ** 2
    inertia = -omega2 * track.sleeper_mass * out.displacement["sleeper"]
    np.testing.assert_allclose(
        out.force["pad"] - out.force["ballast"], inertia, rtol=1e-12, atol=1e-15
    )
    if track.three_layer:
        inertia = -omega2 * track.ballast_mass * out.displacement["ballast_mass"]
        np.testing.assert_allclose(
            out.force["ballast"] - out.force["subgrade"], inertia, rtol=1e-12, atol=1e-15
        )
    # the pad's compression is the rail minus the sleeper displacement
    np.testing.assert_allclose(
        out.compression["pad"], out.displacement["rail"] - out.displacement["sleeper"]
    )
    assert out.foundation == ("subgrade" if track.three_layer else "ballast")


@pytest.mark.parametrize("track", [THOMPSON, THREE_LAYER], ids=["two layers", "three layers"])
def test_the_supports_carry_the_load_less_the_inertia(track):
    # the rail's equilibrium, EI w'''' - m omega^2 w = delta(x - x_F) - sum F_pad,n delta(x - x_n),
    # integrated: sum F_pad = 1 + m omega^2 int w dx; each mass below adds its m omega^2 w.
    # int w dx by the trapezoid rule at 40 points a bay (error ~1e-4 of a term that is
    # itself ~1e-5 of the load at 0.5 Hz); 60 seats each side hold all but e^{-60 beta d}
    # of the load (static decay beta ~ 1.3 /m): checked to 1e-8
    f = np.array([0.5])
    omega2 = (2 * np.pi * f[0]) ** 2
    out = track.support_response(f, 0.3, 60)
    x = np.linspace(out.x[0], out.x[-1], 40 * 120 + 1)
    w = track.receptance(f, [0.3], x)[0, :, 0]
    rail = track.rail.mass_per_length * omega2 * np.sum((w[1:] + w[:-1]) / 2 * np.diff(x))
    np.testing.assert_allclose(out.force["pad"].sum(), 1.0 + rail, rtol=1e-8)
    below = track.sleeper_mass * out.displacement["sleeper"].sum()
    if track.three_layer:
        below += track.ballast_mass * out.displacement["ballast_mass"].sum()
    np.testing.assert_allclose(out.foundation_force.sum(), 1.0 + rail + omega2 * below, rtol=1e-8)
    assert abs(rail) > 1e-6  # the inertia is resolved, not below the tolerance


def test_rigid_base_supports_put_the_pad_force_on_the_ground():
    track = PeriodicTrack(UIC60, Hysteretic(3e8, 0.25), D)
    out = track.support_response([100.0], 0.0, 3)
    np.testing.assert_allclose(out.x, np.arange(-3, 4) * D)
    k = 3e8 * (1 + 0.25j)
    np.testing.assert_allclose(
        out.foundation_force, k * track.receptance([100.0], [0.0], out.x)[:, :, 0]
    )


def test_support_response_arguments_are_checked():
    with pytest.raises(CaseError, match="n_supports"):
        THOMPSON.support_response([10.0], 0.3, -1)
    with pytest.raises(CaseError, match="x_load"):
        THOMPSON.support_response([10.0], float("nan"), 2)


def test_period_is_the_sleeper_spacing_for_the_sleeper_tracks():
    assert THOMPSON.period == D
    assert PeriodicTrack(UIC60, Hysteretic(3e8, 0.25), 0.65).period == 0.65


def test_chn60_preset_is_the_table_of_its_source_per_rail_seat():
    # MPE 2017 Table 1 converted by hand: EI = 210e9 x 3.217e-5, m = 7750 x 7.745e-3,
    # kappa G A = 0.5329 x 80.8e9 x 7.745e-3, rho I = 7750 x 3.217e-5; pad 225 kN/mm,
    # ballast 20 kN/mm, half sleeper 170 kg at 0.55 m (rail_pair: both rails' seats)
    case = load_preset_case("chn60_ballasted")
    track = build_track(case.model_copy(update={"rail_model": "single_rail"}))
    assert isinstance(track, BallastedTrack)
    rail = track.rail
    np.testing.assert_allclose(
        [rail.bending_stiffness, rail.mass_per_length, rail.shear_stiffness, rail.rotary_inertia],
        [6.7557e6, 60.02375, 3.334867e8, 0.2493175],
        rtol=1e-6,  # the preset writes kappa G A to 7 digits
    )
    assert (track.sleeper_spacing, track.sleeper_mass) == (0.55, 170.0)
    k = track.layer_stiffness([100.0])
    np.testing.assert_allclose(k["pad"], 2.25e8 * (1 + 0.25j))
    np.testing.assert_allclose(k["ballast"], 2e7 * (1 + 1j))
    both = build_track(case)
    assert both.sleeper_mass == 340.0  # rail_pair
