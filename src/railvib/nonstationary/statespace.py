"""The vehicle on a rigid track, through its Hertz springs, as a first-order system.

With ``W`` the wheel matrix (``Vehicle.wheel_matrix``), the contact force
``P = k_H (W^T u - r)`` (compressive positive) acts upward on the wheels:

    M u'' + C u' + (K + k_H W W^T) u = k_H W r(t),

so with the state ``z = [u; u']`` it is ``z' = A z + B r`` and the outputs (the
DOF displacements, the DOF accelerations, the contact forces) are ``y = C z + D r``.
``A`` is constant (the track is rigid, the vehicle time-invariant): only the
input moves with the speed. ``A = V diag(lambda) V^-1`` decouples it into modes,
which the exact integrator (:mod:`railvib.nonstationary.exact`) steps exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from railvib.errors import CaseError
from railvib.vehicle.assembly import Vehicle

__all__ = ["RigidTrackVehicle"]

#: largest relative residual ``|V diag(lambda) V^-1 - A| / |A|`` accepted of the modal form
#: (a defective system would show 1e-8 or worse; a sound one shows about 1e-14)
MODAL_RESIDUAL = 1e-9


@dataclass(frozen=True, eq=False)
class RigidTrackVehicle:
    """A vehicle on Hertz springs over a rigid rail, in first-order (state-space) form.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle (wheels front to back).
    contact_stiffness : float
        k_H per contact, N/m (> 0).
    """

    vehicle: Vehicle
    contact_stiffness: float

    def __post_init__(self) -> None:
        if not (np.isfinite(self.contact_stiffness) and self.contact_stiffness > 0):
            raise CaseError("contact.stiffness", self.contact_stiffness, "must be > 0 (N/m)")

    @property
    def n_dof(self) -> int:
        """Number of vehicle DOFs."""
        return len(self.vehicle.dofs)

    @property
    def n_wheel(self) -> int:
        """Number of wheels."""
        return int(self.vehicle.wheel_matrix.shape[1])

    @cached_property
    def matrices(self) -> tuple[NDArray[np.float64], ...]:
        """``A (2n, 2n)``, ``B (2n, n_wheel)``, ``C (n_out, 2n)``, ``D (n_out, n_wheel)``.

        Outputs: the ``n`` DOF displacements (m, rad), the ``n`` DOF accelerations
        (m/s^2, rad/s^2), the ``n_wheel`` contact forces (N), per metre of input.
        """
        v = self.vehicle
        n, kh = self.n_dof, self.contact_stiffness
        w = v.wheel_matrix
        m_inv = np.linalg.inv(v.mass_matrix)
        k = v.stiffness_matrix + kh * w @ w.T
        a = np.block([[np.zeros((n, n)), np.eye(n)], [-m_inv @ k, -m_inv @ v.damping_matrix]])
        b = np.vstack([np.zeros((n, w.shape[1])), kh * m_inv @ w])
        c = np.vstack(
            [
                np.hstack([np.eye(n), np.zeros((n, n))]),
                a[n:],
                np.hstack([kh * w.T, np.zeros((w.shape[1], n))]),
            ]
        )
        d = np.vstack([np.zeros((n, w.shape[1])), b[n:], -kh * np.eye(w.shape[1])])
        return a, b, c, d

    @cached_property
    def modes(
        self,
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]]:
        """``lambda (2n,)`` in 1/s, ``V^-1 B (2n, n_wheel)`` and ``C V (n_out, 2n)``.

        Raises
        ------
        CaseError
            The system has no complete set of modes (a defective ``A``): not met by a
            vehicle with positive masses and stiffnesses.
        """
        a, b, c, _ = self.matrices
        lam, vec = np.linalg.eig(a)
        vinv = np.linalg.inv(vec)
        residual = np.linalg.norm(vec @ np.diag(lam) @ vinv - a) / np.linalg.norm(a)
        if not residual < MODAL_RESIDUAL:
            raise CaseError(
                "vehicle",
                f"modal residual {residual:.2g}",
                "a vehicle with a complete set of modes",
            )
        return lam.astype(complex), (vinv @ b).astype(complex), (c @ vec).astype(complex)

    @property
    def slowest_mode_hz(self) -> float:
        """Natural frequency ``|lambda| / (2 pi)`` of the slowest mode, Hz."""
        return float(np.min(np.abs(self.modes[0]))) / (2.0 * np.pi)
