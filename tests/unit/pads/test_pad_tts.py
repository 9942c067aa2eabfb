"""WLF, re-referencing (seed Eqs. 22-25) and the vertical factor (Eq. 26) against hand values.

Expected numbers come from docs/reference-values.md section 4 (the worked example,
computed independently) and from the formulas evaluated by hand below.
"""

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.pads import (
    WLF,
    FractionalZener,
    SpringDamper,
    TemperatureShifted,
    vertical_shift_factor,
)


def test_rereferencing_from_tg_matches_worked_example():
    # docs/reference-values.md §4: Tg = -40, reference 20 degC -> Delta = 60 K,
    # C1' = 8.064, C2' = 111.6 K
    w = WLF.universal(-40.0).rereferenced(20.0)
    assert w.c1 == pytest.approx(17.44 * 51.6 / (51.6 + 60.0))  # Eq. 23 (corrected), by hand
    assert w.c1 == pytest.approx(8.064, abs=5e-4)  # the note rounds to 3 decimals
    assert w.c2_k == pytest.approx(111.6)  # Eq. 24
    assert w.reference_temperature_c == 20.0


# docs/reference-values.md §4 table: a 0.3 Hz test at T maps to these 20 degC frequencies
# (3 significant digits)
REDUCED_TG40 = [
    (17.5, 0.46),
    (10.0, 1.87),
    (0.0, 17.3),
    (-5.0, 63.8),
    (-10.0, 277.0),
    (-12.5, 617.0),
    (-15.0, 1450.0),
    (-20.0, 9600.0),
]


@pytest.mark.parametrize(("t", "expected"), REDUCED_TG40)
def test_reduced_frequency_table(t, expected):
    w = WLF.universal(-40.0).rereferenced(20.0)
    # tolerance: the table is rounded to 3 significant digits (0.46 to 2), so 1.2 %
    assert w.reduced_frequency(0.3, t) == pytest.approx(expected, rel=0.012)


@pytest.mark.parametrize(("t", "expected"), [(0.0, 11.9), (-10.0, 141.0)])
def test_reduced_frequency_tg45(t, expected):
    w = WLF.universal(-45.0).rereferenced(20.0)
    assert w.reduced_frequency(0.3, t) == pytest.approx(expected, rel=0.005)  # 3 digits


def test_wlf_formula_by_hand():
    w = WLF(8.0, 100.0, 20.0)
    # log10 a_T = -8 * (-30) / (100 - 30) = 240 / 70
    assert w.log_shift(-10.0) == pytest.approx(240.0 / 70.0)
    assert w.log_shift(20.0) == 0.0
    assert w.shift_factor(-10.0) > 1  # cold behaves like high frequency


def test_rereferencing_preserves_the_shift_law():
    w = WLF.universal(-40.0)
    w2 = w.rereferenced(20.0)
    t = np.array([-30.0, -10.0, 0.0, 35.0])
    # log a_T about the new reference = old log a_T(T) - old log a_T(T0'), exactly (WLF is a group)
    assert np.allclose(w2.log_shift(t), w.log_shift(t) - w.log_shift(20.0), rtol=1e-12)
    back = w2.rereferenced(-40.0)
    assert back.c1 == pytest.approx(17.44)
    assert back.c2_k == pytest.approx(51.6)


@pytest.mark.parametrize(("t", "expected"), [(-10.0, 0.911), (-30.0, 0.850)])
def test_vertical_factor(t, expected):
    # docs/reference-values.md §4, with the paper's a_f = 4.8e-4 /K and reference 20 degC; 3 digits
    assert vertical_shift_factor(t, 20.0) == pytest.approx(expected, abs=6e-4)
    t_k, t0_k = t + 273.15, 293.15
    assert vertical_shift_factor(t, 20.0) == pytest.approx(
        (t_k / t0_k) / (1 + 4.8e-4 * (t_k - t0_k)), rel=1e-12
    )


def test_singular_temperature_rejected_with_message():
    w = WLF.universal(-40.0)  # singular at -40 - 51.6 = -91.6 degC
    with pytest.raises(CaseError, match=r"temperature = -95.0: must be above T0 - C2 = -91.6 degC"):
        w.log_shift([-20.0, -95.0])
    with pytest.raises(CaseError, match="singular"):
        w.log_shift(-91.6)
    with pytest.raises(CaseError, match="reference_temperature_c"):
        w.rereferenced(-100.0)
    pad = TemperatureShifted(SpringDamper(5e7, 5e4), w, 20.0)
    with pytest.raises(CaseError, match="singular"):
        pad.stiffness([10.0], -92.0)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"c1": -1.0}, "wlf.c1"),
        ({"c2_k": 0.0}, "wlf.c2_k"),
        ({"reference_temperature_c": -300.0}, "wlf.reference_temperature_c"),
    ],
)
def test_wlf_parameters_validated(kwargs, field):
    args = {"c1": 8.0, "c2_k": 100.0, "reference_temperature_c": 20.0} | kwargs
    with pytest.raises(CaseError) as err:
        WLF(**args)
    assert err.value.field == field


def test_temperature_shifted_applies_eq_20_21():
    base = FractionalZener(3e7, 3e8, 1e-6, 0.4)
    w = WLF.universal(-40.0)
    pad = TemperatureShifted(base, w, 20.0, vertical_shift=True)
    f = np.array([1.0, 10.0, 100.0])
    t = -10.0
    # by hand: a_T about 20 degC from C1' = 8.0637, C2' = 111.6 K; v from Eq. 26
    c1, c2 = 17.44 * 51.6 / 111.6, 111.6
    a_t = 10 ** (-c1 * (t - 20) / (c2 + t - 20))
    v = (263.15 / 293.15) / (1 + 4.8e-4 * (263.15 - 293.15))
    assert np.allclose(pad.stiffness(f, t), v * base.stiffness(f * a_t), rtol=1e-12)
    # without the vertical factor the loss factor is a pure horizontal shift
    flat = TemperatureShifted(base, w, 20.0, vertical_shift=False)
    assert np.allclose(flat.loss_factor(f, t), base.loss_factor(f * a_t), rtol=1e-12)
    # no temperature, or the reference temperature: the master curve itself
    assert np.allclose(pad.stiffness(f), base.stiffness(f))
    assert np.allclose(pad.stiffness(f, 20.0), base.stiffness(f), rtol=1e-12)
    # colder is stiffer
    assert np.all(pad.storage(f, -30.0) > pad.storage(f, 20.0))
