"""``railvib pad fit`` / ``pad predict`` as library calls: pads from measurements, TOML, plots."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import tomli_w

from railvib.case import case_from_dict
from railvib.errors import CaseError, did_you_mean
from railvib.io import new_figure, save_figure, staged_folder, write_text
from railvib.pads import (
    DEFAULT_EXPANSION_COEFFICIENT_PER_K,
    MODEL_ALIASES,
    PADS,
    WLF,
    LogLinearFit,
    ModelFit,
    PadPrediction,
    fit_log_linear,
    fit_pad,
    fittable_models,
    pad_toml,
    predict_pad,
    read_measurements_csv,
    wj7_example_csv,
)
from railvib.pads.fit import check_n_terms
from railvib.pads.tts import wlf_choice
from railvib.plot.pads import (
    plot_hysteresis_loops,
    plot_master_curve,
    plot_stiffness_vs_frequency,
    plot_temperature_sweep,
)
from railvib.presets import list_presets

__all__ = [
    "EXAMPLES",
    "PAD_FIT_FILES",
    "PAD_PREDICT_FILES",
    "PadFitJob",
    "PadFitReport",
    "PadPredictJob",
    "PadPredictReport",
    "fit_pad_to_folder",
    "predict_pad_to_folder",
    "write_example_data",
]

#: the shipped example data sets (synthetic WJ-7 pad, ``railvib/data/wj7/README.md``)
EXAMPLES = {
    "0p3hz": "wj7_synthetic_0p3hz.csv",
    "multifrequency": "wj7_synthetic_multifrequency.csv",
}

#: every file ``railvib pad fit`` writes to its folder (a later fit replaces them)
PAD_FIT_FILES = ("pad.toml", "master_curve.png", "stiffness_vs_frequency.png")
#: the files ``railvib pad predict`` writes into its folder (the set a later prediction replaces)
PAD_PREDICT_FILES = (
    "pad.toml",
    "case.toml",
    "fig06_hysteresis_loops.png",
    "fig07_temperature_sweep.png",
    "fig08_predicted_stiffness.png",
)

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

    Raises
    ------
    railvib.errors.CaseError
        Bad measurements or options, or `outdir` is not a folder (nothing written).
    railvib.errors.OutputError
        `outdir` or one of its files cannot be written (read-only, full disk).

    Notes
    -----
    The files are written into a staging folder put in place at the end
    (:func:`railvib.io.staged_folder`): `outdir` holds one fit's complete set
    (:data:`PAD_FIT_FILES`; other files are kept), and a fit that fails or is stopped
    leaves it as it was.
    """
    data, outdir = Path(data), Path(outdir)
    measurements = read_measurements_csv(data)
    with staged_folder(outdir, PAD_FIT_FILES) as stage:  # an unwritable folder: before fitting
        result = fit_pad(
            measurements,
            job.model,
            job.reference_temperature_c,
            job.wlf(),
            vertical_shift=job.vertical_shift,
            expansion_coefficient_per_k=job.expansion_coefficient_per_k,
            n_terms=job.n_terms,
            f0_hz=job.f0_hz,
        )
        band = (float(job.band_hz[0]), float(job.band_hz[1]))
        fits = tuple(
            fit_log_linear(result.model, t, band, f0_hz=job.f0_hz) for t in job.temperatures_c
        )
        text = "\n".join([result.summary(), *(_log_linear_line(ll, job.f0_hz) for ll in fits)])
        header = f"{job.command_line(data, outdir)}\n" + text
        toml = pad_toml(result.model, header=header)
        files = [write_text(stage.path / "pad.toml", toml)]
        files += _plots(result, job, data.name, stage.path)
    return PadFitReport(result, fits, text, tuple(stage.finals(files)))


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


#: the options of ``railvib pad predict`` by job field (the data file and folder apart)
_PREDICT_OPTIONS = {
    "temperature_c": "--temperature",
    "glass_transition_c": "--tg",
    "frequency_hz": "--frequency",
    "vertical_shift": "--no-vertical-shift",
    "expansion_coefficient_per_k": "--expansion-coefficient",
    "band_hz": "--band",
    "f0_hz": "--f0",
    "preset": "--preset",
}


