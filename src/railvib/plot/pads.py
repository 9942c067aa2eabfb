"""Railpad plots: master curve, K(f) at several temperatures, a temperature sweep, loops.

Plot functions take data already computed (no physics here), draw on the given axes
(created when None) and return them. Stiffness is drawn in kN/mm, the edge unit.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.ticker import FuncFormatter
from numpy.typing import ArrayLike

from railvib.pads.fit import MasterCurve
from railvib.pads.io import Measurements
from railvib.plot.axes import log_axis

__all__ = [
    "plot_hysteresis_loops",
    "plot_master_curve",
    "plot_stiffness_vs_frequency",
    "plot_temperature_sweep",
]

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


def plot_temperature_sweep(
    sweep: Measurements,
    glass_transition_c: float | None = None,
    *,
    axes: tuple[Axes, Axes] | None = None,
    title: str = "",
) -> tuple[Axes, Axes]:
    """Storage stiffness and loss factor against temperature at one frequency (the seed's Fig. 7).

    Parameters
    ----------
    sweep : Measurements
        One frequency, one row per temperature (degC), ``K'`` and ``K''`` in N/m.
    glass_transition_c : float, optional
        Tg (degC), marked on both panels.
    axes : (Axes, Axes), optional
        Axes for ``K'`` and the loss factor; a new two-panel figure when None.
    title : str
        Title of the upper panel (e.g. where the data come from).

    Returns
    -------
    (matplotlib.axes.Axes, matplotlib.axes.Axes)
    """
    if axes is None:  # for interactive use: a pyplot figure, in the user's backend
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    ax_k, ax_e = axes
    t = sweep.temperature_c
    f = float(sweep.frequency_hz[0])
    ax_k.plot(t, sweep.storage_n_per_m / _KN_PER_MM, "o-", ms=4, color="tab:blue")
    ax_k.set_yscale("log")
    plain = FuncFormatter(lambda v, _pos: f"{v:g}")
    ax_k.yaxis.set_major_formatter(plain)
    ax_k.yaxis.set_minor_formatter(plain)
    ax_k.tick_params(axis="y", which="minor", labelsize="x-small")
    ax_k.set_ylabel(f"storage stiffness K' at {f:g} Hz [kN/mm]")
    ax_e.plot(t, sweep.loss_n_per_m / sweep.storage_n_per_m, "o-", ms=4, color="tab:red")
    ax_e.set_ylabel(f"loss factor η at {f:g} Hz [-]")
    ax_e.set_xlabel("temperature [°C]")
    if glass_transition_c is not None:
        for ax in axes:
            ax.axvline(glass_transition_c, color="0.4", ls="--", lw=1.0)
        ax_e.annotate(
            f"Tg = {glass_transition_c:.1f} °C",
            (glass_transition_c, 0.5),
            xycoords=("data", "axes fraction"),
            xytext=(5, 0),
            textcoords="offset points",
            fontsize="small",
        )
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
    if title:
        ax_k.set_title(title, fontsize="medium")
    return ax_k, ax_e


def plot_hysteresis_loops(
    loops: Sequence[tuple[str, ArrayLike, ArrayLike]],
    *,
    colors: Sequence[str] | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Force-displacement loops (the seed's Fig. 6), displacement in mm and force in kN.

    Parameters
    ----------
    loops : sequence of (str, array_like, array_like)
        ``(label, displacement m, force N)`` of each loop (e.g.
        :func:`railvib.pads.hysteresis_loop`).
    colors : sequence of str, optional
        A matplotlib colour per loop (default: the colour cycle).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:  # for interactive use: a pyplot figure, in the user's backend
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(6, 4.5))
    for i, (label, x, force) in enumerate(loops):
        color = None if colors is None else colors[i]
        ax.plot(np.asarray(x) * 1e3, np.asarray(force) / 1e3, label=label, color=color)
    ax.set_xlabel("displacement about the mean [mm]")
    ax.set_ylabel("load [kN]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return ax
