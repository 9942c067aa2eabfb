"""FrequencyGrid: construction, immutability and field-named rejections.

Expected values are hand-derived: grids built from binary-exact numbers (0.5, 0.25 ...)
must come out exactly; decimal steps (0.1) differ from k/10 only by rounding.
"""

import dataclasses
import math

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.grid import FrequencyGrid

EPS = np.finfo(float).eps


# --------------------------------------------------------------------------- linear


def test_linear_binary_exact_grid_endpoints_step_and_count():
    g = FrequencyGrid.linear(0.5, 100.0, step=0.5)
    # 0.5 + 0.5 k is exact in binary for every k here: exact comparison is meaningful
    np.testing.assert_array_equal(g.f, 0.5 * np.arange(1, 201))
    assert len(g) == 200
    assert g.f[0] == 0.5
    assert g.f[-1] == 100.0
    assert np.all(np.diff(g.f) == 0.5)
    assert g.f.dtype == np.float64


@pytest.mark.parametrize(
    ("f_min", "f_max", "step", "n"),
    [
        (1.0, 50.0, 1.0, 50),  # lands: 1, 2, ..., 50
        (1.0, 50.5, 1.0, 50),  # f_max half a step past the last point
        (1.0, 50.999, 1.0, 50),  # f_max just short of the next point
        (2.0, 3.0, 0.25, 5),  # 2, 2.25, 2.5, 2.75, 3
        (2.0, 3.2, 0.25, 5),  # 3.25 would exceed f_max
        (1.0, 2.0, 1.0, 2),  # the smallest grid that spans a band
    ],
)
def test_linear_count_and_last_point_when_f_max_is_off_step(f_min, f_max, step, n):
    g = FrequencyGrid.linear(f_min, f_max, step)
    assert len(g) == n
    assert g.f[0] == f_min
    # all values here are binary exact, so the last point is f_min + (n-1) step exactly
    assert g.f[-1] == f_min + (n - 1) * step
    assert g.f[-1] <= f_max < g.f[-1] + step
    assert np.all(np.diff(g.f) == step)


def test_linear_decimal_step_matches_k_over_10_to_rounding():
    g = FrequencyGrid.linear(0.1, 0.7, 0.1)
    assert len(g) == 7  # 0.1 ... 0.7 inclusive: the last point lands despite 0.1 not binary
    # f_min + step*k rounds twice (product, then sum), each <= 0.5 ulp: 4 eps is ample
    np.testing.assert_allclose(g.f, np.arange(1, 8) / 10.0, rtol=4 * EPS, atol=0)
    # differences of neighbours carry those roundings relative to 0.7, not to 0.1: 1e-14
    np.testing.assert_allclose(np.diff(g.f), 0.1, rtol=1e-14, atol=0)


# --------------------------------------------------------------------- logarithmic


@pytest.mark.parametrize(
    ("f_min", "f_max", "n"), [(0.3, 70.0, 17), (1e-3, 1e4, 1001), (2.0, 8.0, 2)]
)
def test_logarithmic_endpoints_exact_and_ratio_constant(f_min, f_max, n):
    g = FrequencyGrid.logarithmic(f_min, f_max, n)
    assert len(g) == n
    assert g.f[0] == f_min  # the endpoints are the requested numbers, not 10**log10(x)
    assert g.f[-1] == f_max
    q = (f_max / f_min) ** (1.0 / (n - 1))
    # each point is 10**(rounded exponent): relative error ~ ln(10)*|log10 f|*eps per
    # point (|log10 f| <= 4 here -> ~2e-15); a ratio of two points doubles it: 1e-14
    np.testing.assert_allclose(g.f[1:] / g.f[:-1], q, rtol=1e-14, atol=0)


def test_logarithmic_decades_hit_powers_of_ten():
    g = FrequencyGrid.logarithmic(1.0, 1000.0, 4)
    # 10**k from a rounded exponent: a few ulp (same reason as above), 1e-15 relative
    np.testing.assert_allclose(g.f, [1.0, 10.0, 100.0, 1000.0], rtol=1e-15, atol=0)


# ---------------------------------------------------------------------- from_array


def test_from_array_keeps_values_and_converts_to_float():
    g = FrequencyGrid.from_array([1, 2, 4, 8])
    assert g.f.dtype == np.float64
    np.testing.assert_array_equal(g.f, [1.0, 2.0, 4.0, 8.0])
    assert len(g) == 4


def test_from_array_accepts_uneven_spacing():
    f = [0.5, 0.75, 3.0, 40.0]
    g = FrequencyGrid.from_array(f)
    np.testing.assert_array_equal(g.f, f)


# -------------------------------------------------------------------- immutability


def test_frequency_array_is_read_only():
    g = FrequencyGrid.linear(1.0, 10.0, 1.0)
    with pytest.raises(ValueError, match="read-only"):
        g.f[0] = 5.0
    assert g.f[0] == 1.0


