"""A long but finite slab track: rail and slab beams of Hermite elements, pads between them.

The independent reference for the slab tracks' cell solver (:mod:`railvib.track.cells`):
it shares nothing with :mod:`railvib.track` but the parameter objects (`Rail`, the pad
models). The rail and the slab are Euler-Bernoulli beams discretised with cubic Hermite
elements (consistent mass), each with its own DOFs; a continuous foundation is the
consistent Winkler matrix of the slab elements (``k_f`` times the mass matrix of a unit
mass per length), discrete bearings are springs from slab nodes to the ground, each
railpad a spring between the rail node and the slab node at its fastener. Unit slabs are
separate beams, each with its own end nodes; a joint is a shear and a bending spring
between the ends of two neighbouring slabs. The rail's and slabs' outer ends are free;
graded dashpots to the ground under the rail and the slab at the fasteners near both
ends swallow the waves that reach them.

Geometry, as the periodic models define it: fasteners at ``x = n d``; a floating slab's
bearings under the fasteners ``n`` divisible by `bearing_spacing_fasteners`; unit slab
``k`` spans ``[k L_s, (k + 1) L_s]`` with its ``n`` fasteners at ``k L_s + x_0 + j d``,
``x_0 = (L_s - (n - 1) d) / 2``, and bearings (if any) under each of them.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PadModel
from railvib.track.periodic import Rail
from railvib.validation.finite_track import hermite_element_matrices
from railvib.validation.maxwell import Branches, branch_matrices, layer_branches, padded
from railvib.validation.scope import check_rail, viscous_layer

__all__ = ["FiniteSlabTrack"]

#: positions closer than this (m) are one node
_MERGE = 1e-9


@dataclass(frozen=True)
class FiniteSlabTrack:
    """A finite rail on pads on a continuous slab or on unit slabs, over ``[x_min, x_max]``.

    Parameters
    ----------
    rail : Rail
        The rail beam (Euler-Bernoulli: EI in N m^2, m in kg/m, loss factor).
    pad : PadModel
        Railpad, complex stiffness per fastener, N/m.
    fastener_spacing : float
        d in m.
    slab_bending_stiffness, slab_mass_per_length, slab_loss_factor : float
        EI_s (N m^2), m_s (kg/m) and eta_s of the slab beam.
    x_min, x_max : float
        Ends of the rail (and of the slab), m.
    foundation : PadModel, optional
        Continuous foundation per metre of slab, N/m^2.
    bearing : PadModel, optional
        Discrete bearing, N/m.
    bearing_spacing_fasteners : int
        Continuous slab: a bearing under every this many fasteners.
    slab_length : float, optional
        Unit slabs of this length in m; None: one continuous slab.
    fasteners_per_slab : int
        Fasteners per unit slab.
    joint_shear_stiffness, joint_bending_stiffness : float, optional
        Joint springs between unit slabs, N/m and N m/rad; both None: free joints.
    elements_per_span : int
        Hermite elements per fastener spacing (a shorter interval gets proportionally fewer).
    nodes_at : tuple of float
        Rail positions in m that must be nodes (loads, observation points).
    absorber_length : float
        Length in m at each end with graded dashpots under the rail and the slab.
    absorber_damping : float
        The dashpots' damping at the outermost fastener, N s/m; it grows quadratically
        from 0 at the inner edge of each absorber.
    slab_absorber_damping : float, optional
        The slab's dashpots there, N s/m; None: `absorber_damping` (a slab far heavier than
        the rail needs proportionally more to damp its waves as fast).
    pad_temperature : float, optional
        Temperature in degC passed to the pad, foundation and bearing models.
    slab_damping_time : float
        Viscous (Kelvin-Voigt) slab damping tau_s in s: ``EI_s (1 + i eta_s + i omega
        tau_s)``, the time-domain model's stand-in for a loss factor.
    """

    rail: Rail
    pad: PadModel
    fastener_spacing: float
    slab_bending_stiffness: float
    slab_mass_per_length: float
    slab_loss_factor: float
    x_min: float
    x_max: float
    foundation: PadModel | None = None
    bearing: PadModel | None = None
    bearing_spacing_fasteners: int = 1
    slab_length: float | None = None
    fasteners_per_slab: int = 0
    joint_shear_stiffness: float | None = None
    joint_bending_stiffness: float | None = None
    elements_per_span: int = 16
    nodes_at: tuple[float, ...] = ()
    absorber_length: float = 0.0
    absorber_damping: float = 0.0
    pad_temperature: float | None = None
    slab_absorber_damping: float | None = None
    slab_damping_time: float = 0.0

    def __post_init__(self) -> None:
        if self.rail.is_timoshenko:
            raise CaseError("track.rail.shear_stiffness", self.rail.shear_stiffness, "omitted")
        if not self.x_max > self.x_min:
            raise CaseError("finite_slab.x_max", self.x_max, "> x_min (m)")
        if (self.foundation is None) == (self.bearing is None):
            raise CaseError("finite_slab.foundation", self.foundation, "exactly one of it, bearing")
        for x in self.nodes_at:
            if not self.x_min <= x <= self.x_max:
                raise CaseError("finite_slab.nodes_at", x, "inside [x_min, x_max] (m)")

    # -- geometry -----------------------------------------------------------------------------
    @cached_property
    def fasteners(self) -> NDArray[np.float64]:
        """Fastener positions in m, increasing."""
        d = self.fastener_spacing
        if self.slab_length is None:
            k = np.arange(np.ceil(self.x_min / d - 1e-9), np.floor(self.x_max / d + 1e-9) + 1)
            return np.asarray(k * d, dtype=np.float64)
        ls, n = self.slab_length, int(self.fasteners_per_slab)
        first = (ls - (n - 1) * d) / 2.0
        slabs = np.arange(np.floor(self.x_min / ls) - 1, np.ceil(self.x_max / ls) + 1)
        x = (slabs[:, None] * ls + first + d * np.arange(n)[None, :]).ravel()
        return x[(x >= self.x_min - _MERGE) & (x <= self.x_max + _MERGE)]

    @cached_property
    def slabs(self) -> list[tuple[float, float]]:
        """``(start, end)`` of each slab beam in m, left to right."""
        if self.slab_length is None:
            return [(self.x_min, self.x_max)]
        ls = self.slab_length
        k = np.arange(np.floor(self.x_min / ls + 1e-9), np.ceil(self.x_max / ls - 1e-9))
        return [(max(self.x_min, a * ls), min(self.x_max, (a + 1) * ls)) for a in k]

    def _mesh(self, a: float, b: float) -> NDArray[np.float64]:
        """Nodes over ``[a, b]``: breaks at fasteners and `nodes_at`, then subdivided."""
        pts = np.concatenate([[a, b], self.fasteners, np.asarray(self.nodes_at, dtype=float)])
        pts = np.unique(pts[(pts >= a - _MERGE) & (pts <= b + _MERGE)].clip(a, b))
        pts = pts[np.concatenate([[True], np.diff(pts) > _MERGE])]
        out = []
        for lo, hi in zip(pts[:-1], pts[1:], strict=True):
            n_el = max(
                1, int(np.ceil(self.elements_per_span * (hi - lo) / self.fastener_spacing - 1e-9))
            )
            out.append(np.linspace(lo, hi, n_el + 1)[:-1])
        out.append(np.array([b]))
        return np.concatenate(out)

    @cached_property
    def rail_nodes(self) -> NDArray[np.float64]:
        """Rail node positions in m."""
        return self._mesh(self.x_min, self.x_max)

    @cached_property
    def slab_nodes(self) -> list[NDArray[np.float64]]:
        """Node positions in m of each slab beam."""
        return [self._mesh(a, b) for a, b in self.slabs]

    @cached_property
    def _slab_offsets(self) -> list[int]:
        """First node number of each slab (after the rail's nodes)."""
        out, n = [], self.rail_nodes.size
        for nodes in self.slab_nodes:
            out.append(n)
            n += nodes.size
        return out

    @property
    def n_dof(self) -> int:
        """Number of DOFs: w and theta at every rail and slab node."""
        return 2 * (self.rail_nodes.size + sum(x.size for x in self.slab_nodes))

    def w_dof(self, x: ArrayLike) -> NDArray[np.intp]:
        """DOF of the rail displacement at each position `x` (m), as :meth:`rail_dof`."""
        return self.rail_dof(x)

    def rail_dof(self, x: ArrayLike) -> NDArray[np.intp]:
        """DOF of the rail displacement at each position `x` (m; each must be a node)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        idx = np.array([int(np.argmin(np.abs(self.rail_nodes - v))) for v in x])
        if np.any(np.abs(self.rail_nodes[idx] - x) > 1e-6):
            raise CaseError("finite_slab.position", list(x), "positions listed in nodes_at (m)")
        return 2 * idx

    def _slab_node(self, x: float) -> int:
        """Node number of the slab under the rail position `x` (m)."""
        for (a, b), nodes, first in zip(
            self.slabs, self.slab_nodes, self._slab_offsets, strict=True
        ):
            if a - _MERGE <= x <= b + _MERGE:
                return first + int(np.argmin(np.abs(nodes - x)))
        raise CaseError("finite_slab.position", x, "on a slab (m)")

    # -- matrices -----------------------------------------------------------------------------
    def _beam(self, nodes: NDArray[np.float64], first: int, ei: float, m: float) -> tuple:
        """Triplets of the stiffness and mass matrices of one beam's elements."""
        k, mm = hermite_element_matrices(np.diff(nodes), ei, m)
        dofs = 2 * (first + np.arange(nodes.size - 1))[:, None] + np.arange(4)[None, :]
        rows = np.broadcast_to(dofs[:, :, None], k.shape).ravel()
        cols = np.broadcast_to(dofs[:, None, :], k.shape).ravel()
        return rows, cols, k.ravel(), mm.ravel()

    def _sparse(self, rows: list, cols: list, vals: list) -> sp.csc_matrix:
        n = self.n_dof
        if not rows:
            return sp.csc_matrix((n, n))
        return sp.csc_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)
        )

    @cached_property
    def _matrices(self) -> dict[str, sp.csc_matrix]:
        """Frequency-independent parts of the dynamic stiffness, as sparse matrices.

        ``k_rail``, ``mass_rail``: the rail's; ``k_slab``: the slabs' (real EI_s);
        ``mass_slab``: the slabs' for a unit mass per length (times ``m_s``, and, as the
        consistent Winkler matrix, times ``k_f``); ``pads``, ``bearings``: unit springs;
        ``joints``: the joint springs; ``absorber``: the dashpots (times ``i omega``).
        """
        r, c, k, m = self._beam(
            self.rail_nodes, 0, self.rail.bending_stiffness, self.rail.mass_per_length
        )
        parts: dict[str, list[list]] = {
            name: [[], [], []]
            for name in ("k_slab", "mass_slab", "pads", "bearings", "joints", "absorber")
        }
        for nodes, first in zip(self.slab_nodes, self._slab_offsets, strict=True):
            rs, cs, ks, ms = self._beam(nodes, first, self.slab_bending_stiffness, 1.0)
            for name, vals in (("k_slab", ks), ("mass_slab", ms)):
                parts[name][0].append(rs)
                parts[name][1].append(cs)
                parts[name][2].append(vals)

        def spring(name: str, i: int, j: int | None, value: float) -> None:
            rows, cols, vals = parts[name]
            rows.append(np.array([i]))
            cols.append(np.array([i]))
            vals.append(np.array([value]))
            if j is not None:
                rows.append(np.array([j, i, j]))
                cols.append(np.array([j, j, i]))
                vals.append(np.array([value, -value, -value]))

        ramp = self._absorber_profile()
        slab_share = 1.0
        if self.slab_absorber_damping is not None and self.absorber_damping > 0:
            slab_share = self.slab_absorber_damping / self.absorber_damping
        for x, extra in zip(self.fasteners, ramp, strict=True):
            rail, slab = int(self.rail_dof(x)[0]), 2 * self._slab_node(x)
            spring("pads", rail, slab, 1.0)
            if extra > 0:
                spring("absorber", rail, None, extra)
                spring("absorber", slab, None, extra * slab_share)
        if self.bearing is not None:
            for dof in self._bearing_dofs():
                spring("bearings", int(dof), None, 1.0)
        if self.joint_shear_stiffness is not None or self.joint_bending_stiffness is not None:
            for s in range(len(self.slabs) - 1):
                end = self._slab_offsets[s] + self.slab_nodes[s].size - 1
                start = self._slab_offsets[s + 1]
                for dof, value in (
                    (0, self.joint_shear_stiffness),
                    (1, self.joint_bending_stiffness),
                ):
                    if value:
                        spring("joints", 2 * end + dof, 2 * start + dof, float(value))
        out = {"k_rail": self._sparse([r], [c], [k]), "mass_rail": self._sparse([r], [c], [m])}
        out.update({name: self._sparse(*parts[name]) for name in parts})
        return out

    def _absorber_profile(self) -> NDArray[np.float64]:
        """Dashpot at each fastener in N s/m, quadratic from 0 inside to the ends."""
        x = self.fasteners
        length = self.absorber_length
        if length <= 0 or self.absorber_damping <= 0:
            return np.zeros(x.size)
        depth = np.maximum(self.x_min + length - x, x - (self.x_max - length)) / length
        return self.absorber_damping * np.clip(depth, 0.0, 1.0) ** 2

    def _layer(self, model: PadModel | None, f: float) -> complex:
        if model is None:
            return 0j
        return complex(np.asarray(model.stiffness(np.array([f]), self.pad_temperature)).ravel()[0])

    def dynamic_stiffness(self, f: float) -> sp.csc_matrix:
        """The complex dynamic stiffness at one frequency `f` (Hz), N/m-type units."""
        mat = self._matrices
        omega = 2.0 * np.pi * f
        out = (
            mat["k_rail"] * (1.0 + 1j * self.rail.loss_factor)
            - omega**2 * mat["mass_rail"]
            + mat["k_slab"]
            * (1.0 + 1j * self.slab_loss_factor + 1j * omega * self.slab_damping_time)
            + (self._layer(self.foundation, f) - omega**2 * self.slab_mass_per_length)
            * mat["mass_slab"]
            + self._layer(self.pad, f) * mat["pads"]
            + self._layer(self.bearing, f) * mat["bearings"]
            + mat["joints"]
            + 1j * omega * mat["absorber"]
        )
        return out.tocsc()

    def time_domain_matrices(self) -> tuple[sp.csc_matrix, sp.csc_matrix, sp.csc_matrix]:
        """Real ``(M, C, K)`` for time integration (no beam loss factor).

        The same DOFs and springs as :meth:`dynamic_stiffness`: the consistent Winkler
        matrix carries the foundation's ``k_f`` and ``c_f`` per metre of slab, the slab's
        ``slab_damping_time`` times its stiffness matrix its viscous damping; a
        generalised Maxwell pad or bearing adds one massless DOF per branch and element
        after :attr:`n_dof` (:mod:`railvib.validation.maxwell`).

        Returns
        -------
        tuple of scipy.sparse.csc_matrix
            Mass (kg), damping (N s/m) and stiffness (N/m) matrices, ``n_dof`` plus the
            branches' DOFs square.

        Raises
        ------
        CaseError
            ``track.rail.loss_factor`` or ``track.slab_loss_factor`` not 0 (no hysteretic
            beam in the time domain), ``track.<layer>.model`` of a pad or bearing that is
            neither a spring-damper nor a generalised Maxwell model, or of a foundation
            that is not a spring-damper.
        """
        check_rail(self.rail, time_domain=True)
        if self.slab_loss_factor != 0.0:
            raise CaseError(
                "track.slab_loss_factor",
                self.slab_loss_factor,
                "0 for the time-domain Monte Carlo: it has no hysteretic slab (a viscous "
                "slab_damping_time instead)",
            )
        mat = self._matrices
        elements = {
            name: layer_branches(model, f"track.{name}")
            for name, model in (("pad", self.pad), ("bearing", self.bearing))
            if model is not None
        }
        foundation = (
            viscous_layer(self.foundation, "track.foundation")
            if self.foundation is not None
            else (0.0, 0.0)
        )
        m = mat["mass_rail"] + self.slab_mass_per_length * mat["mass_slab"]
        k = mat["k_rail"] + mat["k_slab"] + mat["joints"]
        c = mat["absorber"] + self.slab_damping_time * mat["k_slab"]
        parallel = {"pad": "pads", "bearing": "bearings"}
        for name, (kc, _) in elements.items():
            k = k + kc[0] * mat[parallel[name]]
            c = c + kc[1] * mat[parallel[name]]
        k = k + foundation[0] * mat["mass_slab"]
        c = c + foundation[1] * mat["mass_slab"]
        # the Maxwell branches of the pads and bearings: internal DOFs after the track's own
        pads = [(int(self.rail_dof(x)[0]), 2 * self._slab_node(x)) for x in self.fasteners]
        stack: list[tuple[NDArray[np.intp], NDArray[np.intp] | None, Branches]] = [
            (
                np.array([a for a, _ in pads], dtype=np.intp),
                np.array([b for _, b in pads], dtype=np.intp),
                elements["pad"],
            )
        ]
        if self.bearing is not None:
            stack.append((self._bearing_dofs(), None, elements["bearing"]))
        rows: list[NDArray] = []
        cols: list[NDArray] = []
        k_vals: list[NDArray] = []
        c_vals: list[NDArray] = []
        n = self.n_dof
        for top, bottom, branches in stack:
            r, cc, kv, cv, added = branch_matrices(top, bottom, branches, n)
            rows, cols, k_vals, c_vals, n = rows + r, cols + cc, k_vals + kv, c_vals + cv, n + added
        if n == self.n_dof:
            return m.tocsc(), c.tocsc(), k.tocsc()
        at = (np.concatenate(rows), np.concatenate(cols))
        k_br = sp.csc_matrix((np.concatenate(k_vals), at), shape=(n, n))
        c_br = sp.csc_matrix((np.concatenate(c_vals), at), shape=(n, n))
        return padded(m, n), (padded(c, n) + c_br).tocsc(), (padded(k, n) + k_br).tocsc()

    def _bearing_dofs(self) -> NDArray[np.intp]:
        """Slab DOFs on a bearing, as :attr:`_matrices` places them."""
        d, every = self.fastener_spacing, self.bearing_spacing_fasteners
        return np.array(
            [
                2 * self._slab_node(x)
                for x in self.fasteners
                if self.slab_length is not None or round(x / d) % every == 0
            ],
            dtype=np.intp,
        )

    def slab_dof(self, x: ArrayLike) -> NDArray[np.intp]:
        """DOF of the slab displacement under each rail position `x` (m; slab nodes)."""
        return np.array([2 * self._slab_node(float(v)) for v in np.atleast_1d(x)], dtype=np.intp)

    def displacements(
        self, f: ArrayLike, x_load: float, x_obs: ArrayLike
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
        """Rail and slab displacement at `x_obs` per unit rail force at `x_load`.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.
        x_load : float
            Load position in m (in `nodes_at`).
        x_obs : array_like
            Observation positions in m: rail nodes above slab nodes (fasteners).

        Returns
        -------
        rail, slab : numpy.ndarray
            Complex, m/N, ``(n_freq, n_obs)`` each.
        """
        from scipy.sparse.linalg import splu

        f = np.atleast_1d(np.asarray(f, dtype=float))
        rail_dofs, slab_dofs = self.rail_dof(x_obs), self.slab_dof(x_obs)
        rhs = np.zeros(self.n_dof, dtype=complex)
        rhs[self.rail_dof(x_load)[0]] = 1.0
        rail = np.empty((f.size, rail_dofs.size), dtype=complex)
        slab = np.empty_like(rail)
        for i, fi in enumerate(f):
            u = splu(self.dynamic_stiffness(fi)).solve(rhs)
            rail[i], slab[i] = u[rail_dofs], u[slab_dofs]
        return rail, slab

    def receptance(self, f: ArrayLike, x_load: ArrayLike, x_obs: ArrayLike) -> NDArray:
        """Rail receptance between rail nodes by a direct sparse solve per frequency.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.
        x_load, x_obs : array_like
            Load and observation positions in m (each in `nodes_at`).

        Returns
        -------
        numpy.ndarray
            Complex receptance in m/N, ``(n_freq, n_obs, n_load)``.
        """
        from scipy.sparse.linalg import splu

        f = np.atleast_1d(np.asarray(f, dtype=float))
        jl, jo = self.rail_dof(x_load), self.rail_dof(x_obs)
        rhs = np.zeros((self.n_dof, jl.size), dtype=complex)
        rhs[jl, np.arange(jl.size)] = 1.0
        out = np.empty((f.size, jo.size, jl.size), dtype=complex)
        for i, fi in enumerate(f):
            out[i] = splu(self.dynamic_stiffness(fi)).solve(rhs)[jo]
        return out
