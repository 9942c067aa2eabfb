"""Trains: several cars on one track, against the single car and the finite-track reference."""

from __future__ import annotations

import numpy as np
import pytest

import railvib.coupling as coupling
from railvib.case import case_from_dict
from railvib.case.build import build_system
from railvib.validation import FiniteCoupledSystem

F = np.linspace(0.5, 1000.0, 400)
#: the paper car's wheels span 14.8 m; with a 200 m gap car i + 1 stands 214.8 m = 358
#: sleeper bays behind car i, so every car sees the sleepers exactly as the single car does
FAR_GAP = 200.0


def _system(**train):
    data = {"preset": "wang2017_metro"}
    if train:
        data["train"] = train
    return build_system(case_from_dict(data, warn=False))


def test_cars_far_apart_each_reproduce_the_single_car():
    single = _system().frf(F)
    system = _system(cars=3, gap_m=FAR_GAP)
    train = system.frf(F)
    offsets = system.vehicle.wheel_offsets
    np.testing.assert_allclose(offsets[4], 14.8 + FAR_GAP, rtol=1e-14)
    for car in range(3):
        dofs = [train.dofs.index(f"car{car + 1}.{d}") for d in single.dofs]
        # each car's irregularity arrives offset / v later: the single car's response delayed
        delay = np.exp(-2j * np.pi * F * offsets[4 * car] / system.speed)
        for got, ref in (
            (train.vehicle[:, dofs], single.vehicle),
            (train.rail[:, 4 * car : 4 * car + 4], single.rail),
            (train.contact_force[:, 4 * car : 4 * car + 4], single.contact_force),
        ):
            # the track couples the cars 200 m apart by less than 1e-12 of the driving
            # receptance (pad damping over 358 bays); positions rounded to 1e-13 m: 1e-9
            err = np.abs(got - ref * delay[:, None]).max() / np.abs(ref).max()
            assert err < 1e-9, (car, err)


def test_near_cars_interact_through_the_track():
    # 4 m apart the cars' wheels share the rail's near field: their responses differ from
    # the lone car's by more than 1e-6 (the test above is not passed trivially)
    single = _system().frf(F)
    train = _system(cars=2, gap_m=4.0).frf(F)
    rear = [train.dofs.index(f"car2.{d}") for d in single.dofs]
    assert np.abs(np.abs(train.vehicle[:, rear]) - np.abs(single.vehicle)).max() > 1e-6


@pytest.mark.parametrize("coupler", [0.0, 5.0e6])
def test_dense_solve_of_many_wheels_equals_the_stacked_elimination(monkeypatch, coupler):
    # 3 cars (12 wheels) solved both ways: LAPACK with pivoting against the stacked
    # elimination without exchanges; 1e-12 of each peak (rounding of a 12x12 solve)
    system = _system(cars=3, gap_m=4.0, coupler_stiffness_n_per_m=coupler)
    dense = system.frf(F)
    monkeypatch.setattr(coupling, "DENSE_WHEELS", 100)
    stacked = system.frf(F)
    for a, b in ((dense.vehicle, stacked.vehicle), (dense.rail, stacked.rail)):
        assert np.abs(a - b).max() <= 1e-12 * np.abs(a).max()


def test_train_labels_and_coupler():
    system = _system(cars=3, gap_m=4.0, coupler_stiffness_n_per_m=5.0e6)
    v = system.vehicle
    assert "car2.bogie1.bounce" in v.dofs
    labels = system.frf(F[:3]).labels
    assert "rail@car3.wheel2" in labels
    assert len(labels) == 3 * (10 + 4)
    # a coupler between car bodies 1 and 2: -k between their bounce DOFs
    i, j = v.dofs.index("car1.carbody.bounce"), v.dofs.index("car2.carbody.bounce")
    assert v.stiffness_matrix[i, j] == pytest.approx(-5.0e6, rel=1e-15)
    k = v.dofs.index("car3.carbody.bounce")
    assert v.stiffness_matrix[i, k] == 0.0


