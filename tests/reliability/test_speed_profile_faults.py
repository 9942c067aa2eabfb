"""Bad speed profiles on the command line: one field-named line with the limits, exit 2, no output.

The limits in the expected messages are worked out here from the case's numbers: the
Nyquist step ``wavelength_min / (2 v_max)``, and one period of the slowest mode of the
paper's car (Table 1), its body bouncing on the secondary springs in series with the
primaries of each bogie: ``k = 2 / (1 / 2.75e5 + 1 / (2 * 1.7e6)) = 5.09e5 N/m``,
``f_1 = sqrt(k / 21920) / (2 pi) = 0.767 Hz`` (bogie masses and damping neglected: about
1 % off, so such limits are compared to 2 %).
"""

from __future__ import annotations

import re

import pytest

from railvib.cli.main import main

BASE = 'preset = "wang2017_metro"\nmode = "nonstationary"\n'
NS = "[nonstationary]\nn_wavenumbers = 32\nmap_times = 3\n"
F_1 = (2.0 / (1.0 / 2.75e5 + 1.0 / 3.4e6) / 21920.0) ** 0.5 / (2.0 * 3.141592653589793)


def _uniform(v0: float, v1: float, extra: str = "acceleration_ms2 = 1.0") -> str:
    return f'[speed_profile]\nkind = "uniform"\nv_start_kmh = {v0}\nv_end_kmh = {v1}\n{extra}\n'


def _table(speeds: list[float], axis: str = "time_s") -> str:
    values = [float(i) for i in range(len(speeds))]
    return f'[speed_profile]\nkind = "table"\n{axis} = {values}\nspeeds_kmh = {speeds}\n'


CASES = {
    "negative-speed": (_uniform(30.0, -10.0), "speed_profile.v_end_kmh", ">= 0"),
    "negative-table-speed": (_table([10.0, -5.0, 10.0]), "speed_profile.speeds_kmh[1]", ">= 0"),
    "stop-and-restart": (
        _table([20.0, 0.0, 20.0]),
        "speed_profile.speeds_kmh[1]",
        "does not start again",
    ),
    "stop-and-restart-by-position": (
        _table([20.0, 0.0, 20.0, 10.0], axis="position_m"),
        "speed_profile.speeds_kmh[1]",
        "does not start again",
    ),
    "does-not-move": (_table([0.0, 0.0, 0.0]), "speed_profile.speeds_kmh", "some speed > 0"),
    "constant-zero": (
        '[speed_profile]\nkind = "constant"\nspeed_kmh = 0.0\nduration_s = 10.0\n',
        "speed_profile.speed_kmh",
        "moves",
    ),
    "same-start-and-end": (_uniform(40.0, 40.0), "speed_profile.v_end_kmh", "constant"),
    "time-not-increasing": (
        '[speed_profile]\nkind = "table"\ntime_s = [0.0, 2.0, 2.0]\n'
        "speeds_kmh = [10.0, 20.0, 30.0]\n",
        "speed_profile.time_s[2]",
        "increase",
    ),
    # 80 km/h = 22.22 m/s, wavelength_min 1 m: dt <= 1 / (2 * 22.22) = 0.0225 s
    "step-too-coarse": (
        _uniform(80.0, 0.0) + "time_step_s = 0.05\n",
        "speed_profile.time_step_s",
        "<= 0.0225 s",
    ),
    # 10 -> 0 km/h (2.78 m/s) in one period 1 / f_1 or more: braking <= 2.78 f_1 m/s^2
    "too-short-for-slowest-mode": (
        _uniform(10.0, 0.0, "acceleration_ms2 = 10.0"),
        "speed_profile.acceleration_ms2",
        ("acceleration_ms2 <= ", 10.0 / 3.6 * F_1),
    ),
    "constant-too-short": (
        '[speed_profile]\nkind = "constant"\nduration_s = 0.5\n',
        "speed_profile.duration_s",
        ("must last >= ", 1.0 / F_1),
    ),
    "key-of-another-kind": (
        _uniform(30.0, 0.0) + "speeds_kmh = [1.0, 2.0]\n",
        "speed_profile.speeds_kmh",
        "not a key of kind 'uniform'",
    ),
    "missing-profile": ("", "speed_profile", "required"),
    "unknown-kind": ('[speed_profile]\nkind = "sinusoidal"\n', "speed_profile.kind", "one of"),
}


@pytest.mark.parametrize(("profile", "field", "limit"), CASES.values(), ids=CASES)
def test_bad_speed_profile_is_one_field_named_line(
    tmp_path, monkeypatch, capsys, profile, field, limit
):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(BASE + profile + NS, encoding="utf-8")
    before = set(tmp_path.rglob("*"))
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 2
    captured = capsys.readouterr()
    lines = [s for s in captured.err.splitlines() if s.strip() and not s.startswith("warning:")]
    assert len(lines) == 1, captured.err
    assert lines[0].startswith(f"error: {field} = "), lines[0]
    if isinstance(limit, tuple):  # a limit from a physical estimate: compared to 2 %
        text, value = limit
        found = re.search(re.escape(text) + r"([0-9.]+)", lines[0])
        assert found, lines[0]
        assert float(found.group(1)) == pytest.approx(value, rel=0.02), lines[0]
    else:
        assert limit in lines[0], lines[0]
    assert "Traceback" not in captured.out + captured.err
    assert set(tmp_path.rglob("*")) == before


def test_profile_in_a_stationary_case_is_refused(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    text = 'preset = "wang2017_metro"\n' + _uniform(30.0, 0.0)
    (tmp_path / "case.toml").write_text(text, encoding="utf-8")
    before = set(tmp_path.rglob("*"))
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert err[0].startswith("error: speed_profile = "), err
    assert "mode" in err[0]
    assert set(tmp_path.rglob("*")) == before
