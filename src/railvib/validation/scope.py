"""What the reference models can check, tested before any of them runs.

The finite track is an Euler-Bernoulli rail; the time-domain Monte Carlo needs,
besides, elements with an exact time-domain form: a viscous pad ``K* = k + i omega c``
or a generalised Maxwell one (also as the two-rail doubling of ``rail_model =
"rail_pair"``), the same for ballast, subgrade or bearings, a viscous slab foundation,
and no rail loss factor; hysteretic layers and a slab loss factor are replaced by causal
fits before validating (:mod:`railvib.validation.causal`).
:func:`check_scope` refuses any other case at once, naming the case-file key and the
model the user wrote (``fractional_zener``, not the internal
``temperature_shifted`` wrapper of its ``[track.pad.tts]`` table).
"""

from __future__ import annotations

from railvib.coupling import CoupledSystem
from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.pads.scaled import ScaledPad
from railvib.pads.simple import Hysteretic, SpringDamper
from railvib.track.ballasted import BallastedTrack
from railvib.track.periodic import Rail
from railvib.track.slab import SlabTrack
from railvib.validation.maxwell import layer_branches, pad_model_name

__all__ = [
    "check_pad",
    "check_rail",
    "check_scope",
    "pad_model_name",
    "viscous_layer",
    "viscous_pad",
]


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

    Hysteretic pads, ballast, subgrade and bearings and a slab loss factor pass: ``railvib
    validate`` replaces them by causal fits first (:mod:`railvib.validation.causal`).

    Parameters
    ----------
    system : CoupledSystem
        The vehicle on the periodic track (its rail, pad and layers are checked).

    Raises
    ------
    CaseError
        ``track.rail.shear_stiffness`` for a Timoshenko rail, ``track.rail.loss_factor``
        for a rail loss factor, ``track.pad.model`` (the user's model name) for a pad
        that is neither viscous, generalised Maxwell nor hysteretic, and likewise
        ``track.ballast.model``, ``track.subgrade.model`` or ``track.bearing.model`` for a
        layer of a ballasted or slab track, ``track.foundation.model`` for a slab
        foundation that is not viscous.
    """
    track = system.track
    check_rail(track.rail, time_domain=True)
    layers: dict[str, PadModel | None] = {"pad": track.pad}
    if isinstance(track, SlabTrack):
        layers["bearing"] = track.bearing
        if track.foundation is not None:
            viscous_layer(track.foundation, "track.foundation")
    elif isinstance(track, BallastedTrack):
        layers.update(ballast=track.ballast, subgrade=track.subgrade)
    for name, model in layers.items():
        base = model.base if isinstance(model, ScaledPad) else model
        if model is not None and not isinstance(base, Hysteretic):
            layer_branches(model, f"track.{name}")
