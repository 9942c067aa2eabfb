"""Issue 10, items 2 and 3: every run summary echoes its case and flags results beyond PEM.

Expected values come from the definitions: 80 km/h = 80/3.6 m/s = 22.22 m/s; the
Gaussian loss-of-contact probability Phi(-P0/sigma) with sigma^2 the integral of the
one-sided force PSD (Phi(-2) = 0.0227501..., Phi(-4) = 3.1671...e-5, tabulated).
"""

import numpy as np
import pandas as pd
import pytest
import tomli_w
import xarray as xr

import railvib
from railvib.case import case_header
from railvib.cli.main import main
from railvib.outputs import LOSS_OF_CONTACT_NOTE, ContactCheck, is_linear_model_valid
from railvib.solve import run_to_folder

COARSE = {"f_min": 1.0, "f_max": 200.0, "step": 1.0}

#: the issue's example: a cold (stiff) pad, a poor track, a fast train
STIFF = {
    "preset": "wang2017_metro",
    "title": "cold stiff pad, FRA class 1, 140 km/h",
    "speed_kmh": 140.0,
    "track": {
        "pad": {"model": "spring_damper", "stiffness_n_per_m": 1.0e9, "damping_ns_per_m": 5.0e4}
    },
    "irregularity": {"type": "fra", "class_number": 1},
    "frequency": COARSE,
}
DEFAULT = {"preset": "wang2017_metro", "frequency": COARSE}

PHI_MINUS_2 = 0.022750131948179195  # standard normal CDF at -2 (tables)
PHI_MINUS_4 = 3.167124183311998e-05  # standard normal CDF at -4 (tables)


def _toml(tmp_path, d, name):
    path = tmp_path / name
    path.write_text(tomli_w.dumps(d))
    return path


# --------------------------------------------------------------------------- the header


def test_case_header_states_title_speed_pad_irregularity_and_band():
    case = railvib.case_from_dict({**DEFAULT, "speed_kmh": 120.0, "title": "my case"})
    lines = case_header(case)
    text = "\n".join(lines)
    assert lines[0] == "case: my case"
    assert "speed: 120 km/h (33.33 m/s)" in lines  # 120 / 3.6 = 33.333
    pad = next(line for line in lines if line.startswith("pad: "))
    assert pad.startswith("pad: spring_damper (stiffness_n_per_m = 5e+07")
    assert "pad temperature 20 degC" in pad
    irr = next(line for line in lines if line.startswith("irregularity: "))
    assert irr.startswith("irregularity: combined")
    assert "fra (class_number = 5)" in irr
    assert "shitai" in irr
    # the band and the wavelengths it covers at 33.33 m/s: 33.33 m down to 0.1667 m
    assert (
        "frequency band: 1-200 Hz (linear grid, step 1 Hz; wavelengths 33.33 m to 0.1667 m" in text
    )


def test_a_temperature_dependent_pad_is_not_called_independent():
    from tests.unit.sweep.sweep_cases import BASE_CASE

    pad = [line for line in case_header(railvib.case_from_dict(BASE_CASE)) if "pad:" in line]
    assert pad[0].startswith("pad: fractional_zener")
    assert pad[0].endswith("pad temperature 20 degC")


@pytest.fixture(scope="module")
def folders(tmp_path_factory):
    root = tmp_path_factory.mktemp("runs")
    ok = run_to_folder(railvib.case_from_dict(DEFAULT), root / "ok", plots=False)
    bad = run_to_folder(railvib.case_from_dict(STIFF), root / "bad", plots=False)
    return root, ok, bad


def test_summary_files_are_headed_by_the_case(folders):
    root, ok, _ = folders
    title = railvib.load_preset_case().title
    csv_text = (root / "ok" / "summary.csv").read_text()
    comments = [line for line in csv_text.splitlines() if line.startswith("# ")]
    assert f"# case: {title}" in comments
    assert "# speed: 80 km/h (22.22 m/s)" in comments
    assert any(line.startswith("# pad: spring_damper") for line in comments)
    assert any(line.startswith("# irregularity: combined") for line in comments)
    assert any(line.startswith("# frequency band: 1-200 Hz") for line in comments)
    assert any(line.startswith("# loss of contact: ") for line in comments)
    table = pd.read_csv(root / "ok" / "summary.csv", comment="#", index_col=0)
    assert list(table.index) == [str(r) for r in ok.dataset["response"].values]
    assert table.loc["carbody.pitch", "rms_unit"] == "rad/s^2"
    assert table.loc["wheelset1.bounce", "peak_unit"] == "(m/s^2)^2/Hz"
    md = (root / "ok" / "summary.md").read_text()
    assert md.startswith(f"# {title}\n")
    assert "- speed: 80 km/h (22.22 m/s)" in md
    assert "## Contact check per wheel" in md
    assert ok.text().startswith(f"case: {title}\nspeed: 80 km/h (22.22 m/s)\n")


def test_the_force_csv_is_written_beside_the_others(folders):
    root, ok, _ = folders
    assert (root / "ok" / "psd_force.csv") in ok.files
    head = (root / "ok" / "psd_force.csv").read_text().splitlines()[0]
    assert head == "frequency [Hz],wheel1 [N^2/Hz],wheel2 [N^2/Hz],wheel3 [N^2/Hz],wheel4 [N^2/Hz]"


# --------------------------------------------------------------------- validity flag


