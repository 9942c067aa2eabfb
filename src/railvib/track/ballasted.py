"""The ballasted track: rail - pad - sleeper - ballast (- ballast mass - subgrade) - ground.

Each rail seat carries a sleeper mass ``m_s`` (the half-sleeper of one rail)
connected only through the railpad above (``K_p``) and the ballast below
(``K_b``). Its equation of motion, ``(K_p + K_b - m_s omega^2) w_s = K_p w_r``,
condenses it exactly into the support stiffness the rail sees at that seat:

    K_eff = K_p Z_b / (K_p + Z_b),    Z_b = K_b - m_s omega^2,

i.e. the pad in series with the sleeper-on-ballast impedance. The three-layer
model puts a ballast mass ``m_b`` on a subgrade spring ``K_g`` under the ballast
spring; condensing ``m_b`` the same way replaces ``K_b`` by
``K_b Z_g / (K_b + Z_g)``, ``Z_g = K_g - m_b omega^2``. ``K_p``, ``K_b`` and
``K_g`` are complex (any pad model, temperature-dependent ones included), so the
rail on its supports is the same periodic structure as the rigid-base track and
is solved by the same wave method with ``K_eff(f)`` for its pad.

Passivity, with ``exp(+i omega t)``: a support absorbs power ``omega Im K |w|^2 / 2``,
so it is passive where ``Im K >= 0``. If ``Im K_p >= 0`` and ``Im Z_b = Im K_b >= 0``,
then ``Im(1/K_p) <= 0`` and ``Im(1/Z_b) <= 0``, so ``1/K_eff = 1/K_p + 1/Z_b`` has
``Im <= 0`` and ``Im K_eff >= 0``: a ballasted support built from passive layers is
passive at every frequency, for any mass (the same holds for the nested third layer).
The layer models are checked for ``Im K >= 0`` on every grid the track is solved at.

The sleeper moves only vertically: its rotary inertia and width (its bending and the
pad's extent along the rail) are not modelled.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PADS, PadModel
from railvib.registry import Parameter, check_value
from railvib.track.base import TRACKS, SupportResponse, passive_layer_stiffness
from railvib.track.periodic import RIGID_BASE_PARAMETERS, PeriodicTrack, Rail

__all__ = ["BALLASTED_PARAMETERS", "BallastedTrack", "ballasted_track", "series_support"]

#: keys of the ``[track]`` table of the ballasted track: the rigid-base ones and the layers
BALLASTED_PARAMETERS = (
    *RIGID_BASE_PARAMETERS,
    # a concrete monoblock half-sleeper is 100-200 kg; 1e4 kg is far above any sleeper
    Parameter(
        "sleeper_mass_kg",
        "kg",
        "sleeper mass per rail seat (half a sleeper for one rail)",
        gt=0.0,
        le=1e4,
        typical=(100.0, 200.0),
    ),
    Parameter("ballast", "N/m", "ballast model below one rail seat", "member", family=PADS),
    # the ballast mass per rail seat of the three-layer model is a few hundred kg
    Parameter(
        "ballast_mass_kg",
        "kg",
        "vibrating ballast mass per rail seat of the three-layer model (with subgrade)",
        default=None,
        gt=0.0,
        le=1e5,
        typical=(200.0, 800.0),
    ),
    Parameter(
        "subgrade",
        "N/m",
        "subgrade model below the ballast mass of the three-layer model (with ballast_mass_kg)",
        "member",
        default=None,
        family=PADS,
    ),
)

_BY_KEY = {p.key: p for p in BALLASTED_PARAMETERS}


def series_support(
    upper: NDArray[np.complex128], lower: NDArray[np.complex128]
) -> NDArray[np.complex128]:
    """Spring `upper` in series with the impedance `lower`: ``upper lower / (upper + lower)``.

    Parameters
    ----------
    upper, lower : numpy.ndarray
        Complex stiffnesses in N/m (`lower` may hold an inertia term ``-m omega^2``).

    Returns
    -------
    numpy.ndarray
        The series stiffness in N/m; 0 where `lower` is 0 (a mass at its resonance on
        the layer below it).
    """
    return np.asarray(upper * lower / (upper + lower), dtype=np.complex128)


@dataclass(frozen=True)
class BallastedTrack(PeriodicTrack):
    """Rail on railpads on sleepers on ballast (optionally a ballast mass on subgrade).

    Parameters
    ----------
    rail : Rail
        The rail beam.
    pad : PadModel
        Railpad model, complex stiffness per rail seat in N/m.
    sleeper_spacing : float
        Sleeper spacing d in m (> 0).
    pad_temperature : float, optional
        Temperature in degrees Celsius, passed to the pad, ballast and subgrade models.
    sleeper_mass : float
        Sleeper mass per rail seat in kg (>= 0).
    ballast : PadModel
        Ballast model, complex stiffness per rail seat in N/m.
    ballast_mass : float, optional
        Ballast mass per rail seat in kg (> 0) of the three-layer model; with `subgrade`.
    subgrade : PadModel, optional
        Subgrade model, complex stiffness per rail seat in N/m; with `ballast_mass`.

    Examples
    --------
    >>> from railvib.pads import Hysteretic
    >>> track = BallastedTrack(
    ...     Rail(6.42e6, 60.0), Hysteretic(3e8, 0.25), 0.6,
    ...     sleeper_mass=162.0, ballast=Hysteretic(5e7, 1.0),
    ... )
    >>> track.receptance([100.0], x_load=[0.3], x_obs=[0.3]).shape
    (1, 1, 1)
    """

    sleeper_mass: float = 0.0
    ballast: PadModel | None = None
    ballast_mass: float | None = None
    subgrade: PadModel | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.sleeper_mass == 0.0:
            raise CaseError(
                "track.sleeper_mass_kg",
                self.sleeper_mass,
                "> 0 (kg): a ballast layer stands under a sleeper mass (for pad and ballast "
                "in series without one, give model rigid_base their series stiffness as pad)",
            )
        check_value(_BY_KEY["sleeper_mass_kg"], self.sleeper_mass, "track.sleeper_mass_kg")
        if not isinstance(self.ballast, PadModel):
            raise CaseError("track.ballast", self.ballast, "a PadModel (N/m)")
        if self.ballast_mass is not None:
            check_value(_BY_KEY["ballast_mass_kg"], self.ballast_mass, "track.ballast_mass_kg")
        if self.subgrade is not None and not isinstance(self.subgrade, PadModel):
            raise CaseError("track.subgrade", self.subgrade, "a PadModel (N/m)")
        if self.subgrade is not None and self.ballast_mass is None:
            raise CaseError(
                "track.ballast_mass_kg",
                "<missing>",
                "required with track.subgrade (> 0 kg: the three-layer model's ballast mass)",
            )
        if self.ballast_mass is not None and self.subgrade is None:
            raise CaseError(
                "track.subgrade",
                "<missing>",
                "required with track.ballast_mass_kg (the spring under the ballast mass)",
            )

    @property
    def three_layer(self) -> bool:
        """True with a ballast mass on a subgrade below the ballast spring."""
        return self.subgrade is not None

    def layer_stiffness(self, f: ArrayLike) -> dict[str, NDArray[np.complex128]]:
        """The complex stiffness of each layer per rail seat, N/m, checked passive.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Returns
        -------
        dict
            ``{"pad": K_p, "ballast": K_b}`` and, for three layers, ``"subgrade": K_g``,
            each ``(n_freq,)``.

        Raises
        ------
        CaseError
            A layer has ``Im K < 0`` (it would put power into the track) at a frequency of
            the grid, named ``track.<layer>``.
        """
        models: dict[str, PadModel | None] = {
            "pad": self.pad,
            "ballast": self.ballast,
            "subgrade": self.subgrade,
        }
        return passive_layer_stiffness(models, f, self.pad_temperature, unit=" N/m")

    def support_stiffness(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Rail seat support seen by the rail, ``K_p Z_b / (K_p + Z_b)``, N/m, ``(n_freq,)``.

        ``Z_b = K_b - m_s omega^2`` with, for three layers, ``K_b`` replaced by
        ``K_b Z_g / (K_b + Z_g)``, ``Z_g = K_g - m_b omega^2`` (see the module docstring).

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Returns
        -------
        numpy.ndarray
            ``K_eff(f)`` in N/m; ``Im K_eff >= 0``.
        """
        f = np.asarray(f, dtype=float)
        omega2 = (2.0 * np.pi * f) ** 2
        k = self.layer_stiffness(f)
        below = k["ballast"]
        if self.three_layer:
            assert self.ballast_mass is not None, "checked in __post_init__"
            below = series_support(below, k["subgrade"] - self.ballast_mass * omega2)
        return series_support(k["pad"], below - self.sleeper_mass * omega2)

    def seat_response(
        self, f: ArrayLike, x: NDArray[np.float64], rail: NDArray[np.complex128]
    ) -> SupportResponse:
        """The sleeper (and ballast mass) and the layer forces from the rail displacement.

        The condensed sleeper equation ``(K_p + Z_b) w_s = K_p w_r`` gives the sleeper;
        the pad carries ``K_p (w_r - w_s)``, the ballast ``K_b w_s`` to the ground, or,
        with three layers, ``K_b (w_s - w_m)`` with ``(K_b + Z_g) w_m = K_b w_s`` and the
        subgrade ``K_g w_m`` to the ground (the module docstring).

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, ``(n_freq,)``.
        x : numpy.ndarray
            Seat positions, m, ``(n_supports,)``.
        rail : numpy.ndarray
            Rail displacement at the seats per unit force, m/N, ``(n_freq, n_supports)``.

        Returns
        -------
        SupportResponse
            Masses ``"rail"``, ``"sleeper"`` (``"ballast_mass"``); layers ``"pad"``,
            ``"ballast"`` (``"subgrade"``).
        """
        f = np.asarray(f, dtype=float)
        omega2 = ((2.0 * np.pi * f) ** 2)[:, None]
        k = self.layer_stiffness(f)
        kp, kb = k["pad"][:, None], k["ballast"][:, None]
        below = kb
        if self.three_layer:
            assert self.ballast_mass is not None, "checked in __post_init__"
            zg = k["subgrade"][:, None] - self.ballast_mass * omega2
            below = series_support(kb, zg)
        sleeper = kp * rail / (kp + below - self.sleeper_mass * omega2)
        displacement = {"rail": rail, "sleeper": sleeper}
        compression = {"pad": rail - sleeper, "ballast": sleeper}
        foundation = "ballast"
        if self.three_layer:
            mass = kb * sleeper / (kb + zg)
            displacement["ballast_mass"] = mass
            compression.update(ballast=sleeper - mass, subgrade=mass)
            foundation = "subgrade"
        force = {name: k[name][:, None] * c for name, c in compression.items()}
        return SupportResponse(
            x=np.asarray(x, dtype=float),
            displacement=displacement,
            compression=compression,
            force=force,
            stiffness=k,
            foundation=foundation,
        )


