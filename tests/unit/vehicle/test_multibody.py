"""The multibody vehicle file: topologies against closed forms, the paper's car, bad files."""

from __future__ import annotations

import numpy as np
import pytest

from railvib.case import case_from_dict
from railvib.case.build import build_system, build_vehicle
from railvib.errors import CaseError
from railvib.presets import load_vehicle_preset
from railvib.vehicle import PitchPlaneParameters, parse_vehicle, pitch_plane_10dof

F = np.array([0.5, 3.0, 7.0, 20.0, 48.0, 150.0, 900.0])


def _body(name, mass, inertia=None, x=0.0):
    out = {"name": name, "mass_kg": mass, "x_m": x}
    if inertia is not None:
        out["pitch_inertia_kg_m2"] = inertia
    return out


def _spring(upper, lower, k, c=0.0, x=None, **extra):
    out = {"upper": upper, "lower": lower, "stiffness_n_per_m": k, "damping_ns_per_m": c}
    if x is not None:
        out["x_m"] = x
    return {**out, **extra}


def test_the_paper_car_as_a_file_has_the_library_matrices():
    # the shipped file restates Table 1 of the paper; its matrices must be the library car's
    # to 1e-12 of the largest entry (summation order and x positions such as 6.3 + 1.1 = 7.4
    # differ by a few ulps)
    table = load_vehicle_preset("wang2017_metro_b")
    file_car = parse_vehicle(table["bodies"], table["suspensions"], table["wheels"])
    params = case_from_dict({"preset": "wang2017_metro"}).vehicle.model_dump(exclude_none=True)
    lib_car = pitch_plane_10dof(PitchPlaneParameters(**params))
    assert file_car.dofs == lib_car.dofs
    for name in ("mass_matrix", "stiffness_matrix", "damping_matrix", "wheel_matrix"):
        a, b = getattr(file_car, name), getattr(lib_car, name)
        assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max(), name
    np.testing.assert_allclose(file_car.wheel_offsets, lib_car.wheel_offsets, atol=1e-12)


def test_the_paper_car_as_a_file_gives_the_default_case_frf():
    # the same car through the whole coupled solve: 1e-12 of each response's peak
    f = np.linspace(0.5, 1000.0, 400)
    base = {"preset": "wang2017_metro"}
    a = build_system(case_from_dict(base)).frf(f)
    b = build_system(case_from_dict({**base, "vehicle": {"preset": "wang2017_metro_b"}})).frf(f)
    for x, y in ((a.vehicle, b.vehicle), (a.rail, b.rail), (a.contact_force, b.contact_force)):
        assert np.abs(x - y).max() <= 1e-12 * np.abs(x).max()


def test_single_wheel_mass_condenses_to_its_inertia():
    # a lone mass on the rail: S(f) = -omega^2 m exactly (no spring at all)
    car = parse_vehicle([_body("wheel", 1500.0)], [], [{"body": "wheel"}])
    s = car.condensed_to_wheels(F).stiffness[:, 0, 0]
    np.testing.assert_allclose(s, -((2 * np.pi * F) ** 2) * 1500.0, rtol=1e-13)
    assert car.dofs == ("wheel.bounce",)