@dataclass(frozen=True)
class PadPredictJob:
    """What to predict and report (the options of ``railvib pad predict``).

    Parameters
    ----------
    temperature_c : float
        Analysis temperature (the case's pad temperature and the master curve's
        reference), degC.
    glass_transition_c : float, optional
        Tg, degC; found from the loss-factor peak when omitted.
    frequency_hz : float, optional
        The test frequency to use when the data hold several, Hz.
    vertical_shift : bool
        Apply the density-temperature factor rho T / (rho0 T0).
    expansion_coefficient_per_k : float
        Volume expansion coefficient a_f, 1/K.
    band_hz : (float, float)
        Band of the K(f) plot and of the log-linear fit, Hz.
    f0_hz : float
        Reference frequency of the log-linear law, Hz.
    preset : str
        Preset the written ``case.toml`` starts from.
    """

    temperature_c: float = 20.0
    glass_transition_c: float | None = None
    frequency_hz: float | None = None
    vertical_shift: bool = True
    expansion_coefficient_per_k: float = DEFAULT_EXPANSION_COEFFICIENT_PER_K
    band_hz: tuple[float, float] = (5.0, 1000.0)
    f0_hz: float = 5.0
    preset: str = "wang2017_metro"

    def __post_init__(self) -> None:
        if len(self.band_hz) != 2:
            raise CaseError("pad_predict.band_hz (--band)", self.band_hz, "two frequencies (Hz)")
        presets = list_presets()
        if self.preset not in presets:
            raise CaseError(
                "pad_predict.preset (--preset)",
                self.preset,
                f"one of {', '.join(presets)}{did_you_mean(self.preset, presets)}",
            )

    def command_line(self, data: str | Path, outdir: str | Path | None = None) -> str:
        """The ``railvib pad predict`` command that runs this job on `data` into `outdir`.

        Parameters
        ----------
        data : str or pathlib.Path
            The measurements CSV, as the user gave it.
        outdir : str or pathlib.Path, optional
            The output folder (left out when None).

        Returns
        -------
        str
            E.g. ``railvib pad predict wj7.csv --temperature -10 -o out``; every option
            that differs from its default is written.
        """
        default = PadPredictJob()
        words = ["railvib pad predict", str(data)]
        for name, option in _PREDICT_OPTIONS.items():
            value = getattr(self, name)
            if value == getattr(default, name):
                continue
            if isinstance(value, bool):  # the one flag: --no-vertical-shift
                words.append(option)
            elif isinstance(value, tuple):
                words += [option, ",".join(f"{v:g}" for v in value)]
            elif isinstance(value, str):
                words += [option, value]
            else:
                words += [option, f"{value:g}"]
        if outdir is not None:
            words += ["-o", str(outdir)]
        return " ".join(words)


@dataclass(frozen=True, eq=False)
class PadPredictReport:
    """What :func:`predict_pad_to_folder` predicted and wrote.

    Parameters
    ----------
    prediction : PadPrediction
        The predicted pad and the procedure's numbers.
    log_linear : LogLinearFit
        The paper's log-linear law read off the prediction at the job's temperature.
    text : str
        The report printed by the command.
    files : tuple of pathlib.Path
        Files written.
    """

    prediction: PadPrediction
    log_linear: LogLinearFit
    text: str
    files: tuple[Path, ...]


