"""The vehicle on the finite track through Hertz springs: global matrices and FRFs.

Global DOFs are the vehicle's (first) followed by the finite track's. With the
contact gap ``g = G u - r`` (``G u = u_wheel - u_rail`` at each contact, ``r`` the
irregularity, positive a dip) the contact forces are ``P = k_H g`` (compressive
positive) and the equations of motion read

    M u'' + C u' + (K + k_H G^T G) u = k_H G^T r(t).

The frequency-domain reference solves this sparse system directly at each
frequency with ``r_j = exp(-i omega t_j)`` (unit irregularity, delayed by
``t_j = s_j / v`` at wheel ``j``); no receptance condensation is used.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray
from scipy.sparse.linalg import splu

from railvib.coupling import CoupledSystem  # the system description only, not its solver
from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.response import FRF
from railvib.track.ballasted import BallastedTrack  # its layers only, not its solver
from railvib.track.periodic import PeriodicTrack, Rail  # the parameter records only, not the solver
from railvib.track.slab import FloatingSlabTrack, SlabTrack, UnitSlabTrack  # parameters only
from railvib.validation._legacy import SYSTEM_FROM_BUNDLE, bundle_form, warn_deprecated
from railvib.validation.finite_slab import FiniteSlabTrack
from railvib.validation.finite_track import FiniteTrack
from railvib.validation.maxwell import padded
from railvib.vehicle.assembly import Vehicle

__all__ = ["FiniteCoupledSystem", "FiniteFRF", "finite_track_frf"]


#: responses of the finite model (one container for every solver; kept under its old name)
FiniteFRF = FRF


@dataclass(frozen=True, eq=False)
class FiniteCoupledSystem:
    """Vehicle standing on a :class:`FiniteTrack`, the irregularity moving under it.

    Parameters
    ----------
    vehicle : Vehicle
        Pitch-plane vehicle, wheels front to back.
    track : FiniteTrack or FiniteSlabTrack
        Finite track with nodes at the wheel positions (a rail on pads, on sleepers and
        ballast, or on a slab: every layer as explicit DOFs).
    contact_stiffness : float
        Linear Hertz stiffness k_H per contact, N/m (> 0).
    leading_wheel_position : float
        Position of the leading wheel along the rail, m (sleepers at ``n d``).
    speed : float
        Speed at which the irregularity passes, m/s (> 0).
    """

    vehicle: Vehicle
    track: FiniteTrack | FiniteSlabTrack
    contact_stiffness: float
    leading_wheel_position: float
    speed: float

    def __post_init__(self) -> None:
        if not (np.isfinite(self.contact_stiffness) and self.contact_stiffness > 0):
            raise CaseError("contact.stiffness", self.contact_stiffness, "must be > 0 (N/m)")
        if not (np.isfinite(self.speed) and self.speed > 0):
            raise CaseError("speed", self.speed, "must be > 0 (m/s)")
        self.track.w_dof(self.wheel_positions)  # raises if a wheel is not a node

    @classmethod
    def from_system(
        cls,
        system: CoupledSystem,
        *,
        margin_spans: int = 60,
        elements_per_span: int = 8,
        absorber_spans: int = 0,
        absorber_damping: float = 0.0,
    ) -> FiniteCoupledSystem:
        """The finite-track counterpart of the symplectic path's system description.

        Only the parameters of `system` are read (vehicle; rail, pad, sleeper spacing
        and pad temperature of ``system.track``, a ballasted track's sleeper, ballast,
        ballast mass and subgrade, which become explicit DOFs, a slab track's slab,
        foundation or bearings and joints, which become a beam of its own on springs
        (:class:`~railvib.validation.finite_slab.FiniteSlabTrack`); contact stiffness,
        leading wheel position and speed); nothing of the periodic-track solver is called.

        Parameters
        ----------
        system : CoupledSystem
            Vehicle on the periodic track: k_H in N/m, leading wheel position in m
            (sleepers at ``n d``), speed in m/s.
        margin_spans : int
            Bays of finite track beyond the outermost wheels on each side.
        elements_per_span : int
            Hermite elements per bay (8: 1.7e-5 relative receptance error at 1 kHz).
        absorber_spans : int
            Bays with graded extra pad damping at each end, inside the margins.
        absorber_damping : float
            Extra pad damping at the outermost sleepers, N s/m.

        Returns
        -------
        FiniteCoupledSystem
        """
        track = system.track
        if isinstance(track, SlabTrack):
            x = system.leading_wheel_position - system.vehicle.wheel_offsets
            finite = _finite_slab(
                track, x, margin_spans, elements_per_span, absorber_spans, absorber_damping
            )
            return cls(
                system.vehicle,
                finite,
                system.contact_stiffness,
                system.leading_wheel_position,
                system.speed,
            )
        return _finite_system(
            system.vehicle,
            track.rail,
            track.pad,
            track.sleeper_spacing,
            system.contact_stiffness,
            system.leading_wheel_position,
            system.speed,
            margin_spans=margin_spans,
            elements_per_span=elements_per_span,
            absorber_spans=absorber_spans,
            absorber_damping=absorber_damping,
            pad_temperature=track.pad_temperature,
            **_layers(track),
        )

    @classmethod
    def build(cls, *bundle: Any, **mesh: Any) -> FiniteCoupledSystem:
        """Deprecated: use :meth:`from_system` with a :class:`~railvib.coupling.CoupledSystem`.

        The old form ``build(vehicle, rail, pad, sleeper_spacing, contact_stiffness,
        leading_wheel_position, speed, *, margin_spans=60, elements_per_span=8,
        absorber_spans=0, absorber_damping=0.0, pad_temperature=None)``, unchanged.
        """
        warn_deprecated(
            "FiniteCoupledSystem.build(vehicle, rail, pad, sleeper_spacing, ...)",
            f"FiniteCoupledSystem.from_system(system, ...) with {SYSTEM_FROM_BUNDLE}",
        )
        return _finite_system(*bundle, **mesh)

    @property
    def wheel_positions(self) -> NDArray[np.float64]:
        """Contact positions along the rail, m."""
        return self.leading_wheel_position - self.vehicle.wheel_offsets

    @property
    def delays(self) -> NDArray[np.float64]:
        """Input delay at each wheel, ``s_j / v`` in s."""
        return self.vehicle.wheel_offsets / self.speed

    @property
    def n_vehicle(self) -> int:
        """Number of vehicle DOFs."""
        return len(self.vehicle.dofs)

    @property
    def n_dof(self) -> int:
        """Total number of DOFs (vehicle + track)."""
        return self.n_vehicle + self.track.n_dof

    @cached_property
    def rail_dofs(self) -> NDArray[np.intp]:
        """Global DOF index of the rail displacement under each wheel."""
        return self.n_vehicle + self.track.w_dof(self.wheel_positions)

    @cached_property
    def contact_matrix(self) -> sp.csr_matrix:
        """``G`` (n_wheel, n_dof): ``G u = u_wheel - u_rail`` at each contact (m)."""
        b = self.vehicle.wheel_matrix
        n_wheel = b.shape[1]
        g = np.zeros((n_wheel, self.n_vehicle))
        g[:, :] = b.T
        vehicle_part = sp.csr_matrix(g)
        rail_part = sp.csr_matrix(
            (-np.ones(n_wheel), (np.arange(n_wheel), self.rail_dofs - self.n_vehicle)),
            shape=(n_wheel, self.track.n_dof),
        )
        return sp.hstack([vehicle_part, rail_part], format="csr")

    @cached_property
    def _contact_stiffness_matrix(self) -> sp.csc_matrix:
        g = self.contact_matrix
        return (self.contact_stiffness * (g.T @ g)).tocsc()

    def _vehicle_block(self, matrix: NDArray[np.float64]) -> sp.csc_matrix:
        return sp.block_diag(
            [sp.csc_matrix(matrix), sp.csc_matrix((self.track.n_dof, self.track.n_dof))],
            format="csc",
        )

    def time_domain_matrices(self) -> tuple[sp.csc_matrix, sp.csc_matrix, sp.csc_matrix]:
        """Global real ``(M, C, K)`` (kg, N s/m, N/m), contact springs included in K.

        Square of :attr:`n_dof` plus the internal DOFs of the track's generalised Maxwell
        layers (:mod:`railvib.validation.maxwell`), which come last.

        Raises
        ------
        CaseError
            The vehicle has frequency-dependent suspension elements (no ``M, C, K`` form).
        """
        m_t, c_t, k_t = self.track.time_domain_matrices()
        v = self.vehicle
        if v.elements:
            raise CaseError(
                "vehicle.suspensions",
                "<a frequency-dependent element>",
                "springs and viscous dampers only in the time-domain reference (Newmark)",
            )
        m = sp.block_diag([sp.csc_matrix(v.mass_matrix), m_t], format="csc")
        c = sp.block_diag([sp.csc_matrix(v.damping_matrix), c_t], format="csc")
        k = sp.block_diag([sp.csc_matrix(v.stiffness_matrix), k_t], format="csc")
        # the track's internal DOFs (Maxwell branches of its layers) follow its own n_dof
        return m, c, (k + padded(self._contact_stiffness_matrix, k.shape[0])).tocsc()

    def force_matrix(self) -> sp.csc_matrix:
        """``k_H G^T`` (n_dof, n_wheel): global force per unit irregularity at each wheel, N/m."""
        return (self.contact_stiffness * self.contact_matrix.T).tocsc()

    def frf(self, f: ArrayLike, progress: Callable[[int], None] | None = None) -> FiniteFRF:
        """Responses to a unit irregularity delayed at each wheel, by direct sparse solves.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz (> 0).
        progress : callable, optional
            Called with 1 after each frequency is solved (one sparse LU each).

        Returns
        -------
        FiniteFRF
        """
        f = np.atleast_1d(np.asarray(f, dtype=float))
        v = self.vehicle
        nv = self.n_vehicle
        static = (self._vehicle_block(v.stiffness_matrix) + self._contact_stiffness_matrix).astype(
            complex
        )
        damping = self._vehicle_block(v.damping_matrix)
        mass = self._vehicle_block(v.mass_matrix)
        elements = [(e.stiffness(f), sp.csc_matrix(np.outer(b, b))) for e, b in v.elements]
        force = self.force_matrix().toarray()
        g = self.contact_matrix
        n_wheel = g.shape[0]
        out_v = np.empty((f.size, nv), dtype=complex)
        out_r = np.empty((f.size, n_wheel), dtype=complex)
        out_p = np.empty((f.size, n_wheel), dtype=complex)
        for k, fk in enumerate(f):
            omega = 2.0 * np.pi * fk
            r = np.exp(-1j * omega * self.delays)
            track = sp.block_diag(
                [sp.csc_matrix((nv, nv)), self.track.dynamic_stiffness(fk)], format="csc"
            )
            system = static + 1j * omega * damping - omega**2 * mass + track
            for k_e, pattern in elements:  # frequency-dependent suspension elements
                system = system + k_e[k] * self._vehicle_block(pattern.toarray())
            system = system.tocsc()
            u = splu(system).solve(force @ r)
            out_v[k] = u[:nv]
            out_r[k] = u[self.rail_dofs]
            out_p[k] = self.contact_stiffness * (g @ u - r)
            if progress is not None:
                progress(1)
        return FRF(
            f=f,
            vehicle=out_v,
            rail=out_r,
            contact_force=out_p,
            dofs=v.dofs,
            wheels=v.wheel_names,
        )


def _finite_system(
    vehicle: Vehicle,
    rail: Rail,
    pad: PadModel,
    sleeper_spacing: float,
    contact_stiffness: float,
    leading_wheel_position: float,
    speed: float,
    *,
    margin_spans: int = 60,
    elements_per_span: int = 8,
    absorber_spans: int = 0,
    absorber_damping: float = 0.0,
    pad_temperature: float | None = None,
    **layers: Any,
) -> FiniteCoupledSystem:
    """The finite track around the wheels with the vehicle coupled to it (no warning).

    `layers` are a ballasted track's (``ballast``, ``sleeper_mass``, ``subgrade``,
    ``ballast_mass``: :class:`~railvib.validation.FiniteTrack`); none for a rigid base.
    """
    x = leading_wheel_position - vehicle.wheel_offsets
    track = FiniteTrack.around(
        x,
        rail,
        pad,
        sleeper_spacing,
        margin_spans=margin_spans,
        elements_per_span=elements_per_span,
        absorber_spans=absorber_spans,
        absorber_damping=absorber_damping,
        pad_temperature=pad_temperature,
        **layers,
    )
    return FiniteCoupledSystem(vehicle, track, contact_stiffness, leading_wheel_position, speed)


def _finite_slab(
    track: SlabTrack,
    positions: NDArray[np.float64],
    margin_spans: int,
    elements_per_span: int,
    absorber_spans: int,
    absorber_damping: float,
) -> FiniteSlabTrack:
    """The finite slab track of `track`'s parameters around `positions` (m).

    The rail and slab run `margin_spans` fastener spacings beyond the outermost positions;
    the absorbers fill `absorber_spans` spacings at each end, the slab's dashpots
    `absorber_damping` times the slab's mass per length over the rail's (N s/m): the same
    decay per wavelength for the heavier beam (floating_slab_metro, 240 spacings of margin
    with 200 absorbing at 2e5 N s/m: 1.3e-1 at 1 kHz with the rail's dashpots under the
    slab, 5.4e-3 with the slab's).
    """
    d = track.sleeper_spacing
    unit: dict[str, Any] = {}
    if isinstance(track, UnitSlabTrack):
        unit = {
            "slab_length": track.slab_length,
            "fasteners_per_slab": track.fasteners_per_slab,
            "joint_shear_stiffness": track.joint_shear_stiffness,
            "joint_bending_stiffness": track.joint_bending_stiffness,
        }
    elif isinstance(track, FloatingSlabTrack):
        unit = {"bearing_spacing_fasteners": track.bearing_spacing_fasteners}
    return FiniteSlabTrack(
        track.rail,
        track.pad,
        d,
        track.slab_bending_stiffness,
        track.slab_mass_per_length,
        track.slab_loss_factor,
        x_min=(np.floor(positions.min() / d) - margin_spans) * d,
        x_max=(np.ceil(positions.max() / d) + margin_spans) * d,
        foundation=track.foundation,
        bearing=track.bearing,
        elements_per_span=elements_per_span,
        nodes_at=tuple(float(v) for v in positions),
        absorber_length=absorber_spans * d,
        absorber_damping=absorber_damping,
        slab_absorber_damping=absorber_damping * _slab_to_rail_mass(track),
        pad_temperature=track.pad_temperature,
        slab_damping_time=track.slab_damping_time,
        **unit,
    )


def _slab_to_rail_mass(track: SlabTrack) -> float:
    """Slab mass per length over the rail's (-)."""
    return track.slab_mass_per_length / track.rail.mass_per_length


def _layers(track: PeriodicTrack) -> dict[str, Any]:
    """The layers under the pads of a ballasted track, as :class:`FiniteTrack` takes them."""
    if not isinstance(track, BallastedTrack):
        return {}
    return {
        "ballast": track.ballast,
        "sleeper_mass": track.sleeper_mass,
        "subgrade": track.subgrade,
        "ballast_mass": track.ballast_mass or 0.0,
    }


def _finite_track_frf_bundle(*bundle: Any, **options: Any) -> FRF:
    """The deprecated form ``finite_track_frf(vehicle, rail, pad, d, k_H, x0, v, f, ...)``."""
    *system, f = bundle
    return _finite_system(*system, **options).frf(f)


@bundle_form(
    _finite_track_frf_bundle,
    "finite_track_frf(vehicle, rail, pad, sleeper_spacing, contact_stiffness, "
    "leading_wheel_position, speed, f, ...)",
    f"finite_track_frf(system, f, ...) with {SYSTEM_FROM_BUNDLE}",
)
def finite_track_frf(
    system: CoupledSystem,
    f: ArrayLike,
    *,
    margin_spans: int = 60,
    elements_per_span: int = 8,
) -> FRF:
    """FRFs of the vehicle on a long finite track (independent of the symplectic solver).

    The deprecated form ``finite_track_frf(vehicle, rail, pad, sleeper_spacing,
    contact_stiffness, leading_wheel_position, speed, f, *, margin_spans,
    elements_per_span, pad_temperature)`` still works and warns.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle on the periodic track (its parameters only; see
        :meth:`FiniteCoupledSystem.from_system`).
    f : array_like
        Frequencies in Hz.
    margin_spans : int
        Bays of track beyond the outermost wheels on each side.
    elements_per_span : int
        Hermite elements per bay (8: 1.7e-5 relative receptance error at 1 kHz).

    Returns
    -------
    FRF
        Per metre of irregularity: vehicle DOFs (m/m, rad/m for pitch), rail under each
        wheel (m/m) and contact forces (N/m).
    """
    finite = FiniteCoupledSystem.from_system(
        system, margin_spans=margin_spans, elements_per_span=elements_per_span
    )
    return finite.frf(f)
