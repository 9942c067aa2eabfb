"""The paper's prediction: K*(f, T) from stiffness measured at one frequency over temperatures.

Wang et al. 2017, section 3.2 (Eqs. 20-26 and the procedure's steps 1-5), on a test at
one frequency (0.3 Hz) over many temperatures (-60 to +20 degC every 2.5 degC):

1. degC and K differ by a constant, so temperature differences are the same in both
   (:func:`railvib.units.celsius_to_kelvin` where absolute temperatures are needed);
2. Tg is the temperature of the loss-factor maximum (:func:`loss_factor_peak`); the WLF
   constants at Tg are the universal C1 = 17.44, C2 = 51.6 K (:meth:`WLF.universal`);
3. they are re-referenced to the analysis temperature T0 = Tg + Delta,
   ``C1' = C1 C2 / (C2 + Delta)``, ``C2' = C2 + Delta`` (:meth:`WLF.rereferenced`);
4. the shift factor ``a_T`` follows from WLF (:meth:`WLF.log_shift`), each test point
   moves to the reduced frequency ``f a_T`` (:meth:`WLF.reduced_frequency`);
5. the vertical factor ``rho T / (rho0 T0)`` with ``rho / rho0 = 1 / (1 + a_f (T - T0))``,
   ``a_f = 4.8e-4 /K`` (:func:`vertical_shift_factor`) is divided out: the master curve
   at T0 (:func:`railvib.pads.fit.build_master_curve`).

:func:`predict_pad` runs the steps and returns the master curve as a pad: a
:class:`~railvib.pads.tabulated.TabulatedPad` of the shifted points (interpolated in
log-frequency, no model fitted) wrapped in :class:`~railvib.pads.tts.TemperatureShifted`,
so it gives ``K*(f, T)`` at any temperature and a case's ``track.pad_temperature_c``
decides where it is evaluated.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PADS
from railvib.pads.fit import MasterCurve, build_master_curve
from railvib.pads.io import Measurements
from railvib.pads.tabulated import TabulatedPad
from railvib.pads.tts import (
    DEFAULT_EXPANSION_COEFFICIENT_PER_K,
    UNIVERSAL_C1,
    UNIVERSAL_C2_K,
    WLF,
    TemperatureShifted,
)

__all__ = [
    "LOSS_PEAK_HALF_WIDTH_C",
    "PAPER_LOAD_RANGE_N",
    "PadPrediction",
    "hysteresis_loop",
    "loss_factor_peak",
    "predict_pad",
    "single_frequency_sweep",
]

#: half-width of the window of the loss-peak parabola about the largest loss factor, K:
#: three steps of the paper's 2.5 degC protocol on each side (seven points)
LOSS_PEAK_HALF_WIDTH_C = 7.5

#: the paper's test load on a pad, cycling between 20 and 70 kN (section 3.2.2), N
PAPER_LOAD_RANGE_N = (20.0e3, 70.0e3)

#: refits of the loss-peak parabola about its own vertex when that lies outside the window
_PEAK_ITERATIONS = 4

_TG_HINT = "give Tg (glass_transition_c, --tg)"


def loss_factor_peak(
    temperature_c: ArrayLike,
    loss_factor: ArrayLike,
    half_width_c: float = LOSS_PEAK_HALF_WIDTH_C,
) -> float:
    """Temperature of the loss-factor maximum, degC (step 2: the glass transition Tg).

    A least-squares parabola ``eta(T)`` through the points within `half_width_c` of the
    largest measured loss factor (at least that point and its two neighbours); its vertex
    is the peak. Where noise has moved the largest point so far that the vertex lies
    outside the window, the parabola is refitted about the vertex (a few times at most).
    The parabola averages the measurement noise over the points of the peak's top; on a
    symmetric peak sampled symmetrically it returns the centre exactly.

    Parameters
    ----------
    temperature_c : array_like
        Test temperatures, degC, distinct (any order).
    loss_factor : array_like
        Loss factor ``eta = K''/K'`` at each, dimensionless.
    half_width_c : float
        Half-width of the window about the largest loss factor, K (> 0).

    Returns
    -------
    float
        The peak temperature, degC.

    Raises
    ------
    CaseError
        Fewer than 3 temperatures, or the largest loss factor at the coldest or warmest
        temperature (no peak within the range: Tg cannot be found), or no maximum.
    """
    t = np.asarray(temperature_c, dtype=float).ravel()
    eta = np.asarray(loss_factor, dtype=float).ravel()
    if not (np.isfinite(half_width_c) and half_width_c > 0):
        raise CaseError("half_width_c", half_width_c, "> 0 (K)")
    if t.size != eta.size or t.size < 3:
        raise CaseError(
            "data.temperature_c",
            sorted(set(t.tolist())),
            f"at least 3 temperatures to find the loss-factor peak; Tg cannot be found "
            f"from fewer ({_TG_HINT})",
        )
    order = np.argsort(t)
    t, eta = t[order], eta[order]
    i = int(np.argmax(eta))
    if i in (0, t.size - 1):
        end = "coldest" if i == 0 else "warmest"
        raise CaseError(
            "data.loss_factor",
            f"largest {eta[i]:.4g} at {t[i]:g} degC",
            f"a loss-factor peak inside the measured range {t[0]:g} to {t[-1]:g} degC; the "
            f"largest is at the {end} temperature, so Tg cannot be found ({_TG_HINT})",
        )
    centre = float(t[i])
    for _ in range(_PEAK_ITERATIONS):
        near = np.abs(t - centre) <= half_width_c * (1 + 1e-12)
        j = int(np.argmin(np.abs(t - centre)))
        near[max(j - 1, 0) : j + 2] = True
        x = t[near] - centre
        a, b, _ = np.polyfit(x, eta[near], 2)
        vertex = centre - b / (2 * a) if a < 0 else np.nan
        if not np.isfinite(vertex) or not t[0] < vertex < t[-1]:
            break
        if x.min() <= vertex - centre <= x.max():
            return float(vertex)
        centre = float(vertex)  # noise moved the largest point: fit about the vertex
    raise CaseError(
        "data.loss_factor",
        f"largest {eta[i]:.4g} at {t[i]:g} degC",
        f"a loss-factor peak (a maximum of a parabola over +/-{half_width_c:g} degC about "
        f"it); none found inside {t[0]:g} to {t[-1]:g} degC, so Tg cannot be found ({_TG_HINT})",
    )


def hysteresis_loop(
    storage_n_per_m: float,
    loss_n_per_m: float,
    load_range_n: tuple[float, float] = PAPER_LOAD_RANGE_N,
    n_points: int = 241,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One steady cycle of a linear viscoelastic pad under a sinusoidal load (a Fig. 6 loop).

    The load cycles as ``F = F_m + F_a sin(theta)`` between the two values of
    `load_range_n`; the displacement about its mean lags by the loss angle
    ``delta = atan(K''/K')``: ``x = F_a / |K*| sin(theta - delta)``. The loop is an
    ellipse whose area, the energy dissipated per cycle, is ``pi K'' (F_a / |K*|)^2``.
    It is derived from ``K*`` at the test frequency, not a measured curve.

    Parameters
    ----------
    storage_n_per_m, loss_n_per_m : float
        ``K'`` (> 0) and ``K''`` (>= 0) at the test frequency, N/m.
    load_range_n : (float, float)
        Smallest and largest load of the cycle, N (the paper: 20 and 70 kN).
    n_points : int
        Points along the cycle (the first and last coincide), >= 3.

    Returns
    -------
    displacement_m : numpy.ndarray
        Displacement about the mean, m (positive: compression).
    force_n : numpy.ndarray
        Load, N.
    """
    if not (storage_n_per_m > 0 and loss_n_per_m >= 0):
        raise CaseError("stiffness", (storage_n_per_m, loss_n_per_m), "K' > 0 and K'' >= 0 (N/m)")
    lo, hi = load_range_n
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise CaseError("load_range_n", load_range_n, "(smallest, largest), smallest < largest (N)")
    theta = np.linspace(0.0, 2 * np.pi, max(int(n_points), 3))
    f_m, f_a = 0.5 * (lo + hi), 0.5 * (hi - lo)
    k = complex(storage_n_per_m, loss_n_per_m)
    x = f_a / abs(k) * np.sin(theta - np.angle(k))
    return x, f_m + f_a * np.sin(theta)


