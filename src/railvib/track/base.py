"""The track-model family: infinite periodic tracks that give the rail receptance between points.

A track model registers itself in :data:`TRACKS` with the keys of its case-file
``[track]`` table (declared with :class:`railvib.registry.Parameter`) and a
builder from their checked values.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.registry import Registry

__all__ = [
    "DEFAULT_TRACK_MODEL",
    "TRACKS",
    "SupportResponse",
    "TrackModel",
    "passive_layer_stiffness",
]


def passive_layer_stiffness(
    models: dict[str, PadModel | None],
    f: ArrayLike,
    temperature: float | None,
    *,
    unit: str = "",
    tolerance: float = 0.0,
) -> dict[str, NDArray[np.complex128]]:
    """The complex stiffness of each layer model given, checked finite and passive.

    Parameters
    ----------
    models : dict of str to PadModel or None
        The layers by name (``"pad"``, ``"ballast"``, ...); None: the layer is absent.
    f : array_like
        Frequencies in Hz.
    temperature : float, optional
        Temperature passed to the models, degC.
    unit : str
        Unit written after a refused value (e.g. ``" N/m"``).
    tolerance : float
        ``Im K`` down to ``-tolerance |K|`` counts as passive (round-off; dimensionless).

    Returns
    -------
    dict of str to numpy.ndarray
        The present layers' ``K*(f)``, each ``(n_freq,)``, in the models' units.

    Raises
    ------
    CaseError
        A layer has ``Im K < 0`` (it would put power into the track) or is not finite at a
        frequency of the grid, named ``track.<layer>``.
    """
    f = np.asarray(f, dtype=float)
    out: dict[str, NDArray[np.complex128]] = {}
    for name, model in models.items():
        if model is None:
            continue
        k = np.asarray(model.stiffness(f, temperature), dtype=np.complex128)
        k = np.broadcast_to(k, f.shape).astype(np.complex128)
        bad = ~(np.isfinite(k) & (k.imag >= -tolerance * np.abs(k)))
        if np.any(bad):
            raise CaseError(
                f"track.{name}",
                f"K = {complex(k[bad][0]):.4g}{unit} at {float(f[bad][0]):.6g} Hz",
                "a passive, finite model: Im K >= 0 at every frequency of the grid",
            )
        out[name] = k
    return out


@dataclass(frozen=True, eq=False)
class SupportResponse:
    """The layers below each rail seat near a unit load (:meth:`TrackModel.support_response`).

    Every array is per unit force at the load, ``(n_freq, n_supports)``; forces are
    compressive-positive (downward on the layer below), displacements positive downward.

    Attributes
    ----------
    x : numpy.ndarray
        Positions of the rail seats along the rail, m, ``(n_supports,)``.
    displacement : dict of str to numpy.ndarray
        Displacement of each mass of the seat per unit force, m/N: ``"rail"`` (the rail at
        the seat) and, below it, e.g. ``"sleeper"``, ``"ballast_mass"``.
    compression : dict of str to numpy.ndarray
        Compression of each spring layer per unit force, m/N (top minus bottom
        displacement), e.g. ``"pad"``, ``"ballast"``, ``"subgrade"``.
    force : dict of str to numpy.ndarray
        Force carried by each spring layer per unit force (dimensionless, N/N):
        ``K* compression``.
    stiffness : dict of str to numpy.ndarray
        Complex stiffness of each spring layer, N/m, ``(n_freq,)``.
    foundation : str
        The layer whose force is transmitted to the rigid ground.
    """

    x: NDArray[np.float64]
    displacement: dict[str, NDArray[np.complex128]]
    compression: dict[str, NDArray[np.complex128]]
    force: dict[str, NDArray[np.complex128]]
    stiffness: dict[str, NDArray[np.complex128]]
    foundation: str

    @property
    def foundation_force(self) -> NDArray[np.complex128]:
        """Force transmitted to the ground at each seat per unit force (N/N)."""
        return self.force[self.foundation]


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

    @property
    @abstractmethod
    def period(self) -> float:
        """Length of the periodic cell along the rail, m (a sleeper bay, a unit slab)."""

    @abstractmethod
    def propagation_constants(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Propagation constants ``mu = exp(-gamma period)`` of the right-going waves.

        Parameters
        ----------
        f : array_like
            Frequencies, Hz.

        Returns
        -------
        numpy.ndarray
            ``(n_freq, n_waves)``, ``|mu| <= 1``, each row sorted least-attenuated first
            (largest ``|mu|`` first).
        """

    def support_response(self, f: ArrayLike, x_load: float, n_supports: int) -> SupportResponse:
        """The layers below the rail seats nearest a unit load (displacements and forces).

        Parameters
        ----------
        f : array_like
            Frequencies, Hz.
        x_load : float
            Position of the unit load along the rail, m.
        n_supports : int
            Rail seats on each side of the one nearest the load (``2 n + 1`` in all).

        Returns
        -------
        SupportResponse

        Raises
        ------
        NotImplementedError
            A track model that does not give its support forces.
        """
        raise NotImplementedError(f"{type(self).__name__} does not give its support forces")


#: every track model a case file can describe
TRACKS: Registry[TrackModel] = Registry(
    "track model", TrackModel, "model", where="[track]", tagged=False
)

#: the model of a case's ``[track]`` table (the paper's rail on pads over a rigid base)
DEFAULT_TRACK_MODEL = "rigid_base"
