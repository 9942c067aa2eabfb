"""Issue 10 ("a new user's first hour"): each mistake a new user made, as a regression test.

Every user mistake ends in one line ``error: ...`` naming the field or file and what
to do, exit code 2, before anything is computed or written.
"""

import re
import warnings

import pytest

from railvib.case import case_from_dict
from railvib.cli.main import main
from railvib.errors import CaseError, PlausibilityWarning
from railvib.io import binary_kind, read_toml
from railvib.pads import PadModel

HDF5 = b"\x89HDF\r\n\x1a\n" + bytes(range(256))  # the start of every netCDF-4 file


def _one_error_line(capsys):
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("error: ")
    assert "Traceback" not in captured.err
    return lines[0]


# ---------------------------------------------------------------- item 1: binary case files


@pytest.mark.parametrize(
    ("data", "kind"),
    [
        (HDF5, "a netCDF-4/HDF5 file"),
        (b"CDF\x01\x00\x00\x00\x00", "a netCDF file"),
        (b"\x89PNG\r\n\x1a\n\x00\x00", "a PNG image"),
        (bytes(range(256)), "a binary file"),
        (b"title = 'caf\xc3\xa9'\n", None),  # UTF-8 text is text
    ],
)
def test_binary_kind_names_the_usual_files(data, kind):
    found = binary_kind(data)
    assert found is None if kind is None else found.startswith(kind)


def test_a_netcdf_file_given_as_the_case_is_one_line(tmp_path, capsys):
    case = tmp_path / "results.nc"
    case.write_bytes(HDF5)
    out = tmp_path / "out"
    assert main(["run", str(case), "-o", str(out)]) == 2
    line = _one_error_line(capsys)
    assert line.startswith(f"error: case = '{case}': a TOML case file, not a netCDF-4/HDF5 file")
    assert "railvib template" in line  # what to do
    assert not out.exists()


def test_an_empty_case_file_says_so(tmp_path):
    path = tmp_path / "empty.toml"
    path.write_text("\n  \n")
    with pytest.raises(CaseError, match="a TOML case file, not an empty file"):
        read_toml(path, "case", "`railvib template > case.toml` writes one")


# ---------------------------------------------------------------- item 1: RMS bands


@pytest.mark.parametrize(
    ("band", "holds"),
    [
        ([0.52, 0.58], 0),  # between two points of the 0.1 Hz grid
        ([1500.0, 2000.0], 0),  # above the grid
        ([0.1, 0.4], 0),  # below the grid
        ([0.55, 0.65], 1),  # one point: the trapezoidal integral would be 0
    ],
)
def test_rms_band_the_grid_cannot_resolve_is_refused_when_the_case_loads(band, holds):
    with pytest.raises(CaseError) as info:
        case_from_dict({"preset": "wang2017_metro", "output": {"rms_bands": [[1.0, 2.0], band]}})
    assert info.value.field == "output.rms_bands[1]"
    assert f"holds {holds})" in info.value.allowed
    assert "[0.5, 1000] Hz" in info.value.allowed


def test_a_band_reaching_past_the_grid_is_kept_as_before():
    case = case_from_dict({"preset": "wang2017_metro", "output": {"rms_bands": [[500, 2000]]}})
    assert case.output.rms_bands == [(500.0, 2000.0)]


def test_bad_rms_band_writes_nothing(tmp_path, capsys):
    case = tmp_path / "c.toml"
    case.write_text('preset = "wang2017_metro"\n[output]\nrms_bands = [[1500, 2000]]\n')
    out = tmp_path / "out"
    assert main(["run", str(case), "-o", str(out), "--no-plots"]) == 2
    line = _one_error_line(capsys)
    assert re.match(r"error: output\.rms_bands\[0\] = \[1500\.0, 2000\.0\]: ", line)
    assert not out.exists()


# ---------------------------------------------------------------- item 1: pad fit on a case file


