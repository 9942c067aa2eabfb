"""The published vehicle presets against their sources, value by value, and their axle loads.

``SOURCE`` holds each table's numbers as the source states them (per axle box and per side
where it gives them so, from D. Cantero's transcription of the same tables in the TTB-2D
train-track-bridge toolbox, NTNU, 2021) with the factor that turns them into this
project's whole-car basis (per wheelset, per bogie); the preset files must hold exactly
those. The static axle load is a second, independent check of the basis: a half car read
as a whole one (or the reverse) halves (doubles) it.
"""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

from railvib.case import case_from_dict
from railvib.case.build import build_vehicle
from railvib.presets import vehicle_preset_text

G = 9.81  # m/s^2, the gravity of Vehicle.static_wheel_loads

#: (value in the source, factor to the whole-car basis): car body mass, pitch inertia,
#: bogie mass and pitch inertia, wheelset mass, primary k and c, secondary k and c,
#: half the bogie spacing l_c and half the wheelbase l_t
SOURCE = {
    "iwnicki1998_manchester_coach": {
        "mc": 32000.0,
        "jc": 1.97e6,
        "mt": 2615.0,
        "jt": 1476.0,
        "mw": 1813.0,
        "k1": (1.2e6, 2),  # per axle box
        "c1": (4.0e3, 2),
        "k2": (430e3, 2),  # per side
        "c2": (20e3, 2),
        "lc": 9.5,
        "lt": 1.28,
    },
    "goicolea2014_ave_s103_coach": {
        "mc": 47800.0,
        "jc": 1957888.0,
        "mt": 3500.0,
        "jt": 1715.0,
        "mw": 1800.0,
        "k1": (1.2e6, 2),
        "c1": (10e3, 2),
        "k2": (350e3, 2),
        "c2": (20e3, 2),
        "lc": 17.375 / 2,
        "lt": 2.5 / 2,
    },
    "wu_yang2003_shinkansen_300": {
        "mc": 41750.0,
        "jc": 2.08e6,
        "mt": 3040.0,
        "jt": 3930.0,
        "mw": 1780.0,
        "k1": (1.18e6, 1),  # the source's pitch-plane model: per wheelset, per bogie
        "c1": (39.2e3, 1),
        "k2": (530e3, 1),
        "c2": (90.2e3, 1),
        "lc": 17.5 / 2,
        "lt": 2.5 / 2,
    },
    "zhai2009_china_star_power_car": {
        "mc": 59364.2,
        "jc": 1.723e6,
        "mt": 5630.8,
        "jt": 9487.0,
        "mw": 1843.5,
        "k1": (2.3996e6, 2),
        "c1": (30e3, 2),
        "k2": (0.8858e6, 2),
        "c2": (45e3, 2),
        "lc": 5.73,
        "lt": 1.5,
    },
}

#: static axle load, t: (lowest, highest) a car of this kind has; the China Star power car's
#: is 19.5 t, the upper bound 22.5 t is the highest line category (D) of EN 15528:2021
AXLE_LOAD_T = {
    "iwnicki1998_manchester_coach": (9.0, 16.0),
    "goicolea2014_ave_s103_coach": (12.0, 17.0),  # 17 t: the Velaro E's largest axle load
    "wu_yang2003_shinkansen_300": (10.0, 16.0),
    "zhai2009_china_star_power_car": (19.0, 20.0),
}


def _file(name):
    t = tomllib.loads(vehicle_preset_text(name))
    bodies = {b["name"]: b for b in t["bodies"]}
    susp = {s["name"]: s for s in t["suspensions"]}
    return t, bodies, susp


@pytest.mark.parametrize("name", list(SOURCE))
def test_preset_holds_the_source_values_on_the_whole_car_basis(name):
    want = SOURCE[name]
    _, bodies, susp = _file(name)
    # exact: the files write the source's decimal numbers (times 1 or 2), no arithmetic
    assert bodies["carbody"]["mass_kg"] == want["mc"]
    assert bodies["carbody"]["pitch_inertia_kg_m2"] == want["jc"]
    for i in (1, 2):
        assert bodies[f"bogie{i}"]["mass_kg"] == want["mt"]
        assert bodies[f"bogie{i}"]["pitch_inertia_kg_m2"] == want["jt"]
        assert susp[f"secondary.{i}"]["stiffness_n_per_m"] == want["k2"][0] * want["k2"][1]
        assert susp[f"secondary.{i}"]["damping_ns_per_m"] == want["c2"][0] * want["c2"][1]
    lc, lt = want["lc"], want["lt"]
    for i, x in enumerate((lc + lt, lc - lt, -lc + lt, -lc - lt), start=1):
        assert bodies[f"wheelset{i}"]["mass_kg"] == want["mw"]
        assert susp[f"primary.{i}"]["stiffness_n_per_m"] == want["k1"][0] * want["k1"][1]
        assert susp[f"primary.{i}"]["damping_ns_per_m"] == want["c1"][0] * want["c1"][1]
        # positions: sums of the source's lengths, rounding only (1e-12 m)
        assert bodies[f"wheelset{i}"]["x_m"] == pytest.approx(x, abs=1e-12)
    assert bodies["bogie1"]["x_m"] == pytest.approx(lc, abs=1e-12)


@pytest.mark.parametrize("name", list(SOURCE))
def test_axle_loads_are_those_of_the_whole_car(name):
    want = SOURCE[name]
    car = build_vehicle(
        case_from_dict({"preset": "wang2017_metro", "vehicle": {"preset": name}}, warn=False)
    )
    loads = car.static_wheel_loads()
    # the car is symmetric: each wheelset carries a quarter of the weight of the car body
    # and the bogies, and its own (hand sum of the source's masses)
    total = want["mc"] + 2 * want["mt"] + 4 * want["mw"]
    # a 10x10 linear solve of values 1e3..1e7: 1e-9 relative
    np.testing.assert_allclose(loads, np.full(4, total * G / 4), rtol=1e-9)
    lo, hi = AXLE_LOAD_T[name]
    assert lo <= total / 4 / 1000 <= hi
