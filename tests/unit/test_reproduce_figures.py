"""Issue 12, figures: the reproduce figures read at a glance.

Checked on the drawn figure objects (not on pixels): one colour per case in every
figure, a legend that covers no curve (its box against the curves' points in display
coordinates), our peaks and the paper's points in the legend in their cases' colours,
the irregularity spectra's join marked where the spectrum definition puts it, and a zoom
of a few comb teeth with the measured tooth spacing.
"""

import math

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import to_rgba
from matplotlib.lines import Line2D

import railvib
from railvib.reproduce.cases import load_study_cases, run_cases
from railvib.reproduce.figures import (
    LEGEND_GID,
    draw_figure,
    irregularity_steps,
    legend_entries,
)
from railvib.reproduce.pad_figures import draw_fig8_prediction, study_prediction
from railvib.reproduce.study import CASES, COMPARISONS, FIGURES

pytestmark = pytest.mark.slow  # runs the study's eight cases and draws 13 figures: ~8 s

_COLOUR = {c.label: to_rgba(c.color) for c in CASES}
# the paper's speed and split wavelength (section 3.1): 80 km/h, class 5 above 1 m
_JOIN_HZ = 80.0 / 3.6 / 1.0


@pytest.fixture(scope="module")
def cases():
    return load_study_cases()


@pytest.fixture(scope="module")
def results():
    return run_cases()


@pytest.fixture(scope="module")
def figures(cases, results):
    steps = irregularity_steps(cases)
    # keyed by (the paper's number, file stem): Figs. 13-16 are drawn twice (stated and
    # predicted pads)
    out = {(8, "fig08_pad_stiffness"): draw_fig8_prediction(cases, study_prediction())}
    out.update({(s.number, s.stem): draw_figure(s, results, steps) for s in FIGURES})
    for fig in out.values():
        FigureCanvasAgg(fig).draw()  # lay out the texts, so extents are final
    return out


def _legend(fig):
    legends = [lg for lg in fig.legends if lg.get_gid() == LEGEND_GID]
    assert len(legends) == 1
    assert not any(ax.get_legend() for ax in fig.axes)  # one legend per figure
    return legends[0]


def _entries(legend):
    return dict(zip((t.get_text() for t in legend.get_texts()), legend.legend_handles, strict=True))


def test_every_figure_is_drawn(figures):
    assert {number for number, _ in figures} == {8, *range(9, 17)}
    assert len(figures) == len(FIGURES) + 1


def test_colours_are_distinct_within_each_comparison():
    by_key = {c.key: c.color for c in CASES}
    for comparison in COMPARISONS:
        colours = [to_rgba(by_key[k]) for k in comparison.cases]
        assert len(set(colours)) == len(colours), comparison.key


def test_a_case_has_one_colour_in_every_figure(figures):
    seen = {}
    for (number, _), fig in figures.items():
        for ax in fig.axes:
            for line in ax.get_lines():
                if line.get_gid() in _COLOUR:  # a case's curve, circle or cross
                    colour = to_rgba(line.get_markeredgecolor())
                    if line.get_linestyle() not in ("None", "none"):
                        colour = to_rgba(line.get_color())
                    assert colour == _COLOUR[line.get_gid()], (number, line.get_gid())
                    seen.setdefault(line.get_gid(), set()).add(number)
        for text, handle in _entries(_legend(fig)).items():  # Fig. 8's labels add words
            if text in _COLOUR:
                assert to_rgba(handle.get_color()) == _COLOUR[text], (number, text)
    # every case appears, and the temperature cases in Fig. 8 and Figs. 13-16 alike
    assert set(seen) == set(_COLOUR)
    for case in CASES:
        if case.key in ("m30", "m10", "p20"):
            assert {8, 13, 14, 15, 16} <= seen[case.label]


def _inside(box, xy):
    return (box.x0 < xy[:, 0]) & (xy[:, 0] < box.x1) & (box.y0 < xy[:, 1]) & (xy[:, 1] < box.y1)


def test_the_legend_covers_no_curve(figures):
    for number, fig in figures.items():
        box = _legend(fig).get_window_extent()
        for ax in fig.axes:
            assert not box.overlaps(ax.get_window_extent()), number  # not even the frame
            for line in ax.get_lines():
                xy = np.column_stack([line.get_xdata(), line.get_ydata()]).astype(float)
                xy = line.get_transform().transform(xy)
                assert not _inside(box, xy).any(), (number, line.get_label())


def test_our_peaks_and_the_paper_points_are_in_the_legend_in_case_colours(figures, cases):
    steps = irregularity_steps(cases)
    for spec in FIGURES:
        panels = [*spec.panels, *([spec.zoom] if spec.zoom else [])]
        handles, labels = legend_entries(spec, steps, panels)
        shown = [t.get_text() for t in _legend(figures[spec.number, spec.stem]).get_texts()]
        assert shown == labels  # the legend drawn is made of these entries
        entries = dict(zip(labels, handles, strict=True))
        comparison = next(c for c in COMPARISONS if c.key == spec.comparison)
        colour = {c.key: to_rgba(c.color) for c in CASES}
        ours = [h for t, h in entries.items() if t.startswith("ours: peak")]
        paper = [h for t, h in entries.items() if t.startswith("paper: stated (")]
        assert len(ours) == (1 if spec.marks else 0), spec.number
        assert len(paper) == (1 if spec.paper_points else 0), spec.number
        if spec.marks:  # a circle per case, in its colour
            assert [to_rgba(m.get_markeredgecolor()) for m in ours[0]] == [
                colour[k] for k in comparison.cases
            ]
            assert all(m.get_marker() == "o" for m in ours[0])
        if spec.paper_points:  # a cross per case the paper gives a point for
            pointed = [k for k in comparison.cases if any(p.case == k for p in spec.paper_points)]
            assert [to_rgba(m.get_color()) for m in paper[0]] == [colour[k] for k in pointed]
            assert all(m.get_marker() == "x" for m in paper[0])
        # no marker entry in a single (grey) colour
        for handle in handles:
            if isinstance(handle, Line2D):
                assert handle.get_marker() in ("None", "none", ""), (spec.number, handle)


