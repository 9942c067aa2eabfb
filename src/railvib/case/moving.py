"""The ``[moving]`` section: settings of a ``mode = "moving"`` run (docs/moving-vehicle.md)."""

from __future__ import annotations

from pydantic import Field

from railvib.case.sections import Section
from railvib.track.moving import MAX_HARMONIC_ORDER

__all__ = ["MovingSection"]


class MovingSection(Section):
    """Settings of the moving-vehicle run: harmonic balance over the sleeper passing."""

    harmonic_order: int = Field(
        3,
        ge=1,
        le=MAX_HARMONIC_ORDER,
        description="sleeper-passing harmonics |n| <= N kept (lines at n v/d; responses at "
        "f + n v/d)",
    )
    tolerance: float = Field(
        1e-2,
        gt=0.0,
        lt=1.0,
        description="largest harmonic left out, relative to the largest one (a run whose "
        "order leaves out more is refused, naming the order needed)",
    )
    phases: int = Field(
        8, ge=1, le=64, description="instants per sleeper period of the phase-resolved PSD"
    )
