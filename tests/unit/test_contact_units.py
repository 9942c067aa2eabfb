"""Hertz contact and unit conversions against docs/reference-values.md §1."""

import numpy as np
import pytest

from railvib.contact import hertz_constant_conical, hertz_stiffness
from railvib.errors import CaseError
from railvib.units import celsius_to_kelvin, kelvin_to_celsius, kmh_to_ms


def test_hertz_numbers_of_the_reference_values():
    # conical tread, R = 0.42 m: G = 5.201e-8 m/N^(2/3) (4 digits given)
    assert hertz_constant_conical(0.42) == pytest.approx(5.201e-8, rel=2e-4)
    # k_H at 40.10 kN = 9.873e8 N/m, at 80.20 kN = 1.244e9 N/m
    assert hertz_stiffness(5.2e-8, 40.10e3) == pytest.approx(9.873e8, rel=1e-3)
    assert hertz_stiffness(5.2e-8, 80.20e3) == pytest.approx(1.244e9, rel=1e-3)


def test_linearised_stiffness_is_the_slope_of_the_hertz_law():
    g, p0 = 5.2e-8, 40.1e3

    def load(delta):
        return (delta / g) ** 1.5

    d0 = g * p0 ** (2 / 3)
    h = 1e-4 * d0
    slope = (load(d0 + h) - load(d0 - h)) / (2 * h)
    assert hertz_stiffness(g, p0) == pytest.approx(slope, rel=1e-7)


def test_contact_rejections():
    with pytest.raises(CaseError, match=r"contact\.static_load = -1\.0: must be > 0 \(N\)"):
        hertz_stiffness(5.2e-8, -1.0)
    with pytest.raises(CaseError, match=r"contact\.wheel_radius = 0\.0"):
        hertz_constant_conical(0.0)


def test_unit_conversions():
    assert kmh_to_ms(80.0) == pytest.approx(22.2222222)
    t = np.array([-40.0, 0.0, 20.0])
    np.testing.assert_allclose(celsius_to_kelvin(t), [233.15, 273.15, 293.15])
    np.testing.assert_allclose(kelvin_to_celsius(celsius_to_kelvin(t)), t)
