"""Railpad plots: master curve with shifted data, and K(f) at several temperatures.

Plot functions take data already computed (no physics here), draw on the given axes
(created when None) and return them. Stiffness is drawn in kN/mm, the edge unit.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from matplotlib.axes import Axes
from numpy.typing import ArrayLike

from railvib.pads.fit import MasterCurve
from railvib.plot.axes import log_axis

__all__ = ["plot_master_curve", "plot_stiffness_vs_frequency"]

_KN_PER_MM = 1e6  # N/m


def plot_master_curve(
    master: MasterCurve,
    curve_frequency_hz: ArrayLike | None = None,
    curve_stiffness_n_per_m: ArrayLike | None = None,
    *,
    axes: tuple[Axes, Axes] | None = None,
    curve_label: str = "fitted model",
) -> tuple[Axes, Axes]:
    """Storage and loss stiffness of a master curve against reduced frequency.

    Parameters
    ----------
    master : MasterCurve
        Shifted data; points are coloured by their test temperature.
    curve_frequency_hz : array_like, optional
        Reduced frequencies of a model curve, Hz.
    curve_stiffness_n_per_m : array_like of complex, optional
        Model ``K*`` at `curve_frequency_hz`, N/m.
    axes : (Axes, Axes), optional
        Axes for ``K'`` and ``K''``; a new two-panel figure when None.
    curve_label : str
        Legend label of the model curve.

    Returns
    -------
    (matplotlib.axes.Axes, matplotlib.axes.Axes)
    """
    if axes is None:  # for interactive use: a pyplot figure, in the user's backend
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True)
    ax_s, ax_l = axes
    t = master.temperature_c
    for ax, y, name in (
        (ax_s, master.storage_n_per_m, "storage stiffness K'"),
        (ax_l, master.loss_n_per_m, "loss stiffness K''"),
    ):
        sc = ax.scatter(
            master.reduced_frequency_hz,
            y / _KN_PER_MM,
            c=t,
            cmap="coolwarm",
            s=14,
            label="data, shifted",
        )
        if curve_frequency_hz is not None and curve_stiffness_n_per_m is not None:
            k = np.asarray(curve_stiffness_n_per_m)
            part = k.real if ax is ax_s else k.imag
            ax.plot(curve_frequency_hz, part / _KN_PER_MM, "k-", lw=1.2, label=curve_label)
        log_axis(ax, "x")
        log_axis(ax, "y")
        ax.set_ylabel(f"{name} [kN/mm]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize="small")
    ax_l.set_xlabel(f"reduced frequency f a_T at {master.reference_temperature_c:g} °C [Hz]")
    w = master.wlf
    ax_s.set_title(
        f"Master curve at {master.reference_temperature_c:g} °C "
        f"(WLF C1 = {w.c1:.3g}, C2 = {w.c2_k:.3g} K)"
    )
    ax_s.figure.colorbar(sc, ax=list(axes), label="test temperature [°C]")
    return ax_s, ax_l


def plot_stiffness_vs_frequency(
    frequency_hz: ArrayLike,
    stiffness_by_temperature: Mapping[float, ArrayLike],
    *,
    quantity: str = "storage",
    ax: Axes | None = None,
) -> Axes:
    """Pad stiffness against frequency, one line per temperature (like the seed's Fig. 8).

    Parameters
    ----------
    frequency_hz : array_like
        Frequencies, Hz.
    stiffness_by_temperature : mapping of float to array_like of complex
        ``{temperature degC: K*(f) in N/m}``.
    quantity : {"storage", "modulus", "loss_factor"}
        What to draw: ``K'``, ``|K*|`` (kN/mm) or ``eta``.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.

    Returns
    -------
    matplotlib.axes.Axes
    """
    parts = {
        "storage": (lambda k: k.real / _KN_PER_MM, "storage stiffness K' [kN/mm]"),
        "modulus": (lambda k: np.abs(k) / _KN_PER_MM, "dynamic stiffness |K*| [kN/mm]"),
        "loss_factor": (lambda k: k.imag / k.real, "loss factor η [-]"),
    }
    if quantity not in parts:
        raise ValueError(f"quantity = {quantity!r}: one of {', '.join(parts)}")
    get, ylabel = parts[quantity]
    if ax is None:  # for interactive use: a pyplot figure, in the user's backend
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(7, 4))
    for temp, k in sorted(stiffness_by_temperature.items()):
        ax.plot(frequency_hz, get(np.asarray(k)), label=f"{temp:g} °C")
    log_axis(ax, "x")
    if quantity != "loss_factor":
        log_axis(ax, "y")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small", title="temperature")
    return ax
