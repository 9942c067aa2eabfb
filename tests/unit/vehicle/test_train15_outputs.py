"""A train's run outputs: wheels named by their labels, the per-car table in summary.csv,
and couplers between the car bodies from the case file."""

from __future__ import annotations

import io

import numpy as np
import pandas as pd
import pytest

from railvib.case import case_from_dict
from railvib.case.build import build_system
from railvib.outputs.contact import contact_table
from railvib.results import load_netcdf
from railvib.results.report import summary_csv
from railvib.solve import run, run_to_folder

GRID = {"spacing": "log", "f_min": 1.0, "f_max": 300.0, "n": 30}


def _case(**train):
    data = {"preset": "wang2017_metro", "speed_kmh": 120.0, "frequency": GRID}
    if train:
        data["train"] = train
    return case_from_dict(data, warn=False)


@pytest.fixture(scope="module")
def two_cars(tmp_path_factory):
    out = tmp_path_factory.mktemp("two_cars")
    run_to_folder(_case(cars=2, gap_m=4.0), out, plots=False)
    return out


def _comment_table(text, title):
    """The table written as ``# `` lines after ``# <title>:`` in a summary.csv."""
    lines = text.splitlines()
    start = lines.index(f"# {title}:") + 1
    body = []
    for line in lines[start:]:
        if not line.startswith("# ") or line.startswith("# units:"):
            break
        body.append(line[2:])
    return pd.read_csv(io.StringIO("\n".join(body)), index_col=0)


@pytest.mark.slow  # the module's two-car run: about 4 s
def test_summary_csv_holds_the_per_car_table_and_still_reads_as_one_table(two_cars):
    text = (two_cars / "summary.csv").read_text(encoding="utf-8")
    main = pd.read_csv(two_cars / "summary.csv", comment="#", index_col=0)
    assert len(main) == 2 * (10 + 4)  # every response of both cars, nothing else
    cars = _comment_table(text, "Per car and for the train")
    assert list(cars.index) == ["car1", "car2", "train"]
    ds = load_netcdf(two_cars / "results.nc")
    force = ds["contact_force_rms"].values
    # %.6g in the file: 6 significant digits
    for car in (1, 2):
        body = main.loc[f"car{car}.carbody.bounce", "rms"]
        assert cars.loc[f"car{car}", "car body bounce RMS [m/s^2]"] == pytest.approx(body, rel=1e-5)
        mine = force[4 * (car - 1) : 4 * car]
        assert cars.loc[f"car{car}", "worst contact force RMS [N]"] == pytest.approx(
            mine.max(), rel=1e-5
        )
    assert cars.loc["train", "worst contact force RMS [N]"] == pytest.approx(force.max(), rel=1e-5)


@pytest.mark.slow
def test_the_loss_of_contact_line_and_table_name_a_trains_wheels(two_cars):
    ds = load_netcdf(two_cars / "results.nc")
    worst = int(np.argmax(ds["loss_of_contact_probability"].values))
    label = f"car{worst // 4 + 1}.wheel{worst % 4 + 1}"  # four wheels per car, front to back
    text = (two_cars / "summary.csv").read_text(encoding="utf-8")
    line = next(s for s in text.splitlines() if s.startswith("# loss of contact"))
    assert f"at the worst wheel ({label}:" in line
    table = contact_table(ds)
    assert list(table.index) == [f"car{c}.wheel{j}" for c in (1, 2) for j in range(1, 5)]


def test_a_single_cars_contact_table_keeps_the_wheel_numbers():
    assert list(contact_table(run(_case())).index) == [1, 2, 3, 4]


def test_a_stiff_coupler_joins_the_car_body_ends():
    # a coupler of 1e10 N/m between the bodies: at the coupler point (mid-gap) the two car
    # bodies move together; without a coupler they move apart by as much as they move
    f = np.geomspace(0.5, 5.0, 20)

    def ends(stiffness):
        system = build_system(_case(cars=2, gap_m=4.0, coupler_stiffness_n_per_m=stiffness))
        v = system.vehicle
        frf = system.frf(f)
        x = (v.wheels[3].x + v.wheels[4].x) / 2  # the middle of the gap
        rows = []
        for car in (1, 2):
            b = next(b for b in v.bodies if b.name == f"car{car}.carbody")
            bounce = frf.vehicle[:, v.dofs.index(f"{b.name}.bounce")]
            pitch = frf.vehicle[:, v.dofs.index(f"{b.name}.pitch")]
            rows.append(bounce + (x - b.x) * pitch)
        return rows

    front, rear = ends(1e10)
    # the coupler carries about the car body's inertia force M_c (2 pi f)^2 u at most, so
    # the ends part by at most M_c (2 pi f)^2 / k = 2.2e-3 (5 Hz) of the largest motion
    scale = np.abs(front).max()
    assert np.abs(front - rear).max() < 2.5e-3 * scale
    front, rear = ends(0.0)
    assert np.abs(front - rear).max() > 0.1 * np.abs(front).max()


def test_summary_csv_writes_extra_tables_as_comments():
    table = pd.DataFrame({"rms": [1.5, 2.5]}, index=pd.Index(["a", "b"], name="response"))
    cars = pd.DataFrame({"worst [N]": [3.5, 4.25]}, index=pd.Index(["car1", "train"], name="car"))
    text = summary_csv(table, ["case: x"], ["loss of contact: y"], extra=[("Per car", cars)])
    back = pd.read_csv(io.StringIO(text), comment="#", index_col=0)
    pd.testing.assert_frame_equal(back, table)  # the comment block leaves the table alone
    pd.testing.assert_frame_equal(_comment_table(text, "Per car"), cars)
