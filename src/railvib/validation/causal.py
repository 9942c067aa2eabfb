"""Causal stand-ins for the hysteretic layers that ``railvib validate`` compares.

A hysteretic (constant loss factor) layer ``K* = k (1 + i eta)`` has no causal
time-domain form, so the time-domain Monte Carlo cannot integrate it. ``validate``
therefore replaces, before anything is computed, each hysteretic pad, ballast, subgrade
or bearing by a generalised Maxwell layer (Prony series, :class:`~railvib.pads.
GeneralizedMaxwell`, :data:`BRANCHES` branches) fitted to it by least squares over the
compared band (:func:`railvib.pads.fit.fit_model`: relative errors of ``K'`` and
``K''``), and a slab loss factor ``eta_s`` by a viscous (Kelvin-Voigt) slab
``EI_s (1 + i omega tau_s)`` with ``omega tau_s = eta_s`` at the band's geometric mean
frequency. The same fitted system is then solved by all three routes (PEM, finite track,
Monte Carlo), so their comparison stays exact; one note per replaced layer states the
approximation and its error over the band against the hysteretic original. No causal
model matches a constant loss factor and a constant storage stiffness at once over a
wide band (Kramers-Kronig: constant ``eta`` implies ``K'`` rising by about ``(2 eta /
pi) ln 10`` of itself per decade), so the fit splits the difference.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from railvib.coupling import CoupledSystem
from railvib.pads.base import PadModel
from railvib.pads.fit import fit_model
from railvib.pads.scaled import ScaledPad
from railvib.pads.simple import Hysteretic
from railvib.pads.viscoelastic import GeneralizedMaxwell
from railvib.track.ballasted import BallastedTrack
from railvib.track.slab import SlabTrack

__all__ = ["BRANCHES", "causal_system"]

#: Maxwell branches of a fitted layer: two per decade of the default 1 Hz - 1 kHz band
#: (one internal DOF each per rail seat in the Monte Carlo); 11 branches fit
#: thompson_ballasted's pad (eta 0.25) to 45 % instead of 48 % at 6 (measured)
BRANCHES = 6

#: a fitted branch stiffer than this fraction of the hysteretic k is kept
_NEGLIGIBLE = 1e-9

#: points of the fit over the band (log-spaced)
_FIT_POINTS = 120


def causal_system(
    system: CoupledSystem, f_min: float, f_max: float
) -> tuple[CoupledSystem, tuple[str, ...]]:
    """`system` with its hysteretic layers replaced by causal fits over ``[f_min, f_max]``.

    Parameters
    ----------
    system : CoupledSystem
        The vehicle on the periodic track.
    f_min, f_max : float
        The compared band, Hz (``0 < f_min < f_max``).

    Returns
    -------
    system : CoupledSystem
        The same system, each hysteretic layer (``track.pad``, ``track.ballast``,
        ``track.subgrade``, ``track.bearing``) a fitted generalised Maxwell layer and a
        slab loss factor a viscous slab; `system` itself where there are none.
    notes : tuple of str
        One line per replaced layer: the approximation and its error over the band.
    """
    track = system.track
    f = np.geomspace(f_min, f_max, _FIT_POINTS)
    band = f"{f_min:g}-{f_max:g} Hz"
    keys = ["pad"]
    if isinstance(track, BallastedTrack):
        keys += ["ballast", "subgrade"]
    if isinstance(track, SlabTrack):
        keys += ["bearing"]
    changes: dict[str, Any] = {}
    notes: list[str] = []
    for key in keys:
        model = getattr(track, key)
        base, factor = (model.base, model.factor) if isinstance(model, ScaledPad) else (model, 1.0)
        if not isinstance(base, Hysteretic):
            continue
        fitted, note = _fit_layer(base, f)
        changes[key] = ScaledPad(fitted, factor) if isinstance(model, ScaledPad) else fitted
        notes.append(f"track.{key}: {note} over {band}")
    if isinstance(track, SlabTrack) and track.slab_loss_factor > 0.0:
        eta = track.slab_loss_factor
        f_ref = float(np.sqrt(f_min * f_max))
        changes.update(slab_loss_factor=0.0, slab_damping_time=eta / (2.0 * np.pi * f_ref))
        ratio = f_max / f_ref
        notes.append(
            f"track.slab_loss_factor: hysteretic eta_s = {eta:g} -> viscous slab EI_s (1 + i "
            f"omega tau_s), omega tau_s = eta_s at {f_ref:.3g} Hz; its loss factor "
            f"{eta / ratio:.2g}-{eta * ratio:.2g} over {band} (x{1 / ratio:.2g}-x{ratio:.2g})"
        )
    if not changes:
        return system, ()
    return replace(system, track=replace(track, **changes)), tuple(notes)


def _fit_layer(model: Hysteretic, f: np.ndarray) -> tuple[PadModel, str]:
    """The generalised Maxwell fit of `model` on `f` (Hz) and the note on its error."""
    target = np.asarray(model.stiffness(f), dtype=np.complex128)
    fit = fit_model(f, target, "generalized_maxwell", n_terms=BRANCHES).model
    assert isinstance(fit, GeneralizedMaxwell), "fit_model gives the model it was asked for"
    # branches the fit left at (nearly) zero stiffness carry no force: dropped, so that no
    # internal DOF of the Monte Carlo hangs on a vanishing spring
    keep = [i for i, kb in enumerate(fit.k_n_per_m) if kb > _NEGLIGIBLE * model.stiffness_n_per_m]
    fitted = GeneralizedMaxwell(
        fit.k_inf_n_per_m,
        tuple(fit.k_n_per_m[i] for i in keep),
        tuple(fit.tau_s[i] for i in keep),
    )
    k = np.asarray(fitted.stiffness(f), dtype=np.complex128)
    storage = k.real / target.real - 1.0
    eta = k.imag / k.real
    note = (
        f"hysteretic (k = {model.stiffness_n_per_m:.3g} N/m, eta = {model.loss_factor_:g}) -> "
        f"generalized_maxwell, {len(keep)} branches (causal) fitted: |K*/K*_hyst - 1| <= "
        f"{np.abs(k / target - 1.0).max():.1%}, storage {storage.min():+.0%} to "
        f"{storage.max():+.0%}, loss factor {eta.min():.3g}-{eta.max():.3g}"
    )
    return fitted, note
