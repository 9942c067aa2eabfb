"""The ballasted track's wave solution against the finite track with explicit sleeper DOFs.

The finite model (:class:`railvib.validation.FiniteTrack`) assembles each sleeper (and,
for three layers, each ballast mass) as its own DOF between the pad and ballast springs;
it never forms the condensed support ``K_eff`` the wave solver uses.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.case import build_system, case_from_dict
from railvib.pads import Hysteretic, SpringDamper
from railvib.track import BallastedTrack, Rail
from railvib.validation import FiniteCoupledSystem
from railvib.validation.finite_track import FiniteTrack

RAIL = Rail(6.42e6, 60.0, 0.02)  # UIC60 with a small rail loss, so waves die out in the model
PAD, BALLAST = Hysteretic(3e8, 0.25), Hysteretic(5e7, 1.0)
LAYERS = {
    "double": {},
    "three": {"subgrade": SpringDamper(1e8, 1e5), "ballast_mass": 300.0},
}
X = [0.0, 0.3]  # above a sleeper and at mid-span


def _pair(layers, margin, elements, absorber_spans):
    wave = BallastedTrack(RAIL, PAD, 0.6, sleeper_mass=162.0, ballast=BALLAST, **layers)
    finite = FiniteTrack.around(
        X,
        RAIL,
        PAD,
        0.6,
        margin_spans=margin,
        elements_per_span=elements,
        absorber_spans=absorber_spans,
        absorber_damping=2e5,
        ballast=BALLAST,
        sleeper_mass=162.0,
        **layers,
    )
    return wave, finite


@pytest.mark.parametrize("layers", LAYERS.values(), ids=LAYERS)
def test_low_frequency_receptances_match_the_explicit_sleeper_model(layers):
    # below 500 Hz the Hermite elements (16 per bay) are within 1e-8 of the exact beam and
    # the track's waves decay over a few bays (heavily damped ballast): 1e-6
    wave, finite = _pair(layers, margin=40, elements=16, absorber_spans=10)
    f = np.geomspace(1.0, 500.0, 6)
    a, b = wave.receptance(f, X, X), finite.receptance(f, X, X)
    err = np.abs(a - b) / np.abs(b)
    assert err.max() < 1e-6, err.max()


@pytest.mark.slow
@pytest.mark.parametrize("layers", LAYERS.values(), ids=LAYERS)
def test_receptances_match_the_explicit_sleeper_model_to_2_khz(layers):
    # 1e-6 over 1 Hz - 2 kHz needs the finite model at 64 Hermite elements per bay: its
    # error falls as h^4 (measured 5e-5 at 16, 3e-6 at 32 near the 1.4 kHz pinned-pinned
    # frequency) and 200 bays of margin with 100 of graded absorbers (rail loss 0.02 lets
    # the waves above the pad resonance travel far); the measured maximum is 1.5e-7
    wave, finite = _pair(layers, margin=200, elements=64, absorber_spans=100)
    f = np.geomspace(1.0, 2000.0, 16)
    a, b = wave.receptance(f, X, X), finite.receptance(f, X, X)
    err = np.abs(a - b) / np.abs(b)
    assert err.max() < 1e-6, err.max()


def _coupled_psd_error(f, margin, elements):
    """Largest pointwise relative difference of the coupled PSDs (|FRF|^2), preset case."""
    system = build_system(case_from_dict({"preset": "thompson_ballasted"}))
    finite = FiniteCoupledSystem.from_system(
        system,
        margin_spans=margin,
        elements_per_span=elements,
        absorber_spans=margin // 2,
        absorber_damping=2e5,
    ).frf(f)
    wave = system.frf(f)
    errors = []
    for name in ("vehicle", "rail", "contact_force"):
        a, b = np.abs(getattr(wave, name)) ** 2, np.abs(getattr(finite, name)) ** 2
        errors.append(float((np.abs(a - b) / b).max()))
    return max(errors)


def test_coupled_psds_match_the_explicit_sleeper_model_below_500_hz():
    # the coupled vehicle on thompson_ballasted (undamped rail): 16 elements per bay and 40
    # bays of margin resolve 500 Hz; measured 9.3e-6 pointwise on every response
    assert _coupled_psd_error(np.geomspace(1.0, 500.0, 8), margin=40, elements=16) < 1e-4


@pytest.mark.slow  # 400 bays x 64 elements: ~1 s
def test_coupled_psds_match_the_explicit_sleeper_model_to_2_khz():
    # the undamped rail carries waves far above the pad resonance: 400 bays of margin with
    # 200 of graded absorbers (200 bays left 4.8e-4 on the car body); measured 3.6e-7
    assert _coupled_psd_error(np.geomspace(1.0, 2000.0, 8), margin=400, elements=64) < 1e-4
