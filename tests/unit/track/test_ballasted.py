"""The ballasted track: its condensed support, its rigid-base limit, its checks and preset."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from numpy.typing import ArrayLike, NDArray

from railvib.case import load_preset_case
from railvib.case.build import build_track
from railvib.errors import CaseError
from railvib.pads import Hysteretic, SpringDamper
from railvib.pads.base import PadModel
from railvib.track import BallastedTrack, PeriodicTrack, Rail

#: Thompson (2009) ch. 3, one rail: UIC60, pad, half-sleeper, ballast, spacing
UIC60 = Rail(6.42e6, 60.0)
PAD = Hysteretic(3e8, 0.25)
BALLAST = Hysteretic(5e7, 1.0)
M_S = 162.0
D = 0.6


@dataclass(frozen=True)
class _Constant(PadModel):
    """A test-only support of any constant complex stiffness (beyond the pad family's bounds)."""

    k: complex = 0j

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        return np.full(np.shape(f), self.k, dtype=np.complex128)


def _track(**kw):
    args = {"sleeper_mass": M_S, "ballast": BALLAST, **kw}
    return BallastedTrack(UIC60, PAD, D, **args)


def _condensed_by_solve(f, layers, masses):
    """Support seen by the rail from the explicit chain rail-K1-m1-K2-m2-...-ground.

    Solves the chain's equations of motion (independent of the closed form): the rail
    node driven by a unit force, the support stiffness is 1 / w_rail.
    """
    out = np.empty(f.size, dtype=complex)
    for i, fi in enumerate(f):
        w2 = (2 * np.pi * fi) ** 2
        n = len(masses) + 1
        a = np.zeros((n, n), dtype=complex)
        for j, k in enumerate(layers):  # spring j between node j and node j+1 (or ground)
            a[j, j] += k[i]
            if j + 1 < n:
                a[j + 1, j + 1] += k[i]
                a[j, j + 1] -= k[i]
                a[j + 1, j] -= k[i]
        for j, m in enumerate(masses):
            a[j + 1, j + 1] -= m * w2
        rhs = np.zeros(n, dtype=complex)
        rhs[0] = 1.0
        out[i] = 1.0 / np.linalg.solve(a, rhs)[0]
    return out


F = np.geomspace(0.1, 5000.0, 200)


def test_support_is_the_explicit_sleeper_chain_condensed():
    track = _track(ballast=SpringDamper(5e7, 4e4))
    kp, kb = PAD.stiffness(F), SpringDamper(5e7, 4e4).stiffness(F)
    expected = _condensed_by_solve(F, [kp, kb], [M_S])
    # both are the same rational function evaluated in floating point: a few ulp times the
    # condition of the 2x2 solve (<= 1e3 near the sleeper resonance)
    np.testing.assert_allclose(track.support_stiffness(F), expected, rtol=1e-11)


def test_three_layer_support_is_the_explicit_chain_condensed():
    subgrade = SpringDamper(1e8, 1e5)
    track = _track(ballast_mass=300.0, subgrade=subgrade)
    layers = [PAD.stiffness(F), BALLAST.stiffness(F), subgrade.stiffness(F)]
    expected = _condensed_by_solve(F, layers, [M_S, 300.0])
    np.testing.assert_allclose(track.support_stiffness(F), expected, rtol=1e-11)


def test_a_vanishing_sleeper_mass_is_pad_and_ballast_in_series():
    # 1e-15 kg (zero is refused: issue 14's bad input): omega^2 m_s <= 1e-6 N/m at 5 kHz
    # against K_b = 5e7 N/m changes the series stiffness by 2e-14, below the rounding
    track = _track(sleeper_mass=1e-15)
    kp, kb = PAD.stiffness(F), BALLAST.stiffness(F)
    series = 1.0 / (1.0 / kp + 1.0 / kb)
    np.testing.assert_allclose(track.support_stiffness(F), series, rtol=1e-13)  # rounding


@pytest.mark.parametrize(
    "kw",
    [
        {},
        {"sleeper_mass": 1e-15},
        {"sleeper_mass": 1e4, "ballast": SpringDamper(1e7, 0.0)},  # undamped ballast
        {"ballast_mass": 500.0, "subgrade": Hysteretic(2e8, 0.1)},
        {"ballast": SpringDamper(1e9, 1e3), "ballast_mass": 1.0, "subgrade": SpringDamper(1e6)},
    ],
)
def test_support_is_passive_at_every_frequency(kw):
    # Im K_eff >= 0 is exact for passive layers (module docstring); rounding can only
    # leave -1e-15 |K| where Im K_eff is 0 in exact arithmetic
    k = _track(**kw).support_stiffness(F)
    assert np.all(k.imag >= -1e-15 * np.abs(k))
    assert np.any(k.imag > 0)


@pytest.mark.parametrize("rail", [UIC60, Rail(6.42e6, 60.0, 0.01, 2.45e8, 0.25)])
def test_massless_sleeper_on_rigid_ballast_is_the_rigid_base_track(rail):
    # K_eff = K_p K_b / (K_p + K_b) = K_p (1 - K_p / K_b + ...): with K_b = 1e13 |K_p| the
    # relative change of the support is 1e-13, and the receptance's is at most that times
    # its (order-1) sensitivity to the support, below the 1e-10 asked for
    rigid = _Constant(3e8 * 1e13 + 0j)
    f = np.geomspace(1.0, 2000.0, 150)
    x = [0.0, 0.3, 0.45]
    base = PeriodicTrack(rail, PAD, D).receptance(f, x, x)
    # a vanishing sleeper (1e-15 kg: omega^2 m_s = 1.6e-7 N/m at 2 kHz, 5e-16 of K_p)
    limit = BallastedTrack(rail, PAD, D, sleeper_mass=1e-15, ballast=rigid).receptance(f, x, x)
    err = np.abs(limit - base) / np.abs(base).max(axis=(1, 2), keepdims=True)
    assert err.max() < 1e-10, err.max()


@pytest.mark.parametrize(
    ("kw", "field"),
    [
        ({"sleeper_mass": -1.0}, "track.sleeper_mass_kg"),
        ({"sleeper_mass": 0.0}, "track.sleeper_mass_kg"),
        ({"sleeper_mass": float("nan")}, "track.sleeper_mass_kg"),
        ({"subgrade": Hysteretic(1e8, 0.1)}, "track.ballast_mass_kg"),
        ({"ballast_mass": 300.0}, "track.subgrade"),
        ({"ballast_mass": 0.0, "subgrade": Hysteretic(1e8, 0.1)}, "track.ballast_mass_kg"),
        ({"ballast": None}, "track.ballast"),
    ],
)
def test_inconsistent_layers_are_refused_naming_the_field(kw, field):
    with pytest.raises(CaseError) as err:
        _track(**kw)
    assert err.value.field == field


@pytest.mark.parametrize("layer", ["ballast", "subgrade"])
def test_non_passive_layer_is_refused_on_the_grid(layer):
    active = _Constant(5e7 - 1e6j)  # Im K < 0: it would feed power into the track
    kw = {"ballast": active} if layer == "ballast" else {"ballast_mass": 300.0, "subgrade": active}
    track = _track(**kw)
    with pytest.raises(CaseError) as err:
        track.receptance([10.0], [0.0], [0.0])
    assert err.value.field == f"track.{layer}"


def test_thompson_preset_builds_the_ballasted_track_for_both_rails():
    case = load_preset_case("thompson_ballasted")
    track = build_track(case)
    assert isinstance(track, BallastedTrack)
    # rail_pair: the beam stands for both rails, so every per-seat quantity doubles
    assert track.sleeper_mass == 2 * M_S
    assert track.rail.bending_stiffness == 2 * 6.42e6
    f = np.array([100.0])
    np.testing.assert_allclose(track.support_stiffness(f), 2 * _track().support_stiffness(f))


def test_thompson_track_resonances_are_those_of_rail_bay_and_sleeper():
    """The two peaks of the point receptance over a sleeper, from a two-mass closed form.

    Thompson (2009, ch. 3) reads the ballasted track's two resonances from a rail mass
    ``m d`` (one bay) on the pad over the sleeper ``m_s`` on the ballast: the in-phase
    mode (the whole track bouncing on the ballast, near ``sqrt(K_b / (m_s + m d))``) and
    the anti-phase mode (rail against sleeper on the pad, near
    ``sqrt(K_p (1 / (m d) + 1 / m_s))``). Undamped storage stiffnesses: 79.8 Hz and
    509 Hz. The rail is a beam, not one bay's lumped mass, and the ballast's loss factor
    of 1 broadens and shifts its peak, so only the peaks' places are compared: within
    10 % (ballast, heavily damped) and 5 % (pad, eta = 0.25).
    """
    m, k = np.diag([60.0 * D, M_S]), np.array([[3e8, -3e8], [-3e8, 3e8 + 5e7]])
    f_low, f_high = np.sqrt(np.linalg.eigvals(np.linalg.solve(m, k)).real) / (2 * np.pi)
    f_low, f_high = sorted((f_low, f_high))
    assert abs(f_low - np.sqrt(5e7 / (M_S + 60.0 * D)) / (2 * np.pi)) < 2.0  # the estimate
    f = np.linspace(20.0, 1000.0, 981)
    alpha = np.abs(_track().receptance(f, [0.0], [0.0])[:, 0, 0])
    peaks = f[1:-1][(alpha[1:-1] > alpha[:-2]) & (alpha[1:-1] > alpha[2:])]
    assert peaks.size == 2, peaks
    assert abs(peaks[0] / f_low - 1) < 0.10, (peaks, f_low)
    assert abs(peaks[1] / f_high - 1) < 0.05, (peaks, f_high)
