"""The track-model family: infinite periodic tracks that give the rail receptance between points.

A track model registers itself in :data:`TRACKS` with the keys of its case-file
``[track]`` table (declared with :class:`railvib.registry.Parameter`) and a
builder from their checked values.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.registry import Registry

__all__ = ["DEFAULT_TRACK_MODEL", "TRACKS", "TrackModel"]


class TrackModel(ABC):
    """An infinite track: the rail receptance between any points, at any frequencies."""

    sleeper_spacing: float

    @abstractmethod
    def receptance(
        self, f: ArrayLike, x_load: ArrayLike, x_obs: ArrayLike
    ) -> NDArray[np.complex128]:
        """Rail displacement per unit force, m/N, ``(n_freq, n_obs, n_load)``.

        Parameters
        ----------
        f : array_like
            Frequencies, Hz.
        x_load, x_obs : array_like
            Positions of the loads and of the observation points along the rail, m.
        """


#: every track model a case file can describe
TRACKS: Registry[TrackModel] = Registry(
    "track model", TrackModel, "model", where="[track]", tagged=False
)

#: the model of a case's ``[track]`` table (the paper's rail on pads over a rigid base)
DEFAULT_TRACK_MODEL = "rigid_base"
