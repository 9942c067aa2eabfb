"""Master curves from measurements, WLF fitting and pad-model fitting (scipy least_squares).

The chain (the paper's section 3.2, Eqs. 20-26): remove the vertical factor, shift each
temperature horizontally by ``log10 a_T`` (given WLF constants, or free shifts fitted
by superposing overlapping segments and then fitted with WLF), then fit a pad model
to ``K'`` and ``K''`` of the master curve together by least squares.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PADS, FitStart, PadModel
from railvib.pads.io import Measurements
from railvib.pads.simple import LogLinear
from railvib.pads.tts import (
    DEFAULT_EXPANSION_COEFFICIENT_PER_K,
    WLF,
    TemperatureShifted,
    vertical_shift_factor,
)
from railvib.registry import declared_parameters

__all__ = [
    "FITTABLE_MODELS",
    "MAX_PRONY_TERMS",
    "LogLinearFit",
    "MasterCurve",
    "ModelFit",
    "build_master_curve",
    "check_n_terms",
    "fit_free_shifts",
    "fit_log_linear",
    "fit_model",
    "fit_pad",
    "fittable_models",
]

_F = NDArray[np.float64]

#: most Prony branches of a fit (two per decade over 25 decades of reduced frequency)
MAX_PRONY_TERMS = 50


def check_n_terms(n_terms: int | None, field: str = "n_terms") -> None:
    """Refuse a number of Prony branches that is not an integer from 1 to :data:`MAX_PRONY_TERMS`.

    Parameters
    ----------
    n_terms : int, optional
        Number of branches (None: chosen from the data).
    field : str
        Name of the value in the error (``"pad_fit.n_terms (--n-terms)"``).

    Raises
    ------
    CaseError
        Naming `field`, the value and the range.
    """
    if n_terms is None:
        return
    whole = isinstance(n_terms, int | np.integer) and not isinstance(n_terms, bool)
    if not (whole and 1 <= n_terms <= MAX_PRONY_TERMS):
        raise CaseError(field, n_terms, f"an integer from 1 to {MAX_PRONY_TERMS} (branches)")


@dataclass(frozen=True, eq=False)
class MasterCurve:
    """Measurements shifted onto one reference temperature.

    Parameters
    ----------
    reference_temperature_c : float
        Reference temperature T0, degC.
    wlf : WLF
        Shift law used, written about `reference_temperature_c`.
    vertical_shift : bool
        Whether the vertical factor ``rho T / (rho0 T0)`` was removed.
    expansion_coefficient_per_k : float
        a_f used for the vertical factor, 1/K.
    temperature_c, frequency_hz : numpy.ndarray
        Test temperature (degC) and frequency (Hz) of each point.
    reduced_frequency_hz : numpy.ndarray
        ``f a_T`` of each point, Hz.
    storage_n_per_m, loss_n_per_m : numpy.ndarray
        ``K'`` and ``K''`` of each point at the reference temperature, N/m.
    free_shift_temperature_c, free_log_shift : numpy.ndarray or None
        Temperatures (degC) and model-free ``log10 a_T`` when the WLF constants were
        fitted (None when they were given).
    """

    reference_temperature_c: float
    wlf: WLF
    vertical_shift: bool
    expansion_coefficient_per_k: float
    temperature_c: _F
    frequency_hz: _F
    reduced_frequency_hz: _F
    storage_n_per_m: _F
    loss_n_per_m: _F
    free_shift_temperature_c: _F | None = None
    free_log_shift: _F | None = None

    @property
    def stiffness(self) -> NDArray[np.complex128]:
        """``K' + i K''`` at the reference temperature, N/m."""
        return self.storage_n_per_m + 1j * self.loss_n_per_m