def single_frequency_sweep(data: Measurements, frequency_hz: float | None = None) -> Measurements:
    """The rows of one test frequency, sorted by temperature (the paper's protocol).

    Parameters
    ----------
    data : Measurements
        Measured stiffness.
    frequency_hz : float, optional
        The test frequency to use, Hz; needed only when `data` holds several.

    Returns
    -------
    Measurements
        One row per temperature, coldest first, all at one frequency.

    Raises
    ------
    CaseError
        Several frequencies and none chosen, a frequency not in the data, a repeated
        temperature, or fewer than 2 temperatures.
    """
    freqs = np.unique(data.frequency_hz)
    if frequency_hz is None:
        if freqs.size > 1:
            raise CaseError(
                "data.frequency_hz",
                [float(f) for f in freqs],
                "one test frequency (the paper's protocol: one frequency over many "
                "temperatures); choose one (frequency_hz, --frequency) or fit a model to "
                "multi-frequency data with `railvib pad fit`",
            )
        frequency_hz = float(freqs[0])
    rows = np.flatnonzero(np.isclose(data.frequency_hz, frequency_hz, rtol=1e-9, atol=0.0))
    if rows.size == 0:
        raise CaseError(
            "frequency_hz",
            frequency_hz,
            f"one of the test frequencies {', '.join(f'{f:g}' for f in freqs)} (Hz)",
        )
    t = data.temperature_c[rows]
    values, counts = np.unique(t, return_counts=True)
    if np.any(counts > 1):
        raise CaseError(
            "data.temperature_c",
            float(values[np.argmax(counts > 1)]),
            f"one row per temperature at {frequency_hz:g} Hz (this one is repeated)",
        )
    if rows.size < 2:
        raise CaseError(
            "data.temperature_c",
            [float(x) for x in t],
            f"at least 2 temperatures at {frequency_hz:g} Hz: the prediction shifts a "
            "temperature sweep onto frequency (3 to find Tg from the loss-factor peak)",
        )
    rows = rows[np.argsort(t)]
    return Measurements(
        data.temperature_c[rows],
        data.frequency_hz[rows],
        data.storage_n_per_m[rows],
        data.loss_n_per_m[rows],
    )


