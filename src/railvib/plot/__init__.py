"""Plotting: functions take result datasets and return matplotlib axes or figures.

This package module loads no matplotlib; its submodules do.
"""

from __future__ import annotations

from collections.abc import Collection
from pathlib import Path
from typing import TYPE_CHECKING

from railvib.labels import rail_label

if TYPE_CHECKING:
    import xarray as xr

    from railvib.io import Background, StagedFolder

__all__ = [
    "DEFAULT_SWEEP_RESPONSES",
    "OVERVIEW_GROUPS",
    "OVERVIEW_STEMS",
    "RUN_FIGURE_PARTS",
    "RunFigures",
    "save_run_figures",
    "start_run_figures",
]

#: responses drawn by :func:`railvib.plot.sweep.save_sweep_plots` when none is given
DEFAULT_SWEEP_RESPONSES = ("carbody.bounce", "wheelset1.bounce", rail_label(1))

#: (file stem, title, responses) of the response figures written by ``railvib run``
OVERVIEW_GROUPS: tuple[tuple[str, str, tuple[str, ...]], ...] = (
    ("psd_carbody", "Car body", ("carbody.bounce",)),
    ("psd_bogie", "Bogies", ("bogie1.bounce", "bogie2.bounce")),
    ("psd_wheelset", "Wheelsets", tuple(f"wheelset{i}.bounce" for i in range(1, 5))),
    ("psd_rail", "Rail under the wheels", tuple(rail_label(i) for i in range(1, 5))),
    ("psd_pitch", "Pitch", ("carbody.pitch", "bogie1.pitch", "bogie2.pitch")),
)

#: the file stems of every figure :func:`railvib.plot.psd.save_overview` may write (the
#: groups, then the contact forces, the irregularity and the pad), known without
#: matplotlib (``railvib run`` replaces an earlier run's figures with its own)
OVERVIEW_STEMS = (
    *(stem for stem, _, _ in OVERVIEW_GROUPS),
    "psd_force",
    "irregularity_psd",
    "pad_stiffness",
)


#: the figures of ``railvib run`` in the parts drawn side by side, each by one process
#: (:func:`start_run_figures`), of about the same CPU time (0.75-0.95 s each at a load
#: of 13, matplotlib loaded): the seven one-panel overview figures; the two-panel pad
#: figure and the two criteria figures
RUN_FIGURE_PARTS: tuple[tuple[str, ...], ...] = (
    OVERVIEW_STEMS[:-1],
    ("pad_stiffness", "third_octave", "comfort"),
)


def save_run_figures(
    ds: xr.Dataset, outdir: str | Path, stems: Collection[str] | None = None
) -> list[Path]:
    """Write the figures of ``railvib run``: the overview, then the criteria figures.

    :func:`railvib.plot.psd.save_overview` and
    :func:`railvib.plot.criteria.save_criteria_plots`, loading matplotlib on the call.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset of :func:`railvib.run`.
    outdir : str or pathlib.Path
        Folder for the PNG files.
    stems : collection of str, optional
        Only the figures of these file stems; None: all.

    Returns
    -------
    list of pathlib.Path
        The files written, in that order.
    """
    from railvib.plot.criteria import save_criteria_plots  # matplotlib: when drawing
    from railvib.plot.psd import save_overview

    return [
        *save_overview(ds, outdir, stems=stems),
        *save_criteria_plots(ds, outdir, stems=stems),
    ]


class RunFigures:
    """The figures of ``railvib run`` being drawn (:func:`start_run_figures`).

    Parameters
    ----------
    parts : list of railvib.io.Background
        The work under way, one per part of :data:`RUN_FIGURE_PARTS`.
    """

    def __init__(self, parts: list[Background]) -> None:
        self._parts = parts

    def result(self) -> list[Path]:
        """The files written, in the order of :func:`save_run_figures` (waiting for them).

        Returns
        -------
        list of pathlib.Path
        """
        files: list[Path] = [f for part in self._parts for f in part.result()]
        drawn = (stem for part in RUN_FIGURE_PARTS for stem in part)
        order = list(dict.fromkeys([*OVERVIEW_STEMS, *drawn]))
        return sorted(files, key=lambda f: order.index(f.stem))


def start_run_figures(stage: StagedFolder, ds: xr.Dataset) -> RunFigures:
    """Start drawing the figures of ``railvib run`` into `stage`, beside the run's other work.

    Each part of :data:`RUN_FIGURE_PARTS` is drawn by a process of its own where the
    system allows (:meth:`railvib.io.StagedFolder.background`: forked, so the result is
    not copied), while the run writes ``results.nc`` and its tables; else the figures
    are drawn in the run's process when :meth:`RunFigures.result` is called. Matplotlib
    is loaded here, before the processes are forked: once (0.3-0.45 s CPU), not once in
    each.

    Parameters
    ----------
    stage : railvib.io.StagedFolder
        The run's staging folder (the figures are written to its ``path``).
    ds : xarray.Dataset
        A result dataset of :func:`railvib.run`.

    Returns
    -------
    RunFigures
        Its :meth:`~RunFigures.result` lists the files written.
    """
    from railvib.plot import criteria, psd  # noqa: F401 - matplotlib loaded once, not per child

    return RunFigures(
        [stage.background(save_run_figures, ds, stage.path, part) for part in RUN_FIGURE_PARTS]
    )