@dataclass(frozen=True, eq=False)
class ModelFit:
    """A fitted pad model and its residuals.

    Parameters
    ----------
    model : PadModel
        The fitted model (wrapped in TemperatureShifted by :func:`fit_pad`).
    residual_storage, residual_loss : numpy.ndarray
        Relative residuals ``K'_model / K'_data - 1`` and ``K''_model / K''_data - 1``
        (dimensionless) at each point.
    success : bool
        Whether the optimiser reported convergence.
    message : str
        Optimiser message.
    master : MasterCurve or None
        The master curve fitted to, when built by :func:`fit_pad`.
    notes : tuple of str
        One line per parameter that ended at a search bound (the data pushed it
        there: the model may not suit them).
    """

    model: PadModel
    residual_storage: _F
    residual_loss: _F
    success: bool
    message: str
    master: MasterCurve | None = None
    notes: tuple[str, ...] = ()

    @property
    def rms_storage(self) -> float:
        """RMS relative residual of ``K'`` (dimensionless)."""
        return float(np.sqrt(np.mean(self.residual_storage**2)))

    @property
    def rms_loss(self) -> float:
        """RMS relative residual of ``K''`` (dimensionless)."""
        return float(np.sqrt(np.mean(self.residual_loss**2)))

    def summary(self) -> str:
        """Multi-line text report of the residuals."""
        name = self.model.model_name
        if isinstance(self.model, TemperatureShifted):
            name += f" ({self.model.base.model_name})"
        lines = [
            f"model: {name}",
            f"points: {self.residual_storage.size}",
            f"storage K': rms {100 * self.rms_storage:.2f} %, "
            f"max {100 * np.max(np.abs(self.residual_storage)):.2f} %",
            f"loss K'':   rms {100 * self.rms_loss:.2f} %, "
            f"max {100 * np.max(np.abs(self.residual_loss)):.2f} %",
            f"converged: {self.success} ({self.message})",
            *(f"note: {note}" for note in self.notes),
        ]
        if self.master is not None:
            w = self.master.wlf
            lines.insert(
                1,
                f"WLF at {w.reference_temperature_c:g} degC: C1 = {w.c1:.4g}, C2 = {w.c2_k:.4g} K"
                + (" (fitted)" if self.master.free_log_shift is not None else " (given)"),
            )
        return "\n".join(lines)


# ---------------------------------------------------------------- master curve


def _segments(data: Measurements) -> list[tuple[float, NDArray[np.intp]]]:
    temps = np.unique(data.temperature_c)
    return [(float(t), np.flatnonzero(data.temperature_c == t)) for t in temps]


_NO_OVERLAP = 1e6  # cost of a shift that leaves too little overlap (finite for the optimiser)


def _pair_shift(xa: _F, ya: _F, xb: _F, yb: _F, max_shift: float) -> float:
    """Shift d (decades) that lays curve b (x + d) over curve a; y columns compared."""
    span = min(np.ptp(xa), np.ptp(xb))
    ia, ib = np.argsort(xa), np.argsort(xb)
    xa, ya, xb, yb = xa[ia], ya[ia], xb[ib], yb[ib]

    def cost(d: float) -> float:
        lo, hi = max(xa[0], xb[0] + d), min(xa[-1], xb[-1] + d)
        if hi - lo < 0.3 * span:
            return _NO_OVERLAP
        x = np.concatenate([xa, xb + d])
        x = x[(x >= lo) & (x <= hi)]
        err = [
            np.interp(x, xa, ya[:, k]) - np.interp(x, xb + d, yb[:, k]) for k in range(ya.shape[1])
        ]
        return float(np.mean(np.square(err)))

    step = 0.02
    grid = np.arange(-max_shift, max_shift + step, step)
    costs = np.array([cost(d) for d in grid])
    if np.all(costs >= _NO_OVERLAP):
        return np.nan
    d0 = grid[int(np.argmin(costs))]
    if abs(d0) >= max_shift - step:  # best superposition at the search limit: none found
        return np.nan
    from scipy.optimize import minimize_scalar  # lazy: 0.2 s, only for fitting

    res = minimize_scalar(cost, bounds=(d0 - step, d0 + step), method="bounded")
    return float(res.x) if res.fun <= costs.min() else float(d0)


