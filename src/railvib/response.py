"""The one response container every solver returns, and the rule that names responses.

Whatever computes the coupled response — the symplectic track with the
pseudo-excitation method, the finite-track reference, the batched sweep solver —
returns an :class:`FRF`: complex responses per metre of irregularity of the
vehicle DOFs, of the rail under each wheel and of each contact force, with the
vehicle DOF names. The result pipeline (:func:`railvib.results.build_dataset`)
turns one into a labelled dataset, so labels, units and PSDs are derived in one
place.

Response labels (``CONVENTIONS.md``): vehicle DOFs ``<body>.bounce`` /
``<body>.pitch``, then the rail under wheel ``j`` (numbered from the front,
from 1) ``rail@wheel<j>``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from railvib.labels import displacement_unit, rail_label, response_labels

__all__ = ["FRF", "displacement_unit", "rail_label", "response_labels"]


@dataclass(frozen=True, eq=False)
class FRF:
    """Complex frequency responses per metre of irregularity, delayed coherently at the wheels.

    Arrays may carry leading batch axes (cases of a sweep, speeds of one system)
    before the frequency axis; ``f`` is shared by all of them.

    Attributes
    ----------
    f : numpy.ndarray
        Frequencies, Hz, ``(n_freq,)``.
    vehicle : numpy.ndarray
        Vehicle DOF displacements, ``(..., n_freq, n_dof)``, m/m (rad/m for pitch).
    rail : numpy.ndarray
        Rail displacement under each wheel, ``(..., n_freq, n_wheel)``, m/m.
    contact_force : numpy.ndarray
        Dynamic contact force at each wheel (compressive positive), ``(..., n_freq,
        n_wheel)``, N/m.
    dofs : tuple of str
        Names of the vehicle DOFs (the last axis of `vehicle`).
    receptance : numpy.ndarray or None
        Rail receptance between the contact points, ``(n_freq, n_wheel, n_wheel)``,
        m/N, where the solver computes it.
    wheels : tuple of str
        Names of the wheels where they are named per car (a train, ``car1.wheel1``, ...);
        empty: the rail labels are numbered ``rail@wheel<j>``.
    rail_observed : numpy.ndarray or None
        Rail displacement at further points of the rail, ``(..., n_freq, n_obs)``, m/m,
        where the solver was asked for them
        (:meth:`railvib.coupling.CoupledSystem.frf_blocks`: the rail seats under the
        wheels, from the same waves as the contact).
    """

    f: NDArray[np.float64]
    vehicle: NDArray[np.complex128]
    rail: NDArray[np.complex128]
    contact_force: NDArray[np.complex128]
    dofs: tuple[str, ...] = ()
    receptance: NDArray[np.complex128] | None = None
    wheels: tuple[str, ...] = ()
    rail_observed: NDArray[np.complex128] | None = None

    @property
    def n_wheel(self) -> int:
        """Number of wheels (contacts)."""
        return int(self.rail.shape[-1])

    @property
    def labels(self) -> tuple[str, ...]:
        """Response labels: the vehicle DOFs, then ``rail@wheel<j>``."""
        return response_labels(self.dofs, self.n_wheel, self.wheels)

    @property
    def displacement(self) -> NDArray[np.complex128]:
        """Vehicle and rail displacements side by side, ``(..., n_freq, n_resp)``."""
        return np.concatenate([self.vehicle, self.rail], axis=-1)

    def at(self, index: int) -> FRF:
        """The responses of batch entry `index` (first leading axis)."""
        return FRF(
            self.f,
            self.vehicle[index],
            self.rail[index],
            self.contact_force[index],
            self.dofs,
            self.receptance,
            self.wheels,
            None if self.rail_observed is None else self.rail_observed[index],
        )
