"""Where ride comfort is evaluated by default: the car body, in a train the leading car's."""

import numpy as np
import pytest

from railvib.case import build_system, case_from_dict
from railvib.errors import CaseError
from railvib.solve import criteria_settings

F = np.geomspace(0.5, 100.0, 50)


def test_a_trains_default_comfort_body_is_the_leading_cars_with_its_own_wheelbase():
    case = case_from_dict({"preset": "wang2017_metro_train6"})
    system = build_system(case)
    comfort = criteria_settings(case, system, F)["ride_comfort"]
    assert comfort["body"] == "car1.carbody"
    # the paper's B car (Wang et al. 2017, Table 1): bogie centres at +-6.3 m, half the
    # bogie wheelbase 1.1 m -> wheels at +-7.4 m
    # (the extent is the car's own wheels, not the train's 100 m of them)
    assert comfort["floor_positions_m"] == (6.3, 0.0, -6.3)
    assert comfort["floor_extent_m"] == pytest.approx((-7.4, 7.4))


def test_another_car_is_named_and_a_missing_body_is_one_line():
    case = case_from_dict(
        {"preset": "wang2017_metro_train6", "criteria": {"comfort_body": "car3.carbody"}}
    )
    assert criteria_settings(case, build_system(case), F)["ride_comfort"]["body"] == "car3.carbody"
    bad = case_from_dict(
        {"preset": "wang2017_metro_train6", "criteria": {"comfort_body": "car9.carbody"}}
    )
    with pytest.raises(CaseError, match=r"criteria.comfort_body = 'car9.carbody'"):
        criteria_settings(bad, build_system(bad), F)
