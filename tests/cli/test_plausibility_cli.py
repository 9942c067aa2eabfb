"""``railvib run`` prints each plausibility warning on one line and refuses a huge grid."""

import pytest

from railvib.cli.main import main

CASE = (
    'preset = "wang2017_metro"\n{extra}[frequency]\nf_min = 1.0\nf_max = 20.0\nstep = {step}\n'
    "[output]\nrms_bands = [[1.0, 20.0]]\n"
)


def _case(tmp_path, extra="", step=1.0):
    path = tmp_path / "case.toml"
    path.write_text(CASE.format(extra=extra, step=step))
    return path


@pytest.mark.filterwarnings("default::railvib.errors.PlausibilityWarning")
def test_a_warning_is_one_line_on_stderr_and_the_case_runs(tmp_path, capsys):
    path = _case(tmp_path, extra="speed_kmh = 500.0\n[track]\npad_temperature_c = -30.0\n")
    assert main(["run", str(path), "-o", str(tmp_path / "out"), "--no-plots"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2, err  # no file name, no source line, no traceback
    assert err[0].startswith("warning: speed_kmh = 500.0: above 10-450 km/h")
    assert err[1].startswith("warning: track.pad_temperature_c = -30.0: ignored")
    assert (tmp_path / "out" / "results.nc").exists()


def test_a_warning_escalated_by_w_error_is_a_one_line_error(tmp_path, capsys):
    # pytest runs with filterwarnings = error, as `python -W error` would
    path = _case(tmp_path, extra="speed_kmh = 500.0\n")
    assert main(["run", str(path), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: speed_kmh = 500.0: above 10-450 km/h")
    assert err.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_a_huge_grid_is_refused_with_its_cost_and_the_way_out(tmp_path, capsys):
    path = _case(tmp_path, step=1e-6)  # 19,000,001 frequencies
    assert main(["run", str(path), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: frequency.step = 1e-06: a grid of at most 2,000,000")
    assert "19,000,001" in err
    assert "GB of memory" in err
    assert "railvib run --force" in err
    assert err.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_run_has_a_force_option(capsys):
    assert main(["run", "--help"]) == 0
    assert "--force" in capsys.readouterr().out
