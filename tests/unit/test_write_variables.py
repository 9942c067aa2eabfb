"""`write_variables` fills the result arrays in place with `compute_variables`' values.

It is the same arithmetic on the same responses (the vehicle's and the rail's parts
written side by side instead of joined first; the acceleration PSD from the
displacement PSD just written, which is how `compute_variables` forms it too), so the
values must be bit for bit equal, for every variable of `VARIABLES`.
"""

import numpy as np
import pytest

import railvib
from railvib.case import build_spectrum, build_system
from railvib.grid import FrequencyGrid
from railvib.results.variables import VARIABLES, compute_variables, write_variables


@pytest.mark.parametrize("name", ["wang2017_metro", "wang2017_metro_train6"])
def test_written_in_place_equals_computed(name):
    case = railvib.load_preset_case(name)
    system, spectrum = build_system(case), build_spectrum(case)
    f = FrequencyGrid.linear(0.5, 300.0, 0.5).f
    s_r = spectrum.temporal(f, system.speed)
    frf = system.frf(f)
    expected = compute_variables(frf, s_r, VARIABLES)
    out = {k: np.full_like(v, np.nan) for k, v in expected.items()}
    write_variables(out, frf, s_r)
    assert out.keys() == VARIABLES.keys()
    for key, value in expected.items():
        np.testing.assert_array_equal(out[key], value, err_msg=key)