@pytest.mark.parametrize("maxwell", [False, True])
def test_quarter_car_condenses_to_the_closed_form(maxwell):
    # sprung mass m2 on a spring-damper (k2 + i omega c2) [+ a Maxwell branch K1 i w tau /
    # (1 + i w tau) from the pad family] on wheel mass m1:
    # S = -w^2 m1 + k* (-w^2 m2) / (k* - w^2 m2); rounding of a 2x2 elimination: 1e-12
    m1, m2, k2, c2, k1, tau = 1200.0, 9000.0, 6.0e5, 1.2e4, 3.0e5, 2.0e-3
    extra = (
        {
            "element": {
                "model": "generalized_maxwell",
                "k_inf_n_per_m": 1.0,
                "k_n_per_m": [k1],
                "tau_s": [tau],
            }
        }
        if maxwell
        else {}
    )
    car = parse_vehicle(
        [_body("sprung", m2), _body("wheel", m1)],
        [_spring("sprung", "wheel", k2, c2, **extra)],
        [{"body": "wheel"}],
    )
    w = 2 * np.pi * F
    ks = k2 + 1j * w * c2
    if maxwell:
        ks = ks + 1.0 + k1 * 1j * w * tau / (1 + 1j * w * tau)
    expected = -(w**2) * m1 + ks * (-(w**2) * m2) / (ks - w**2 * m2)
    cond = car.condensed_to_wheels(F)
    np.testing.assert_allclose(cond.stiffness[:, 0, 0], expected, rtol=1e-12)
    # recovery of the sprung mass per wheel displacement: ks / (ks - w^2 m2)
    np.testing.assert_allclose(cond.recovery[:, 0, 0], ks / (ks - w**2 * m2), rtol=1e-12)
    # the dense dynamic stiffness agrees with the stacked elimination's closed form
    d = car.dynamic_stiffness(F)
    np.testing.assert_allclose(d[:, 0, 0], ks - w**2 * m2, rtol=1e-13)


def test_two_axle_wagon_body_modes_are_the_closed_form():
    # body bounce/pitch on one spring k per wheelset at +-a (wheels held):
    # f_bounce = sqrt(2k/M)/2pi, f_pitch = sqrt(2k a^2/J)/2pi (uncoupled: symmetric)
    mass, inertia, k, a = 20000.0, 5.0e5, 1.0e6, 4.5
    car = parse_vehicle(
        [
            _body("carbody", mass, inertia),
            _body("wheelset1", 1200.0, x=a),
            _body("wheelset2", 1200.0, x=-a),
        ],
        [_spring("carbody", "wheelset1", k), _spring("carbody", "wheelset2", k)],
        [{"body": "wheelset1"}, {"body": "wheelset2"}],
    )
    body = [0, 1]
    kb, mb = car.stiffness_matrix[np.ix_(body, body)], car.mass_matrix[np.ix_(body, body)]
    f = np.sort(np.sqrt(np.linalg.eigvals(np.linalg.solve(mb, kb)).real)) / (2 * np.pi)
    expected = np.sort([np.sqrt(2 * k / mass), np.sqrt(2 * k * a**2 / inertia)]) / (2 * np.pi)
    np.testing.assert_allclose(f, expected, rtol=1e-12)
    assert car.wheel_names == ("wheel1", "wheel2")
    # static loads: the body's weight split evenly, plus each wheelset's own
    np.testing.assert_allclose(
        car.static_wheel_loads(), 9.81 * (mass / 2 + 1200.0) * np.ones(2), rtol=1e-12
    )


def test_condensation_of_an_arbitrary_tree_matches_a_dense_solve():
    # a three-stage chain with unequal bogies and a Maxwell element: the stacked
    # min-degree elimination against S = D_ww - D_wb D_bb^-1 D_bw by LAPACK (1e-10:
    # condition of D_bb near the body resonances, some 1e4)
    bodies = [
        _body("carbody", 3.0e4, 1.5e6),
        _body("bogieA", 3000.0, 2500.0, 6.0),
        _body("bogieB", 2000.0, 1800.0, -7.0),
        _body("w1", 1500.0, x=7.2),
        _body("w2", 1500.0, x=4.8),
        _body("w3", 1400.0, x=-6.0),
        _body("w4", 1400.0, x=-8.0),
    ]
    el = {"model": "generalized_maxwell", "k_inf_n_per_m": 2e5, "k_n_per_m": [1e5], "tau_s": [0.01]}
    susp = [
        _spring("carbody", "bogieA", 3e5, 2e4, x=6.0),
        _spring("carbody", "bogieB", 0.0, 1e4, x=-7.0, element=el),
        _spring("bogieA", "w1", 1e6, 3e3),
        _spring("bogieA", "w2", 1.2e6, 3e3),
        _spring("bogieB", "w3", 9e5, 2e3),
        _spring("bogieB", "w4", 9e5, 2e3),
    ]
    wheels = [{"body": b} for b in ("w1", "w2", "w3", "w4")]
    car = parse_vehicle(bodies, susp, wheels)
    d = car.dynamic_stiffness(F)
    w, b = car.wheel_dofs, np.setdiff1d(np.arange(len(car.dofs)), car.wheel_dofs)
    dense = d[:, w][:, :, w] - d[:, w][:, :, b] @ np.linalg.solve(
        d[:, b][:, :, b], d[:, b][:, :, w]
    )
    s = car.condensed_to_wheels(F).stiffness
    assert np.abs(s - dense).max() <= 1e-10 * np.abs(dense).max()