def fit_free_shifts(
    data: Measurements,
    reference_temperature_c: float,
    *,
    vertical_shift: bool = True,
    expansion_coefficient_per_k: float = DEFAULT_EXPANSION_COEFFICIENT_PER_K,
    max_shift_decades: float = 8.0,
) -> tuple[_F, _F, WLF]:
    """Model-free horizontal shifts between adjacent temperatures, then WLF fitted to them.

    Each pair of adjacent temperatures is superposed by the shift (in decades of
    frequency) that minimises the mean squared difference of ``log10 K'`` and
    ``log10 K''`` over their overlap; the shifts are summed from the warmest
    temperature; C1, C2 and the unknown offset are then fitted by least squares.

    Parameters
    ----------
    data : Measurements
        At least two frequencies at each of at least three temperatures.
    reference_temperature_c : float
        Reference temperature T0 of the fitted WLF law, degC.
    vertical_shift : bool
        Remove the vertical factor before shifting.
    expansion_coefficient_per_k : float
        a_f for the vertical factor, 1/K.
    max_shift_decades : float
        Largest shift searched between two adjacent temperatures, decades.

    Returns
    -------
    temperature_c : numpy.ndarray
        The distinct test temperatures, degC.
    log_shift : numpy.ndarray
        ``log10 a_T`` at each, aligned to the fitted WLF law.
    wlf : WLF
        Fitted law written about `reference_temperature_c`.
    """
    segs = _segments(data)
    if len(segs) < 3 or any(np.unique(data.frequency_hz[i]).size < 2 for _, i in segs):
        raise CaseError(
            "wlf",
            "fit",
            "fitting WLF constants needs >= 2 frequencies at each of >= 3 temperatures; "
            "for single-frequency data give c1 and c2 or the glass transition temperature",
        )
    v = _vertical(
        data.temperature_c, reference_temperature_c, vertical_shift, expansion_coefficient_per_k
    )
    x = np.log10(data.frequency_hz)
    cols = [np.log10(data.storage_n_per_m / v)]
    if np.all(data.loss_n_per_m > 0):
        cols.append(np.log10(data.loss_n_per_m / v))
    y = np.column_stack(cols)
    temps = np.array([t for t, _ in segs])
    log_a = np.zeros(len(segs))
    for j in range(len(segs) - 2, -1, -1):  # from warm (last) to cold (first)
        ia, ib = segs[j + 1][1], segs[j][1]
        d = _pair_shift(x[ia], y[ia], x[ib], y[ib], max_shift_decades)
        if not np.isfinite(d):
            raise CaseError(
                "data",
                f"{temps[j]:g} and {temps[j + 1]:g} degC",
                "frequency windows that overlap after shifting (increase the band or add "
                "temperatures)",
            )
        log_a[j] = log_a[j + 1] + d
    dt = temps - reference_temperature_c
    c2_min = max(1e-3, -dt.min() + 1e-3)

    def resid(p: _F) -> _F:
        c1, c2, b = p
        return -c1 * dt / (c2 + dt) - (log_a + b)

    from scipy.optimize import least_squares  # lazy: 0.2 s, only for fitting

    b0 = -float(np.interp(reference_temperature_c, temps, log_a))
    sol = least_squares(
        resid, [8.0, max(100.0, 2 * c2_min), b0], bounds=([1e-6, c2_min, -np.inf], np.inf)
    )
    c1, c2, b = sol.x
    return temps, log_a + b, WLF(float(c1), float(c2), float(reference_temperature_c))


def _vertical(t: _F, t_ref: float, on: bool, a_f: float) -> _F:
    return vertical_shift_factor(t, t_ref, a_f) if on else np.ones_like(t)


def build_master_curve(
    data: Measurements,
    reference_temperature_c: float,
    wlf: WLF | None = None,
    *,
    vertical_shift: bool = True,
    expansion_coefficient_per_k: float = DEFAULT_EXPANSION_COEFFICIENT_PER_K,
) -> MasterCurve:
    """Shift measurements onto a master curve at `reference_temperature_c`.

    Parameters
    ----------
    data : Measurements
        Measured ``K'``, ``K''`` (N/m) at temperatures (degC) and frequencies (Hz).
    reference_temperature_c : float
        Reference temperature T0, degC.
    wlf : WLF, optional
        Given shift law (any reference temperature; re-referenced with Eqs. 23-25).
        When omitted, the WLF constants are fitted with :func:`fit_free_shifts`.
    vertical_shift : bool
        Divide by the vertical factor ``rho T / (rho0 T0)`` (Eqs. 20, 21, 26).
    expansion_coefficient_per_k : float
        Volume expansion coefficient a_f, 1/K.

    Returns
    -------
    MasterCurve
    """
    free_t = free_a = None
    if wlf is None:
        free_t, free_a, wlf = fit_free_shifts(
            data,
            reference_temperature_c,
            vertical_shift=vertical_shift,
            expansion_coefficient_per_k=expansion_coefficient_per_k,
        )
    else:
        wlf = wlf.rereferenced(reference_temperature_c)
    log_a = wlf.log_shift(data.temperature_c, field="data.temperature_c")
    v = _vertical(
        data.temperature_c, reference_temperature_c, vertical_shift, expansion_coefficient_per_k
    )
    return MasterCurve(
        reference_temperature_c=float(reference_temperature_c),
        wlf=wlf,
        vertical_shift=vertical_shift,
        expansion_coefficient_per_k=expansion_coefficient_per_k,
        temperature_c=data.temperature_c,
        frequency_hz=data.frequency_hz,
        reduced_frequency_hz=data.frequency_hz * 10.0**log_a,
        storage_n_per_m=data.storage_n_per_m / v,
        loss_n_per_m=data.loss_n_per_m / v,
        free_shift_temperature_c=free_t,
        free_log_shift=free_a,
    )


