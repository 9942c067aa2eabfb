"""Shipped vehicle presets: sources and bases written down, body frequencies against closed forms.

None of the sources prints natural frequencies, so the check is the closed form of the
undamped car with its wheels held: the bounce of the car body on the two bogies is a
two-mass chain (car body ``M_c`` on ``2 K_2``, the two bogies ``2 M_t`` on ``4 K_1``) and so
is its pitch (``J_c / l_c^2`` on ``2 K_2``, the bogies in antiphase ``2 M_t`` on ``4 K_1``);
each chain's squared frequencies are the roots of
``m1 m2 w^4 - (k11 m2 + k22 m1) w^2 + (k11 k22 - k12^2) = 0`` with ``k11 = 2 K_2``,
``k12 = -2 K_2``, ``k22 = 2 K_2 + 4 K_1``. A bogie pitches alone: ``w^2 = 2 K_1 l_t^2 / J_t``.
Values are read from the TOML text here (not through the vehicle model).
"""

from __future__ import annotations

import re
import tomllib

import numpy as np
import pytest

from railvib.case import case_from_dict
from railvib.case.build import build_vehicle
from railvib.presets import list_vehicle_presets, vehicle_preset_text

PRESETS = list_vehicle_presets()


def _chain(m1, m2, k11, k12, k22):
    """The two squared angular frequencies of a two-mass chain (quadratic formula)."""
    a, b, c = m1 * m2, -(k11 * m2 + k22 * m1), k11 * k22 - k12**2
    disc = np.sqrt(b * b - 4 * a * c)
    return np.array([(-b - disc) / (2 * a), (-b + disc) / (2 * a)])


def _values(name):
    t = tomllib.loads(vehicle_preset_text(name))
    bodies = {b["name"]: b for b in t["bodies"]}
    susp = {s["name"]: s for s in t["suspensions"]}
    return dict(
        mc=bodies["carbody"]["mass_kg"],
        jc=bodies["carbody"]["pitch_inertia_kg_m2"],
        mt=bodies["bogie1"]["mass_kg"],
        jt=bodies["bogie1"]["pitch_inertia_kg_m2"],
        lc=bodies["bogie1"]["x_m"],
        lt=bodies["wheelset1"]["x_m"] - bodies["bogie1"]["x_m"],
        k1=susp["primary.1"]["stiffness_n_per_m"],
        k2=susp["secondary.1"]["stiffness_n_per_m"],
    )


def test_at_least_five_vehicle_presets_ship():
    # the paper's car and at least four published vehicles (issue 15)
    assert "wang2017_metro_b" in PRESETS
    assert len(PRESETS) >= 5


@pytest.mark.parametrize("name", PRESETS)
def test_preset_states_source_and_basis_beside_every_value(name):
    text = vehicle_preset_text(name)
    t = tomllib.loads(text)
    assert t["source"]
    assert t["basis"] in ("whole_car", "half_car")
    assert re.search(r"\b(19|20)\d\d\b", t["source"]), "source with its year"
    assert re.search(r"^# Source: ", text, re.M)
    assert re.search(r"^# Basis: ", text, re.M)
    for line in text.splitlines():
        if re.match(r"^(mass_kg|pitch_inertia_kg_m2|stiffness_n_per_m|damping_ns_per_m) =", line):
            assert "#" in line, f"{name}: no basis beside {line!r}"


@pytest.mark.parametrize("name", PRESETS)
def test_body_frequencies_are_the_closed_form(name):
    v = _values(name)
    car = build_vehicle(
        case_from_dict({"preset": "wang2017_metro", "vehicle": {"preset": name}}, warn=False)
    )
    body = np.setdiff1d(np.arange(len(car.dofs)), car.wheel_dofs)
    k = car.static_stiffness_matrix[np.ix_(body, body)]
    m = car.mass_matrix[np.ix_(body, body)]
    numeric = np.sort(np.linalg.eigvals(np.linalg.solve(m, k)).real)
    k11, k22 = 2 * v["k2"], 2 * v["k2"] + 4 * v["k1"]
    bounce = _chain(v["mc"], 2 * v["mt"], k11, -k11, k22)
    pitch = _chain(v["jc"] / v["lc"] ** 2, 2 * v["mt"], k11, -k11, k22)
    bogie_pitch = 2 * v["k1"] * v["lt"] ** 2 / v["jt"]
    expected = np.sort(np.concatenate([bounce, pitch, [bogie_pitch, bogie_pitch]]))
    # eigenvalues of a 6x6 problem whose entries span 1e3..1e8: 1e-9 relative
    np.testing.assert_allclose(numeric, expected, rtol=1e-9)
    # the car body's bounce and pitch of a passenger car lie near 1 Hz (0.5-2 Hz), the
    # ride-comfort design range; a value outside points to a basis slip (x2 or /2)
    f_body = np.sqrt([bounce[0], pitch[0]]) / (2 * np.pi)
    assert np.all((f_body > 0.5) & (f_body < 2.0)), f_body