@dataclass(frozen=True, eq=False)
class PadPrediction:
    """The pad predicted from a single-frequency temperature sweep (:func:`predict_pad`).

    Parameters
    ----------
    sweep : Measurements
        The sweep used: one frequency, one row per temperature, coldest first.
    glass_transition_c : float
        Tg, degC.
    glass_transition_found : bool
        True when Tg was found from the loss-factor peak, False when it was given.
    temperature_c : float
        Analysis temperature T0: the master curve's reference, degC.
    master : MasterCurve
        The sweep shifted onto T0 (its `wlf` is the universal law re-referenced to T0).
    pad : TemperatureShifted
        The master curve as a tabulated pad with the universal WLF law at Tg:
        ``pad.stiffness(f, T)`` is the prediction at any temperature T, N/m.
    """

    sweep: Measurements
    glass_transition_c: float
    glass_transition_found: bool
    temperature_c: float
    master: MasterCurve
    pad: TemperatureShifted

    @property
    def test_frequency_hz(self) -> float:
        """The sweep's test frequency, Hz."""
        return float(self.sweep.frequency_hz[0])

    def stiffness(
        self, frequency_hz: ArrayLike, temperature_c: float | None = None
    ) -> NDArray[np.complex128]:
        """Predicted ``K' + i K''`` in N/m at `frequency_hz` (Hz) and `temperature_c` (degC).

        Parameters
        ----------
        frequency_hz : array_like
            Frequencies, Hz.
        temperature_c : float, optional
            Temperature, degC (default: the analysis temperature).

        Returns
        -------
        numpy.ndarray
            Complex stiffness, N/m, shape of `frequency_hz`.
        """
        t = self.temperature_c if temperature_c is None else float(temperature_c)
        return self.pad.stiffness(frequency_hz, t)

    def frequency_window_hz(self, temperature_c: float | None = None) -> tuple[float, float]:
        """Frequencies (Hz) the measured points cover at `temperature_c` (degC).

        Outside the window the tabulated pad holds its end values (no extrapolation).

        Parameters
        ----------
        temperature_c : float, optional
            Temperature, degC (default: the analysis temperature).

        Returns
        -------
        (float, float)
            Lowest and highest frequency, Hz, whose stiffness comes from a test point.
        """
        t = self.temperature_c if temperature_c is None else float(temperature_c)
        a_t, _ = self.pad.shift(t)
        fr = self.master.reduced_frequency_hz
        return float(fr.min() / a_t), float(fr.max() / a_t)

    def hysteresis_loops(
        self, wanted_c: tuple[float, ...] = (-30.0, 20.0)
    ) -> list[tuple[float, str, NDArray[np.float64], NDArray[np.float64]]]:
        """Fig. 6-style loops at the test temperatures nearest to `wanted_c` (degC).

        The paper's Fig. 6 shows -30 and +20 degC; each loop is the ellipse of
        :func:`hysteresis_loop` from the measured ``K'`` and ``K''`` under the paper's
        20-70 kN load (derived, not a measured curve).

        Parameters
        ----------
        wanted_c : tuple of float
            Temperatures wanted, degC.

        Returns
        -------
        list of (float, str, numpy.ndarray, numpy.ndarray)
            ``(temperature degC, label, displacement m, force N)`` per distinct measured
            temperature, warmest first; the label names the temperature, ``K'`` (kN/mm)
            and the loss factor.
        """
        s = self.sweep
        t = s.temperature_c
        out = []
        for temp in sorted({float(t[np.argmin(np.abs(t - w))]) for w in wanted_c}, reverse=True):
            i = int(np.flatnonzero(t == temp)[0])
            k, loss = float(s.storage_n_per_m[i]), float(s.loss_n_per_m[i])
            x, force = hysteresis_loop(k, loss)
            label = f"{temp:+g} °C: K' = {k / 1e6:.1f} kN/mm, η = {loss / k:.3f}"
            out.append((temp, label, x, force))
        return out

    def pad_table(self) -> dict[str, Any]:
        """The ``[track.pad]`` table of :attr:`pad` (tabulated master curve and ``tts``).

        The ``tts`` table names Tg (universal constants at Tg) rather than C1 and C2;
        ``pad_from_dict(pad_table())`` rebuilds :attr:`pad`.
        """
        return {
            **PADS.to_dict(self.pad.base),
            "tts": {
                "reference_temperature_c": float(self.temperature_c),
                "glass_transition_c": float(self.glass_transition_c),
                "vertical_shift": bool(self.pad.vertical_shift),
                "expansion_coefficient_per_k": float(self.pad.expansion_coefficient_per_k),
            },
        }

    def case_tables(self, temperature_c: float | None = None) -> dict[str, Any]:
        """``{"track": {"pad_temperature_c": T, "pad": ...}}``, to merge into a case dict.

        Parameters
        ----------
        temperature_c : float, optional
            The case's pad temperature, degC (default: the analysis temperature).

        Returns
        -------
        dict
            The case tables (SI units, temperatures in degC).
        """
        t = self.temperature_c if temperature_c is None else float(temperature_c)
        return {"track": {"pad_temperature_c": t, "pad": self.pad_table()}}

    def summary(self) -> str:
        """The procedure's steps with this prediction's numbers, one line each."""
        s, w = self.sweep, self.master.wlf
        eta = s.loss_n_per_m / s.storage_n_per_m
        i = int(np.argmax(eta))
        tg = (
            f"Tg = {self.glass_transition_c:.1f} degC from the loss-factor peak (parabola "
            f"over +/-{LOSS_PEAK_HALF_WIDTH_C:g} degC about the largest measured loss "
            f"factor, {eta[i]:.3g} at {s.temperature_c[i]:g} degC)"
            if self.glass_transition_found
            else f"Tg = {self.glass_transition_c:g} degC (given)"
        )
        lo, hi = self.frequency_window_hz()
        v = self.pad.vertical_shift
        return "\n".join(
            [
                f"data: {s.temperature_c.size} temperatures, {s.temperature_c[0]:g} to "
                f"{s.temperature_c[-1]:g} degC, at {self.test_frequency_hz:g} Hz",
                f"step 2: {tg}; WLF at Tg: C1 = {UNIVERSAL_C1:g}, C2 = {UNIVERSAL_C2_K:g} K",
                f"step 3: at T0 = {self.temperature_c:g} degC (Delta = "
                f"{self.temperature_c - self.glass_transition_c:.1f} K): C1' = {w.c1:.4g}, "
                f"C2' = {w.c2_k:.4g} K",
                "step 4: reduced frequency f a_T of each test point at T0: "
                f"{lo:.3g} to {hi:.3g} Hz",
                "step 5: vertical factor rho T/(rho0 T0) "
                + (
                    f"divided out, a_f = {self.pad.expansion_coefficient_per_k:g} /K"
                    if v
                    else "not applied"
                ),
            ]
        )