def test_finite_track_reference_accepts_a_train():
    # two cars 4 m apart: the symplectic solve against the finite track (8 Hermite
    # elements per bay: 1.7e-5 relative receptance error at 1 kHz, less below; 100 bays
    # beyond the outer wheels, absorbing ends); below 400 Hz (away from the pinned-pinned
    # band, where the finite answer depends on its length): within 1e-4 of each peak
    system = _system(cars=2, gap_m=4.0)
    f = np.geomspace(2.0, 400.0, 12)
    got = system.frf(f)
    finite = FiniteCoupledSystem.from_system(
        system, margin_spans=100, elements_per_span=8, absorber_spans=33, absorber_damping=2e6
    )
    ref = finite.frf(f)
    assert ref.labels == got.labels
    for a, b in ((got.vehicle, ref.vehicle), (got.rail, ref.rail)):
        err = np.abs(a - b).max(axis=0) / np.abs(b).max(axis=0)
        assert err.max() < 1e-4, err.max()


def test_time_domain_reference_accepts_a_train():
    # Newmark on the finite track under a 5 Hz sine reaching each wheel at its delay: the
    # labels are per car, and far below the wheel-rail resonance every wheelset follows
    # the 1 mm input: acceleration amplitude (2 pi 5)^2 1e-3 m/s^2 within 5 % (the
    # contact and the track deflect by well under 5 % of the input at 5 Hz)
    from railvib.validation.time_domain import simulate_time_domain

    system = _system(cars=2, gap_m=4.0)
    finite = FiniteCoupledSystem.from_system(system, margin_spans=20, elements_per_span=4)
    dt, n = 1e-3, 1400  # car 2's leading wheel is reached at 18.8 m / 22.2 m/s = 0.85 s
    t = np.arange(n + 1) * dt
    irr = np.stack(
        [1e-3 * np.sin(2 * np.pi * 5.0 * (t - d)) * (t > d) for d in finite.delays], axis=1
    )
    history = simulate_time_domain(finite, irr, dt)
    assert history.labels[-1] == "rail@car2.wheel4"
    late = history.t > 1.15  # 0.3 s after car 2's input starts: its transient decayed
    expected = (2 * np.pi * 5.0) ** 2 * 1e-3
    for label in ("car1.wheelset1.bounce", "car2.wheelset1.bounce"):
        col = history.labels.index(label)
        amp = np.abs(history.acceleration[late, col]).max()
        assert abs(amp - expected) < 0.05 * expected, (label, amp)


def test_time_domain_refuses_frequency_dependent_elements():
    from railvib.errors import CaseError
    from railvib.vehicle import parse_vehicle

    el = {"model": "generalized_maxwell", "k_inf_n_per_m": 1.0, "k_n_per_m": [1e5], "tau_s": [0.01]}
    car = parse_vehicle(
        [{"name": "body", "mass_kg": 1e4}, {"name": "ws", "mass_kg": 1e3}],
        [{"upper": "body", "lower": "ws", "stiffness_n_per_m": 1e6, "element": el}],
        [{"body": "ws"}],
    )
    system = coupling.CoupledSystem(car, _system().track, 1e9, 0.3, 20.0)
    finite = FiniteCoupledSystem.from_system(system, margin_spans=10, elements_per_span=4)
    with pytest.raises(CaseError, match="time-domain"):
        finite.time_domain_matrices()


def test_validation_plots_pick_the_leading_car_of_a_train():
    # `railvib validate` on a train plotted labels its vehicle lacks (KeyError traceback)
    from railvib.validation.plots import DEFAULT_PLOT_RESPONSES, _present

    labels = set(_system(cars=2, gap_m=4.0).frf(F[:2]).labels)
    assert _present(DEFAULT_PLOT_RESPONSES, labels) == [
        "car1.carbody.bounce",
        "car1.bogie1.bounce",
        "car1.wheelset2.bounce",
        "rail@car1.wheel1",
    ]
    # a two-axle wagon has no bogie: that figure is left out
    assert _present(DEFAULT_PLOT_RESPONSES, {"carbody.bounce", "rail@wheel1"}) == [
        "carbody.bounce",
        "rail@wheel1",
    ]
