"""Overlay plots of the three routes: PEM, finite track and Monte Carlo with its band."""

from __future__ import annotations

from pathlib import Path

from matplotlib.figure import Figure

from railvib.io import save_figure
from railvib.labels import leading_car_label, rail_label
from railvib.validation.result import ValidationResult

__all__ = ["DEFAULT_PLOT_RESPONSES", "plot_file_name", "plot_overlays"]

#: car body, bogie, wheelset and rail (the paper's figures)
DEFAULT_PLOT_RESPONSES = ("carbody.bounce", "bogie1.bounce", "wheelset2.bounce", rail_label(1))


def plot_file_name(prefix: str, response: str) -> str:
    """The overlay PNG of `response`: ``<prefix>_<response>.png`` (``.`` and ``@`` as ``_``).

    Parameters
    ----------
    prefix : str
        File name prefix.
    response : str
        Response label, e.g. ``rail@wheel1``.

    Returns
    -------
    str
        The PNG's file name.
    """
    return f"{prefix}_{response.replace('.', '_').replace('@', '_')}.png"


def plot_overlays(
    result: ValidationResult,
    outdir: str | Path,
    responses: tuple[str, ...] = DEFAULT_PLOT_RESPONSES,
    prefix: str = "validate",
) -> list[Path]:
    """Write one PNG per response: PEM, finite track, Monte Carlo and its band vs frequency.

    Parameters
    ----------
    result : ValidationResult
        Output of :func:`~railvib.validation.validate_case`.
    outdir : str or pathlib.Path
        Folder for the figures (created if missing).
    responses : tuple of str
        Response labels to plot; a label the vehicle lacks is drawn for a train's leading
        car (``car1.<label>``, ``rail@car1.wheel<j>``) where it has it, else left out (a
        vehicle without bogies).
    prefix : str
        File name prefix.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    units = dict(zip(result.frf["response"].values, result.frf.attrs["psd_units"], strict=True))
    for resp in _present(responses, set(units)):
        frf = result.frf.sel(response=resp)
        mc = result.mc.sel(response=resp)
        fig = Figure(figsize=(7.0, 4.2))
        ax = fig.add_subplot()
        ax.fill_between(
            mc["frequency"], mc["mc_lower"], mc["mc_upper"], color="0.8", label="MC 95 % band"
        )
        ax.plot(mc["frequency"], mc["mc_psd"], color="0.35", lw=0.6, label="Monte Carlo (Welch)")
        ax.plot(frf["frequency"], frf["pem_psd"], color="C0", lw=1.2, label="symplectic + PEM")
        ax.plot(frf["frequency"], frf["finite_psd"], "--", color="C3", lw=1.0, label="finite track")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("frequency (Hz)")
        ax.set_ylabel(f"acceleration PSD {units[resp]}")
        frac = float(mc["inside"].mean())
        err = float(frf["relative_error"].max())
        ax.set_title(f"{resp}: FE max err {err:.1e}, PEM in MC band {frac:.0%}")
        ax.legend(fontsize=8)
        ax.grid(True, which="both", lw=0.3)
        path = out / plot_file_name(prefix, resp)
        written.append(save_figure(fig, path))
    return written


def _present(responses: tuple[str, ...], labels: set[str]) -> list[str]:
    """`responses` found in `labels`, or their leading-car label in a train's."""
    out = []
    for resp in responses:
        label = resp if resp in labels else leading_car_label(resp)
        out += [label] if label in labels else []
    return out
