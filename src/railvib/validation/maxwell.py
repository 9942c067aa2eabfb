"""Generalised Maxwell layers in the time-domain reference: one internal DOF per branch.

A layer ``K* = k + i omega c + sum_i K_i (i omega tau_i) / (1 + i omega tau_i)`` (a
spring-damper, or a :class:`~railvib.pads.GeneralizedMaxwell` pad, possibly doubled for
``rail_pair``) between two DOFs (or a DOF and the ground) is, in the time domain, the
spring-damper ``(k, c)`` in parallel with branches, each a spring ``K_i`` in series with
a dashpot ``K_i tau_i``: the massless node between them is an internal DOF. Its equation
``K_i (z - u_top) + K_i tau_i (z' - u_bottom') = 0`` is first order, which the Newmark
average-acceleration scheme integrates as the trapezoidal rule (no mass is needed: the
effective matrix holds ``2 / dt`` times the dashpot), so the time-domain layer is
exactly the frequency-domain one, up to the scheme's frequency warp.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.pads.scaled import ScaledPad
from railvib.pads.simple import SpringDamper
from railvib.pads.tts import TemperatureShifted
from railvib.pads.viscoelastic import GeneralizedMaxwell

__all__ = ["Branches", "branch_matrices", "layer_branches", "pad_model_name", "padded"]

#: ``((k, c), ((K_i, K_i tau_i), ...))``: the parallel spring-damper (N/m, N s/m) and the
#: Maxwell branches (spring N/m, dashpot N s/m)
Branches = tuple[tuple[float, float], tuple[tuple[float, float], ...]]


def layer_branches(model: PadModel, field: str) -> Branches:
    """The time-domain elements of a layer, or a CaseError naming its table.

    Parameters
    ----------
    model : PadModel
        A spring-damper or generalised Maxwell layer, or either doubled (``ScaledPad``).
    field : str
        Its case-file table (``track.pad``), named in the error.

    Returns
    -------
    Branches
        ``((k, c), ((K_i, K_i tau_i), ...))`` in N/m and N s/m (per metre for a
        continuous foundation).

    Raises
    ------
    CaseError
        ``<field>.model`` for any other model (no exact time-domain form here).
    """
    if isinstance(model, ScaledPad):
        (k, c), branches = layer_branches(model.base, field)
        s = model.factor
        return (s * k, s * c), tuple((s * kb, s * cb) for kb, cb in branches)
    if isinstance(model, SpringDamper):
        return (float(model.stiffness_n_per_m), float(model.damping_ns_per_m)), ()
    if isinstance(model, GeneralizedMaxwell):
        branches = tuple(
            (float(kb), float(kb) * float(tau))
            for kb, tau in zip(model.k_n_per_m, model.tau_s, strict=True)
            if kb > 0.0
        )
        return (float(model.k_inf_n_per_m), 0.0), branches
    raise CaseError(
        f"{field}.model",
        pad_model_name(model),
        "spring_damper or generalized_maxwell for the time-domain Monte Carlo (hysteretic "
        "layers are fitted by railvib validate): other models have no exact time-domain form",
    )


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


def padded(matrix: sp.spmatrix, n: int) -> sp.csc_matrix:
    """`matrix` in the top-left corner of an ``n x n`` sparse matrix (zeros elsewhere)."""
    extra = n - matrix.shape[0]
    if extra == 0:
        return sp.csc_matrix(matrix)
    return sp.block_diag([matrix, sp.csc_matrix((extra, extra))], format="csc")


def branch_matrices(
    top: NDArray[np.intp], bottom: NDArray[np.intp] | None, branches: Branches, first: int
) -> tuple[list[NDArray], list[NDArray], list[NDArray], list[NDArray], int]:
    """Triplets of the branches of one layer under each DOF of `top` (numbered from `first`).

    Parameters
    ----------
    top : numpy.ndarray
        DOFs above the layer (dimensionless indices), one per element of the layer.
    bottom : numpy.ndarray or None
        DOFs below it (dimensionless indices), same length, or None for the ground.
    branches : Branches
        :func:`layer_branches` of the layer (its parallel part is left to the caller).
    first : int
        Number of the first internal DOF (dimensionless index).

    Returns
    -------
    rows, cols, k_vals, c_vals : list of numpy.ndarray
        COO triplets of the stiffness (N/m) and damping (N s/m) entries.
    n_new : int
        Internal DOFs added (``len(branches[1]) * top.size``).
    """
    rows: list[NDArray] = []
    cols: list[NDArray] = []
    k_vals: list[NDArray] = []
    c_vals: list[NDArray] = []
    n = top.size
    for i, (kb, cb) in enumerate(branches[1]):
        z = first + i * n + np.arange(n)
        one = np.ones(n)
        # the spring between top and z, the dashpot between z and bottom (or the ground)
        rows += [top, z, top, z]
        cols += [top, z, z, top]
        k_vals += [kb * one, kb * one, -kb * one, -kb * one]
        c_vals += [0 * one] * 4
        if bottom is None:
            rows.append(z)
            cols.append(z)
            k_vals.append(0 * one)
            c_vals.append(cb * one)
        else:
            rows += [z, bottom, z, bottom]
            cols += [z, bottom, bottom, z]
            k_vals += [0 * one] * 4
            c_vals += [cb * one, cb * one, -cb * one, -cb * one]
    return rows, cols, k_vals, c_vals, len(branches[1]) * n