def _flat_force(levels_n2_per_hz, loads_n):
    """Flat force PSDs on 0..10 Hz (trapezoid exact): sigma^2 = 10 S0."""
    f = np.arange(0.0, 11.0)
    levels = np.atleast_1d(levels_n2_per_hz)
    psd = np.broadcast_to(levels[:, None, None], (levels.size, f.size, 2)).copy()
    loads = np.broadcast_to(np.asarray(loads_n, dtype=float)[:, None], (levels.size, 2))
    return xr.Dataset(
        {
            "psd_force": (("case", "frequency", "wheel"), psd),
            "static_contact_load": (("case", "wheel"), loads.copy()),
        },
        coords={"frequency": f, "wheel": [1, 2]},
    )


def test_flag_against_the_gaussian_closed_form():
    s0 = 4.0e6  # N^2/Hz over 10 Hz: sigma = sqrt(4e7) N
    sigma = np.sqrt(10.0 * s0)
    ds = _flat_force([s0, s0], [2.0 * sigma, 4.0 * sigma])
    out = ContactCheck().compute(ds)
    # trapezoid of a constant is exact; Phi from scipy to ~1e-15 relative: 1e-12
    np.testing.assert_allclose(out["contact_force_rms"].values, sigma, rtol=1e-12)
    np.testing.assert_allclose(
        out["loss_of_contact_probability"].values,
        [[PHI_MINUS_2] * 2, [PHI_MINUS_4] * 2],
        rtol=1e-12,
    )
    assert out["linear_model_valid"].dims == ("case",)
    assert list(out["linear_model_valid"].values) == [False, True]  # 2.3 % > 1 %, 0.003 % < 1 %
    assert out["linear_model_valid"].attrs["loss_of_contact_threshold"] == LOSS_OF_CONTACT_NOTE
    relaxed = ContactCheck(loss_of_contact_threshold=0.05).compute(ds)
    assert list(relaxed["linear_model_valid"].values) == [True, True]


def test_threshold_must_be_a_probability():
    with pytest.raises(railvib.CaseError):
        ContactCheck(loss_of_contact_threshold=1.5)
    with pytest.raises(railvib.CaseError) as err:
        railvib.case_from_dict({**DEFAULT, "output": {"loss_of_contact_threshold": 0.0}})
    assert err.value.field == "output.loss_of_contact_threshold"


def _probability_by_definition(ds):
    """Phi(-P0/sigma), sigma^2 = trapezoid of psd_force, written out here."""
    from scipy.stats import norm

    f = ds["frequency"].values
    psd = ds["psd_force"].values
    var = (0.5 * (psd[1:] + psd[:-1]) * np.diff(f)[:, None]).sum(axis=0)
    return norm.cdf(-ds["static_contact_load"].values / np.sqrt(var))


def test_the_stiff_fast_case_is_beyond_the_linear_model(folders):
    _, ok, bad = folders
    for out, valid in ((ok, True), (bad, False)):
        ds = out.dataset
        # summation order differs from scipy's trapezoid: 1e-12 relative
        np.testing.assert_allclose(
            ds["loss_of_contact_probability"].values, _probability_by_definition(ds), rtol=1e-12
        )
        assert bool(ds["linear_model_valid"]) is valid
        assert out.linear_model_valid is valid
    worst = float(bad.dataset["loss_of_contact_probability"].max())
    assert 0.3 < worst < 0.5  # the example: about 40 %
    assert "BEYOND THE LINEAR MODEL" in bad.contact
    assert "linear model valid" in ok.contact
    summary_csv = next(p for p in bad.files if p.name == "summary.csv")
    table = pd.read_csv(summary_csv, comment="#", index_col=0)  # readable as a table
    assert len(table) == bad.dataset.sizes["response"]


def test_the_threshold_is_set_in_the_output_section():
    lenient = railvib.run(
        railvib.case_from_dict({**STIFF, "output": {"loss_of_contact_threshold": 0.45}})
    )
    assert bool(lenient["linear_model_valid"])
    strict = railvib.run(
        railvib.case_from_dict({**DEFAULT, "output": {"loss_of_contact_threshold": 1e-4}})
    )
    assert not bool(strict["linear_model_valid"])  # 0.11 % > 0.01 %
    assert not is_linear_model_valid(strict)


def test_the_flag_survives_netcdf(folders, tmp_path):
    _, _, bad = folders
    loaded = railvib.load_netcdf(railvib.save_netcdf(bad.dataset, tmp_path / "r.nc"))
    assert loaded["linear_model_valid"].dtype == bool
    assert not bool(loaded["linear_model_valid"])
    assert loaded["linear_model_valid"].attrs == bad.dataset["linear_model_valid"].attrs


def test_run_strict_exits_3_beyond_the_linear_model_and_still_writes(tmp_path, capsys):
    stiff = _toml(tmp_path, STIFF, "stiff.toml")
    fine = _toml(tmp_path, DEFAULT, "fine.toml")
    assert main(["run", str(stiff), "-o", str(tmp_path / "a"), "--no-plots"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(
        "case: cold stiff pad, FRA class 1, 140 km/h\nspeed: 140 km/h (38.89 m/s)"
    )
    assert "BEYOND THE LINEAR MODEL" in out
    assert main(["run", str(stiff), "-o", str(tmp_path / "b"), "--no-plots", "--strict"]) == 3
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: --strict: loss of contact: probability 41")
    assert err.count("\n") == 0
    assert (tmp_path / "b" / "summary.csv").exists()
    assert main(["run", str(fine), "-o", str(tmp_path / "c"), "--no-plots", "--strict"]) == 0
