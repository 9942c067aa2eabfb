"""Bad vehicle files on the command line: one field-named line, exit 2, no output left."""

from __future__ import annotations

import pytest

from railvib.cli.main import main

BASE = (
    'preset = "wang2017_metro"\n[frequency]\nspacing = "log"\nf_min = 1.0\nf_max = 100.0\nn = 8\n'
)
CAR = """model = "multibody"
[[bodies]]
name = "carbody"
mass_kg = {mass}
pitch_inertia_kg_m2 = 5.0e5
[[bodies]]
name = "ws1"
mass_kg = 1200.0
x_m = 4.0
[[bodies]]
name = "ws2"
mass_kg = 1200.0
x_m = -4.0
{extra}
[[suspensions]]
upper = "carbody"
lower = "ws1"
stiffness_n_per_m = 1e6
[[suspensions]]
upper = "carbody"
lower = "ws2"
stiffness_n_per_m = 1e6
[[wheels]]
body = "ws1"
[[wheels]]
body = "{wheel2}"
"""
LOOSE = '[[bodies]]\nname = "loose"\nmass_kg = 10.0\n'

CASES = {
    "negative-mass": (CAR.format(mass=-2e4, extra="", wheel2="ws2"), "vehicle.bodies[0].mass_kg"),
    "unconnected-body": (CAR.format(mass=2e4, extra=LOOSE, wheel2="ws2"), "vehicle.bodies[3]"),
    "wheel-on-no-body": (CAR.format(mass=2e4, extra="", wheel2="ws9"), "vehicle.wheels[1].body"),
    "duplicate-wheel": (CAR.format(mass=2e4, extra="", wheel2="ws1"), "vehicle.wheels[1].body"),
    "not-toml": ("bodies = [[[", "vehicle.file"),
    "empty": ("", "vehicle.file"),
}


def _run(tmp_path, monkeypatch, capsys, case_text, field):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(case_text, encoding="utf-8")
    before = set(tmp_path.rglob("*"))
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 2
    captured = capsys.readouterr()
    lines = [s for s in captured.err.splitlines() if s.strip() and not s.startswith("warning:")]
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("error: "), lines[0]
    assert field in lines[0], lines[0]
    assert "Traceback" not in captured.out + captured.err
    assert set(tmp_path.rglob("*")) == before


@pytest.mark.parametrize(("car", "field"), CASES.values(), ids=CASES)
def test_bad_vehicle_file_is_one_field_named_line(tmp_path, monkeypatch, capsys, car, field):
    (tmp_path / "car.toml").write_text(car, encoding="utf-8")
    _run(tmp_path, monkeypatch, capsys, BASE + '[vehicle]\nfile = "car.toml"\n', field)


@pytest.mark.parametrize(
    ("vehicle", "field"),
    [
        ('file = "missing.toml"', "vehicle.file"),
        ('preset = "crh9"', "vehicle.preset"),
        ('file = "car.toml"\ncarbody_mass = 1.0', "vehicle.carbody_mass"),
        ("file = 3", "vehicle.file"),
    ],
    ids=["missing-file", "unknown-preset", "file-and-key", "not-a-path"],
)
def test_bad_vehicle_reference_is_one_field_named_line(
    tmp_path, monkeypatch, capsys, vehicle, field
):
    (tmp_path / "car.toml").write_text(CAR.format(mass=2e4, extra="", wheel2="ws2"), "utf-8")
    _run(tmp_path, monkeypatch, capsys, BASE + f"[vehicle]\n{vehicle}\n", field)


@pytest.mark.parametrize(
    ("train", "field"),
    [
        ("cars = 0", "train.cars"),
        ("cars = 1000", "train.cars"),
        ("cars = 2\ngap_m = -1.0", "train.gap_m"),
        ("cars = 2\ncoupler_damping_ns_per_m = 1e4", "train.coupler_stiffness_n_per_m"),
        ("cars = 2\nlength = 3", "train.length"),
    ],
    ids=["no-cars", "too-many-cars", "negative-gap", "damper-without-spring", "unknown-key"],
)
def test_bad_train_is_one_field_named_line(tmp_path, monkeypatch, capsys, train, field):
    _run(tmp_path, monkeypatch, capsys, BASE + f"[train]\n{train}\n", field)


def test_sweep_over_vehicle_topology_is_refused_on_one_line(tmp_path, monkeypatch, capsys):
    # the cases of a sweep share one response axis: another topology (a car of three
    # wheelsets against one of two) changes it (before the check: IndexError traceback from
    # the batched solve); a train length is swept with train.cars (tests/unit/vehicle/
    # test_train15_sweep.py)
    (tmp_path / "base.toml").write_text(BASE + '[vehicle]\nfile = "car.toml"\n', "utf-8")
    (tmp_path / "car.toml").write_text(CAR.format(mass=2e4, extra="", wheel2="ws2"), "utf-8")
    sweep = (
        'base = "base.toml"\n[[axes]]\nfield = "vehicle"\nlabels = ["two", "three"]\n'
        f"values = [{_inline_car(2)}, {_inline_car(3)}]\n"
    )
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sweep.toml").write_text(sweep, encoding="utf-8")
    before = set(tmp_path.rglob("*"))
    assert main(["sweep", "sweep.toml", "-o", "out"]) == 2
    captured = capsys.readouterr()
    lines = [s for s in captured.err.splitlines() if s.strip() and not s.startswith("warning:")]
    assert len(lines) == 1, captured.err
    assert "axes.vehicle" in lines[0]
    assert "Traceback" not in captured.out + captured.err
    assert set(tmp_path.rglob("*")) == before


def _inline_car(n: int) -> str:
    """A car body on `n` wheelsets as one TOML inline table (a whole [vehicle] table)."""
    bodies = ['{ name = "carbody", mass_kg = 2.0e4, pitch_inertia_kg_m2 = 5.0e5 }'] + [
        f'{{ name = "ws{i}", mass_kg = 1200.0, x_m = {4.0 - 8.0 * i / n} }}' for i in range(n)
    ]
    springs = [
        f'{{ upper = "carbody", lower = "ws{i}", stiffness_n_per_m = 1e6 }}' for i in range(n)
    ]
    wheels = [f'{{ body = "ws{i}" }}' for i in range(n)]
    return (
        f'{{ model = "multibody", bodies = [{", ".join(bodies)}], '
        f"suspensions = [{', '.join(springs)}], wheels = [{', '.join(wheels)}] }}"
    )
