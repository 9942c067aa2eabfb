"""Settings and outcome of a validation: :class:`ValidationSettings`, :class:`ValidationResult`.

Acceptance (issue 5):

* the finite-track frequency-domain acceleration PSDs agree with PEM within 2 %
  (``| S_finite / S_pem - 1 |``) at every frequency from 1 Hz to 1 kHz;
* the PEM PSDs lie inside the Monte Carlo 95 % chi-square band in at least 90 % of
  the Welch bins from 1 to 500 Hz, for each response. PEM is compared as the Welch
  estimator sees it (:func:`~railvib.validation.statistics.welch_expectation`:
  the PEM PSD convolved with the spectral window of one segment), which is the
  expectation of the Monte Carlo estimate; the raw point values are reported too.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import xarray as xr

from railvib.validation.monte_carlo import MonteCarloSettings

__all__ = [
    "BAND_FRACTION",
    "FRF_TOLERANCE",
    "ValidationResult",
    "ValidationSettings",
    "monte_carlo_work",
]

FRF_TOLERANCE = 0.02  # issue 5: finite track vs PEM within 2 %
BAND_FRACTION = 0.90  # issue 5: PEM inside the MC band in >= 90 % of bins


@dataclass(frozen=True)
class ValidationSettings:
    """Settings of :func:`~railvib.validation.validate_case`.

    Parameters
    ----------
    f_min : float
        Lowest compared frequency, Hz.
    f_max_frf : float
        Highest frequency of the finite-track comparison, Hz.
    f_max_mc : float
        Highest frequency of the Monte Carlo comparison, Hz.
    n_frf : int
        Number of log-spaced frequencies of the finite-track comparison.
    frf_margin_spans : int
        Bays of finite track beyond the outer wheels (frequency domain).
    frf_elements_per_span : int
        Hermite elements per bay (frequency domain).
    frf_slab_margin_spans : int
        Fastener spacings of finite slab track beyond the outer wheels (frequency domain),
        the outer 5/6 absorbing: near a stop-band edge of the slab on its bearings a wave
        reaches far (floating_slab_metro with a lossless slab, at 396 Hz: 3.9e-2 with 240
        spacings, 1.3e-2 with 480, 3.2e-3 with 960).
    confidence : float
        Confidence level of the Monte Carlo band.
    bands : tuple of (float, float)
        Frequency bands of the agreement table, Hz.
    monte_carlo : MonteCarloSettings
        Time-domain settings.
    """

    f_min: float = 1.0
    f_max_frf: float = 1000.0
    f_max_mc: float = 500.0
    n_frf: int = 600
    frf_margin_spans: int = 60
    frf_elements_per_span: int = 8
    frf_slab_margin_spans: int = 960
    confidence: float = 0.95
    bands: tuple[tuple[float, float], ...] = ((1.0, 10.0), (10.0, 100.0), (100.0, 1000.0))
    monte_carlo: MonteCarloSettings = field(default_factory=MonteCarloSettings)

    @classmethod
    def quick(cls, realisations: int | None = None) -> ValidationSettings:
        """Settings for the test suite: 150 FRF points, short Monte Carlo (about 20 s a case).

        Parameters
        ----------
        realisations : int, optional
            Number of Monte Carlo realisations; None keeps that of
            :meth:`MonteCarloSettings.quick`.

        Returns
        -------
        ValidationSettings
        """
        mc = MonteCarloSettings.quick()
        if realisations is not None:
            mc = replace(mc, realisations=int(realisations))
        return cls(n_frf=150, frf_margin_spans=40, frf_slab_margin_spans=480, monte_carlo=mc)

    def with_realisations(self, realisations: int | None) -> ValidationSettings:
        """These settings with `realisations` Monte Carlo realisations (unchanged if None)."""
        if realisations is None:
            return self
        return replace(self, monte_carlo=replace(self.monte_carlo, realisations=int(realisations)))


@dataclass(frozen=True, eq=False)
class ValidationResult:
    """Outcome of :func:`~railvib.validation.validate_case`.

    Attributes
    ----------
    frf : xarray.Dataset
        Finite track vs PEM on a log grid (dims ``frequency`` in Hz, ``response``):
        acceleration PSDs ``pem_psd`` and ``finite_psd`` in (m/s^2)^2/Hz ((rad/s^2)^2/Hz
        for pitch; per-response units in the ``psd_units`` attribute) and
        ``relative_error`` (1).
    mc : xarray.Dataset
        Monte Carlo on the Welch bins, PSDs in the same units: ``pem_psd``,
        ``pem_expected``, ``mc_psd``, ``mc_lower``, ``mc_upper``; booleans ``inside``,
        ``inside_raw`` (units 1).
    table : xarray.Dataset
        Per band (Hz) and response, units 1: ``max_relative_error`` (finite track),
        ``fraction_inside`` and ``fraction_inside_raw`` (Monte Carlo).
    timings : dict
        Wall-clock seconds of each route (``pem_seconds``, ``finite_track_seconds``,
        ``monte_carlo_seconds``).
    approximations : tuple of str
        One line per layer that all three routes took as a causal fit of a hysteretic
        one (:func:`railvib.validation.causal.causal_system`), with its error over the
        band; empty where none was needed.
    """

    frf: xr.Dataset
    mc: xr.Dataset
    table: xr.Dataset
    timings: dict[str, float]
    approximations: tuple[str, ...] = ()

    @property
    def max_relative_error(self) -> xr.DataArray:
        """Finite track vs PEM, max over the whole FRF band, per response."""
        return self.frf["relative_error"].max("frequency")

    @property
    def fraction_inside(self) -> xr.DataArray:
        """Fraction of Welch bins with PEM inside the band, over the MC range, per response."""
        return self.mc["inside"].mean("frequency")

    @property
    def passed(self) -> bool:
        """Both acceptance criteria of issue 5 hold for every response."""
        return bool(
            (self.max_relative_error <= FRF_TOLERANCE).all()
            and (self.fraction_inside >= BAND_FRACTION).all()
        )

    def summary_markdown(self) -> str:
        """Markdown table: per response, finite-track max error and fraction inside the MC band."""
        lines = [
            "| response | finite track max rel. error | PEM inside MC band | raw PEM inside |",
            "|---|---|---|---|",
        ]
        raw = self.mc["inside_raw"].mean("frequency")
        for resp in self.frf["response"].values:
            lines.append(
                f"| {resp} | {float(self.max_relative_error.sel(response=resp)):.2e} "
                f"| {float(self.fraction_inside.sel(response=resp)):.1%} "
                f"| {float(raw.sel(response=resp)):.1%} |"
            )
        return "\n".join(lines)

    def table_markdown(self) -> str:
        """Markdown table of agreement per frequency band and response."""
        bands = list(self.table["band"].values)
        head = "| response | " + " | ".join(f"{b} Hz: FE err / MC in" for b in bands) + " |"
        lines = [head, "|---" * (len(bands) + 1) + "|"]
        for resp in self.table["response"].values:
            cells = []
            for b in bands:
                err = float(self.table["max_relative_error"].sel(band=b, response=resp))
                frac = float(self.table["fraction_inside"].sel(band=b, response=resp))
                frac_s = "-" if np.isnan(frac) else f"{frac:.0%}"
                cells.append(f"{err:.1e} / {frac_s}")
            lines.append(f"| {resp} | " + " | ".join(cells) + " |")
        return "\n".join(lines)


def monte_carlo_work(settings: ValidationSettings) -> int:
    """Total Newmark steps times realisations of one case (for a progress bar).

    Parameters
    ----------
    settings : ValidationSettings
        The validation settings; only their Monte Carlo part is used.

    Returns
    -------
    int
        ``round((discard_seconds + record_seconds) / dt) * realisations``.
    """
    mc = settings.monte_carlo
    steps = int(round((mc.discard_seconds + mc.record_seconds) / mc.dt))
    return steps * mc.realisations
