"""The figures of ``railvib run`` after the wall-time work of issue 13.

Drawn in two forked children, the files must be those the run's own process draws, byte
for byte; the criteria figures, laid out with fixed margins instead of the constrained
layout, must keep every label inside the figure and the panels apart; PNGs written at
zlib level 1 hold the pixels of Pillow's default level.
"""

import io

import numpy as np
import pytest

import railvib
import railvib.io as rio
from railvib.plot import OVERVIEW_STEMS, RUN_FIGURE_PARTS, save_run_figures
from railvib.solve import CRITERIA_STEMS, run_to_folder


def _case(**frequency):
    grid = {"f_min": 0.5, "f_max": 1000.0, "step": 2.0, **frequency}
    return railvib.case_from_dict({"preset": "wang2017_metro", "frequency": grid})


@pytest.mark.slow  # two runs with figures: ~6 s
def test_forked_figures_are_the_files_drawn_in_the_process(tmp_path, monkeypatch):
    case = _case()
    monkeypatch.setattr(rio, "_can_fork", lambda: True)
    forked = run_to_folder(case, tmp_path / "forked")
    monkeypatch.setenv(rio.BACKGROUND_ENV, "0")
    monkeypatch.setattr(rio, "_can_fork", lambda: False)
    serial = run_to_folder(case, tmp_path / "serial")
    assert [p.name for p in forked.files] == [p.name for p in serial.files]
    pngs = [p.name for p in serial.files if p.suffix == ".png"]
    assert pngs == [f"{s}.png" for s in (*OVERVIEW_STEMS, *CRITERIA_STEMS)]
    for name in pngs:
        assert (tmp_path / "forked" / name).read_bytes() == (
            tmp_path / "serial" / name
        ).read_bytes()


def test_the_parts_draw_every_figure_once():
    drawn = [stem for part in RUN_FIGURE_PARTS for stem in part]
    assert sorted(drawn) == sorted((*OVERVIEW_STEMS, *CRITERIA_STEMS))


@pytest.mark.slow  # figures of three grids: ~5 s
@pytest.mark.parametrize(
    "frequency", [{}, {"f_min": 1.0, "f_max": 80.0, "step": 0.5}, {"f_min": 20.0, "step": 5.0}]
)
def test_criteria_figures_keep_everything_inside(frequency, tmp_path):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    import railvib.plot.criteria as criteria

    ds = railvib.run(_case(**frequency))
    figures = []
    monkeypatch = pytest.MonkeyPatch()
    monkeypatch.setattr(criteria, "save_figure", lambda fig, path, **kw: figures.append(fig))
    try:
        criteria.save_criteria_plots(ds, tmp_path)
    finally:
        monkeypatch.undo()
    assert len(figures) == 2
    for fig in figures:
        assert isinstance(fig, Figure)
        renderer = FigureCanvasAgg(fig).get_renderer()
        box, frame = fig.get_tightbbox(renderer), fig.bbox_inches
        # inches; 0.02 in (2 px at 110 dpi): rounding of the text extents
        assert box.x0 >= -0.02
        assert box.y0 >= -0.02
        assert box.x1 <= frame.x1 + 0.02
        assert box.y1 <= frame.y1 + 0.02
        if len(fig.axes) == 2:  # the comfort figure: the right panel's labels clear the left
            left, right = fig.axes
            left_box = left.get_tightbbox(renderer)
            right_labels = right.yaxis.get_tightbbox(renderer)
            assert left_box.x1 < right_labels.x0


@pytest.mark.slow  # ten figures: ~2 s
def test_png_at_level_one_holds_the_pixels_of_the_default_level(tmp_path):
    from matplotlib.image import imread

    ds = railvib.run(_case(step=5.0))
    for path in save_run_figures(ds, tmp_path, stems=("psd_rail", "comfort")):
        default = io.BytesIO()
        from PIL import Image

        Image.open(path).save(default, format="png")  # Pillow's default level, 6
        default.seek(0)
        np.testing.assert_array_equal(imread(path), imread(default), err_msg=path.name)