def test_the_spectra_join_is_marked_in_every_panel_that_shows_it(figures):
    for spec in FIGURES:
        fig = figures[spec.number, spec.stem]
        for ax, (lo, hi) in zip(fig.axes, spec.panels, strict=False):
            joins = [
                ln
                for ln in ax.get_lines()
                if ln.get_transform() == ax.get_xaxis_transform()
                and ln.get_label().startswith("spectra join")
            ]
            if lo < _JOIN_HZ < hi:
                assert len(joins) == 1, spec.number
                # 1e-9: the line is placed at the computed frequency, not rounded
                assert float(joins[0].get_xdata()[0]) == pytest.approx(_JOIN_HZ, rel=1e-9)
                assert any("spectra join" in t.get_text() for t in ax.texts)
            else:
                assert not joins, spec.number


def test_the_join_follows_the_spectrum_and_the_speed():
    base = {"preset": "wang2017_metro"}
    faster = railvib.case_from_dict({**base, "speed_kmh": 120.0})
    longer = railvib.case_from_dict({**base, "irregularity": {"split_wavelength_m": 2.0}})
    blended = railvib.case_from_dict({**base, "irregularity": {"blend_decades": 0.2}})
    (step,) = irregularity_steps({"v": faster})
    assert step.frequency_hz == pytest.approx(120.0 / 3.6, rel=1e-12)  # v / (1 m)
    (step,) = irregularity_steps({"l": longer})
    assert step.frequency_hz == pytest.approx(80.0 / 3.6 / 2.0, rel=1e-12)
    assert step.wavelength_m == pytest.approx(2.0, rel=1e-12)
    assert irregularity_steps({"b": blended}) == ()  # a smooth blend has no step


@pytest.mark.parametrize("number", [12, 16])
def test_the_comb_has_a_zoom_with_the_measured_spacing(figures, number):
    spec = next(s for s in FIGURES if s.number == number)
    assert spec.zoom is not None
    fig = figures[number, spec.stem]
    zoom = fig.axes[-1]
    assert zoom.get_xlim() == pytest.approx(spec.zoom)
    assert "zoom" in zoom.get_title()
    # a few teeth: the comb period v / (2 l_t) = 22.22 m/s / 2.2 m = 10.10 Hz
    period = 80.0 / 3.6 / 2.2
    teeth = (spec.zoom[1] - spec.zoom[0]) / period
    assert 3 <= teeth <= 8
    texts = [t.get_text() for t in zoom.texts if "f_int" in t.get_text()]
    assert len(texts) == 1
    f_int = float(texts[0].split("=")[1].split("Hz")[0])
    # 2 %: the other wheels' 1.76 Hz comb shifts single teeth (the table row's note)
    assert f_int == pytest.approx(period, rel=0.02)
    # the band zoomed into is shaded in its panel
    assert any(p.get_label() == "zoomed band" for ax in fig.axes[:-1] for p in ax.patches)


def test_labels_of_fig8_carry_k0(figures):
    labels = list(_entries(_legend(figures[8, "fig08_pad_stiffness"])))
    # both "20 degC" pads (Figs. 9-12 and Figs. 13-16), each with its K0
    for key in ("freqdep", "m30", "m10", "p20"):
        label = next(c.label for c in CASES if c.key == key)
        assert "K0 = " in label
        assert any(label in text for text in labels), label
    for key in ("pm30", "pm10", "pp20"):  # the predicted pads, K0 read off the prediction
        label = next(c.label for c in CASES if c.key == key)
        assert any(text.startswith(label) and "K0 = " in text for text in labels), label


def test_log_axes_of_the_paper_figures_have_plain_labels(figures):
    # Fig. 8's stiffness axis spans 30-100 kN/mm: labelled 30, 40, 60, 100, no powers
    ax = figures[8, "fig08_pad_stiffness"].axes[0]
    ticks = [*ax.get_yticklabels(), *ax.get_yticklabels(minor=True)]
    labels = [t.get_text() for t in ticks if t.get_text()]
    assert labels
    assert not any("×" in t or "⁰" in t or "¹" in t for t in labels)
    assert {"40", "60", "100"} <= set(labels)
    # Fig. 12(b): a PSD of about one decade gets more than one label
    ax = next(fig for (n, _), fig in figures.items() if n == 12).axes[1]
    visible = [
        t.get_text()
        for t, v in zip(ax.get_yticklabels(), ax.get_yticks(), strict=True)
        if t.get_text() and ax.get_ylim()[0] <= v <= ax.get_ylim()[1]
    ]
    assert len(visible) >= 2
    assert all(not math.isnan(float(t)) for t in visible)  # plain numbers
