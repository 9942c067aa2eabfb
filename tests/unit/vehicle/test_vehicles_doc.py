"""docs/vehicles.md: its examples run and its quoted messages are the library's."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from railvib.case import case_from_dict
from railvib.errors import CaseError

DOC = Path(__file__).resolve().parents[3] / "docs" / "vehicles.md"


def test_python_example_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), flags=re.S)
    assert blocks
    for block in blocks:
        exec(compile(block, str(DOC), "exec"), {})  # noqa: S102


def test_toml_example_is_a_valid_case():
    (block,) = re.findall(r"```toml\n(.*?)```", DOC.read_text(), flags=re.S)
    case = case_from_dict(tomllib.loads(block), warn=False)
    assert case.train is not None
    assert case.train.cars == 6


def test_quoted_mass_error_is_the_librarys():
    doc = DOC.read_text()
    quoted = "vehicle.bodies[1].mass_kg = -5.0: must be > 0 and <= 1e+07 (kg)"
    assert quoted in doc
    bodies = [
        {"name": "carbody", "mass_kg": 2e4, "pitch_inertia_kg_m2": 5e5},
        {"name": "ws1", "mass_kg": -5.0, "x_m": 4.0},
    ]
    vehicle = {"model": "multibody", "bodies": bodies, "wheels": [{"body": "ws1"}]}
    with pytest.raises(CaseError) as err:
        case_from_dict({"preset": "wang2017_metro", "vehicle": vehicle})
    assert str(err.value) == quoted