# ---------------------------------------------------------------- model fitting


def fittable_models() -> list[str]:
    """Names of the registered pad models that :func:`fit_model` can fit.

    A model is fittable when its class provides :meth:`PadModel.fit_starts`.
    """
    base = PadModel.fit_starts.__func__  # type: ignore[attr-defined]
    return [m.name for m in PADS if m.cls.fit_starts.__func__ is not base]  # type: ignore[attr-defined]


def _fit_starts(
    name: str, f: _F, k: NDArray[np.complex128], n_terms: int | None, f0_hz: float
) -> list[FitStart]:
    """Start points, bounds and builder of registered model `name`, scaled to the data."""
    fittable = fittable_models()
    member = PADS.get(name) if name in PADS else None
    if member is None or member.name not in fittable:
        raise CaseError("model", name, f"one of {', '.join(fittable)}")
    starts = member.cls.fit_starts(f, k, n_terms=n_terms, f0_hz=f0_hz)
    assert starts is not None, "a fittable model gives its fit starts"
    return starts


#: Model names :func:`fit_model` can fit (the built-in ones; see :func:`fittable_models`).
FITTABLE_MODELS = tuple(fittable_models())


def _residuals(
    model: PadModel, f: _F, k: NDArray[np.complex128], loss_weight: float
) -> tuple[_F, _F]:
    km = model.stiffness(f)
    rs = km.real / k.real - 1.0
    scale = np.where(k.imag > 0, k.imag, np.abs(k))
    rl = (km.imag - k.imag) / scale
    return rs, loss_weight * rl


def fit_model(
    frequency_hz: ArrayLike,
    stiffness_n_per_m: ArrayLike,
    model: str,
    *,
    n_terms: int | None = None,
    f0_hz: float = 5.0,
    loss_weight: float = 1.0,
) -> ModelFit:
    """Fit pad model `model` to complex stiffness data by least squares.

    The residuals are the relative errors of ``K'`` and of ``K''`` (``K''`` relative to
    ``|K*|`` where ``K'' = 0``), stacked; parameters are bounded to the passive range.

    Parameters
    ----------
    frequency_hz : array_like
        Frequencies, Hz (e.g. a master curve's reduced frequencies).
    stiffness_n_per_m : array_like of complex
        ``K' + i K''`` at those frequencies, N/m.
    model : str
        One of :data:`FITTABLE_MODELS` (or the aliases ``zener``, ``prony``).
    n_terms : int, optional
        Number of Prony branches (``generalized_maxwell``); default two per decade
        over the data's band widened by one decade each side, relaxation times
        spread log-uniformly.
    f0_hz : float
        Reference frequency of ``log_linear`` / ``constant_phase``, Hz.
    loss_weight : float
        Weight of the ``K''`` residuals relative to the ``K'`` residuals.

    Returns
    -------
    ModelFit
    """
    check_n_terms(n_terms)
    name = model
    f = np.asarray(frequency_hz, dtype=float).ravel()
    k = np.asarray(stiffness_n_per_m, dtype=complex).ravel()
    if f.size != k.size or f.size < 2 or np.any(f <= 0) or np.any(k.real <= 0):
        raise CaseError("data", f"{f.size} points", ">= 2 points with f > 0 (Hz) and K' > 0 (N/m)")
    from scipy.optimize import least_squares  # lazy: 0.2 s, only for fitting

    best = None
    for start in _fit_starts(name, f, k, n_terms, f0_hz):

        def resid(x: _F, build: Callable[[_F], PadModel] = start.build) -> _F:
            return np.concatenate(_residuals(build(x), f, k, loss_weight))

        x0 = np.clip(start.x0, start.lower, start.upper)
        sol = least_squares(
            resid, x0, bounds=(start.lower, start.upper), x_scale="jac", xtol=1e-12, ftol=1e-12
        )
        if best is None or sol.cost < best[0].cost:
            best = (sol, start)
    assert best is not None, "at least one start point is always tried"
    sol, start = best
    fitted = start.build(sol.x)
    rs, rl = _residuals(fitted, f, k, 1.0)
    notes = tuple(_bound_notes(fitted, start, _at_bounds(sol.x, start)))
    return ModelFit(fitted, rs, rl, bool(sol.success), str(sol.message), notes=notes)