def _prediction_plots(
    prediction: PadPrediction, fit: LogLinearFit, job: PadPredictJob, name: str, outdir: Path
) -> list[Path]:
    f_test = prediction.test_frequency_hz
    _, (ax_k, ax_e) = new_figure(figsize=(7, 6), nrows=2, ncols=1, sharex=True)
    plot_temperature_sweep(
        prediction.sweep,
        prediction.glass_transition_c,
        axes=(ax_k, ax_e),
        title=f"{name}: K' and loss factor at {f_test:g} Hz (cf. the paper's Fig. 7)",
    )
    files = [save_figure(ax_k, outdir / "fig07_temperature_sweep.png")]
    _, ax = new_figure(figsize=(6, 4.5))
    plot_hysteresis_loops([loop[1:] for loop in prediction.hysteresis_loops()], ax=ax)
    ax.set_title(
        f"{name}: loops at {f_test:g} Hz, 20-70 kN, derived from K' and K''\n"
        "(linear viscoelastic ellipses; cf. the paper's Fig. 6)",
        fontsize="medium",
    )
    files.append(save_figure(ax, outdir / "fig06_hysteresis_loops.png"))
    f = np.geomspace(job.band_hz[0], job.band_hz[1], 200)
    t = job.temperature_c
    _, (ax_s, ax_l) = new_figure(figsize=(7, 6), nrows=2, ncols=1, sharex=True)
    k = prediction.stiffness(f, t)
    plot_stiffness_vs_frequency(f, {t: k}, ax=ax_s)
    ll = fit.model
    ax_s.plot(
        f,
        ll.storage(f) / 1e6,
        "k--",
        lw=1.0,
        label=f"K0 (f/f0)^κ: K0 = {ll.k0_n_per_m / 1e6:.1f} kN/mm, κ = {ll.exponent:.3f}",
    )
    ax_s.legend(fontsize="small")
    ax_s.set_title(f"{name}: predicted K(f) at {t:g} °C (cf. the paper's Fig. 8)")
    plot_stiffness_vs_frequency(f, {t: k}, quantity="loss_factor", ax=ax_l)
    files.append(save_figure(ax_s, outdir / "fig08_predicted_stiffness.png"))
    return files


def predict_pad_to_folder(
    data: str | Path, outdir: str | Path, job: PadPredictJob
) -> PadPredictReport:
    """Predict the pad from the sweep in CSV `data`; write ``pad.toml``, ``case.toml``, plots.

    The paper's procedure (:func:`railvib.pads.predict_pad`) on a single-frequency
    temperature sweep, at `job.temperature_c`. Everything is computed and the case is
    validated before any file is written; the files are written into a staging folder
    put in place at the end (:func:`railvib.io.staged_folder`), so `outdir` holds one
    prediction's complete set (:data:`PAD_PREDICT_FILES`; other files are kept).

    Parameters
    ----------
    data : str or pathlib.Path
        Measurements CSV (see :func:`railvib.pads.read_measurements_csv`): one test
        frequency, many temperatures.
    outdir : str or pathlib.Path
        Output folder: ``pad.toml`` (``[track]`` with ``pad_temperature_c`` and the
        ``[track.pad]`` table), ``case.toml`` (the same on `job.preset`, runnable with
        ``railvib run``), ``fig06_hysteresis_loops.png``, ``fig07_temperature_sweep.png``
        and ``fig08_predicted_stiffness.png``.
    job : PadPredictJob
        The options.

    Returns
    -------
    PadPredictReport
    """
    data, outdir = Path(data), Path(outdir)
    prediction = predict_pad(
        read_measurements_csv(data),
        job.temperature_c,
        glass_transition_c=job.glass_transition_c,
        frequency_hz=job.frequency_hz,
        vertical_shift=job.vertical_shift,
        expansion_coefficient_per_k=job.expansion_coefficient_per_k,
    )
    band = (float(job.band_hz[0]), float(job.band_hz[1]))
    fit = fit_log_linear(prediction.pad, job.temperature_c, band, f0_hz=job.f0_hz)
    lo, hi = prediction.frequency_window_hz()
    text = "\n".join(
        [
            prediction.summary(),
            f"at {job.temperature_c:g} degC the test points cover {lo:.3g} to {hi:.3g} Hz "
            "(outside, the end values are held)",
            _log_linear_line(fit, job.f0_hz),
        ]
    )
    tables = prediction.case_tables()
    case_doc = {
        "preset": job.preset,
        "title": f"{job.preset} with the pad predicted from {data.name} at "
        f"{job.temperature_c:g} degC",
        **tables,
    }
    case_from_dict(case_doc, warn=False)  # refuse a case that would not load, before writing
    header = "".join(f"# {line}\n" for line in (job.command_line(data, outdir), *text.splitlines()))
    with staged_folder(outdir, PAD_PREDICT_FILES) as stage:
        files = [
            write_text(stage.path / "pad.toml", header + tomli_w.dumps(tables)),
            write_text(stage.path / "case.toml", header + tomli_w.dumps(case_doc)),
        ]
        files += _prediction_plots(prediction, fit, job, data.name, stage.path)
    return PadPredictReport(prediction, fit, text, tuple(stage.finals(files)))


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