def test_half_car_basis_doubles_to_the_whole_car():
    table = load_vehicle_preset("wang2017_metro_b")
    whole = build_vehicle(case_from_dict({"preset": "wang2017_metro", "vehicle": table}))
    half = dict(table, basis="half_car")
    half["bodies"] = [
        {k: (v / 2 if k in ("mass_kg", "pitch_inertia_kg_m2") else v) for k, v in b.items()}
        for b in table["bodies"]
    ]
    half["suspensions"] = [
        {k: (v / 2 if k.endswith(("_n_per_m", "_ns_per_m")) else v) for k, v in s.items()}
        for s in table["suspensions"]
    ]
    doubled = build_vehicle(case_from_dict({"preset": "wang2017_metro", "vehicle": half}))
    for name in ("mass_matrix", "stiffness_matrix", "damping_matrix"):
        np.testing.assert_allclose(getattr(doubled, name), getattr(whole, name), rtol=1e-15)


GOOD = {
    "bodies": [
        _body("carbody", 2e4, 5e5),
        _body("ws1", 1200.0, x=4.0),
        _body("ws2", 1200.0, x=-4.0),
    ],
    "suspensions": [_spring("carbody", "ws1", 1e6), _spring("carbody", "ws2", 1e6)],
    "wheels": [{"body": "ws1"}, {"body": "ws2"}],
}


def _with(path, value):
    table = {k: [dict(t) for t in v] for k, v in GOOD.items()}
    group, index, key = path
    if key is None:
        table[group].append(value)
    elif value is None:
        del table[group][index][key]
    else:
        table[group][index][key] = value
    return table


@pytest.mark.parametrize(
    ("where", "value", "field", "words"),
    [
        (("bodies", 1, "mass_kg"), -5.0, "vehicle.bodies[1].mass_kg", "must be > 0"),
        (("bodies", 0, "pitch_inertia_kg_m2"), 0.0, "vehicle.bodies[0].pitch_inertia_kg_m2", "> 0"),
        (("bodies", 2, "name"), "ws1", "vehicle.bodies[2].name", "no other body"),
        (("bodies", 0, "masss_kg"), 1.0, "vehicle.bodies[0].masss_kg", "did you mean"),
        (("bodies", None, None), _body("loose", 500.0), "vehicle.bodies[3]", "unconnected"),
        (("suspensions", 0, "lower"), "ws3", "vehicle.suspensions[0].lower", "a body among"),
        (("suspensions", 0, "lower"), "carbody", "vehicle.suspensions[0].lower", "other than"),
        (
            ("suspensions", 1, "stiffness_n_per_m"),
            -1.0,
            "vehicle.suspensions[1].stiffness_n_per_m",
            "> 0",
        ),
        (("wheels", 0, "body"), "carbody", "vehicle.wheels[0].body", "without a pitch DOF"),
        (("wheels", 1, "x_m"), 9.0, "vehicle.wheels[1].x_m", "front to back"),
        (("wheels", 1, "body"), "ws1", "vehicle.wheels[1].body", "one wheel per"),
        (("wheels", 1, "body"), None, "vehicle.wheels[1].body", "required"),
        (
            ("suspensions", 1, "x_m"),
            4.0,
            "vehicle.bodies[0].pitch_inertia_kg_m2",
            "two x positions",
        ),
    ],
)
def test_bad_vehicle_tables_name_the_field(where, value, field, words):
    data = {"preset": "wang2017_metro", "vehicle": {"model": "multibody", **_with(where, value)}}
    with pytest.raises(CaseError) as err:
        case_from_dict(data)
    assert err.value.field == field
    assert words in str(err.value)
    assert "\n" not in str(err.value)


