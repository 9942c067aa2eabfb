"""Plotting: functions take result datasets and return matplotlib axes or figures.

This package module loads no matplotlib; its submodules do.
"""

from railvib.labels import rail_label

__all__ = ["DEFAULT_SWEEP_RESPONSES"]

#: responses drawn by :func:`railvib.plot.sweep.save_sweep_plots` when none is given
DEFAULT_SWEEP_RESPONSES = ("carbody.bounce", "wheelset1.bounce", rail_label(1))