def test_pad_fit_on_a_case_file_says_it_is_not_a_measurements_csv(tmp_path, capsys):
    case = tmp_path / "my_case.toml"
    assert main(["template"]) == 0
    case.write_text(capsys.readouterr().out)
    out = tmp_path / "out"
    assert main(["pad", "fit", str(case), "-o", str(out)]) == 2
    line = _one_error_line(capsys)
    assert line.startswith(f"error: data = '{case}': a measurements CSV, not a TOML file")
    assert "temperature_c, frequency_hz, storage_n_per_m or storage_kn_per_mm" in line
    assert "railvib pad example" in line  # where a good file comes from
    assert "title" not in line  # the case's first key is not read as a column
    assert not out.exists()


@pytest.mark.parametrize(
    ("data", "message"),
    [
        (HDF5, "a measurements CSV, not a netCDF-4/HDF5 file"),
        (b"", "it is empty"),
        (b"a,b\n1,2\n", "whose header row names its columns (this one is 'a,b')"),
        (
            b"temperature_c,frequency_hz,storage_kn_per_mm,los_factor\n1,2,3,4\n",
            "unknown column; columns from temperature_c,",
        ),
    ],
)
def test_measurements_csv_errors_name_the_file_and_the_columns(tmp_path, data, message):
    from railvib.pads import read_measurements_csv

    path = tmp_path / "d.csv"
    path.write_bytes(data)
    with pytest.raises(CaseError, match=re.escape(message)):
        read_measurements_csv(path)


# ---------------------------------------------------------------- item 7: did you mean


@pytest.mark.parametrize(
    ("overrides", "field", "suggestion"),
    [
        ({"speed_kmhh": 80.0}, "speed_kmhh", "speed_kmh"),  # pydantic: a fixed section
        ({"vehicle": {"carbody_mas": 1.0}}, "vehicle.carbody_mas", "carbody_mass"),
        ({"track": {"rail": {"shear_stifness": 1.0}}}, "track.rail.shear_stifness", None),
        (  # a family table (Registry.from_dict)
            {"track": {"pad": {"model": "spring_damper", "stiffness_n_per_m": 5e7, "dampin": 1}}},
            "track.pad.dampin",
            None,
        ),
        ({"track": {"pad": {"model": "fractional_zenr"}}}, "track.pad.model", "fractional_zener"),
        (  # a plain table of a family (take_table)
            {"track": {"pad": {"tts": {"reference_temperature": 20.0}}}},
            "track.pad.tts.reference_temperature",
            "reference_temperature_c",
        ),
        ({"irregularity": {"type": "fra", "clas_number": 5}}, "irregularity.clas_number", None),
        ({"rail_model": "rail_pairs"}, "rail_model", "rail_pair"),
        ({"preset": "wang2017_metr"}, "preset", "wang2017_metro"),
    ],
)
def test_unknown_keys_and_names_suggest_the_closest(overrides, field, suggestion):
    with pytest.raises(CaseError) as info:
        case_from_dict({"preset": "wang2017_metro", **overrides})
    assert info.value.field == field
    if suggestion is None:  # the key itself, less its typo
        suggestion = {
            "track.rail.shear_stifness": "shear_stiffness",
            "track.pad.dampin": "damping_ns_per_m",
            "irregularity.clas_number": "class_number",
        }[field]
    assert info.value.allowed.endswith(f"; did you mean {suggestion!r}?")


def test_no_suggestion_when_nothing_is_close():
    with pytest.raises(CaseError) as info:
        case_from_dict({"preset": "wang2017_metro", "colour": "red"})
    assert "did you mean" not in str(info.value)


# ---------------------------------------------------------------- item 1: passivity and round-off

COLD_ZENER = {
    "model": "fractional_zener",
    "k0_n_per_m": 4.0e7,
    "k_inf_n_per_m": 2.0e8,
    "tau_s": 1.0e-3,
    "alpha": 0.4,
    "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -50.0},
}


def test_a_cold_wlf_pad_is_not_refused_for_round_off_in_its_loss():
    # at -85 degC the shifted Zener is deep in its glassy plateau: K'' ~ 1e-17 |K*| on
    # parts of the grid, computed with either sign; it used to be "a passive pad needs
    # K' > 0 and K'' >= 0 ... K*(9.2 Hz) = 1.352e+08-6.609e-09j"
    with pytest.warns(PlausibilityWarning, match="outside"):  # beyond its WLF range: warned
        case = case_from_dict(
            {"preset": "wang2017_metro", "track": {"pad": COLD_ZENER, "pad_temperature_c": -85.0}}
        )
    assert case.track.pad_temperature_c == -85.0


