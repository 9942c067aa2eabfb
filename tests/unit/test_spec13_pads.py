"""Issue 13: pads of a sweep's chunk evaluated together (`pad_stiffnesses`).

Each row must be what the pad's own ``stiffness(f, T)`` gives, bit for bit: the
vectorised path does the same floating-point operations in the same order.
"""

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.pads import PADS, FractionalZener, Hysteretic, SpringDamper
from railvib.pads.scaled import ScaledPad
from railvib.pads.stack import pad_stiffnesses

F = np.geomspace(0.5, 1000.0, 257)

TTS = {"reference_temperature_c": 20.0, "glass_transition_c": -50.0}


def _zener(k0, alpha=0.4, tts=None):
    table = {
        "model": "fractional_zener",
        "k0_n_per_m": k0,
        "k_inf_n_per_m": 2.0e8,
        "tau_s": 1.0e-3,
        "alpha": alpha,
    }
    if tts is not None:
        table["tts"] = tts
    return PADS.from_dict(table, "track.pad")


def _one_by_one(pads, temperatures):
    return np.stack([p.stiffness(F, t) for p, t in zip(pads, temperatures, strict=True)])


def test_shifted_zener_pads_over_temperatures_equal_each_pad():
    pads = [_zener(k0, tts=TTS) for k0 in np.geomspace(2e7, 8e7, 7)] * 3
    temperatures = list(np.repeat([-40.0, 0.0, 40.0], 7))
    np.testing.assert_array_equal(
        pad_stiffnesses(pads, temperatures, F), _one_by_one(pads, temperatures)
    )


def test_mixed_models_and_shifts_equal_each_pad():
    other_tts = {"reference_temperature_c": 10.0, "c1": 9.0, "c2_k": 120.0, "vertical_shift": False}
    pads = [
        _zener(3e7, alpha=1.0),
        _zener(3e7, alpha=0.5, tts=TTS),
        _zener(5e7, alpha=0.5, tts=other_tts),
        _zener(6e7, alpha=0.7, tts=other_tts),
        _zener(4e7, tts=TTS),  # shifted pad at its reference (no temperature)
        SpringDamper(1.2e8, 5.0e4),
        SpringDamper(9.0e7, 0.0),
        Hysteretic(1.0e8, 0.25),
        Hysteretic(3.0e8, 0.0),
        ScaledPad(_zener(4e7, tts=TTS), 2.0),
        ScaledPad(Hysteretic(1.0e8, 0.3), 2.0),
        PADS.from_dict(
            {
                "model": "generalized_maxwell",
                "k_inf_n_per_m": 1e8,
                "k_n_per_m": [5e7, 2e7],
                "tau_s": [1e-4, 1e-2],
            },
            "track.pad",
        ),  # fmt: skip
    ]
    temperatures = [5.0, -20.0, 30.0, 0.0, None, 10.0, None, 0.0, 50.0, -10.0, 20.0, 0.0]
    np.testing.assert_array_equal(
        pad_stiffnesses(pads, temperatures, F), _one_by_one(pads, temperatures)
    )


@pytest.mark.parametrize("model", [FractionalZener, SpringDamper, Hysteretic])
def test_each_model_s_rows_equal_its_stiffness(model):
    pads = {
        FractionalZener: [FractionalZener(2e7, 3e8, 1e-4, a) for a in (0.1, 0.5, 0.93, 1.0)],
        SpringDamper: [SpringDamper(k, c) for k, c in ((1e7, 0.0), (3e8, 1e5), (5e7, 7.3e3))],
        Hysteretic: [Hysteretic(k, e) for k, e in ((1e7, 0.0), (3e8, 1.7), (5e7, 0.31))],
    }[model]
    f = np.stack([F * (1.0 + 0.1 * i) for i in range(len(pads))])
    rows = model.stiffness_rows(pads, f)
    np.testing.assert_array_equal(
        rows, np.stack([p.stiffness(r) for p, r in zip(pads, f, strict=True)])
    )


def test_a_temperature_the_shift_cannot_take_is_refused_as_by_the_pad():
    pad = _zener(4e7, tts=TTS)
    with pytest.raises(CaseError) as one:
        pad.stiffness(F, -130.0)  # below T0 - C2 of WLF about Tg = -50 degC
    with pytest.raises(CaseError) as stacked:
        pad_stiffnesses([pad, pad], [0.0, -130.0], F)
    assert (stacked.value.field, stacked.value.value, stacked.value.allowed) == (
        one.value.field,
        one.value.value,
        one.value.allowed,
    )


def test_no_pads_is_an_empty_stack():
    assert pad_stiffnesses([], [], F).shape == (0, F.size)
