"""What a new user waits for (issue 10): what each entry point imports, not how long it takes.

Timings live in benchmarks/bench_startup.py; these tests check the causes instead, in
fresh processes: which heavy modules ``import railvib``, ``railvib --help`` and the run
pipeline load, that no library module switches matplotlib's backend, that files are
drawn without pyplot, and that the faster writers give the bytes and numbers they
replaced.
"""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import railvib
import railvib.plot.psd as psd_plot
from railvib.grid import trapezoid

SRC = Path(__file__).resolve().parents[2] / "src"
HEAVY = ("numpy", "scipy", "pandas", "xarray", "matplotlib", "pydantic", "dask", "h5py")


def _loaded_after(code, modules=HEAVY):
    """The `modules` a fresh interpreter has loaded after running `code`."""
    report = f"print(json.dumps([m for m in {list(modules)!r} if m in sys.modules]))"
    probe = f"{code}\nimport json, sys\n{report}"
    path = os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path}
    out = subprocess.run(
        [sys.executable, "-c", probe], env=env, check=True, capture_output=True, text=True
    ).stdout
    return json.loads(out.strip().splitlines()[-1])


def test_import_railvib_loads_no_numerical_library():
    # main: 1.3 s, numpy, scipy (optimize, stats), pandas, xarray, pydantic
    assert _loaded_after("import railvib") == []


def test_cli_help_loads_no_numerical_library():
    # main: 1.9 s, the whole library and matplotlib (railvib pad, validate imported it)
    code = "from railvib.cli.main import main\nassert main(['--help']) == 0"
    assert _loaded_after(code) == []
    assert _loaded_after("from railvib.cli.main import main\nmain(['pad', 'fit', '--help'])")


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_the_run_pipeline_loads_no_fitting_statistics_or_plotting():
    # main: scipy.optimize (pads.fit, 0.2 s) and scipy.stats (one norm.cdf, 0.35 s)
    unwanted = ("scipy.optimize", "scipy.stats", "scipy.integrate", "matplotlib")
    assert _loaded_after("import railvib.solve, railvib.cli.run", unwanted) == []


def test_the_facade_loads_names_on_first_use_as_before():
    assert _loaded_after("import railvib\nrailvib.FrequencyGrid", ("xarray",)) == []
    assert sorted(railvib.__all__) == railvib.__all__
    for name in railvib.__all__:
        assert getattr(railvib, name) is not None
    from railvib.case import case_from_dict

    assert railvib.case_from_dict is case_from_dict
    assert railvib.case.build_grid is not None  # a subpackage, as an attribute
    assert "run" in dir(railvib)
    with pytest.raises(AttributeError, match="no attribute 'not_a_name'"):
        _ = railvib.not_a_name


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_no_library_module_switches_the_matplotlib_backend(tmp_path):
    # main: importing railvib.plot.* (or railvib reproduce/padfit) called matplotlib.use("Agg")
    code = (
        "import matplotlib\nmatplotlib.use('svg')\n"
        "import railvib.plot.psd, railvib.plot.pads, railvib.plot.sweep\n"
        "import railvib.padfit, railvib.reproduce.figures, railvib.validation.plots\n"
        "from railvib.plot.psd import save_overview\n"
        "from railvib.case import case_from_dict\n"
        "case = case_from_dict({'preset': 'wang2017_metro', 'frequency': "
        "{'f_min': 1.0, 'f_max': 50.0, 'step': 1.0}})\n"
        f"save_overview(railvib.run(case), {str(tmp_path)!r})\n"
        "assert matplotlib.get_backend() == 'svg', matplotlib.get_backend()\n"
    )
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    env.pop("MPLBACKEND", None)
    subprocess.run([sys.executable, "-c", code], env=env, check=True)
    assert len(list(tmp_path.glob("*.png"))) == 8


def test_no_library_module_calls_matplotlib_use():
    offenders = [
        str(p.relative_to(SRC))
        for p in (SRC / "railvib").rglob("*.py")
        if "matplotlib.use(" in p.read_text(encoding="utf-8")
    ]
    assert offenders == []


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_file_figures_are_not_pyplot_figures(tmp_path):
    import matplotlib.pyplot as plt

    from railvib.plot.psd import save_overview

    case = railvib.case_from_dict(
        {"preset": "wang2017_metro", "frequency": {"f_min": 1.0, "f_max": 50.0, "step": 1.0}}
    )
    before = plt.get_fignums()
    assert len(save_overview(railvib.run(case), tmp_path)) == 8
    assert plt.get_fignums() == before  # no window, no figure left in pyplot


@pytest.fixture(scope="module")
def result():
    case = railvib.case_from_dict(
        {"preset": "wang2017_metro", "frequency": {"f_min": 0.5, "f_max": 200.0, "step": 0.5}}
    )
    return railvib.run(case)


@pytest.mark.parametrize("variable", ["psd_acceleration", "psd_displacement", "psd_force"])
def test_csv_bytes_are_those_of_pandas(result, variable, tmp_path):
    from railvib.results.dataset import column_units, save_csv

    da = result[variable]
    units = column_units(da)
    da = da.drop_vars([c for c in da.coords if c not in da.dims])
    df = da.to_pandas()
    prefix = "wheel" if "wheel" in da.dims else ""
    df.columns = [f"{prefix}{c} [{u}]" for c, u in zip(df.columns, units, strict=True)]
    df.index.name = "frequency [Hz]"
    expected = df.to_csv(float_format="%.6e")  # what save_csv wrote before issue 10
    path = save_csv(result, tmp_path / "t.csv", variable=variable)
    assert path.read_text(encoding="utf-8") == expected


