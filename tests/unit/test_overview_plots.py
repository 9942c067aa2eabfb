"""Issue 10, item 4: the figures of ``railvib run`` are those a vibration engineer expects.

Checked on the figure objects, not on pixels: log frequency axes, PSD limits from the
data drawn (peak / 1e8 to 2 x peak, by the definition in the issue), units in the
labels (rad-based for pitch), a title with the case and its speed, and the extra
figures (contact forces, irregularity, pad stiffness).
"""

import numpy as np
import pytest

import railvib
import railvib.plot.criteria as criteria_plot
import railvib.plot.psd as psd_plot
from railvib.plot.psd import OVERVIEW_GROUPS, overview_figures, psd_ylim
from railvib.solve import CRITERIA_STEMS, run_to_folder

STEMS = [stem for stem, _, _ in OVERVIEW_GROUPS] + [
    "psd_force",
    "irregularity_psd",
    "pad_stiffness",
]


@pytest.fixture(scope="module")
def ds():
    case = railvib.case_from_dict(
        {"preset": "wang2017_metro", "frequency": {"f_min": 1.0, "f_max": 200.0, "step": 1.0}}
    )
    return railvib.run(case)


@pytest.fixture(scope="module")
def figures(ds):
    return dict(overview_figures(ds))


def test_psd_ylim_by_definition():
    assert psd_ylim([0.0, 3.0, -1.0, np.nan, 1e-30]) == (3.0e-8, 6.0)
    assert psd_ylim([0.0, np.nan]) is None


def test_every_figure_is_drawn(figures):
    assert list(figures) == STEMS


def test_frequency_axes_are_logarithmic(figures):
    for stem, fig in figures.items():
        for ax in fig.axes:
            assert ax.get_xscale() == "log", stem


def test_titles_state_the_case_and_its_speed(figures, ds):
    title = ds.attrs["title"]
    for stem, fig in figures.items():
        text = fig._suptitle.get_text().replace("\n", " ")
        assert title in text, stem
        assert "80 km/h (22.22 m/s)" in text, stem  # 80 / 3.6 = 22.22


@pytest.mark.parametrize(("stem", "title", "responses"), OVERVIEW_GROUPS)
def test_response_psds_limits_and_units(figures, ds, stem, title, responses):
    (ax,) = figures[stem].axes
    assert ax.get_title() == title
    assert ax.get_yscale() == "log"
    top = float(ds["psd_acceleration"].sel(response=list(responses)).max())
    # set_ylim stores the values given: exact but for the float product, 1e-12
    np.testing.assert_allclose(ax.get_ylim(), (top / 1e8, 2.0 * top), rtol=1e-12)
    pitch = all(r.endswith(".pitch") for r in responses)
    unit = "(rad/s^2)^2/Hz" if pitch else "(m/s^2)^2/Hz"
    assert ax.get_ylabel() == f"acceleration PSD [{unit}]"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == list(responses)


def test_contact_force_and_irregularity_figures(figures, ds):
    (ax,) = figures["psd_force"].axes
    assert ax.get_ylabel() == "dynamic wheel-rail contact force PSD [N^2/Hz]"
    top = float(ds["psd_force"].max())
    np.testing.assert_allclose(ax.get_ylim(), (top / 1e8, 2.0 * top), rtol=1e-12)
    assert len(ax.lines) == ds.sizes["wheel"]
    (ax,) = figures["irregularity_psd"].axes
    assert ax.get_ylabel() == "irregularity PSD applied [m^2/Hz]"
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), ds["irregularity_psd"].values)


def test_pad_figure_shows_storage_stiffness_and_loss_factor(figures, ds):
    ax_k, ax_eta = figures["pad_stiffness"].axes
    assert ax_k.get_ylabel() == "storage stiffness K' [kN/mm]"
    assert ax_eta.get_ylabel() == "loss factor K''/K' [-]"
    f = ds["frequency"].values
    # spring_damper of the preset: K' = 5e7 N/m = 50 kN/mm, eta = 2 pi f c / k, c = 5e4 N s/m
    np.testing.assert_allclose(ax_k.lines[0].get_ydata(), 50.0, rtol=1e-15)
    np.testing.assert_allclose(
        ax_eta.lines[0].get_ydata(), 2 * np.pi * f * 5.0e4 / 5.0e7, rtol=1e-12
    )


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_run_to_folder_writes_every_png_through_save_figure(tmp_path, monkeypatch):
    saved = []
    real = psd_plot.save_figure

    def spy(fig, path, **kw):
        saved.append(path.name)
        return real(fig, path, **kw)

    monkeypatch.setattr(psd_plot, "save_figure", spy)
    monkeypatch.setattr(criteria_plot, "save_figure", spy)
    monkeypatch.setenv("RAILVIB_BACKGROUND", "0")  # the spy's list is this process's
    case = railvib.case_from_dict(
        {"preset": "wang2017_metro", "frequency": {"f_min": 1.0, "f_max": 200.0, "step": 2.0}}
    )
    out = run_to_folder(case, tmp_path)
    pngs = sorted(p.name for p in tmp_path.glob("*.png"))
    # the overview figures and the criteria figures (one-third octaves, comfort: issue 16)
    assert pngs == sorted(f"{stem}.png" for stem in [*STEMS, *CRITERIA_STEMS])
    assert sorted(saved) == pngs
    assert {p.name for p in out.files} >= set(pngs) | {"psd_force.csv"}