def test_the_tolerance_is_a_few_roundings_of_the_modulus():
    import numpy as np

    from railvib.pads import PASSIVITY_TOLERANCE

    eps = np.finfo(float).eps
    assert PASSIVITY_TOLERANCE == 16 * eps  # a loss factor of -3.6e-15: no real pad


class _GivesEnergyBelowMinus50(PadModel):
    """A test pad whose loss factor (T + 50)/100 turns negative below -50 degC."""

    def stiffness(self, f, temperature=None):
        import numpy as np

        eta = (20.0 if temperature is None else temperature + 50.0) / 100.0
        return np.full(np.shape(f), 5e7 * (1 + 1j * eta))


def test_a_really_non_passive_pad_names_temperature_frequency_and_why():
    import numpy as np

    pad = _GivesEnergyBelowMinus50()
    pad.check_passive(np.array([1.0, 10.0]), -40.0)  # eta = 0.1
    with pytest.raises(CaseError) as info:
        pad.check_passive(np.array([1.0, 10.0]), -60.0)  # eta = -0.1
    err = info.value
    assert err.field == "track.pad"
    assert err.value.startswith("K*(1 Hz, -60 degC) = 5e+07-5e+06j N/m")
    assert "loss factor K''/K' = -0.1 < 0 gives energy to the track" in err.allowed
    assert "round-off" in err.allowed  # the tolerance is stated


# ---------------------------------------------------------------- items 1 and 4: plot


@pytest.fixture(scope="module")
def sweep_folder(tmp_path_factory):
    """A finished 2 x 2 sweep (temperature x speed) on a coarse grid, and a run folder."""
    import copy

    from railvib.sweep import run_sweep, sweep_from_dict
    from tests.unit.sweep.sweep_cases import small_sweep

    d = small_sweep(
        axes=[
            {"field": "track.pad_temperature_c", "name": "temperature", "values": [-20.0, 20.0]},
            {"field": "speed_kmh", "name": "speed", "values": [40.0, 80.0]},
        ]
    )
    d["case"] = copy.deepcopy(d["case"])
    d["case"]["frequency"]["n"] = 30
    out = tmp_path_factory.mktemp("sweep") / "s.sweep"
    run_sweep(sweep_from_dict(d), out, workers=1, progress=False)
    return out


def _pngs(folder):
    return sorted(p.name for p in folder.glob("*.png")) if folder.exists() else []


def test_plot_with_x_equal_to_y_is_one_line(sweep_folder, tmp_path, capsys):
    out = tmp_path / "p"
    args = ["plot", str(sweep_folder), "--x", "temperature", "--y", "temperature", "-o", str(out)]
    assert main(args) == 2
    line = _one_error_line(capsys)
    assert line == (
        "error: y = 'temperature': a sweep dimension other than x = 'temperature': one of speed"
    )
    assert not out.exists()


def test_plot_y_alone_takes_the_other_dimension_for_x(sweep_folder, tmp_path):
    out = tmp_path / "p"
    args = ["--y", "temperature", "-v", "peak", "-r", "carbody.bounce", "-o", str(out)]
    assert main(["plot", str(sweep_folder), *args]) == 0
    assert _pngs(out) == ["sweep_peak_carbody_bounce.png"]  # a heat map, x = speed


def test_plot_on_a_run_folder_says_plot_takes_a_sweep(tmp_path, capsys):
    run = tmp_path / "run"
    run.mkdir()
    (run / "results.nc").write_bytes(HDF5)
    (run / "summary.md").write_text("|")
    assert main(["plot", str(run)]) == 2
    line = _one_error_line(capsys)
    assert line.startswith(f"error: sweep = '{run}': a sweep folder (written by `railvib sweep`)")
    assert "this is a folder of `railvib run`, which draws its PSD plots itself" in line
    assert not (run / "plots").exists()