def _at_bounds(x: _F, start: FitStart) -> NDArray[np.int_]:
    """-1 / +1 where scaled parameter `x` ended at its lower / upper bound, else 0.

    The scaled parameters are of order one (or logarithms), so a distance of 1e-4
    (relative to the bound where it is larger than one) is "at the bound"; the
    optimiser (``trf``) keeps its iterates strictly inside, so its own ``active_mask``
    would miss a parameter that merely creeps towards a bound.
    """
    lower, upper = np.asarray(start.lower, dtype=float), np.asarray(start.upper, dtype=float)
    with np.errstate(invalid="ignore"):
        at_lower = np.isfinite(lower) & (x - lower <= 1e-4 * np.maximum(1.0, np.abs(lower)))
        at_upper = np.isfinite(upper) & (upper - x <= 1e-4 * np.maximum(1.0, np.abs(upper)))
    return np.where(at_lower, -1, np.where(at_upper, 1, 0))


def _bound_notes(model: PadModel, start: FitStart, active: NDArray[np.int_]) -> list[str]:
    """One line per parameter (key) of `model` whose scaled parameter ended at a bound."""
    params = {p.key: p for p in declared_parameters(type(model))}
    found: dict[tuple[str, int], list[tuple[str, float | None]]] = {}
    for i in (int(j) for j in np.flatnonzero(active)):
        name = start.names[i] if i < len(start.names) else f"parameter {i}"
        key, _, index = name.partition("[")
        found.setdefault((key, int(active[i])), []).append(
            (index.rstrip("]"), _value_at_bound(start, i, int(active[i]), key, index))
        )
    notes = []
    for (key, side), items in found.items():
        p = params.get(key)
        unit = f" {p.unit}" if p is not None and p.unit not in ("", "-") else ""
        value = getattr(model, p.name) if p is not None else None
        bounds = {b for _, b in items if b is not None}
        at = f" ({bounds.pop():.4g}{unit})" if len(bounds) == 1 else ""
        where = f"{'lower' if side < 0 else 'upper'} search bound{at}"
        if value is None:
            notes.append(f"{key} ended at its {where}")
        elif items[0][0]:  # terms of a series, e.g. Prony branch stiffnesses
            indices = ", ".join(j for j, _ in items)
            shown = ", ".join(f"{float(value[int(j)]):.4g}" for j, _ in items)
            notes.append(f"{key}[{indices}] = {shown}{unit} ended at the {where}")
        else:
            notes.append(
                f"{key} = {float(value):.4g}{unit} ended at its {where}: the data push it "
                "there, so this model may not suit them"
            )
    return notes


def _value_at_bound(start: FitStart, i: int, side: int, key: str, index: str) -> float | None:
    """Parameter `key` (term `index`) of the model whose scaled parameter i is at its bound."""
    x = np.clip(np.array(start.x0, dtype=float), start.lower, start.upper)
    x[i] = start.lower[i] if side < 0 else start.upper[i]
    try:
        model = start.build(x)
    except (CaseError, ValueError, ZeroDivisionError):  # a bound no model can take
        return None
    p = {q.key: q for q in declared_parameters(type(model))}.get(key)
    if p is None:
        return None
    value = getattr(model, p.name)
    return float(value[int(index.rstrip("]"))] if index else value)


