"""Assemble mass, stiffness and damping matrices of a vehicle from its parts."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

__all__ = ["Vehicle", "WheelCondensation"]

GRAVITY = 9.81  # m/s^2


@dataclass(frozen=True, eq=False)
class WheelCondensation:
    """A vehicle's dynamic stiffness condensed onto its wheel DOFs.

    Attributes
    ----------
    stiffness : numpy.ndarray
        ``(n_freq, n_wheel, n_wheel)``, N/m: wheel forces per wheel displacement with
        the bodies free.
    recovery : numpy.ndarray
        ``(n_freq, n_dof, n_wheel)``: all DOF displacements per wheel displacement.
    """

    stiffness: NDArray[np.complex128]
    recovery: NDArray[np.complex128]


@dataclass(frozen=True)
class Vehicle:
    """A pitch-plane multibody vehicle: bodies, suspensions and wheels, with named DOFs.

    Displacements are positive downward; a pitch rotation ``theta`` moves a point
    at longitudinal position ``x`` (relative to the body's centre) by ``x theta``.

    Parameters
    ----------
    bodies : tuple of RigidBody
        All bodies; wheelsets are bodies without a pitch DOF.
    suspensions : tuple of Suspension
        Spring-damper connections between body points.
    wheels : tuple of Wheel
        Contacts, listed from the leading wheel backwards, one per wheelset body
        (a body without a pitch DOF).
    """

    bodies: tuple[RigidBody, ...]
    suspensions: tuple[Suspension, ...]
    wheels: tuple[Wheel, ...]

    def __post_init__(self) -> None:
        names = [b.name for b in self.bodies]
        if len(set(names)) != len(names):
            raise CaseError("vehicle.bodies", names, "body names must be unique")
        for s in self.suspensions:
            for a in (s.upper, s.lower):
                if a.body not in names:
                    raise CaseError(f"vehicle.{s.name}", a.body, f"a body among {names}")
        xs = [w.x for w in self.wheels]
        if not self.wheels or any(np.diff(xs) >= 0):
            raise CaseError("vehicle.wheels", xs, "at least one wheel, listed front to back")
        for w in self.wheels:
            if w.body not in names:
                raise CaseError("vehicle.wheels", w.body, f"a body among {names}")
            if self._body(w.body).pitch_inertia is not None:
                raise CaseError("vehicle.wheels", w.body, "a body without a pitch DOF (a wheelset)")
        carriers = [w.body for w in self.wheels]
        if len(set(carriers)) != len(carriers):
            raise CaseError("vehicle.wheels", carriers, "one wheel per wheelset body")

    @cached_property
    def dofs(self) -> tuple[str, ...]:
        """DOF labels in matrix order."""
        return tuple(dof for body in self.bodies for dof in body.dofs)

    def _body(self, name: str) -> RigidBody:
        return next(b for b in self.bodies if b.name == name)

    def point_vector(self, point: Attachment) -> NDArray[np.float64]:
        """Row vector mapping the DOFs to the vertical displacement of `point`."""
        body = self._body(point.body)
        vec = np.zeros(len(self.dofs))
        vec[self.dofs.index(f"{body.name}.bounce")] = 1.0
        if body.pitch_inertia is not None:
            vec[self.dofs.index(f"{body.name}.pitch")] = point.x - body.x
        return vec

    @cached_property
    def mass_matrix(self) -> NDArray[np.float64]:
        """Mass matrix in kg and kg m^2, ``(n_dof, n_dof)``."""
        diag = []
        for b in self.bodies:
            diag.append(b.mass)
            if b.pitch_inertia is not None:
                diag.append(b.pitch_inertia)
        return np.diag(diag)

    def _spring_matrix(self, attr: str) -> NDArray[np.float64]:
        n = len(self.dofs)
        out = np.zeros((n, n))
        for s in self.suspensions:
            b = self.point_vector(s.upper) - self.point_vector(s.lower)
            out += getattr(s, attr) * np.outer(b, b)
        return out

    @cached_property
    def stiffness_matrix(self) -> NDArray[np.float64]:
        """Stiffness matrix (N/m, N, N m), ``(n_dof, n_dof)``."""
        return self._spring_matrix("stiffness")

    @cached_property
    def damping_matrix(self) -> NDArray[np.float64]:
        """Viscous damping matrix (N s/m, ...), ``(n_dof, n_dof)``."""
        return self._spring_matrix("damping")

    @cached_property
    def wheel_matrix(self) -> NDArray[np.float64]:
        """``B``, ``(n_dof, n_wheel)``: column j maps a force at wheel j onto the DOFs."""
        return np.stack([self.point_vector(Attachment(w.body, w.x)) for w in self.wheels], axis=1)

    @cached_property
    def wheel_offsets(self) -> NDArray[np.float64]:
        """Distance of each wheel behind the leading wheel, m (first is 0)."""
        xs = np.array([w.x for w in self.wheels])
        return xs[0] - xs

    def dynamic_stiffness(self, f: ArrayLike) -> NDArray[np.complex128]:
        """``K + i omega C - omega^2 M`` stacked over frequency, ``(n_freq, n_dof, n_dof)``.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, shape ``(n_freq,)`` (a scalar counts as one).

        Returns
        -------
        numpy.ndarray
            Complex dynamic stiffness in SI units (N/m, N/rad, N m/m, N m/rad by DOF pair),
            shape ``(n_freq, n_dof, n_dof)``.
        """
        return _dynamic_stiffness(f, self.mass_matrix, self.damping_matrix, self.stiffness_matrix)

    @cached_property
    def wheel_dofs(self) -> NDArray[np.int64]:
        """Index of the bounce DOF of each wheel's wheelset (``B`` is a selection)."""
        return np.array([self.dofs.index(f"{w.body}.bounce") for w in self.wheels])

    def condensed_to_wheels(self, f: ArrayLike) -> WheelCondensation:
        """Dynamic stiffness condensed onto the wheel DOFs, with the body recovery.

        With the DOFs split into bodies ``b`` and wheels ``w``,
        ``S = D_ww - D_wb D_bb^-1 D_bw`` and ``u = R u_w`` with ``R_b = -D_bb^-1 D_bw``.
        ``D_bb`` (the vehicle with its wheels held) is regular at every ``f > 0`` and at
        ``f = 0``, so no digits are lost at low frequency.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Returns
        -------
        WheelCondensation
        """
        order = self._body_then_wheel_order
        n_dof, n_w = int(order.size), int(self.wheel_dofs.size)
        n_b = n_dof - n_w
        m, c, k = (a[np.ix_(order, order)] for a in self._matrices)

        def block(rows: slice, cols: slice) -> NDArray[np.complex128]:
            return _dynamic_stiffness(f, m[rows, cols], c[rows, cols], k[rows, cols])

        bodies, wheels = slice(0, n_b), slice(n_b, n_dof)
        x = np.linalg.solve(block(bodies, bodies), block(bodies, wheels))  # D_bb^-1 D_bw
        stiffness = block(wheels, wheels) - block(wheels, bodies) @ x
        recovery = np.empty((int(x.shape[0]), n_dof, n_w), dtype=np.complex128)
        recovery[:, order[:n_b], :] = -x
        recovery[:, order[n_b:], :] = np.eye(n_w)
        return WheelCondensation(
            stiffness=np.asarray(stiffness, dtype=np.complex128), recovery=recovery
        )

    @cached_property
    def _body_then_wheel_order(self) -> NDArray[np.int64]:
        """DOF indices reordered: sprung-body DOFs first, then the wheel DOFs in wheel order."""
        w = self.wheel_dofs
        return np.concatenate([np.setdiff1d(np.arange(len(self.dofs)), w), w])

    @property
    def _matrices(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        return self.mass_matrix, self.damping_matrix, self.stiffness_matrix

    def static_wheel_loads(self, gravity: float = GRAVITY) -> NDArray[np.float64]:
        """Static load carried at each wheel contact (N), wheels held rigidly.

        Solves the static equilibrium of the sprung bodies with the wheel points
        fixed; the contact reactions then balance the weight of everything.

        Parameters
        ----------
        gravity : float
            Gravitational acceleration in m/s^2 (default 9.81).

        Returns
        -------
        numpy.ndarray
            Contact load at each wheel in N, wheels front to back, shape ``(n_wheel,)``.
        """
        b = self.wheel_matrix
        weight = np.zeros(len(self.dofs))
        for body in self.bodies:
            weight[self.dofs.index(f"{body.name}.bounce")] = body.mass * gravity
        # Solve min over u of the energy with B^T u = 0 (wheels fixed): KKT system
        k = self.stiffness_matrix
        n, m = b.shape
        kkt = np.block([[k, b], [b.T, np.zeros((m, m))]])
        sol = np.linalg.solve(kkt, np.concatenate([weight, np.zeros(m)]))
        return sol[n:]


def _dynamic_stiffness(
    f: ArrayLike, m: NDArray[np.float64], c: NDArray[np.float64], k: NDArray[np.float64]
) -> NDArray[np.complex128]:
    """``K + i omega C - omega^2 M`` for (blocks of) real matrices, ``(n_freq, rows, cols)``."""
    omega = 2.0 * np.pi * np.atleast_1d(np.asarray(f, dtype=float))[:, None, None]
    out = np.empty((int(omega.shape[0]),) + k.shape, dtype=np.complex128)
    out.real = k - omega**2 * m
    out.imag = omega * c
    return out
