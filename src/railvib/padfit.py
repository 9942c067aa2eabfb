"""``railvib pad fit`` as a library call: fit a pad model to measurements, write TOML and plots."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from railvib.errors import CaseError, did_you_mean
from railvib.io import new_figure, save_figure, write_text
from railvib.pads import (
    DEFAULT_EXPANSION_COEFFICIENT_PER_K,
    MODEL_ALIASES,
    PADS,
    WLF,
    LogLinearFit,
    ModelFit,
    fit_log_linear,
    fit_pad,
    fittable_models,
    pad_toml,
    read_measurements_csv,
    wj7_example_csv,
)
from railvib.pads.fit import check_n_terms
from railvib.pads.tts import wlf_choice
from railvib.plot.pads import plot_master_curve, plot_stiffness_vs_frequency

__all__ = ["EXAMPLES", "PadFitJob", "PadFitReport", "fit_pad_to_folder", "write_example_data"]

#: the shipped example data sets (synthetic WJ-7 pad, ``railvib/data/wj7/README.md``)
EXAMPLES = {
    "0p3hz": "wj7_synthetic_0p3hz.csv",
    "multifrequency": "wj7_synthetic_multifrequency.csv",
}

#: the job's fields with their command-line options (model and output folder apart)
_OPTIONS = {
    "reference_temperature_c": "--reference-temperature",
    "glass_transition_c": "--tg",
    "c1": "--c1",
    "c2_k": "--c2",
    "wlf_reference_temperature_c": "--wlf-reference",
    "vertical_shift": "--no-vertical-shift",
    "expansion_coefficient_per_k": "--expansion-coefficient",
    "n_terms": "--n-terms",
    "temperatures_c": "--temperatures",
    "band_hz": "--band",
    "f0_hz": "--f0",
}

#: the WLF choices with their command-line options, for error messages
_NAMES = {
    "glass_transition_c": "glass_transition_c (--tg)",
    "c1": "c1 (--c1)",
    "c2_k": "c2_k (--c2)",
    "wlf_reference_temperature_c": "wlf_reference_temperature_c (--wlf-reference)",
}


@dataclass(frozen=True)
class PadFitJob:
    """What to fit and report (the options of ``railvib pad fit``).

    Parameters
    ----------
    model : str
        Pad model to fit to the master curve (a fittable registered model).
    reference_temperature_c : float
        Master-curve reference temperature, degC.
    glass_transition_c : float, optional
        Tg, degC: use the universal WLF constants at Tg.
    c1, c2_k : float, optional
        Given WLF constants (dimensionless, K); with neither these nor Tg the WLF
        constants are fitted (multi-frequency data needed).
    wlf_reference_temperature_c : float, optional
        Temperature at which `c1` and `c2_k` apply, degC (default: the reference).
    vertical_shift : bool
        Apply the density-temperature factor rho T / (rho0 T0).
    expansion_coefficient_per_k : float
        Volume expansion coefficient a_f, 1/K.
    n_terms : int, optional
        Prony branches (``generalized_maxwell``).
    temperatures_c : tuple of float
        Temperatures of the K(f) plot and of the log-linear fits, degC.
    band_hz : (float, float)
        Frequency band of the K(f) plot and of the log-linear fits, Hz.
    f0_hz : float
        Reference frequency of the log-linear law, Hz.
    """

    model: str = "fractional_zener"
    reference_temperature_c: float = 20.0
    glass_transition_c: float | None = None
    c1: float | None = None
    c2_k: float | None = None
    wlf_reference_temperature_c: float | None = None
    vertical_shift: bool = True
    expansion_coefficient_per_k: float = DEFAULT_EXPANSION_COEFFICIENT_PER_K
    n_terms: int | None = None
    temperatures_c: tuple[float, ...] = (-30.0, -10.0, 20.0)
    band_hz: tuple[float, float] = (1.0, 1000.0)
    f0_hz: float = 5.0

    def __post_init__(self) -> None:
        fittable = fittable_models()
        if self.model not in PADS or PADS.get(self.model).name not in fittable:
            aliases = [a for a, n in MODEL_ALIASES.items() if n in fittable]
            close = did_you_mean(self.model, [*fittable, *aliases])
            raise CaseError(
                "model",
                self.model,
                f"one of {', '.join(fittable)} (aliases {', '.join(aliases)}){close}",
            )
        check_n_terms(self.n_terms, "pad_fit.n_terms (--n-terms)")
        if len(self.band_hz) != 2:
            raise CaseError("pad_fit.band_hz (--band)", self.band_hz, "two frequencies (Hz)")
        self.wlf()  # a contradictory WLF choice is refused before any fitting

    def command_line(self, data: str | Path, outdir: str | Path | None = None) -> str:
        """The ``railvib pad fit`` command that runs this job on `data` into `outdir`.

        Every option that differs from its default is written (``--model`` always), so
        the command reproduces the fit.

        Parameters
        ----------
        data : str or pathlib.Path
            The measurements CSV, as the user gave it.
        outdir : str or pathlib.Path, optional
            The output folder (left out when None).

        Returns
        -------
        str
            E.g. ``railvib pad fit wj7.csv --model zener --tg -40 -o out``.
        """
        default = PadFitJob()
        words = ["railvib pad fit", str(data), "--model", self.model]
        for name, option in _OPTIONS.items():
            value = getattr(self, name)
            if value == getattr(default, name):
                continue
            if isinstance(value, bool):  # the one flag: --no-vertical-shift
                words.append(option)
            elif isinstance(value, tuple):
                words += [option, ",".join(f"{v:g}" for v in value)]
            else:
                words += [option, f"{value:g}"]
        if outdir is not None:
            words += ["-o", str(outdir)]
        return " ".join(words)

    def wlf(self) -> WLF | None:
        """The WLF law chosen (None: fit it), see :func:`railvib.pads.tts.wlf_choice`."""
        return wlf_choice(
            self.reference_temperature_c,
            self.glass_transition_c,
            self.c1,
            self.c2_k,
            self.wlf_reference_temperature_c,
            field="pad_fit",
            names=_NAMES,
        )


@dataclass(frozen=True, eq=False)
class PadFitReport:
    """What :func:`fit_pad_to_folder` fitted and wrote.

    Parameters
    ----------
    fit : ModelFit
        The temperature-shifted model and its residuals.
    log_linear : tuple of LogLinearFit
        The paper's log-linear law fitted at each requested temperature.
    text : str
        The report printed by the command.
    files : tuple of pathlib.Path
        Files written.
    """

    fit: ModelFit
    log_linear: tuple[LogLinearFit, ...]
    text: str
    files: tuple[Path, ...]


def fit_pad_to_folder(data: str | Path, outdir: str | Path, job: PadFitJob) -> PadFitReport:
    """Fit `job.model` to the measurements in CSV `data`; write ``pad.toml`` and two plots.

    Parameters
    ----------
    data : str or pathlib.Path
        Measurements CSV (see :func:`railvib.pads.read_measurements_csv`).
    outdir : str or pathlib.Path
        Output folder: ``pad.toml`` (a ``[track.pad]`` table usable in a case file),
        ``master_curve.png``, ``stiffness_vs_frequency.png``.
    job : PadFitJob
        The options.

    Returns
    -------
    PadFitReport
    """
    data, outdir = Path(data), Path(outdir)
    result = fit_pad(
        read_measurements_csv(data),
        job.model,
        job.reference_temperature_c,
        job.wlf(),
        vertical_shift=job.vertical_shift,
        expansion_coefficient_per_k=job.expansion_coefficient_per_k,
        n_terms=job.n_terms,
        f0_hz=job.f0_hz,
    )
    band = (float(job.band_hz[0]), float(job.band_hz[1]))
    fits = tuple(fit_log_linear(result.model, t, band, f0_hz=job.f0_hz) for t in job.temperatures_c)
    text = "\n".join([result.summary(), *(_log_linear_line(ll, job.f0_hz) for ll in fits)])
    header = f"{job.command_line(data, outdir)}\n" + text
    files = [write_text(outdir / "pad.toml", pad_toml(result.model, header=header))]
    files += _plots(result, job, data.name, outdir)
    return PadFitReport(result, fits, text, tuple(files))


def _log_linear_line(ll: LogLinearFit, f0_hz: float) -> str:
    lo, hi = ll.band_hz
    return (
        f"log-linear at {ll.temperature_c:g} degC over {lo:g}-{hi:g} Hz: "
        f"K0 = {ll.model.k0_n_per_m / 1e6:.1f} kN/mm at {f0_hz:g} Hz, "
        f"k = {ll.model.exponent:.3f} (rms {ll.rms_log10:.3f} decades)"
    )


def _plots(result: ModelFit, job: PadFitJob, name: str, outdir: Path) -> Sequence[Path]:
    master = result.master
    assert master is not None, "fit_pad returns the master curve it fitted"
    fr = master.reduced_frequency_hz
    f_curve = np.geomspace(fr.min(), fr.max(), 400)
    _, panels = new_figure(figsize=(7, 6.5), nrows=2, ncols=1, sharex=True)
    axes = plot_master_curve(
        master, f_curve, result.model.stiffness(f_curve), axes=(panels[0], panels[1])
    )
    f_plot = np.geomspace(job.band_hz[0], job.band_hz[1], 200)
    curves = {t: result.model.stiffness(f_plot, t) for t in job.temperatures_c}
    _, ax = new_figure(figsize=(7, 4))
    ax = plot_stiffness_vs_frequency(f_plot, curves, ax=ax)
    ax.set_title(f"{name}: {job.model} with TTS")
    return [
        save_figure(axes[0], outdir / "master_curve.png", tight=False),
        save_figure(ax, outdir / "stiffness_vs_frequency.png"),
    ]


def write_example_data(outdir: str | Path, multifrequency: bool = False) -> Path:
    """Copy a shipped example measurements CSV into `outdir` (``railvib pad example``).

    The data are synthetic (a WJ-7-like pad; ``railvib/data/wj7/README.md`` says how
    they were made), in the columns :func:`railvib.pads.read_measurements_csv` reads.

    Parameters
    ----------
    outdir : str or pathlib.Path
        Folder to write into (created if missing).
    multifrequency : bool
        The DMA-style file (7 frequencies, 0.1-100 Hz, at each temperature, enough to
        fit the WLF constants) instead of the 0.3 Hz temperature sweep.

    Returns
    -------
    pathlib.Path
        The CSV written.
    """
    name = EXAMPLES["multifrequency" if multifrequency else "0p3hz"]
    text = wj7_example_csv(name).read_text(encoding="utf-8")
    return write_text(Path(outdir) / name, text)