def test_plot_on_an_unfinished_sweep_says_rerun(tmp_path, capsys):
    (tmp_path / "manifest.json").write_text("{}")
    assert main(["sweep", "plot", str(tmp_path)]) == 2
    assert "this sweep is unfinished (no sweep.zarr yet)" in _one_error_line(capsys)


@pytest.mark.slow  # ~1.4 s: whole commands with their files, kept out of the fast suite
def test_plot_accepts_comma_separated_and_repeated_options(sweep_folder, tmp_path):
    out = tmp_path / "p"
    args = ["-v", "peak,rms_20_100_hz", "-r", "wheelset2.bounce,rail@wheel1", "-r", "bogie1.bounce"]
    assert main(["plot", str(sweep_folder), *args, "-o", str(out)]) == 0
    assert _pngs(out) == sorted(
        f"sweep_{v}_{r}.png"
        for v in ("peak", "rms_20_100_hz")
        for r in ("wheelset2_bounce", "rail_at_wheel1", "bogie1_bounce")
    )


def test_a_bad_variable_among_good_ones_writes_no_plot(sweep_folder, tmp_path, capsys):
    out = tmp_path / "p"
    assert main(["plot", str(sweep_folder), "-v", "peak,rms_20_100", "-o", str(out)]) == 2
    assert "did you mean 'rms_20_100_hz'?" in _one_error_line(capsys)
    assert _pngs(out) == []


def test_plot_help_lists_real_labels_as_the_default(sweep_folder):
    from railvib.cli.sweep import plot
    from railvib.sweep import load_sweep_dataset

    option = next(p for p in plot.params if p.name == "responses")
    default = re.search(r"\[default: ([^\]]*)\]", option.help).group(1).split(", ")
    labels = {str(r) for r in load_sweep_dataset(sweep_folder)["response"].values}
    assert default == ["carbody.bounce", "wheelset1.bounce", "rail@wheel1"]
    shown = re.findall(r"[a-z0-9]+(?:\.bounce|\.pitch|@wheel\d)", option.help)
    assert len(shown) > 10
    assert set(shown) <= labels  # every label the help shows is one plot accepts


# ---------------------------------------------------------------- item 2: the Dask extra