def test_attribute_assignment_is_refused():
    g = FrequencyGrid.linear(1.0, 10.0, 1.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        g.f = np.array([1.0, 2.0])  # type: ignore[misc]
    assert len(g) == 10


def test_grid_does_not_alias_the_callers_buffer():
    base = np.array([1.0, 2.0, 3.0])
    g = FrequencyGrid.from_array(base[:])
    base[1] = -5.0
    np.testing.assert_array_equal(g.f, [1.0, 2.0, 3.0])


def test_building_a_grid_leaves_the_callers_array_writable():
    f = np.array([1.0, 2.0, 3.0])
    FrequencyGrid.from_array(f)
    assert f.flags.writeable


# ------------------------------------------------------------------- omega, len, repr


def test_omega_is_two_pi_f():
    g = FrequencyGrid.from_array([0.5, 1.0, 2.0, 8.0])
    # 2*pi*f with f a power of two only shifts pi's exponent: exact
    np.testing.assert_array_equal(g.omega, [math.pi, 2 * math.pi, 4 * math.pi, 16 * math.pi])


def test_omega_of_a_decimal_grid():
    g = FrequencyGrid.linear(0.1, 0.7, 0.1)
    # two roundings in the test's k*pi/5 and two in the grid's value: 1e-15 relative
    np.testing.assert_allclose(g.omega, np.arange(1, 8) * math.pi / 5.0, rtol=1e-15, atol=0)


def test_len_and_repr():
    g = FrequencyGrid.linear(0.5, 100.0, step=0.5)
    assert len(g) == 200
    assert repr(g) == "FrequencyGrid(0.5–100 Hz, n=200)"
    assert "\n" not in repr(FrequencyGrid.logarithmic(1.0, 1e4, 5000))  # no array dump


# ----------------------------------------------------------------------- rejections


def _raises_case_error(build, field):
    with pytest.raises(CaseError) as info:
        build()
    err = info.value
    assert err.field == field
    msg = str(err)
    assert "\n" not in msg
    assert msg.startswith(f"{field} = ")
    assert isinstance(err, ValueError)  # CaseError is also a ValueError
    return err


@pytest.mark.parametrize(
    "f",
    [
        pytest.param([], id="empty"),
        pytest.param([[1.0, 2.0], [3.0, 4.0]], id="2-D"),
        pytest.param(5.0, id="0-D"),
    ],
)
def test_rejects_wrong_shape(f):
    _raises_case_error(lambda: FrequencyGrid.from_array(f), "frequency")


@pytest.mark.parametrize(
    ("f", "bad"),
    [
        pytest.param([1.0, np.nan, 3.0], None, id="nan"),
        pytest.param([1.0, 2.0, np.inf], np.inf, id="inf"),
        pytest.param([-np.inf, 1.0, 2.0], -np.inf, id="-inf"),
        pytest.param([0.0, 1.0, 2.0], 0.0, id="zero"),
        pytest.param([1.0, -2.0, 3.0], -2.0, id="negative"),
    ],
)
def test_rejects_non_finite_or_non_positive(f, bad):
    err = _raises_case_error(lambda: FrequencyGrid.from_array(f), "frequency")
    if bad is None:
        assert math.isnan(err.value)
    else:
        assert err.value == bad  # the offending value is reported


@pytest.mark.parametrize(
    "f",
    [
        pytest.param([1.0, 2.0, 2.0], id="repeated"),
        pytest.param([1.0, 3.0, 2.0], id="decreasing"),
    ],
)
def test_rejects_non_increasing(f):
    _raises_case_error(lambda: FrequencyGrid.from_array(f), "frequency")


def test_constructor_validates_like_from_array():
    _raises_case_error(lambda: FrequencyGrid(np.array([2.0, 1.0])), "frequency")


@pytest.mark.parametrize("make", [FrequencyGrid.linear, FrequencyGrid.logarithmic])
@pytest.mark.parametrize("f_min", [0.0, -1.0, np.nan, np.inf])
def test_rejects_bad_f_min(make, f_min):
    third = 1.0 if make is FrequencyGrid.linear else 10
    _raises_case_error(lambda: make(f_min, 10.0, third), "frequency.f_min")


@pytest.mark.parametrize("make", [FrequencyGrid.linear, FrequencyGrid.logarithmic])
@pytest.mark.parametrize("f_max", [5.0, 4.0, np.nan, np.inf])
def test_rejects_f_max_not_above_f_min(make, f_max):
    third = 1.0 if make is FrequencyGrid.linear else 10
    _raises_case_error(lambda: make(5.0, f_max, third), "frequency.f_max")


@pytest.mark.parametrize("step", [0.0, -0.5, np.nan])
def test_linear_rejects_bad_step(step):
    _raises_case_error(lambda: FrequencyGrid.linear(1.0, 10.0, step), "frequency.step")


def test_linear_rejects_infinite_step():
    _raises_case_error(lambda: FrequencyGrid.linear(1.0, 10.0, np.inf), "frequency.step")


@pytest.mark.parametrize("n", [1, 0, -3])
def test_logarithmic_rejects_fewer_than_two_points(n):
    _raises_case_error(lambda: FrequencyGrid.logarithmic(1.0, 10.0, n), "frequency.n")


def test_logarithmic_rejects_nan_count():
    _raises_case_error(lambda: FrequencyGrid.logarithmic(1.0, 10.0, np.nan), "frequency.n")