def predict_pad(
    measurements: Measurements,
    temperature_c: float = 20.0,
    *,
    glass_transition_c: float | None = None,
    frequency_hz: float | None = None,
    vertical_shift: bool = True,
    expansion_coefficient_per_k: float = DEFAULT_EXPANSION_COEFFICIENT_PER_K,
) -> PadPrediction:
    """Predict the pad's ``K*(f, T)`` from a single-frequency temperature sweep (§3.2).

    Runs the paper's steps 1-5 (module docstring): Tg from the loss-factor peak (unless
    given), the universal WLF constants at Tg re-referenced to `temperature_c`, the
    reduced frequency and the vertical factor of every test point: the master curve at
    `temperature_c`, returned as a tabulated, temperature-shifted pad.

    Parameters
    ----------
    measurements : Measurements
        ``K'`` and ``K''`` (N/m) measured at one frequency (Hz) over temperatures (degC),
        e.g. :func:`railvib.pads.read_measurements_csv` of
        :func:`railvib.pads.wj7_example_csv`.
    temperature_c : float
        Analysis temperature T0 (the master curve's reference), degC (> Tg - 51.6 K).
    glass_transition_c : float, optional
        Tg in degC; found from the loss-factor peak when omitted.
    frequency_hz : float, optional
        The test frequency to use when the data hold several, Hz.
    vertical_shift : bool
        Apply the density-temperature factor (Eqs. 20, 21, 26).
    expansion_coefficient_per_k : float
        Volume expansion coefficient a_f, 1/K (the paper: 4.8e-4).

    Returns
    -------
    PadPrediction
        ``prediction.pad`` is usable as a case's pad (``prediction.case_tables()``).

    Raises
    ------
    CaseError
        Data not of the single-frequency form (:func:`single_frequency_sweep`), no
        loss-factor peak inside the range when Tg is not given (:func:`loss_factor_peak`),
        or a temperature at or below the WLF singularity Tg - 51.6 K.
    """
    if not np.isfinite(temperature_c):
        raise CaseError("temperature_c", temperature_c, "a finite temperature (degC)")
    sweep = single_frequency_sweep(measurements, frequency_hz)
    found = glass_transition_c is None
    if glass_transition_c is None:
        eta = sweep.loss_n_per_m / sweep.storage_n_per_m
        glass_transition_c = loss_factor_peak(sweep.temperature_c, eta)
    try:
        wlf = WLF.universal(float(glass_transition_c))
    except CaseError as err:
        raise CaseError("glass_transition_c", err.value, err.allowed) from None
    try:
        wlf.rereferenced(float(temperature_c))
    except CaseError as err:
        raise CaseError("temperature_c", err.value, err.allowed) from None
    master = build_master_curve(
        sweep,
        float(temperature_c),
        wlf,
        vertical_shift=vertical_shift,
        expansion_coefficient_per_k=expansion_coefficient_per_k,
    )
    order = np.argsort(master.reduced_frequency_hz)
    table = TabulatedPad(
        tuple(float(x) for x in master.reduced_frequency_hz[order]),
        tuple(float(x) for x in master.storage_n_per_m[order]),
        tuple(float(x) for x in master.loss_n_per_m[order]),
    )
    pad = TemperatureShifted(
        table, wlf, float(temperature_c), vertical_shift, expansion_coefficient_per_k
    )
    return PadPrediction(sweep, float(glass_transition_c), found, float(temperature_c), master, pad)