def test_scheduler_without_distributed_is_one_line_before_any_work(
    sweep_folder, tmp_path, capsys, monkeypatch
):
    import sys

    import tomli_w

    from tests.unit.sweep.sweep_cases import small_sweep

    monkeypatch.setitem(sys.modules, "distributed", None)  # as if the extra were missing
    path = tmp_path / "s.toml"
    path.write_text(tomli_w.dumps(small_sweep()))
    out = tmp_path / "out"
    assert main(["sweep", str(path), "-o", str(out), "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert _one_error_line(capsys) == (
        "error: scheduler = 'tcp://127.0.0.1:1': a Dask cluster needs the \"distributed\" "
        'package: pip install "railvib[sweep]"'
    )
    assert not out.exists()


def test_the_readme_error_example_is_what_the_cli_prints(tmp_path, capsys):
    from pathlib import Path

    readme = Path(__file__).resolve().parents[2] / "README.md"
    shown = re.search(r"\$ railvib run bad\.toml\n(error: .*)\n", readme.read_text()).group(1)
    bad = tmp_path / "bad.toml"
    bad.write_text('preset = "wang2017_metro"\n[vehicle]\ncarbody_mass = -1.0\n')
    assert main(["run", str(bad), "-o", str(tmp_path / "out")]) == 2
    assert _one_error_line(capsys) == shown


# ---------------------------------------------------------------- item 3: validate


def _system(**overrides):
    from railvib.case import build_system

    return build_system(case_from_dict({"preset": "wang2017_metro", **overrides}))


@pytest.mark.parametrize(
    ("overrides", "field", "value"),
    [
        (
            {"track": {"pad": COLD_ZENER}},
            "track.pad.model",
            "fractional_zener (with [track.pad.tts])",
        ),
        ({"track": {"rail": {"shear_stiffness": 2.45e8}}}, "track.rail.shear_stiffness", 2.45e8),
        ({"track": {"rail": {"loss_factor": 0.01}}}, "track.rail.loss_factor", 0.01),
    ],
)
def test_validate_scope_names_the_users_model_before_computing(overrides, field, value):
    from railvib.validation import check_scope

    with pytest.raises(CaseError) as info:
        check_scope(_system(**overrides))
    assert (info.value.field, info.value.value) == (field, value)
    assert "railvib validate" in info.value.allowed


def test_validate_scope_takes_the_two_rail_doubling_of_a_viscous_pad():
    from railvib.validation import check_scope
    from railvib.validation.scope import viscous_pad

    system = _system(rail_model="rail_pair")
    check_scope(system)  # used to fail in the Monte Carlo: "track.pad.model = 'scaled'"
    assert viscous_pad(system.track.pad) == (2 * 5.0e7, 2 * 5.0e4)  # both rails' pads


def test_validate_out_of_scope_is_one_line_before_any_work(tmp_path, capsys, monkeypatch):
    import railvib.validation.compare as compare

    def must_not_run(*args, **kwargs):
        raise AssertionError("computed before refusing the case")

    monkeypatch.setattr(compare, "_finite_track_comparison", must_not_run)
    case = tmp_path / "zener.toml"
    case.write_text(
        'preset = "wang2017_metro"\n[track.pad]\nmodel = "fractional_zener"\nk0_n_per_m = 4e7\n'
        "k_inf_n_per_m = 2e8\ntau_s = 1e-3\nalpha = 0.4\n"
        "tts = { reference_temperature_c = 20.0, glass_transition_c = -50.0 }\n"
    )
    out = tmp_path / "out"
    assert main(["validate", str(case), "-o", str(out)]) == 2
    line = _one_error_line(capsys)  # no progress bar either
    assert line.startswith(
        "error: track.pad.model = 'fractional_zener (with [track.pad.tts])': spring_damper"
    )
    assert "temperature_shifted" not in line
    assert not out.exists()


def test_finite_track_frf_reports_each_frequency():
    import numpy as np

    from railvib.validation import FiniteCoupledSystem

    finite = FiniteCoupledSystem.from_system(_system(), margin_spans=10)
    done = []
    finite.frf(np.array([5.0, 50.0, 500.0]), progress=done.append)
    assert done == [1, 1, 1]


def _fake_result():
    import numpy as np
    import xarray as xr

    from railvib.validation import ValidationResult

    labels = [
        *(f"{b}.{d}" for b in ("carbody", "bogie1", "bogie2") for d in ("bounce", "pitch")),
        *(f"wheelset{j}.bounce" for j in range(1, 5)),
        *(f"rail@wheel{j}" for j in range(1, 5)),
    ]
    f = np.geomspace(1.0, 500.0, 5)
    grid = {"frequency": f, "response": labels}
    ones = np.ones((f.size, len(labels)))
    frf = xr.Dataset({"relative_error": (("frequency", "response"), 1e-4 * ones)}, coords=grid)
    mc = xr.Dataset(
        {n: (("frequency", "response"), ones.astype(bool)) for n in ("inside", "inside_raw")},
        coords=grid,
    )
    return ValidationResult(frf=frf, mc=mc, table=xr.Dataset(), timings={})


def test_agreement_text_fits_an_80_column_terminal():
    from railvib.validation import agreement_text

    text = agreement_text(_fake_result(), "paper_case", "validation/paper_case_agreement.md")
    lines = text.splitlines()
    assert max(len(line) for line in lines) <= 80
    assert lines[0] == "Agreement per response (paper_case)"
    assert lines[2].split() == ["carbody.bounce", "1.00e-04", "100.0%", "100.0%"]
    assert lines[-2] == "Acceptance (issue 5): PASSED (FE error <= 2%, PEM in band >= 90%)"
    assert lines[-1] == "per-band tables and timings: validation/paper_case_agreement.md"


def test_validate_shows_both_stages_and_the_compact_table(tmp_path, capsys, monkeypatch):
    import railvib.validation as validation_api
    from railvib.validation import ValidationSettings

    calls = {}

    def fake(system, spectrum, outdir, *, settings, seed, progress, name, frf_progress):
        frf_progress(settings.n_frf)
        progress(10)
        calls["settings"] = settings
        return _fake_result()

    monkeypatch.setattr(validation_api, "validate_to_folder", fake)  # the CLI's one call
    monkeypatch.setenv("COLUMNS", "80")
    case = tmp_path / "metro.toml"
    case.write_text('preset = "wang2017_metro"\n')
    assert main(["validate", str(case), "--quick", "-o", str(tmp_path / "v")]) == 0
    out = capsys.readouterr().out
    assert calls["settings"] == ValidationSettings.quick()
    assert "finite track (frequencies)" in out
    assert "Monte Carlo (Newmark steps)" in out
    assert "| response |" not in out  # no Markdown table on the terminal
    assert max(len(line) for line in out.splitlines()) <= 80


# ---------------------------------------------------------------- item 5: the template


def _key_lines(text):
    """``(line number, line)`` of every key, commented-out key and table header."""
    for i, line in enumerate(text.splitlines()):
        bare = line.removeprefix("# ")
        if re.match(r"^\[[a-z_.]+\]$", line) or re.match(r"^[a-z_0-9]+ = ", bare):
            yield i, line


@pytest.mark.parametrize("preset", ["wang2017_metro", "wang2017_temp_m10c"])
def test_template_comments_stand_right_above_what_they_document(preset):
    from railvib.case.template import render_template

    lines = render_template(preset).splitlines()
    body = lines[lines.index("") + 1 :]  # after the file's header block
    for i, line in _key_lines("\n".join(body)):
        above = body[i - 1]
        assert above.startswith("# "), f"{line!r} has no comment right above it"
        assert not re.match(r"^# [a-z_0-9]+ = ", above), f"{line!r} is under another key"
        if line.startswith("["):
            assert body[i - 2] == "" or body[i - 2].startswith("# "), line


def test_template_documents_every_irregularity_key_and_writes_bands_inline():
    from railvib.case.template import render_template
    from railvib.spectra import SPECTRA

    text = render_template()
    lines = text.splitlines()
    for spectrum in ("combined", "fra", "shitai"):
        for p in SPECTRA.get(spectrum).parameters:
            if p.kind == "member":  # a nested table: its description above its header
                i = lines.index(f"[irregularity.{p.key}]")
                assert lines[i - 1].startswith(f"# {p.doc} ["), lines[i - 1]
                continue
            i = next(j for j, line in enumerate(lines) if re.match(rf"^(# )?{p.key} = ", line))
            assert lines[i - 1].startswith(f"# {p.doc}"), (p.key, lines[i - 1])
    assert "rms_bands = [[0.5, 20.0], [20.0, 100.0], [100.0, 1000.0]]" in lines
    assert "# coefficient = 0.036" in lines  # an optional key left out is shown, commented


def test_template_still_loads_as_its_preset(tmp_path):
    import railvib
    from railvib.case import load_case
    from railvib.case.template import render_template
    from railvib.presets import list_presets

    for name in list_presets():
        path = tmp_path / f"{name}.toml"
        path.write_text(render_template(name))
        with warnings.catch_warnings():
            # the template writes the preset's pad temperature, a label for a pad that
            # ignores it (wang2017_temp_*): rightly a plausibility warning, not the point here
            warnings.simplefilter("ignore", PlausibilityWarning)
            assert load_case(path) == railvib.load_preset_case(name), name


def test_bands_a_preset_brings_that_the_grid_cannot_hold_are_left_out():
    # the preset's bands are 0.5-20, 20-100 and 100-1000 Hz; a 1-50 Hz grid holds the first
    # two (in part) and nothing of the third, which the user never asked for
    case = case_from_dict({"preset": "wang2017_metro", "frequency": {"f_min": 1.0, "f_max": 50.0}})
    assert [tuple(b) for b in case.output.rms_bands] == [(0.5, 20.0), (20.0, 100.0)]
    with pytest.raises(CaseError) as info:  # the same band, given by the user: refused
        case_from_dict(
            {
                "preset": "wang2017_metro",
                "frequency": {"f_min": 1.0, "f_max": 50.0},
                "output": {"rms_bands": [[100.0, 1000.0]]},
            }
        )
    assert info.value.field == "output.rms_bands[0]"
    assert "widen or move the band" in info.value.allowed
