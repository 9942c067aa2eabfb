"""A train through the whole validation: PEM vs finite track vs time-domain Monte Carlo.

The acceptance criteria of the single car (``test_validation_acceptance.py``) hold for a
two-car train, for the responses of both cars: the finite-track PSDs within 2 % of PEM,
PEM inside the Monte Carlo 95 % band in >= 90 % of the bins. The run is seeded.
"""

import pytest

from railvib.coupling import CoupledSystem
from railvib.spectra import Combined, FRAClass, ShiTai
from railvib.validation import ValidationSettings, validate_case
from railvib.vehicle import make_train

K_H = 9.873e8
SPEED = 80 / 3.6
SPECTRUM = Combined(FRAClass(5), ShiTai())


@pytest.mark.slow
@pytest.mark.validation
def test_two_car_train_three_ways(paper_vehicle, paper_track):
    train = make_train([paper_vehicle, paper_vehicle], 4.0)
    system = CoupledSystem(train, paper_track, K_H, 0.3, SPEED)
    res = validate_case(system, SPECTRUM, settings=ValidationSettings.quick(), seed=3)
    responses = [str(r) for r in res.fraction_inside.response.values]
    assert "car2.carbody.bounce" in responses
    assert "rail@car2.wheel4" in responses
    assert float(res.max_relative_error.max()) < 0.02
    assert float(res.fraction_inside.min()) >= 0.90
    assert res.passed
