"""Time-domain Monte Carlo: sampled irregularities, Newmark runs, pooled Welch PSDs."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from railvib.coupling import CoupledSystem  # the system description only, not its solver
from railvib.errors import CaseError
from railvib.spectra.base import SpatialSpectrum
from railvib.validation._legacy import SYSTEM_FROM_BUNDLE, bundle_form
from railvib.validation.coupled import FiniteCoupledSystem, _finite_system
from railvib.validation.samples import wheel_irregularities
from railvib.validation.statistics import WelchEstimate, welch_psd
from railvib.validation.time_domain import output_dofs, simulate_time_domain

__all__ = ["MonteCarloResult", "MonteCarloSettings", "monte_carlo"]


@dataclass(frozen=True)
class MonteCarloSettings:
    """Settings of the time-domain Monte Carlo.

    Parameters
    ----------
    realisations : int
        Number of independent irregularity samples (>= 1).
    record_seconds : float
        Length of the analysed record of each realisation, s.
    discard_seconds : float
        Start-up time dropped before the record (fade-in plus decay of transients), s.
    ramp_seconds : float
        Half-cosine fade-in of the irregularity at the start, s.
    dt : float
        Newmark time step, s (1e-4: +0.8 % frequency warp at 500 Hz).
    decimation : int
        Record every `decimation`-th step; ``1 / (2 dt decimation)`` must exceed the input band.
    segment_seconds : float
        Welch segment length, s (frequency resolution ``1 / segment_seconds``).
    input_band : (float, float)
        Temporal band of the sampled irregularity, Hz.
    elements_per_span : int
        Hermite elements per bay of the time-domain track (2: 8e-4 receptance error at 500 Hz).
    margin_spans : int
        Bays of track beyond the outer wheels on each side.
    absorber_spans : int
        Bays with graded extra pad damping at each end (inside the margin).
    absorber_damping : float
        Extra pad damping at the outermost sleeper, N s/m.
    batch : int
        Realisations integrated together (columns of one right-hand side).
    """

    realisations: int = 8
    record_seconds: float = 40.0
    discard_seconds: float = 6.0
    ramp_seconds: float = 1.0
    dt: float = 1.0e-4
    decimation: int = 4
    segment_seconds: float = 4.0
    input_band: tuple[float, float] = (0.2, 650.0)
    elements_per_span: int = 2
    margin_spans: int = 40
    absorber_spans: int = 20
    absorber_damping: float = 2.0e5
    batch: int = 8

    def __post_init__(self) -> None:
        if int(self.realisations) < 1:
            raise CaseError("validate.realisations", self.realisations, ">= 1")
        nyquist = 0.5 / (self.dt * self.decimation)
        if not (0 < self.input_band[0] < self.input_band[1] < nyquist):
            raise CaseError(
                "validate.input_band", self.input_band, f"0 < low < high < {nyquist:g} (Hz)"
            )
        if self.segment_seconds > self.record_seconds:
            raise CaseError("validate.segment_seconds", self.segment_seconds, "<= record (s)")
        if self.discard_seconds < self.ramp_seconds:
            raise CaseError("validate.discard_seconds", self.discard_seconds, ">= ramp (s)")

    @classmethod
    def quick(cls) -> MonteCarloSettings:
        """Short records and few realisations, for the test suite (about 15 s per case)."""
        return cls(
            realisations=4,
            record_seconds=10.0,
            discard_seconds=4.0,
            ramp_seconds=0.5,
            segment_seconds=2.0,
            batch=4,
        )


@dataclass(frozen=True, eq=False)
class MonteCarloResult:
    """Pooled Welch estimate of the accelerations and the system that produced it.

    Attributes
    ----------
    estimate : WelchEstimate
        PSDs in (m/s^2)^2/Hz ((rad/s^2)^2/Hz for pitch), ``(n_freq, n_output)``.
    labels : tuple of str
        Output names (vehicle DOFs, then ``rail@wheel1`` ...).
    system : FiniteCoupledSystem
        The finite model integrated in time.
    """

    estimate: WelchEstimate
    labels: tuple[str, ...]
    system: FiniteCoupledSystem


def _monte_carlo_bundle(
    *bundle: Any,
    settings: MonteCarloSettings | None = None,
    seed: int = 0,
    progress: Callable[[int], None] | None = None,
) -> MonteCarloResult:
    """The deprecated form ``monte_carlo(vehicle, rail, pad, d, k_H, x0, v, spectrum, ...)``."""
    *system_bundle, spectrum = bundle
    s = settings if settings is not None else MonteCarloSettings()
    mesh: dict[str, Any] = {
        "margin_spans": s.margin_spans,
        "elements_per_span": s.elements_per_span,
        "absorber_spans": s.absorber_spans,
        "absorber_damping": s.absorber_damping,
    }
    system = _finite_system(*system_bundle, **mesh)
    return _run_monte_carlo(system, spectrum, s, seed, progress)


@bundle_form(
    _monte_carlo_bundle,
    "monte_carlo(vehicle, rail, pad, sleeper_spacing, contact_stiffness, "
    "leading_wheel_position, speed, spectrum, ...)",
    f"monte_carlo(system, spectrum, ...) with {SYSTEM_FROM_BUNDLE}",
)
def monte_carlo(
    system: CoupledSystem,
    spectrum: SpatialSpectrum,
    *,
    settings: MonteCarloSettings | None = None,
    seed: int = 0,
    progress: Callable[[int], None] | None = None,
) -> MonteCarloResult:
    """Acceleration PSDs of the vehicle and rail by time-domain Monte Carlo.

    The deprecated form ``monte_carlo(vehicle, rail, pad, sleeper_spacing,
    contact_stiffness, leading_wheel_position, speed, spectrum, ...)`` still works
    and warns.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle on the periodic track; its parameters build the finite track
        (:meth:`FiniteCoupledSystem.from_system`). The rail needs no loss factor and
        the pad must be a :class:`~railvib.pads.SpringDamper` (N/m, N s/m).
        k_H in N/m, leading wheel position in m, speed in m/s.
    spectrum : SpatialSpectrum
        One-sided irregularity spectrum, m^2/(rad/m).
    settings : MonteCarloSettings, optional
        Defaults to ``MonteCarloSettings()``.
    seed : int
        Base seed; realisation ``i`` is reproducible alone (see :func:`wheel_irregularities`).
    progress : callable, optional
        Called with the number of Newmark steps just done, summed over realisations.

    Returns
    -------
    MonteCarloResult
        PSDs in (m/s^2)^2/Hz, (rad/s^2)^2/Hz for pitch.
    """
    s = settings if settings is not None else MonteCarloSettings()
    finite = FiniteCoupledSystem.from_system(
        system,
        margin_spans=s.margin_spans,
        elements_per_span=s.elements_per_span,
        absorber_spans=s.absorber_spans,
        absorber_damping=s.absorber_damping,
    )
    return _run_monte_carlo(finite, spectrum, s, seed, progress)


def _run_monte_carlo(
    system: FiniteCoupledSystem,
    spectrum: SpatialSpectrum,
    s: MonteCarloSettings,
    seed: int,
    progress: Callable[[int], None] | None,
) -> MonteCarloResult:
    """Integrate the realisations in batches and pool their Welch PSDs."""
    dofs, labels = output_dofs(system)
    duration = s.discard_seconds + s.record_seconds
    fs = 1.0 / (s.dt * s.decimation)
    first = int(round(s.discard_seconds * fs))
    records = []
    for start in range(0, s.realisations, s.batch):
        idx = np.arange(start, min(start + s.batch, s.realisations))
        r = wheel_irregularities(
            spectrum,
            system.speed,
            system.vehicle.wheel_offsets,
            duration,
            s.dt,
            seed,
            realisations=idx,
            frequency_band=s.input_band,
            ramp=s.ramp_seconds,
        )
        width = idx.size

        def report(n: int, width: int = width) -> None:
            if progress is not None:
                progress(n * width)

        history = simulate_time_domain(
            system, r, s.dt, decimation=s.decimation, dofs=dofs, labels=labels, progress=report
        )
        records.append(history.acceleration[first:])
    data = np.concatenate(records, axis=2)
    estimate = welch_psd(data, fs, s.segment_seconds)
    return MonteCarloResult(estimate=estimate, labels=labels, system=system)
