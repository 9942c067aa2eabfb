"""``railvib run``, ``template``, ``presets``, ``models`` and the shared CLI conventions."""

import click
import pytest

import railvib
from railvib.cli.main import cli, main
from railvib.models import FAMILIES, models_markdown
from railvib.presets import list_presets


def test_cli_prints_one_line_and_writes_nothing(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text('preset = "wang2017_metro"\n[vehicle]\ncarbody_mass = -1.0\n')
    out = tmp_path / "out"
    assert main(["run", str(bad), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == "error: vehicle.carbody_mass = -1.0: must be > 0.0 (kg)"
    assert not out.exists()


@pytest.mark.slow  # ~2.4 s: whole commands with their files, kept out of the fast suite
def test_cli_run_writes_dataset_summary_and_plots(tmp_path):
    case = tmp_path / "c.toml"
    case.write_text(
        'preset = "wang2017_metro"\n[frequency]\nf_min = 1.0\nf_max = 200.0\nstep = 1.0\n'
    )
    out = tmp_path / "out"
    assert main(["run", str(case), "-o", str(out)]) == 0
    names = {p.name for p in out.iterdir()}
    assert {
        "results.nc",
        "psd_acceleration.csv",
        "summary.csv",
        "summary.md",
        "psd_wheelset.png",
        "psd_rail.png",
    } <= names
    assert not any(n.endswith(".part") for n in names)
    ds = railvib.load_netcdf(out / "results.nc")
    assert ds.frf_displacement.dtype.kind == "c"
    assert ds.sizes["frequency"] == 200
    assert "case_toml" in ds.attrs


def test_template_is_a_runnable_case(tmp_path, capsys):
    assert main(["template"]) == 0
    path = tmp_path / "case.toml"
    path.write_text(capsys.readouterr().out)
    assert railvib.load_case(path).title == railvib.load_preset_case().title


def test_presets_lists_every_preset(capsys):
    assert main(["presets"]) == 0
    out = capsys.readouterr().out
    assert [line.split(":")[0] for line in out.splitlines()] == list_presets()


@pytest.mark.parametrize("family", [None, *FAMILIES])
def test_models_prints_the_families_docs(family, capsys):
    assert main(["models"] + ([family] if family else [])) == 0
    assert capsys.readouterr().out == models_markdown(family)


def test_models_rejects_an_unknown_family(capsys):
    assert main(["models", "wheels"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: family = 'wheels': one of pad, spectrum")
    assert err.count("\n") == 1


def _commands(group, prefix=()):
    for name, command in group.commands.items():
        if isinstance(command, click.Group):
            yield from _commands(command, (*prefix, name))
        else:
            yield " ".join((*prefix, name)), command


def test_every_output_folder_option_is_spelled_o_output():
    seen = 0
    for name, command in _commands(cli):
        for param in command.params:
            if param.name in ("outdir", "output") and not getattr(param, "hidden", False):
                seen += 1
                assert "-o" in param.opts, name
                assert "--output" in param.opts, name
    assert seen >= 5  # run, pad fit, reproduce, sweep run, sweep plot, validate


def test_plot_alias_is_hidden_and_the_same_command(capsys):
    from railvib.cli.sweep import plot

    assert cli.commands["plot"].hidden
    assert cli.commands["plot"].callback is plot.callback