def fit_pad(
    data: Measurements,
    model: str,
    reference_temperature_c: float,
    wlf: WLF | None = None,
    *,
    vertical_shift: bool = True,
    expansion_coefficient_per_k: float = DEFAULT_EXPANSION_COEFFICIENT_PER_K,
    n_terms: int | None = None,
    f0_hz: float = 5.0,
) -> ModelFit:
    """Master curve + model fit: the temperature- and frequency-dependent pad ``K*(f, T)``.

    Parameters
    ----------
    data : Measurements
        Measured stiffness.
    model : str
        Pad model to fit to the master curve (see :func:`fit_model`).
    reference_temperature_c : float
        Master-curve reference temperature, degC.
    wlf : WLF, optional
        Given WLF law; fitted when omitted (needs multi-frequency data).
    vertical_shift : bool
        Apply the density-temperature factor.
    expansion_coefficient_per_k : float
        a_f, 1/K.
    n_terms : int, optional
        Prony branches.
    f0_hz : float
        Reference frequency of the power-law models, Hz.

    Returns
    -------
    ModelFit
        Its `model` is a :class:`TemperatureShifted`; residuals are per measured point
        (the same on the master curve and on the data, since TTS scales both alike).
    """
    master = build_master_curve(
        data,
        reference_temperature_c,
        wlf,
        vertical_shift=vertical_shift,
        expansion_coefficient_per_k=expansion_coefficient_per_k,
    )
    fit = fit_model(
        master.reduced_frequency_hz, master.stiffness, model, n_terms=n_terms, f0_hz=f0_hz
    )
    shifted = TemperatureShifted(
        fit.model, master.wlf, reference_temperature_c, vertical_shift, expansion_coefficient_per_k
    )
    return ModelFit(
        shifted,
        fit.residual_storage,
        fit.residual_loss,
        fit.success,
        fit.message,
        master,
        fit.notes,
    )


# ---------------------------------------------------------------- paper's Eq. 27


@dataclass(frozen=True, eq=False)
class LogLinearFit:
    """The paper's ``K = K0 (f / f0)^k`` fitted at one temperature over one band.

    Parameters
    ----------
    model : LogLinear
        ``K0`` (N/m) at ``f0`` (Hz) and slope ``k``; no damping, held below f0.
    temperature_c : float
        Temperature, degC.
    band_hz : tuple of float
        Band fitted, Hz.
    rms_log10 : float
        RMS residual of ``log10 K`` (decades).
    """

    model: LogLinear
    temperature_c: float
    band_hz: tuple[float, float]
    rms_log10: float


def fit_log_linear(
    pad: PadModel,
    temperature_c: float,
    band_hz: tuple[float, float] = (1.0, 1000.0),
    *,
    f0_hz: float = 5.0,
    n_points: int = 61,
    quantity: str = "storage",
) -> LogLinearFit:
    """Fit K0 and k of the log-linear law (Eq. 27, corrected) to a pad at one temperature.

    ``log10 K = k (log10 f - log10 f0) + log10 K0`` is fitted by linear least squares
    to `n_points` log-spaced frequencies over `band_hz`.

    Parameters
    ----------
    pad : PadModel
        Pad, e.g. a fitted :class:`TemperatureShifted` model.
    temperature_c : float
        Temperature, degC.
    band_hz : tuple of float
        ``(f_min, f_max)``, Hz.
    f0_hz : float
        Reference frequency f0, Hz (seed: 3-5 Hz).
    n_points : int
        Number of frequencies in the band.
    quantity : {"storage", "modulus"}
        Fit ``K'`` or ``|K*|``.

    Returns
    -------
    LogLinearFit
    """
    lo, hi = band_hz
    if not (0 < lo < hi and np.isfinite(hi)):
        raise CaseError("band_hz", band_hz, "0 < f_min < f_max (Hz)")
    if quantity not in ("storage", "modulus"):
        raise CaseError("quantity", quantity, "'storage' or 'modulus'")
    f = np.geomspace(lo, hi, n_points)
    k = pad.stiffness(f, temperature_c)
    y = np.log10(k.real if quantity == "storage" else np.abs(k))
    x = np.log10(f / f0_hz)
    a = np.column_stack([x, np.ones_like(x)])
    (slope, icpt), *_ = np.linalg.lstsq(a, y, rcond=None)
    rms = float(np.sqrt(np.mean((a @ [slope, icpt] - y) ** 2)))
    return LogLinearFit(
        LogLinear(float(10.0**icpt), f0_hz, max(float(slope), 0.0)),
        float(temperature_c),
        (lo, hi),
        rms,
    )