def test_csv_with_nan_is_written_as_pandas_does(result, tmp_path):
    from railvib.results.dataset import save_csv

    ds = result.copy(deep=True)
    ds["psd_acceleration"][3, 2] = np.nan  # pandas writes an empty field
    text = save_csv(ds, tmp_path / "t.csv").read_text(encoding="utf-8")
    row = text.splitlines()[4].split(",")
    assert row[3] == ""


@pytest.mark.parametrize("shape_axis", [((50,), 0), ((50, 3), 0), ((4, 50, 3), 1), ((3, 50), -1)])
def test_trapezoid_is_bit_identical_to_scipy(shape_axis):
    from scipy.integrate import trapezoid as scipy_trapezoid

    shape, axis = shape_axis
    rng = np.random.default_rng(1)
    f = np.sort(rng.uniform(0.5, 1000.0, shape[axis]))
    y = rng.lognormal(size=shape)
    assert np.array_equal(trapezoid(y, f, axis=axis), scipy_trapezoid(y, f, axis=axis))


def test_loss_of_contact_probability_is_scipy_stats_norm_cdf(result):
    from scipy.stats import norm

    from railvib.outputs import ContactCheck

    p0 = result.static_contact_load.values
    for scale in (1.0, 10.0, 30.0, 60.0, 1e3):  # probabilities from ~1e-200 to ~0.5
        out = ContactCheck().compute(result.assign(psd_force=result.psd_force * scale**2))
        sigma = out["contact_force_rms"].values
        expected = norm.cdf(-p0 / np.maximum(sigma, np.finfo(float).tiny))
        assert np.array_equal(out["loss_of_contact_probability"].values, expected)
    x = -np.logspace(-3, 1.6, 20001)  # and over the whole range, bit for bit
    from scipy.special import ndtr

    assert np.array_equal(ndtr(x), norm.cdf(x))


def test_superscript_tick_labels_read_as_matplotlib_mathtext():
    from matplotlib.figure import Figure
    from matplotlib.ticker import LogFormatterSciNotation

    from railvib.plot.psd import SuperscriptLogFormatter

    ax = Figure().subplots()
    ax.set_yscale("log")
    ax.set_ylim(1e-13, 30.0)
    ours, theirs = SuperscriptLogFormatter(), LogFormatterSciNotation()
    ours.set_axis(ax.yaxis)
    theirs.set_axis(ax.yaxis)
    cases = {1e-5: "10⁻⁵", 1e-13: "10⁻¹³", 1.0: "10⁰", 10.0: "10¹", 2e-5: "2×10⁻⁵"}
    for x, label in cases.items():
        assert ours(x) == label
        mathtext = theirs(x)  # e.g. $\mathdefault{2\times10^{-5}}$
        assert mathtext.replace("\\times", "×").count("×") == label.count("×")
    assert SuperscriptLogFormatter(labelOnlyBase=True)(2e-5) == ""  # matplotlib's choice kept


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_overview_figures_keep_their_dpi_and_size(result, tmp_path):
    from matplotlib.image import imread

    from railvib.io import FIGURE_DPI
    from railvib.plot.psd import save_overview

    for path in save_overview(result, tmp_path):
        height = 5.5 if path.stem == "pad_stiffness" else 4.3  # inches, as before
        assert imread(path).shape[:2] == (round(height * FIGURE_DPI), 7 * FIGURE_DPI)


def test_netcdf_round_trip_is_unchanged(result, tmp_path):
    # the writer is unchanged; this pins that the faster CSV/plot path did not touch it
    out = railvib.load_netcdf(railvib.save_netcdf(result, tmp_path / "r.nc"))
    xr.testing.assert_identical(out.drop_attrs(deep=False), result.drop_attrs(deep=False))


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
@pytest.mark.parametrize("title", [None, "short", "a long title " * 16])
def test_overview_figures_with_fixed_margins_keep_everything_inside(title):
    # the margins are not measured per figure: check nothing is cut off, for suptitles of
    # one to three lines and the response groups' PSD ranges
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from railvib.plot.psd import overview_figures

    data = {"preset": "wang2017_metro", "frequency": {"f_min": 0.5, "f_max": 1000.0, "step": 1.0}}
    if title is not None:
        data["title"] = title
    ds = railvib.run(railvib.case_from_dict(data))
    lines = {None: 2, "short": 1}.get(title, 3)  # of the suptitle: title and speed
    assert len(textwrap.wrap(psd_plot.case_title(ds), 90)) == lines
    for stem, fig in overview_figures(ds):
        renderer = FigureCanvasAgg(fig).get_renderer()
        box, frame = fig.get_tightbbox(renderer), fig.bbox_inches
        # inches; 0.02 in (2 px at 110 dpi): rounding of the text extents
        assert box.x0 >= -0.02, stem
        assert box.y0 >= -0.02, stem
        assert box.x1 <= frame.x1 + 0.02, stem
        assert box.y1 <= frame.y1 + 0.02, stem
        for ax in fig.axes:  # the suptitle does not run into the axes title
            title_box = ax.title.get_window_extent(renderer)
            assert title_box.y1 <= fig._suptitle.get_window_extent(renderer).y0 + 1, stem