def ballasted_track(
    sleeper_spacing: float,
    rail: Rail,
    pad: PadModel,
    sleeper_mass_kg: float,
    ballast: PadModel,
    pad_temperature_c: float | None = None,
    ballast_mass_kg: float | None = None,
    subgrade: PadModel | None = None,
) -> BallastedTrack:
    """The ballasted track of a ``[track]`` table's checked values (see :class:`BallastedTrack`).

    Parameters
    ----------
    sleeper_spacing : float
        Sleeper spacing d in m.
    rail : Rail
        The rail beam.
    pad : PadModel
        Railpad model per rail seat, N/m.
    sleeper_mass_kg : float
        Sleeper mass per rail seat in kg.
    ballast : PadModel
        Ballast model per rail seat, N/m.
    pad_temperature_c : float, optional
        Temperature of the pad (and layer) models in degC.
    ballast_mass_kg : float, optional
        Ballast mass per rail seat in kg (three layers).
    subgrade : PadModel, optional
        Subgrade model per rail seat, N/m (three layers).

    Returns
    -------
    BallastedTrack
        The track.
    """
    return BallastedTrack(
        rail,
        pad,
        sleeper_spacing,
        pad_temperature_c,
        sleeper_mass=sleeper_mass_kg,
        ballast=ballast,
        ballast_mass=ballast_mass_kg,
        subgrade=subgrade,
    )


TRACKS.register("ballasted", parameters=BALLASTED_PARAMETERS, build=ballasted_track)(BallastedTrack)
