"""A case run with a temperature-dependent pad model equals one with its tabulated stiffness."""

import numpy as np
import pytest

import railvib
from railvib.case import build_grid
from railvib.errors import CaseError
from railvib.pads import TabulatedPad, pad_from_dict, pad_to_dict

ZENER_TTS = {
    "model": "fractional_zener",
    "k0_n_per_m": 3.0e7,
    "k_inf_n_per_m": 6.0e8,
    "tau_s": 1.0e-7,
    "alpha": 0.35,
    "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -40.0},
}
GRID = {"f_min": 1.0, "f_max": 300.0, "spacing": "linear", "step": 1.0}


@pytest.mark.parametrize("temperature_c", [-30.0, -10.0, 20.0])
def test_case_with_pad_model_at_t_equals_tabulated_run(temperature_c):
    case = railvib.case_from_dict(
        {
            "preset": "wang2017_metro",
            "frequency": GRID,
            "track": {"pad": ZENER_TTS, "pad_temperature_c": temperature_c},
        }
    )
    f = build_grid(case).f
    k = pad_from_dict(ZENER_TTS).stiffness(f, temperature_c)
    table = {
        "model": "tabulated",
        "frequency_hz": f.tolist(),
        "storage_n_per_m": k.real.tolist(),
        "loss_n_per_m": k.imag.tolist(),
    }
    tabulated = railvib.case_from_dict(
        {"preset": "wang2017_metro", "frequency": GRID, "track": {"pad": table}}
    )
    a = railvib.run(case)
    b = railvib.run(tabulated)
    np.testing.assert_allclose(a.psd_acceleration, b.psd_acceleration, rtol=1e-12)
    np.testing.assert_allclose(a.pad_stiffness, k, rtol=1e-15)
    # the temperature really matters: colder is stiffer
    if temperature_c < 20.0:
        warm = pad_from_dict(ZENER_TTS).stiffness(f, 20.0)
        assert np.all(k.real > warm.real)


def test_tabulated_pad_interpolates_in_log_frequency_and_holds_ends():
    pad = TabulatedPad((1.0, 100.0), (1e7, 3e7), (1e6, 1e6))
    # halfway in log10 f between 1 and 100 Hz is 10 Hz
    assert pad.stiffness([10.0])[0] == pytest.approx(2e7 + 1e6j)
    assert pad.stiffness([0.1, 1e4]).tolist() == [1e7 + 1e6j, 3e7 + 1e6j]
    assert pad_from_dict(pad_to_dict(pad)) == pad


@pytest.mark.parametrize(
    ("table", "message"),
    [
        (
            {"frequency_hz": [10.0, 1.0], "storage_n_per_m": [1, 2], "loss_n_per_m": [0, 0]},
            "track.pad.frequency_hz",
        ),
        (
            {"frequency_hz": [1.0, 10.0], "storage_n_per_m": [1, -2], "loss_n_per_m": [0, 0]},
            "track.pad.storage_n_per_m",
        ),
        (
            {"frequency_hz": [1.0, 10.0], "storage_n_per_m": [1, 2], "loss_n_per_m": [0, -1]},
            "track.pad.loss_n_per_m",
        ),
        ({"frequency_hz": [1.0], "storage_n_per_m": [1], "loss_n_per_m": [0]}, "at least 2 rows"),
    ],
)
def test_tabulated_pad_rejections(table, message):
    with pytest.raises(CaseError, match=message):
        pad_from_dict({"model": "tabulated", **table})


def test_case_temperature_outside_the_wlf_range_is_a_case_error():
    # T0 - C2 = 20 - 111.6 = -91.6 degC for Tg = -40 degC re-referenced to 20 degC
    with pytest.raises(CaseError, match=r"track\.pad_temperature_c = -100\.0: must be above"):
        railvib.case_from_dict(
            {
                "preset": "wang2017_metro",
                "track": {"pad": ZENER_TTS, "pad_temperature_c": -100.0},
            }
        )
