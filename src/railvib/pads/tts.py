"""Time-temperature superposition: WLF shift factor, re-referencing, vertical factor.

Temperatures are in degrees Celsius at every public interface and in kelvin inside
this module (differences are the same in both scales; the vertical factor needs
absolute temperatures).

References
----------
Seed paper, section 3.2.1, Eqs. 20-26 (Eq. 20/21 and Eq. 23 as corrected in
``docs/paper-interpretation.md``) and Williams, Landel & Ferry, *J. Am. Chem. Soc.*
77:3701 (1955).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PADS, PadModel
from railvib.registry import Parameter, take_table
from railvib.units import celsius_to_kelvin

__all__ = [
    "DEFAULT_EXPANSION_COEFFICIENT_PER_K",
    "MAX_LOG10_SHIFT",
    "UNIVERSAL_C1",
    "UNIVERSAL_C2_K",
    "WLF",
    "WLF_SPAN_ABOVE_TG_K",
    "WLF_WINDOW_WITHOUT_TG_K",
    "TTS_PARAMETERS",
    "TemperatureShifted",
    "tts_from_dict",
    "vertical_shift_factor",
    "wlf_choice",
]

#: "Universal" WLF constants at T0 = Tg (the seed attributes them to ISO 4664-1).
UNIVERSAL_C1 = 17.44
UNIVERSAL_C2_K = 51.6
#: Volume expansion coefficient a_f used by the seed (Eq. 26), 1/K.
DEFAULT_EXPANSION_COEFFICIENT_PER_K = 4.8e-4
#: Width above Tg over which the WLF equation holds, K (Williams, Landel & Ferry 1955).
WLF_SPAN_ABOVE_TG_K = 100.0
#: Half-width of the trusted window about the reference temperature when Tg is unknown, K.
WLF_WINDOW_WITHOUT_TG_K = 80.0
#: Largest ``|log10 a_T|`` a temperature may give (decades). Measured master curves span 10-20
#: decades; at 100, the reduced frequency f a_T of any grid frequency (<= 1e5 Hz) stays
#: below 1e105 and its square (Maxwell branches, complex division) below 1e210, within
#: float64 (1.8e308). Nearer to the WLF singularity T0 - C2 (within 7.7 K for the
#: universal constants), a_T and the pad's stiffness overflow to inf and nan.
MAX_LOG10_SHIFT = 100.0


@dataclass(frozen=True)
class WLF:
    """Williams-Landel-Ferry shift: ``log10 a_T = -C1 (T - T0) / (C2 + T - T0)`` (Eq. 22).

    The property at ``(f, T)`` equals the property at the reference temperature
    ``T0`` at the reduced frequency ``f a_T``; for ``T < T0``, ``a_T > 1``.

    Parameters
    ----------
    c1 : float
        C1 (dimensionless, > 0).
    c2_k : float
        C2 in K (> 0).
    reference_temperature_c : float
        T0, the temperature at which `c1` and `c2_k` apply, degC.
    """

    c1: float
    c2_k: float
    reference_temperature_c: float

    def __post_init__(self) -> None:
        if not (np.isfinite(self.c1) and self.c1 > 0):
            raise CaseError("wlf.c1", self.c1, "must be > 0 (dimensionless)")
        if not (np.isfinite(self.c2_k) and self.c2_k > 0):
            raise CaseError("wlf.c2_k", self.c2_k, "must be > 0 (K)")
        if not (
            np.isfinite(self.reference_temperature_c) and self.reference_temperature_c > -273.15
        ):
            raise CaseError(
                "wlf.reference_temperature_c",
                self.reference_temperature_c,
                "must be a finite temperature above absolute zero (degC)",
            )

    @classmethod
    def universal(cls, glass_transition_c: float) -> WLF:
        """WLF with the universal constants C1 = 17.44, C2 = 51.6 K at ``T0 = Tg``.

        Parameters
        ----------
        glass_transition_c : float
            Glass transition temperature Tg, degC.
        """
        return cls(UNIVERSAL_C1, UNIVERSAL_C2_K, glass_transition_c)

    @property
    def singular_temperature_c(self) -> float:
        """``T0 - C2`` in degC, where the WLF denominator vanishes."""
        return self.reference_temperature_c - self.c2_k

    @property
    def temperature_limits_c(self) -> tuple[float, float]:
        """``(T_lo, T_hi)`` in degC between which ``|log10 a_T| <= MAX_LOG10_SHIFT``.

        From ``log10 a_T = L`` at ``T - T0 = -L C2 / (C1 + L)``: ``T_lo`` for
        ``L = MAX_LOG10_SHIFT`` (just above the singularity ``T0 - C2``); ``T_hi`` for
        ``L = -MAX_LOG10_SHIFT``, infinite when ``C1 <= MAX_LOG10_SHIFT`` (``log10 a_T``
        tends to ``-C1`` as T grows).
        """
        big = MAX_LOG10_SHIFT
        t0, c1, c2 = self.reference_temperature_c, self.c1, self.c2_k
        hi = t0 + big * c2 / (c1 - big) if c1 > big else np.inf
        return t0 - big * c2 / (c1 + big), float(hi)

    def _check_temperature(self, temperature_c: NDArray[np.float64], field: str) -> None:
        """Refuse temperatures at or below the singularity, checked in degC as given."""
        bad = ~np.isfinite(temperature_c) | (temperature_c <= self.singular_temperature_c)
        if np.any(bad):
            value = float(temperature_c.ravel()[np.flatnonzero(bad.ravel())[0]])
            raise CaseError(
                field,
                value,
                f"must be above T0 - C2 = {self.singular_temperature_c:.4g} degC, where WLF "
                f"(C1 = {self.c1:.4g}, C2 = {self.c2_k:.4g} K, T0 = "
                f"{self.reference_temperature_c:.4g} degC) is singular",
            )

    def log_shift(
        self, temperature_c: ArrayLike, *, field: str = "temperature"
    ) -> NDArray[np.float64]:
        """``log10 a_T`` (dimensionless) at temperatures in degC.

        Parameters
        ----------
        temperature_c : array_like
            Temperatures T, degC (> T0 - C2).
        field : str
            Field name used if a temperature is rejected.

        Returns
        -------
        numpy.ndarray
            ``log10 a_T``, same shape as `temperature_c`.
        """
        t = np.asarray(temperature_c, dtype=float)
        self._check_temperature(t, field)  # in degC: no round trip through kelvin
        dt = t - self.reference_temperature_c
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            log_a = -self.c1 * dt / (self.c2_k + dt)
        self._check_shift(t, log_a, field)
        return np.asarray(log_a, dtype=np.float64)

    def _check_shift(
        self, temperature_c: NDArray[np.float64], log_a: NDArray[np.float64], field: str
    ) -> None:
        """Refuse temperatures whose ``|log10 a_T|`` passes :data:`MAX_LOG10_SHIFT`."""
        bad = ~(np.abs(log_a) <= MAX_LOG10_SHIFT)  # nan and inf too
        if not np.any(bad):
            return
        i = int(np.flatnonzero(bad.ravel())[0])
        value, shift = float(temperature_c.ravel()[i]), float(np.ravel(log_a)[i])
        lo, hi = self.temperature_limits_c
        where = (
            f"above {lo:.6g} degC: nearer to T0 - C2 = {self.singular_temperature_c:.4g} degC, "
            "where WLF"
            if value < self.reference_temperature_c
            else f"below {hi:.6g} degC: beyond, WLF"
        )
        raise CaseError(
            field,
            value,
            f"must be {where} (C1 = {self.c1:.4g}, C2 = {self.c2_k:.4g} K, T0 = "
            f"{self.reference_temperature_c:.4g} degC) is singular or shifts by more than "
            f"{MAX_LOG10_SHIFT:g} decades (|log10 a_T| = {abs(shift):.4g}): a_T and the pad's "
            "stiffness would overflow",
        )

    def shift_factor(self, temperature_c: ArrayLike) -> NDArray[np.float64]:
        """``a_T`` (dimensionless) at temperatures in degC.

        Parameters
        ----------
        temperature_c : array_like
            Temperatures T in degC (> T0 - C2), any shape.

        Returns
        -------
        numpy.ndarray
            Shift factor ``a_T = 10^log_shift`` (dimensionless), shape of `temperature_c`.
        """
        return 10.0 ** self.log_shift(temperature_c)

    def reduced_frequency(self, f: ArrayLike, temperature_c: float) -> NDArray[np.float64]:
        """Reduced frequency ``f a_T`` in Hz at the reference temperature.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz at temperature `temperature_c`.
        temperature_c : float
            Temperature, degC.
        """
        return np.asarray(f, dtype=float) * self.shift_factor(temperature_c)

    def rereferenced(self, reference_temperature_c: float) -> WLF:
        """Return the same shift law written about another reference temperature (Eqs. 23-25).

        With ``T0' = T0 + Delta``: ``C1' = C1 C2 / (C2 + Delta)`` and ``C2' = C2 + Delta``.

        Parameters
        ----------
        reference_temperature_c : float
            New reference temperature T0', degC (> T0 - C2).

        Returns
        -------
        WLF
        """
        self.log_shift(reference_temperature_c, field="reference_temperature_c")
        delta = reference_temperature_c - self.reference_temperature_c
        return WLF(
            self.c1 * self.c2_k / (self.c2_k + delta),
            self.c2_k + delta,
            float(reference_temperature_c),
        )


def vertical_shift_factor(
    temperature_c: ArrayLike,
    reference_temperature_c: float,
    expansion_coefficient_per_k: float = DEFAULT_EXPANSION_COEFFICIENT_PER_K,
) -> NDArray[np.float64]:
    """Vertical TTS factor ``rho T / (rho0 T0)`` (Eqs. 20, 21 and 26), dimensionless.

    ``K(f, T) = rho T / (rho0 T0) * K_ref(f a_T)`` for storage and loss alike, with
    ``rho / rho0 = 1 / (1 + a_f (T - T0))`` and T, T0 in kelvin.

    Parameters
    ----------
    temperature_c : array_like
        Temperatures T, degC.
    reference_temperature_c : float
        Reference temperature T0, degC.
    expansion_coefficient_per_k : float
        Volume expansion coefficient a_f, 1/K (>= 0). Seed: 4.8e-4.

    Returns
    -------
    numpy.ndarray
        The factor, same shape as `temperature_c`.
    """
    if not (np.isfinite(expansion_coefficient_per_k) and expansion_coefficient_per_k >= 0):
        raise CaseError(
            "expansion_coefficient_per_k", expansion_coefficient_per_k, "must be >= 0 (1/K)"
        )
    t_k = celsius_to_kelvin(np.asarray(temperature_c, dtype=float))
    t0_k = celsius_to_kelvin(float(reference_temperature_c))
    if np.any(t_k <= 0) or t0_k <= 0:
        raise CaseError("temperature", temperature_c, "must be above absolute zero (degC)")
    expansion = 1.0 + expansion_coefficient_per_k * (t_k - t0_k)
    if np.any(expansion <= 0):
        raise CaseError(
            "temperature", temperature_c, "gives a non-positive density ratio in Eq. 26 (degC)"
        )
    return (t_k / t0_k) / expansion


@dataclass(frozen=True)
class TemperatureShifted(PadModel):
    """A pad whose master curve at one reference temperature is shifted by TTS.

    ``K*(f, T) = v(T) K*_ref(f a_T)`` with ``a_T`` from `wlf` (re-referenced to
    `reference_temperature_c`) and ``v(T) = rho T / (rho0 T0)`` when `vertical_shift`
    is true, else 1. The loss factor is shifted horizontally only.

    Parameters
    ----------
    base : PadModel
        Master-curve model: the pad at `reference_temperature_c`, N/m.
    wlf : WLF
        Shift law; its own reference temperature may differ (e.g. universal
        constants at Tg): it is re-referenced with Eqs. 23-25.
    reference_temperature_c : float
        Temperature at which `base` describes the pad, degC.
    vertical_shift : bool
        Apply the density-temperature factor of Eqs. 20-21.
    expansion_coefficient_per_k : float
        Volume expansion coefficient a_f for the vertical factor, 1/K.

    Notes
    -----
    ``stiffness(f, None)`` returns the pad at `reference_temperature_c`.
    """

    base: PadModel
    wlf: WLF
    reference_temperature_c: float
    vertical_shift: bool = True
    expansion_coefficient_per_k: float = DEFAULT_EXPANSION_COEFFICIENT_PER_K
    model_name = "temperature_shifted"

    @property
    def temperature_dependent(self) -> bool:
        """Always true: the stiffness is shifted to the given temperature."""
        return True

    @property
    def temperature_range_c(self) -> tuple[float, float]:
        """``(T_lo, T_hi)`` in degC where the WLF shift can be trusted.

        The WLF equation is an empirical law of amorphous polymers that holds from the
        glass transition Tg to about Tg + 100 K (Williams, Landel & Ferry 1955): below
        Tg the polymer is glassy and shifts by an Arrhenius law, far above it the
        free-volume reasoning behind WLF no longer applies (and an elastomer pad
        degrades). So:

        * universal constants (C1 = 17.44, C2 = 51.6 K, which are written about Tg, so
          the law's reference temperature *is* Tg): ``[Tg, Tg + 100 K]``;
        * fitted or given constants (Tg not known):
          ``[T_ref - 80 K, T_ref + 80 K]`` about the master curve's reference
          temperature ``T_ref``. Pad master curves are measured over roughly -40 to
          +60 degC about ``T_ref`` ~ 20 degC, and Tg of pad elastomers lies near
          -60 to -30 degC; the window is wide on purpose, so it flags only
          temperatures no pad data can have covered (e.g. +400 degC, a Kelvin value
          typed as degC).

        Outside the range a case still runs (the shift is defined down to the WLF
        singularity ``T0 - C2``, below which the case is refused), with a
        :class:`~railvib.errors.PlausibilityWarning`.
        """
        if self.wlf.c1 == UNIVERSAL_C1 and self.wlf.c2_k == UNIVERSAL_C2_K:
            tg = self.wlf.reference_temperature_c
            return (tg, tg + WLF_SPAN_ABOVE_TG_K)
        t_ref = self.reference_temperature_c
        return (t_ref - WLF_WINDOW_WITHOUT_TG_K, t_ref + WLF_WINDOW_WITHOUT_TG_K)

    def __post_init__(self) -> None:
        if not isinstance(self.base, PadModel) or isinstance(self.base, TemperatureShifted):
            raise CaseError("track.pad.model", self.base, "a single (unshifted) pad model")
        # validates the reference temperature against the WLF singularity
        self.wlf.rereferenced(self.reference_temperature_c)
        if not (
            np.isfinite(self.expansion_coefficient_per_k) and self.expansion_coefficient_per_k >= 0
        ):
            raise CaseError(
                "track.pad.tts.expansion_coefficient_per_k",
                self.expansion_coefficient_per_k,
                "must be >= 0 (1/K)",
            )

    @property
    def wlf_at_reference(self) -> WLF:
        """The WLF law written about `reference_temperature_c`."""
        return self.wlf.rereferenced(self.reference_temperature_c)

    def shift(self, temperature_c: float) -> tuple[float, float]:
        """Return ``(a_T, v(T))``, both dimensionless, at `temperature_c` in degC.

        ``a_T`` is relative to `reference_temperature_c`; its ``|log10 a_T|`` is at most
        :data:`MAX_LOG10_SHIFT` (else a :class:`~railvib.errors.CaseError` names the
        temperature), as is the shift about the WLF law's own reference.

        Parameters
        ----------
        temperature_c : float
            Pad temperature T, degC.

        Returns
        -------
        (float, float)
            ``a_T`` and ``v(T)`` (1 without `vertical_shift`), both dimensionless.
        """
        t = np.asarray(float(temperature_c))
        log_a = self.wlf.log_shift(t) - self.wlf.log_shift(self.reference_temperature_c)
        self.wlf_at_reference._check_shift(t, log_a, "temperature")
        a_t = float(10.0**log_a)
        v = (
            float(
                vertical_shift_factor(
                    temperature_c, self.reference_temperature_c, self.expansion_coefficient_per_k
                )
            )
            if self.vertical_shift
            else 1.0
        )
        return a_t, v

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``v(T) K*_ref(f a_T)`` in N/m; `temperature` in degC (None: the reference)."""
        f = np.asarray(f, dtype=float)
        if temperature is None:
            return self.base.stiffness(f)
        a_t, v = self.shift(float(temperature))
        return v * self.base.stiffness(f * a_t)


#: keys of a pad's optional ``[... .tts]`` table (time-temperature superposition)
TTS_PARAMETERS: tuple[Parameter, ...] = (
    Parameter(
        "reference_temperature_c",
        "degC",
        "temperature at which the pad model describes the pad",
        gt=-273.15,
        le=1000.0,
    ),
    Parameter(
        "glass_transition_c",
        "degC",
        "glass transition Tg: universal WLF constants C1 = 17.44, C2 = 51.6 K at Tg",
        default=None,
        gt=-273.15,
        le=1000.0,
    ),
    # C1 and C2 of polymers are about 10-50 and 20-200 K (universal: 17.44, 51.6 K)
    Parameter("c1", "-", "WLF C1 (with c2_k)", default=None, gt=0.0, le=1e3),
    Parameter("c2_k", "K", "WLF C2 (with c1)", default=None, gt=0.0, le=1e4),
    Parameter(
        "wlf_reference_temperature_c",
        "degC",
        "temperature at which c1 and c2_k apply (default: reference_temperature_c)",
        default=None,
        gt=-273.15,
        le=1000.0,
    ),
    Parameter(
        "vertical_shift",
        "",
        "apply the density-temperature factor rho T/(rho0 T0)",
        "boolean",
        True,
    ),
    Parameter(
        "expansion_coefficient_per_k",
        "1/K",
        "volume expansion coefficient a_f of the vertical factor",
        default=DEFAULT_EXPANSION_COEFFICIENT_PER_K,
        ge=0.0,
        le=1e-2,  # elastomers: about 5e-4; 1e-2 halves the density over 100 K
    ),
)


def tts_from_dict(base: PadModel, d: Any, field: str) -> TemperatureShifted:
    """Wrap `base` in :class:`TemperatureShifted` as a pad's ``tts`` table `d` describes.

    Parameters
    ----------
    base : PadModel
        The master-curve model at the reference temperature.
    d : mapping
        The ``tts`` table; keys :data:`TTS_PARAMETERS`: ``reference_temperature_c``
        (degC, required), then either ``glass_transition_c`` (degC) or both ``c1`` and
        ``c2_k`` (K) with optional ``wlf_reference_temperature_c`` (degC).
    field : str
        Dotted name of the table (``"track.pad.tts"``), used in errors.

    Returns
    -------
    TemperatureShifted
    """
    v = take_table(d, TTS_PARAMETERS, field)
    t_ref = v["reference_temperature_c"]
    has_c = v["c1"] is not None or v["c2_k"] is not None
    if (v["glass_transition_c"] is None) == (not has_c):
        raise CaseError(
            field,
            dict(d) if isinstance(d, Mapping) else d,
            "give either glass_transition_c (degC) or both c1 and c2_k (K), not both",
        )
    try:
        wlf = wlf_choice(
            t_ref,
            v["glass_transition_c"],
            v["c1"],
            v["c2_k"],
            v["wlf_reference_temperature_c"],
            field=field,
        )
        assert wlf is not None, "a tts table gives Tg or C1 and C2 (checked above)"
        return TemperatureShifted(
            base,
            wlf,
            t_ref,
            v["vertical_shift"],
            v["expansion_coefficient_per_k"],
        )
    except CaseError as err:
        if err.field.startswith(field):
            raise
        key = err.field.rpartition(".")[2]
        if key == "reference_temperature_c" and err.field.startswith("wlf"):
            key = "wlf_reference_temperature_c"
        raise CaseError(f"{field}.{key}", err.value, err.allowed) from None


def wlf_choice(
    reference_temperature_c: float,
    glass_transition_c: float | None = None,
    c1: float | None = None,
    c2_k: float | None = None,
    wlf_reference_temperature_c: float | None = None,
    *,
    field: str = "tts",
    names: Mapping[str, str] | None = None,
) -> WLF | None:
    """The WLF law a user chose: universal constants at Tg, or given C1 and C2 (or none).

    Parameters
    ----------
    reference_temperature_c : float
        Reference temperature of the pad model, degC (default WLF reference).
    glass_transition_c : float, optional
        Tg, degC: the universal constants C1 = 17.44, C2 = 51.6 K at Tg.
    c1, c2_k : float, optional
        Given WLF constants (dimensionless, K), together.
    wlf_reference_temperature_c : float, optional
        Temperature at which `c1` and `c2_k` apply, degC.
    field : str
        Dotted name used in errors (``"track.pad.tts"``).
    names : mapping, optional
        How the four choices are called in the error text where the user gave them
        differently (e.g. ``{"glass_transition_c": "glass_transition_c (--tg)"}``).

    Returns
    -------
    WLF or None
        None when neither Tg nor C1/C2 is given.

    Raises
    ------
    CaseError
        Tg together with C1/C2, C1 without C2 (or the reverse), or a WLF reference
        temperature without C1/C2.
    """
    name = {
        key: (names or {}).get(key, key)
        for key in ("glass_transition_c", "c1", "c2_k", "wlf_reference_temperature_c")
    }
    has_c = c1 is not None or c2_k is not None
    if glass_transition_c is not None and has_c:
        raise CaseError(
            f"{field}.glass_transition_c",
            glass_transition_c,
            f"give either {name['glass_transition_c']} (degC) or both {name['c1']} and "
            f"{name['c2_k']} (K), not both",
        )
    if has_c:
        for key, value in (("c1", c1), ("c2_k", c2_k)):
            if value is None:
                raise CaseError(
                    f"{field}.{name[key]}",
                    None,
                    f"missing; {name['c1']} and {name['c2_k']} go together",
                )
        t_wlf = wlf_reference_temperature_c
        t0 = reference_temperature_c if t_wlf is None else t_wlf
        return WLF(cast(float, c1), cast(float, c2_k), t0)  # both given: checked above
    if wlf_reference_temperature_c is not None:
        raise CaseError(
            f"{field}.wlf_reference_temperature_c",
            wlf_reference_temperature_c,
            f"only with {name['c1']} and {name['c2_k']} ({name['glass_transition_c']} is the "
            "WLF reference)",
        )
    return None if glass_transition_c is None else WLF.universal(glass_transition_c)


def tts_to_dict(model: TemperatureShifted) -> dict[str, Any]:
    """The ``tts`` table of `model` (WLF constants written about their own reference)."""
    return {
        "reference_temperature_c": float(model.reference_temperature_c),
        "c1": float(model.wlf.c1),
        "c2_k": float(model.wlf.c2_k),
        "wlf_reference_temperature_c": float(model.wlf.reference_temperature_c),
        "vertical_shift": bool(model.vertical_shift),
        "expansion_coefficient_per_k": float(model.expansion_coefficient_per_k),
    }


PADS.extra_tables["tts"] = (TTS_PARAMETERS, tts_from_dict)
