"""Reproduce the paper's study (Wang et al. 2017, Figs. 9-16) with one call.

:func:`reproduce` runs the study's cases (shipped presets ``wang2017_*``), redraws the
paper's Figs. 9-16, reads every number the paper states from our curves and writes, to
one folder: the figures (PNG), ``paper_comparison.md``/``.csv`` and a self-contained
``report.html``. The study itself (cases, figures, numbers and how each is read) is
data, ``reproduce/paper_wang2017.toml``, read and checked by :mod:`railvib.reproduce.study`.

Examples
--------
>>> from railvib.reproduce import reproduce
>>> out = reproduce("railvib-reproduce")          # doctest: +SKIP
>>> out.table.set_index("id").loc["fig11.frequency.constant", "ours"]  # doctest: +SKIP
45.9
"""

from railvib.reproduce.cases import load_study_cases, run_cases
from railvib.reproduce.metrics import METRICS
from railvib.reproduce.pipeline import (
    DEFAULT_OUTDIR,
    ReproduceResult,
    n_steps,
    reproduce,
    reproduce_files,
)
from railvib.reproduce.study import CASES, COMPARISONS, FIGURES, PAPER_NUMBERS
from railvib.reproduce.table import compare

__all__ = [
    "CASES",
    "COMPARISONS",
    "DEFAULT_OUTDIR",
    "FIGURES",
    "METRICS",
    "PAPER_NUMBERS",
    "ReproduceResult",
    "compare",
    "load_study_cases",
    "n_steps",
    "reproduce",
    "reproduce_files",
    "run_cases",
]
