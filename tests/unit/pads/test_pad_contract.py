"""One contract for every pad model: finite, passive, shape-preserving, dict round trip."""

import numpy as np
import pytest

from railvib.pads import (
    WLF,
    ConstantPhase,
    FractionalZener,
    GeneralizedMaxwell,
    Hysteretic,
    LogLinear,
    SpringDamper,
    TemperatureShifted,
    pad_from_dict,
    pad_to_dict,
)

F = np.geomspace(1e-3, 1e6, 181)  # the band the issue names

MODELS = {
    "spring_damper": SpringDamper(5e7, 5e4),
    "hysteretic": Hysteretic(6.5e7, 0.25),
    "log_linear": LogLinear(3.1e7, 5.0, 0.07, 5e4),
    "constant_phase": ConstantPhase(3.1e7, 5.0, 0.07),
    "fractional_zener": FractionalZener(3e7, 6e8, 1e-7, 0.35),
    "zener_alpha1": FractionalZener(3e7, 6e8, 1e-3, 1.0),
    "generalized_maxwell": GeneralizedMaxwell(3e7, (1e7, 5e7, 2e8), (1e-1, 1e-3, 1e-6)),
    "tts_zener": TemperatureShifted(
        FractionalZener(3e7, 6e8, 1e-7, 0.35), WLF.universal(-40), 20.0
    ),
    "tts_prony_given_c": TemperatureShifted(
        GeneralizedMaxwell(3e7, (1e7, 5e7), (1e-2, 1e-5)), WLF(8.0, 110.0, 20.0), 10.0, False
    ),
}
TEMPERATURES = [None, -40.0, -10.0, 20.0, 45.0]


@pytest.fixture(params=list(MODELS), ids=list(MODELS))
def model(request):
    return MODELS[request.param]


@pytest.mark.parametrize("temperature", TEMPERATURES)
def test_finite_and_passive(model, temperature):
    k = model.stiffness(F, temperature)
    assert k.dtype == np.complex128
    assert np.all(np.isfinite(k))
    assert np.all(k.real > 0)
    assert np.all(model.loss_factor(F, temperature) >= 0)
    model.check_passive(F, temperature)  # the base-class check agrees


def test_shape_preserving(model):
    assert model.stiffness(5.0).shape == ()
    assert model.stiffness(F[:12].reshape(3, 4), 0.0).shape == (3, 4)
    assert model.stiffness(np.array([])).shape == (0,)


def test_dict_round_trip(model):
    d = pad_to_dict(model)
    again = pad_from_dict(d)
    assert type(again) is type(model)
    assert np.allclose(again.stiffness(F, -10.0), model.stiffness(F, -10.0), rtol=1e-14)
    assert pad_to_dict(again) == d


def test_fractional_zener_with_alpha_one_is_standard_zener():
    k0, kinf, tau = 3e7, 6e8, 2e-3
    w = 2 * np.pi * F
    # standard linear solid, closed form: K0 + (Kinf - K0) i w tau / (1 + i w tau)
    # real part K0 + dK (w tau)^2 / (1 + (w tau)^2), imaginary dK w tau / (1 + (w tau)^2)
    dk, wt = kinf - k0, w * tau
    expected = k0 + dk * wt**2 / (1 + wt**2) + 1j * dk * wt / (1 + wt**2)
    got = FractionalZener(k0, kinf, tau, 1.0).stiffness(F)
    assert np.allclose(got, expected, rtol=1e-12)  # same closed form; rounding only


def test_prony_single_branch_is_standard_zener():
    k0, k1, tau = 3e7, 2e8, 1e-4
    a = GeneralizedMaxwell(k0, (k1,), (tau,)).stiffness(F)
    b = FractionalZener(k0, k0 + k1, tau, 1.0).stiffness(F)
    assert np.allclose(a, b, rtol=1e-12)


def test_fractional_zener_limits():
    z = FractionalZener(3e7, 6e8, 1e-4, 0.5)
    assert z.storage(1e-9) == pytest.approx(3e7, rel=1e-3)
    assert z.storage(1e12) == pytest.approx(6e8, rel=1e-3)
