"""Log axes an engineer reads at a glance: plain numbers where they are short, powers else.

:func:`log_axis` makes an axis logarithmic and labels it with :class:`ReadableLogFormatter`:
an axis whose view lies within :data:`PLAIN_RANGE` (a frequency axis, a stiffness axis, a
PSD axis of a few decades) is labelled 0.5, 30, 40, 60, 1000; a wider one keeps powers of
ten (``10⁻⁵``, ``2×10⁻⁵``), written in Unicode (:class:`SuperscriptLogFormatter`). Which
ticks carry a label stays matplotlib's choice in both.
"""

from __future__ import annotations

import re
from typing import Any

import matplotlib as mpl
import numpy as np
from matplotlib.axes import Axes
from matplotlib.ticker import LogFormatterSciNotation, LogLocator, NullLocator

__all__ = [
    "MINOR_THRESHOLDS",
    "DecadeLocator",
    "PLAIN_RANGE",
    "ReadableLogFormatter",
    "SuperscriptLogFormatter",
    "label_log_axis",
    "log_axis",
]

#: an axis whose view lies in this range, in axis units, gets plain labels (at most five
#: characters: 0.01 ... 10000); a wider one gets powers of ten
PLAIN_RANGE = (1e-2, 1e5)

_MATHTEXT_POWER = re.compile(
    r"^\$\\mathdefault\{(?P<sign>-?)(?:(?P<coeff>[0-9.e+]+)\\times)?(?P<base>\d+)"
    r"\^\{(?P<exponent>-?\d+)\}\}\$$"
)
_SUPERSCRIPTS = str.maketrans(
    "-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079"
)


class SuperscriptLogFormatter(LogFormatterSciNotation):
    r"""Log-axis tick labels as matplotlib's default (``10^-5``, ``2x10^-5``), in Unicode.

    Matplotlib writes them as mathtext (``$\mathdefault{10^{-5}}$``), whose parser
    costs about 6 ms per distinct label, a fifth of the time of drawing a log-log
    PSD figure; the same labels with superscript characters (``10⁻⁵``, ``2×10⁻⁵``)
    look the same in the default font and draw as plain text. Which ticks are
    labelled is matplotlib's choice (this is a
    :class:`matplotlib.ticker.LogFormatterSciNotation`); labels of another form, and
    every label when ``text.usetex`` is on, are left as matplotlib writes them.
    """

    def __call__(self, x: float, pos: int | None = None) -> str:
        """The label of the tick at `x` (in axis units) and position `pos`."""
        label = str(super().__call__(x, pos))
        match = _MATHTEXT_POWER.match(label)
        if match is None or mpl.rcParams["text.usetex"]:
            return label
        sign = "\u2212" if match["sign"] else ""  # the minus sign mathtext draws
        coeff = f"{match['coeff']}\u00d7" if match["coeff"] else ""
        return f"{sign}{coeff}{match['base']}{match['exponent'].translate(_SUPERSCRIPTS)}"


class ReadableLogFormatter(SuperscriptLogFormatter):
    """Plain tick labels (30, 40, 60) on a log axis whose view lies in :data:`PLAIN_RANGE`.

    A wider axis (a PSD over many decades) keeps the powers of
    :class:`SuperscriptLogFormatter`. The ticks labelled are those matplotlib labels.
    """

    def __call__(self, x: float, pos: int | None = None) -> str:
        """The label of the tick at `x` (in axis units) and position `pos`."""
        label = super().__call__(x, pos)
        if not label or self.axis is None:
            return label
        low, high = sorted(self.axis.get_view_interval())
        if PLAIN_RANGE[0] <= low and high < PLAIN_RANGE[1]:
            return f"{x:.6g}"
        return label


#: decades of view below which some minor ticks are labelled (2, 3, 5, ...), and below
#: which all are (matplotlib's ``minor_thresholds``; its default (1, 0.4) leaves an axis
#: of 1-2 decades with one or two labels)
MINOR_THRESHOLDS = (2.0, 0.5)


class DecadeLocator(LogLocator):
    """Ticks at each decade of a log axis, and at 2 and 5 times each where it spans few.

    For an axis without minor ticks (a PSD): one over many decades keeps a tick per
    decade (or per few decades, matplotlib's choice); one over at most
    ``MINOR_THRESHOLDS[0]`` decades (a zoomed PSD) also gets ticks at 2 and 5, else it
    would carry a single label.
    """

    def tick_values(self, vmin: float, vmax: float) -> Any:
        """Tick positions for the view `vmin`-`vmax` (axis units, > 0)."""
        ticks = super().tick_values(vmin, vmax)
        low, high = sorted((vmin, vmax))
        if low <= 0 or np.log10(high / low) > MINOR_THRESHOLDS[0]:
            return ticks
        decades = 10.0 ** np.arange(np.floor(np.log10(low)) - 1, np.ceil(np.log10(high)) + 1)
        return np.sort(np.concatenate([decades, 2 * decades, 5 * decades]))


def _formatters(axis: Any) -> None:
    axis.set_major_formatter(ReadableLogFormatter(minor_thresholds=MINOR_THRESHOLDS))
    axis.set_minor_formatter(
        ReadableLogFormatter(labelOnlyBase=False, minor_thresholds=MINOR_THRESHOLDS)
    )


def log_axis(ax: Axes, which: str, *, minor: bool = True) -> None:
    """Make the x or y axis of `ax` logarithmic, labelled by :class:`ReadableLogFormatter`.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    which : {"x", "y"}
        Which axis.
    minor : bool
        Keep the minor ticks; False for an axis over many decades (a PSD), where a tick
        and a grid line per decade are readable and minor ticks cost most of a figure's
        drawing time (hundreds of tick objects).
    """
    getattr(ax, f"set_{which}scale")("log")
    axis = ax.xaxis if which == "x" else ax.yaxis
    _formatters(axis)
    if not minor:
        axis.set_major_locator(DecadeLocator())
        axis.set_minor_locator(NullLocator())


def label_log_axis(axis: Any) -> None:
    """Label an already logarithmic `axis` (``ax.xaxis``) with :class:`ReadableLogFormatter`.

    For an axis shared with another (setting the scale there resets the formatters).

    Parameters
    ----------
    axis : matplotlib.axis.Axis
        A log-scaled axis.
    """
    _formatters(axis)
