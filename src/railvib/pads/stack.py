"""The complex stiffness of many pads, each at its own temperature, in one pass per model."""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from typing import cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.pads.base import PadModel
from railvib.pads.scaled import ScaledPad
from railvib.pads.tts import TemperatureShifted, vertical_shift_factor

__all__ = ["pad_stiffnesses"]


def pad_stiffnesses(
    pads: Sequence[PadModel], temperatures: Sequence[float | None], f: ArrayLike
) -> NDArray[np.complex128]:
    """``pads[i].stiffness(f, temperatures[i])`` of every pad, N/m, ``(n, n_freq)``.

    Pads of one model (:meth:`~railvib.pads.PadModel.stiffness_rows`) are evaluated
    together, over arrays of their parameters; those sharing a temperature shift
    (the same WLF law, reference temperature and vertical shift) are shifted
    together, over the array of their temperatures. The operations are those of
    :meth:`~railvib.pads.PadModel.stiffness` pad by pad. A scaled pad (both rails on
    one beam) is its base pad times its factor. Any other pad (a temperature-dependent
    model without a shift table) is evaluated by itself.

    Parameters
    ----------
    pads : sequence of PadModel
        The pads, ``n``.
    temperatures : sequence of float or None
        The temperature of each pad, degC (None: its reference), ``n``.
    f : array_like
        Frequencies in Hz, ``(n_freq,)``.

    Returns
    -------
    numpy.ndarray of complex
        ``(n, n_freq)``.

    Raises
    ------
    CaseError
        A temperature a pad's shift cannot take, as ``stiffness`` refuses it.
    """
    f = np.asarray(f, dtype=float).reshape(-1)
    out = np.empty((len(pads), f.size), dtype=np.complex128)
    factors = np.ones(len(pads))
    groups: dict[Hashable, list[int]] = {}
    inner: list[PadModel] = []
    for i, (pad, t) in enumerate(zip(pads, temperatures, strict=True)):
        if isinstance(pad, ScaledPad):
            factors[i], pad = pad.factor, pad.base
        inner.append(pad)
        if isinstance(pad, TemperatureShifted) and not pad.base.temperature_dependent:
            shift = (
                None
                if t is None
                else (
                    pad.wlf,
                    pad.reference_temperature_c,
                    pad.vertical_shift,
                    pad.expansion_coefficient_per_k,
                )
            )
            key: Hashable = (type(pad.base), shift)
        elif not pad.temperature_dependent:
            key = (type(pad), None)
        else:
            key = i  # evaluated by itself
        groups.setdefault(key, []).append(i)
    for key, rows in groups.items():
        if not isinstance(key, tuple):
            (i,) = rows
            out[i] = inner[i].stiffness(f, temperatures[i])
            continue
        model, shift = key
        pads_of = [inner[i] for i in rows]  # of one model, or shifted pads of one base model
        if shift is None:
            bases = [p.base if isinstance(p, TemperatureShifted) else p for p in pads_of]
            out[rows] = model.stiffness_rows(bases, np.broadcast_to(f, (len(rows), f.size)))
            continue
        shifted_pads = cast("list[TemperatureShifted]", pads_of)
        a_t, v = _shifts(shifted_pads[0], np.array([temperatures[i] for i in rows], dtype=float))
        shifted = model.stiffness_rows([p.base for p in shifted_pads], f * a_t[:, None])
        out[rows] = shifted if v is None else v[:, None] * shifted
    scaled = factors != 1.0
    out[scaled] = factors[scaled, None] * out[scaled]
    return out


def _shifts(
    pad: TemperatureShifted, t: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """``(a_T, v(T))`` of :meth:`TemperatureShifted.shift` over temperatures `t` (degC).

    ``v`` is None without a vertical shift (the stiffness is not scaled).
    """
    log_a = pad.wlf.log_shift(t) - pad.wlf.log_shift(pad.reference_temperature_c)
    pad.wlf_at_reference._check_shift(t, log_a, "temperature")
    # a scalar power per temperature, as `shift` takes it (NumPy's array power may round
    # the last bit otherwise)
    a_t = np.array([float(10.0**x) for x in log_a])
    if not pad.vertical_shift:
        return a_t, None
    v = vertical_shift_factor(t, pad.reference_temperature_c, pad.expansion_coefficient_per_k)
    return a_t, np.asarray(v, dtype=float)
