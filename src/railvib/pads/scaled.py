"""A pad model scaled by a constant factor (e.g. two rail seats acting in parallel)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PadModel

__all__ = ["ScaledPad"]


@dataclass(frozen=True)
class ScaledPad(PadModel):
    """``factor * base.stiffness(f, T)``: `factor` identical pads in parallel.

    Parameters
    ----------
    base : PadModel
        The pad of one rail seat.
    factor : float
        Number of seats in parallel (> 0); 2 when one beam stands for both rails.
    """

    base: PadModel
    factor: float
    model_name = "scaled"

    def __post_init__(self) -> None:
        if not (np.isfinite(self.factor) and self.factor > 0):
            raise CaseError("track.pad.factor", self.factor, "must be > 0")

    @property
    def temperature_dependent(self) -> bool:
        """As the base pad."""
        return self.base.temperature_dependent

    @property
    def temperature_range_c(self) -> tuple[float, float] | None:
        """As the base pad (degC)."""
        return self.base.temperature_range_c

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``factor * K*_base(f, T)`` in N/m."""
        return np.asarray(self.factor * self.base.stiffness(f, temperature), dtype=np.complex128)
