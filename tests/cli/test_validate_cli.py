"""``railvib validate``: parse, one library call, print; the deprecated spellings still work.

The command writes what :func:`railvib.validation.validate_to_folder` writes; ``-o`` is
the spelling of ``railvib run``; ``--outdir`` (hidden) and the library alias
``railvib.cli.validate.run_validation`` are deprecated and give the same files. One
quick realisation keeps each run to a few seconds: the Monte Carlo is seeded, so
the datasets of two runs are identical.
"""

import io

import pytest
import xarray as xr
from rich.console import Console

from railvib.case import build_spectrum, build_system, load_case
from railvib.cli.main import main
from railvib.errors import RailvibDeprecationWarning
from railvib.results import load_netcdf
from railvib.validation import DEFAULT_PLOT_RESPONSES

pytestmark = [pytest.mark.slow, pytest.mark.validation]

QUICK = ["--quick", "--realisations", "1", "--seed", "5"]


@pytest.fixture(scope="module")
def case_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("case") / "metro.toml"
    path.write_text('preset = "wang2017_metro"\n', encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def written(case_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("out")
    assert main(["validate", str(case_file), *QUICK, "-o", str(out)]) == 0
    return out


def _assert_same_datasets(a, b, name="metro"):
    for key in ("frf", "mc", "table"):
        xr.testing.assert_identical(
            load_netcdf(a / f"{name}_{key}.nc"), load_netcdf(b / f"{name}_{key}.nc")
        )


def test_output_option_writes_every_file(written):
    stems = [r.replace(".", "_").replace("@", "_") for r in DEFAULT_PLOT_RESPONSES]
    for stem in stems:
        assert (written / f"metro_{stem}.png").is_file()
    assert "Acceptance (issue 5)" in (written / "metro_agreement.md").read_text()
    mc = load_netcdf(written / "metro_mc.nc")
    assert mc["inside"].dtype == bool
    assert mc.attrs["realisations"] == 1
    assert not list(written.glob("*.part"))


def test_hidden_outdir_alias_still_works(case_file, written, tmp_path, capsys):
    assert main(["validate", str(case_file), *QUICK, "--outdir", str(tmp_path)]) == 0
    assert "--outdir is deprecated; use -o/--output" in capsys.readouterr().err
    _assert_same_datasets(written, tmp_path)


def test_output_given_twice_is_a_usage_error(case_file, tmp_path):
    args = ["validate", str(case_file), "-o", str(tmp_path), "--outdir", str(tmp_path)]
    assert main(args) == 2
    assert not list(tmp_path.iterdir())


def test_help_shows_output_not_outdir(capsys):
    assert main(["validate", "--help"]) == 0
    text = capsys.readouterr().out
    assert "-o, --output" in text
    assert "--outdir" not in text


def test_deprecated_run_validation_alias(case_file, written, tmp_path):
    from railvib.cli.validate import run_validation

    case = load_case(case_file)
    console = Console(file=io.StringIO())
    with pytest.warns(RailvibDeprecationWarning, match="validate_to_folder"):
        res = run_validation(
            build_system(case),
            build_spectrum(case),
            tmp_path,
            quick=True,
            realisations=1,
            seed=5,
            console=console,
            name="metro",
        )
    assert "Agreement per response" in console.file.getvalue()
    assert res.mc.attrs["realisations"] == 1
    _assert_same_datasets(written, tmp_path)
