"""``save_overview`` draws its one-panel figures on one reused figure (issue 13).

The files must be those of fresh figures, pixel for pixel: nothing of one figure (a
line, a legend, a data limit, the colour cycle) may be left in the next.
"""

import numpy as np
import pytest

import railvib
from railvib.io import save_figure
from railvib.plot.psd import overview_figures, save_overview


@pytest.mark.slow  # ~2 s: sixteen figures
def test_the_reused_figure_gives_the_pixels_of_fresh_figures(tmp_path):
    from matplotlib.image import imread

    case = railvib.case_from_dict(
        {"preset": "wang2017_metro", "frequency": {"f_min": 1.0, "f_max": 100.0, "step": 0.5}}
    )
    ds = railvib.run(case)
    (tmp_path / "fresh").mkdir()
    (tmp_path / "reused").mkdir()
    fresh = [
        save_figure(fig, tmp_path / "fresh" / f"{stem}.png", tight=False)
        for stem, fig in overview_figures(ds)
    ]
    reused = save_overview(ds, tmp_path / "reused")
    assert [p.name for p in reused] == [p.name for p in fresh]
    assert len(reused) == 8  # five response groups, the forces, the irregularity, the pad
    for a, b in zip(fresh, reused, strict=True):
        np.testing.assert_array_equal(imread(a), imread(b), err_msg=a.name)
