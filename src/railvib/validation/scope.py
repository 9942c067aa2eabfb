"""What the reference models can check, tested before any of them runs.

The finite track is an Euler-Bernoulli rail; the time-domain Monte Carlo needs,
besides, elements with an exact time-domain form: a viscous pad ``K* = k + i omega c``
(also as the two-rail doubling of ``rail_model = "rail_pair"``), viscous ballast,
subgrade, slab foundation or bearings, and no rail or slab loss factor.
:func:`check_scope` refuses any other case at once, naming the case-file key and the
model the user wrote (``fractional_zener``, not the internal
``temperature_shifted`` wrapper of its ``[track.pad.tts]`` table).
"""

from __future__ import annotations

from railvib.coupling import CoupledSystem
from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.pads.scaled import ScaledPad
from railvib.pads.simple import SpringDamper
from railvib.pads.tts import TemperatureShifted
from railvib.track.ballasted import BallastedTrack
from railvib.track.periodic import Rail
from railvib.track.slab import SlabTrack

__all__ = [
    "check_pad",
    "check_rail",
    "check_scope",
    "pad_model_name",
    "viscous_layer",
    "viscous_pad",
]


def pad_model_name(pad: PadModel) -> str:
    """The pad model as the case file names it: ``fractional_zener (with [track.pad.tts])``.

    Parameters
    ----------
    pad : PadModel
        A pad as built from a case, possibly doubled (``rail_pair``) or temperature-shifted.

    Returns
    -------
    str
        The registered name of the model underneath the wrappers, and the TTS table if any.
    """
    if isinstance(pad, ScaledPad):
        return pad_model_name(pad.base)
    if isinstance(pad, TemperatureShifted):
        return f"{pad_model_name(pad.base)} (with [track.pad.tts])"
    return pad.model_name or type(pad).__name__


def viscous_pad(pad: PadModel) -> tuple[float, float] | None:
    """``(k, c)`` of a viscous pad ``K* = k + i omega c`` (N/m, N s/m), else None.

    Parameters
    ----------
    pad : PadModel
        A spring-damper pad, or one doubled for ``rail_pair`` (``factor * (k + i omega c)``).

    Returns
    -------
    (float, float) or None
        Stiffness in N/m and damping in N s/m; None for any other model.
    """
    if isinstance(pad, ScaledPad):
        inner = viscous_pad(pad.base)
        return None if inner is None else (pad.factor * inner[0], pad.factor * inner[1])
    if isinstance(pad, SpringDamper):
        return float(pad.stiffness_n_per_m), float(pad.damping_ns_per_m)
    return None


def viscous_layer(model: PadModel, field: str) -> tuple[float, float]:
    """``(k, c)`` of a viscous layer for the time-domain model, or a CaseError.

    Parameters
    ----------
    model : PadModel
        A pad, ballast, subgrade, slab foundation or bearing model.
    field : str
        Its case-file table (``track.ballast``), named in the error.

    Returns
    -------
    (float, float)
        Stiffness (N/m; N/m^2 for a foundation) and damping (N s/m; N s/m^2).

    Raises
    ------
    CaseError
        ``<field>.model = '<the user's model>'`` for any model but a spring-damper.
    """
    viscous = viscous_pad(model)
    if viscous is None:
        raise CaseError(
            f"{field}.model",
            pad_model_name(model),
            "spring_damper for railvib validate: its time-domain Monte Carlo needs a "
            "viscous layer (K* = k + i omega c); other models have no exact time-domain "
            "form there",
        )
    return viscous


def check_rail(rail: Rail, time_domain: bool) -> None:
    """Refuse a rail the reference models do not represent.

    Parameters
    ----------
    rail : Rail
        The rail beam (EI in N m^2, mass in kg/m, optional kappa G A in N).
    time_domain : bool
        Check for the time-domain model too (no rail loss factor).

    Raises
    ------
    CaseError
        ``track.rail.shear_stiffness`` (a Timoshenko rail) or ``track.rail.loss_factor``.
    """
    if rail.is_timoshenko:
        raise CaseError(
            "track.rail.shear_stiffness",
            rail.shear_stiffness,
            "omitted for railvib validate: the finite-track reference model is an "
            "Euler-Bernoulli rail (remove shear_stiffness and rotary_inertia)",
        )
    if time_domain and rail.loss_factor != 0.0:
        raise CaseError(
            "track.rail.loss_factor",
            rail.loss_factor,
            "0 for railvib validate: the time-domain Monte Carlo has no hysteretic rail",
        )


def check_pad(pad: PadModel) -> None:
    """Refuse a pad the time-domain Monte Carlo cannot integrate (any but a viscous pad).

    Parameters
    ----------
    pad : PadModel
        The pad per rail seat (complex stiffness in N/m).

    Raises
    ------
    CaseError
        ``track.pad.model = '<the user's model>': spring_damper ...``.
    """
    if viscous_pad(pad) is None:
        raise CaseError(
            "track.pad.model",
            pad_model_name(pad),
            "spring_damper for railvib validate: its time-domain Monte Carlo needs a "
            "viscous pad (K* = k + i omega c); other pad models have no exact "
            "time-domain form there",
        )


def check_scope(system: CoupledSystem) -> None:
    """Raise at once if `system` is outside what the reference models can check.

    Parameters
    ----------
    system : CoupledSystem
        The vehicle on the periodic track (its rail, pad and layers are checked).

    Raises
    ------
    CaseError
        ``track.rail.shear_stiffness`` for a Timoshenko rail, ``track.rail.loss_factor``
        for a rail loss factor, ``track.pad.model`` (the user's model name) for a pad
        that is not viscous, and likewise ``track.ballast.model``, ``track.subgrade.model``,
        ``track.foundation.model`` or ``track.bearing.model`` for a layer of a ballasted or
        slab track, ``track.slab_loss_factor`` for a hysteretic slab.
    """
    track = system.track
    check_rail(track.rail, time_domain=True)
    check_pad(track.pad)
    if isinstance(track, SlabTrack):
        if track.slab_loss_factor != 0.0:
            raise CaseError(
                "track.slab_loss_factor",
                track.slab_loss_factor,
                "0 for railvib validate: the time-domain Monte Carlo has no hysteretic "
                "slab (damp it through [track.foundation] or [track.bearing])",
            )
        layers = {"foundation": track.foundation, "bearing": track.bearing}
    elif isinstance(track, BallastedTrack):
        layers = {"ballast": track.ballast, "subgrade": track.subgrade}
    else:
        layers = {}
    for name, model in layers.items():
        if model is not None:
            viscous_layer(model, f"track.{name}")
