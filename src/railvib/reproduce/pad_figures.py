"""The paper's pad figures from the (synthetic) 0.3 Hz sweep: Figs. 6, 7 and 8 as a prediction.

Fig. 6 (force-displacement loops at 0.3 Hz), Fig. 7 (stiffness and loss factor against
temperature at 0.3 Hz) and Fig. 8 (K(f) at -30, -10 and +20 degC within 1000 Hz), the
last one predicted by the paper's section 3.2 procedure (:func:`railvib.pads.predict_pad`)
and drawn beside the paper's stated log-linear laws, the two "20 degC" pads included.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from railvib.case import Case, build_pad
from railvib.io import new_figure
from railvib.pads import (
    PadPrediction,
    fit_log_linear,
    predict_pad,
    read_measurements_csv,
    wj7_example_csv,
)
from railvib.plot.axes import log_axis
from railvib.plot.pads import plot_hysteresis_loops, plot_temperature_sweep
from railvib.reproduce.figures import LEGEND_GID
from railvib.reproduce.study import CASES, StudyCase

__all__ = [
    "FIG8_BAND_HZ",
    "FIG8_PREDICTED",
    "FIG8_STATED",
    "PAD_FIGURE_FILES",
    "SYNTHETIC_LABEL",
    "draw_fig6_loops",
    "draw_fig7_sweep",
    "draw_fig8_prediction",
    "draw_pad_figures",
    "study_prediction",
]

_CASES: Mapping[str, StudyCase] = {c.key: c for c in CASES}
_KN_PER_MM = 1e6  # N/m

#: what every figure drawn from the shipped sweep says about its data
SYNTHETIC_LABEL = "SYNTHETIC WJ-7 data (railvib/data/wj7), not measurements"
#: cases whose predicted pads Fig. 8 draws (solid)
FIG8_PREDICTED = ("pm30", "pm10", "pp20")
#: cases whose stated log-linear laws Fig. 8 draws (dashed): Figs. 13-16 and Figs. 9-12
FIG8_STATED = ("m30", "m10", "p20", "freqdep")
#: PNG file of each pad figure, by the paper's figure number
PAD_FIGURE_FILES = {
    6: "fig06_pad_loops.png",
    7: "fig07_pad_temperature_sweep.png",
    8: "fig08_pad_stiffness.png",
}
#: band (Hz) and f0 (Hz) of the log-linear law read off each prediction
FIG8_BAND_HZ = (5.0, 1000.0)
_F0_HZ = 5.0


def study_prediction() -> PadPrediction:
    """The prediction from the shipped synthetic 0.3 Hz sweep at 20 degC (Tg found from it).

    Returns
    -------
    PadPrediction
        The pad of the study's predicted-pad presets (``wang2017_predicted_*``).
    """
    return predict_pad(read_measurements_csv(wj7_example_csv()), 20.0)


def _color_at(temperature_c: float) -> str:
    """The colour of the stated-value case nearest in pad temperature (one colour per case)."""
    near = min(("m30", "m10", "p20"), key=lambda k: abs(_TEMPERATURES_C[k] - temperature_c))
    return _CASES[near].color


#: pad temperatures of the stated-value temperature cases, degC (the paper's §3.4)
_TEMPERATURES_C = {"m30": -30.0, "m10": -10.0, "p20": 20.0}


def draw_fig6_loops(prediction: PadPrediction) -> Figure:
    """Fig. 6: force-displacement loops at the test frequency, -30 and +20 degC (derived).

    Parameters
    ----------
    prediction : PadPrediction
        Its sweep gives ``K'`` and ``K''`` at the test temperatures nearest -30, +20 degC.

    Returns
    -------
    matplotlib.figure.Figure
        The figure, laid out.
    """
    loops = prediction.hysteresis_loops()
    fig, ax = new_figure(figsize=(6.5, 4.6))
    plot_hysteresis_loops(
        [loop[1:] for loop in loops], colors=[_color_at(loop[0]) for loop in loops], ax=ax
    )
    ax.set_title(
        f"Fig. 6: loops at {prediction.test_frequency_hz:g} Hz, load 20-70 kN, derived from K' "
        f"and K''\n(linear viscoelastic ellipses) of the {SYNTHETIC_LABEL}",
        fontsize="small",
    )
    fig.tight_layout()
    return fig


def draw_fig7_sweep(prediction: PadPrediction) -> Figure:
    """Fig. 7: K' and loss factor against temperature at the test frequency, Tg marked.

    Parameters
    ----------
    prediction : PadPrediction
        The sweep and its Tg.

    Returns
    -------
    matplotlib.figure.Figure
        The figure, laid out.
    """
    fig, (ax_k, ax_e) = new_figure(figsize=(6.5, 5.6), nrows=2, ncols=1, sharex=True)
    plot_temperature_sweep(
        prediction.sweep,
        prediction.glass_transition_c,
        axes=(ax_k, ax_e),
        title=f"Fig. 7: {SYNTHETIC_LABEL}\nTg from the loss-factor peak (the paper: -40, -45, "
        "-45 °C for its three pads)",
    )
    ax_k.title.set_fontsize("small")
    fig.tight_layout()
    return fig


def _stated(ax_k: Axes, ax_e: Axes, cases: Mapping[str, Case], f: np.ndarray) -> None:
    for key in FIG8_STATED:
        case, study = cases[key], _CASES[key]
        k = build_pad(case).stiffness(f, case.track.pad_temperature_c)
        ax_k.plot(
            f,
            k.real / _KN_PER_MM,
            "--",
            color=study.color,
            lw=1.1,
            label=f"stated: {study.label}",
            gid=study.label,
        )
        ax_e.plot(f, k.imag / k.real, "--", color=study.color, lw=1.1, gid=study.label)


def _predicted(
    ax_k: Axes, ax_e: Axes, cases: Mapping[str, Case], prediction: PadPrediction, f: np.ndarray
) -> None:
    for key in FIG8_PREDICTED:
        case, study = cases[key], _CASES[key]
        t = case.track.pad_temperature_c
        pad = build_pad(case)
        k = pad.stiffness(f, t)
        law = fit_log_linear(pad, t, FIG8_BAND_HZ, f0_hz=_F0_HZ).model
        label = (
            f"{study.label}: K0 = {law.k0_n_per_m / _KN_PER_MM:.1f} kN/mm, κ = {law.exponent:.3f}"
        )
        ax_k.plot(f, k.real / _KN_PER_MM, color=study.color, lw=1.8, label=label, gid=study.label)
        ax_e.plot(f, k.imag / k.real, color=study.color, lw=1.8, gid=study.label)
        a_t, _ = prediction.pad.shift(t)
        nodes = prediction.master.reduced_frequency_hz / a_t
        nodes = nodes[(nodes >= f[0]) & (nodes <= f[-1])]
        kn = prediction.stiffness(nodes, t)
        ax_k.plot(nodes, kn.real / _KN_PER_MM, "o", color=study.color, ms=4, mfc="none")
        ax_e.plot(nodes, kn.imag / kn.real, "o", color=study.color, ms=4, mfc="none")
    ax_k.plot([], [], "o", color="0.3", ms=4, mfc="none", label="0.3 Hz test points, shifted")


def draw_fig8_prediction(cases: Mapping[str, Case], prediction: PadPrediction) -> Figure:
    """Fig. 8 as a prediction: K' and loss factor at -30, -10, +20 degC within 1000 Hz.

    Solid: the pads predicted from the 0.3 Hz sweep (the cases of :data:`FIG8_PREDICTED`,
    at their pad temperatures), with K0 and kappa read off over :data:`FIG8_BAND_HZ` in the
    legend and the shifted test points as circles. Dashed: the paper's stated laws
    ``K0 (f/f0)^0.07`` (with the viscous damping of those presets) of
    :data:`FIG8_STATED`, both "20 degC" pads (31.0 and 50 kN/mm) included.

    Parameters
    ----------
    cases : mapping of str to Case
        Validated study cases by key (all of :data:`FIG8_PREDICTED` and :data:`FIG8_STATED`).
    prediction : PadPrediction
        The prediction the predicted cases' pads come from (for the test points).

    Returns
    -------
    matplotlib.figure.Figure
        The figure, laid out.
    """
    f = np.geomspace(1.0, 1000.0, 300)
    fig, (ax_k, ax_e) = new_figure(
        figsize=(8.0, 8.6), nrows=2, ncols=1, sharex=True, height_ratios=(3, 2)
    )
    _stated(ax_k, ax_e, cases, f)
    _predicted(ax_k, ax_e, cases, prediction, f)
    for ax in (ax_k, ax_e):
        log_axis(ax, "x")
        log_axis(ax, "y")
        ax.grid(True, which="both", alpha=0.3)
    ax_k.tick_params(axis="y", which="minor", labelsize="x-small")
    ax_k.set_ylabel("storage stiffness K' [kN/mm]")
    ax_e.set_ylabel("loss factor η = K''/K' [-]")
    ax_e.set_xlabel("frequency [Hz]")
    fig.subplots_adjust(left=0.11, right=0.97, top=0.93, bottom=0.2, hspace=0.08)
    handles, labels = ax_k.get_legend_handles_labels()
    legend = fig.legend(
        handles, labels, loc="lower center", ncol=2, fontsize="x-small", frameon=False
    )
    legend.set_gid(LEGEND_GID)
    lo, hi = FIG8_BAND_HZ
    ax_k.set_title(
        f"Fig. 8: WJ-7 pad predicted from the 0.3 Hz sweep (solid; {SYNTHETIC_LABEL})\n"
        f"beside the paper's stated laws K0 (f/f0)^0.07 (dashed); K0, κ fitted over "
        f"{lo:g}-{hi:g} Hz, f0 = {_F0_HZ:g} Hz",
        fontsize="small",
    )
    return fig


def draw_pad_figures(
    cases: Mapping[str, Case], prediction: PadPrediction
) -> list[tuple[int, Figure, str]]:
    """Figs. 6, 7 and 8 (see the three functions above), with their numbers and file names.

    Parameters
    ----------
    cases : mapping of str to Case
        Validated study cases by key.
    prediction : PadPrediction
        The prediction from the sweep (:func:`study_prediction`).

    Returns
    -------
    list of (int, matplotlib.figure.Figure, str)
        The paper's figure number, the laid-out figure and its PNG file name.
    """
    return [
        (6, draw_fig6_loops(prediction), PAD_FIGURE_FILES[6]),
        (7, draw_fig7_sweep(prediction), PAD_FIGURE_FILES[7]),
        (8, draw_fig8_prediction(cases, prediction), PAD_FIGURE_FILES[8]),
    ]