def test_a_vehicle_without_wheels_is_refused():
    data = {"preset": "wang2017_metro", "vehicle": {**GOOD, "model": "multibody", "wheels": []}}
    with pytest.raises(CaseError, match=r"^vehicle\.wheels = \[\]: at least one"):
        case_from_dict(data)


def test_keys_of_the_other_model_are_refused():
    data = {
        "preset": "wang2017_metro",
        "vehicle": {**GOOD, "model": "multibody", "carbody_mass": 1.0},
    }
    with pytest.raises(CaseError, match=r"^vehicle\.carbody_mass = 1\.0: not a key of vehicle "):
        case_from_dict(data)


def test_condensation_of_a_topology_with_loops_matches_a_dense_solve():
    # not a tree: the car body also reaches each wheelset directly (a loop body - bogie -
    # wheelset - body) and the two bogies are tied; the minimum-degree elimination fills
    # in and must still equal the dense condensation (1e-10, as for the tree)
    bodies = [
        _body("carbody", 3.0e4, 1.5e6),
        _body("bogieA", 3000.0, 2500.0, 6.0),
        _body("bogieB", 2000.0, 1800.0, -6.0),
        _body("w1", 1500.0, x=7.0),
        _body("w2", 1500.0, x=5.0),
        _body("w3", 1400.0, x=-5.0),
        _body("w4", 1400.0, x=-7.0),
    ]
    susp = [
        _spring("carbody", "bogieA", 3e5, 2e4, x=6.0),
        _spring("carbody", "bogieB", 3e5, 2e4, x=-6.0),
        _spring("bogieA", "bogieB", 1e5, 1e3, x=0.0),
        _spring("bogieA", "w1", 1e6, 3e3),
        _spring("bogieA", "w2", 1.2e6, 3e3),
        _spring("bogieB", "w3", 9e5, 2e3),
        _spring("bogieB", "w4", 9e5, 2e3),
        _spring("carbody", "w1", 5e4, 0.0),
        _spring("carbody", "w4", 5e4, 0.0),
    ]
    car = parse_vehicle(bodies, susp, [{"body": b} for b in ("w1", "w2", "w3", "w4")])
    d = car.dynamic_stiffness(F)
    w, b = car.wheel_dofs, np.setdiff1d(np.arange(len(car.dofs)), car.wheel_dofs)
    dense = d[:, w][:, :, w] - d[:, w][:, :, b] @ np.linalg.solve(
        d[:, b][:, :, b], d[:, b][:, :, w]
    )
    s = car.condensed_to_wheels(F).stiffness
    assert np.abs(s - dense).max() <= 1e-10 * np.abs(dense).max()


def test_a_huge_vehicle_file_is_refused_before_it_is_parsed():
    # the connectivity check is quadratic in the bodies; a file of thousands is refused by
    # count before it runs
    bodies = [_body(f"b{i}", 1.0) for i in range(5_000)]
    data = {"preset": "wang2017_metro", "vehicle": {**GOOD, "model": "multibody", "bodies": bodies}}
    with pytest.raises(CaseError, match=r"^vehicle\.bodies = '<5,000 tables>': at most 200"):
        case_from_dict(data)
