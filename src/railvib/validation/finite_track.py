"""A long but finite rail on discrete pads, assembled from Hermite beam elements.

This is the independent reference for the symplectic periodic solver: it shares
nothing with :mod:`railvib.track` except the parameter objects (`Rail`, the pad
model). The rail is an Euler-Bernoulli beam discretised with cubic Hermite
elements (consistent mass), several per sleeper bay, plus extra nodes wherever a
load or observation point lies inside a bay (so no shape-function interpolation
is needed). A pad is a vertical spring (complex in the frequency domain) at every
sleeper node, rigid below; or, for the ballasted track, a pad spring to an explicit
sleeper DOF of mass ``m_s`` on a ballast spring to the ground (and, for three layers,
the ballast spring to an explicit ballast-mass DOF on a subgrade spring): these DOFs
are assembled into the structure, not condensed. The rail ends are free, just beyond the outermost
sleepers; optional absorbing layers of graded extra pad damping near both ends
swallow the waves that reach them.

Accuracy of the Hermite element for the seed track (docs/validation.md,
infinite-track point receptance): relative error 1.9e-4 at 1 kHz with 4
elements per 0.6 m bay, 1.2e-5 with 8. The default for the frequency-domain
reference is 8 elements per bay; the time-domain model (band 1-500 Hz) uses 4.
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
from railvib.validation.maxwell import Branches, branch_matrices, layer_branches, padded
from railvib.validation.scope import check_rail

__all__ = ["FiniteTrack", "hermite_element_matrices"]

#: nodes closer than this fraction of a bay are merged
_MERGE_TOLERANCE = 1e-9


def hermite_element_matrices(
    length: NDArray[np.float64], bending_stiffness: float, mass_per_length: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Stiffness and consistent mass matrices of cubic Hermite beam elements.

    Parameters
    ----------
    length : numpy.ndarray
        Element lengths in m, ``(n_el,)``.
    bending_stiffness : float
        EI in N m^2.
    mass_per_length : float
        m in kg/m.

    Returns
    -------
    k, m : numpy.ndarray
        ``(n_el, 4, 4)`` in N/m-type units and kg-type units, DOFs
        ``(w_1, theta_1, w_2, theta_2)`` (w down, theta = dw/dx).
    """
    ell = np.asarray(length, dtype=float)[:, None, None]
    one = np.ones_like(ell)
    k = np.block(
        [
            [12 * one, 6 * ell, -12 * one, 6 * ell],
            [6 * ell, 4 * ell**2, -6 * ell, 2 * ell**2],
            [-12 * one, -6 * ell, 12 * one, -6 * ell],
            [6 * ell, 2 * ell**2, -6 * ell, 4 * ell**2],
        ]
    ) * (bending_stiffness / ell**3)
    m = np.block(
        [
            [156 * one, 22 * ell, 54 * one, -13 * ell],
            [22 * ell, 4 * ell**2, 13 * ell, -3 * ell**2],
            [54 * one, 13 * ell, 156 * one, -22 * ell],
            [-13 * ell, -3 * ell**2, -22 * ell, 4 * ell**2],
        ]
    ) * (mass_per_length * ell / 420.0)
    return k, m


@dataclass(frozen=True)
class FiniteTrack:
    """Finite rail on discrete pads at sleepers ``x = n d``, ``n = first_sleeper ... last_sleeper``.

    Parameters
    ----------
    rail : Rail
        Rail beam (EI in N m^2, m in kg/m, loss factor).
    pad : PadModel
        Railpad, complex stiffness per rail seat in N/m.
    sleeper_spacing : float
        d in m (> 0).
    first_sleeper, last_sleeper : int
        Indices of the outermost sleepers; the rail runs from ``first_sleeper d``
        to ``last_sleeper d`` with free ends.
    elements_per_span : int
        Hermite elements per bay (>= 1); a bay holding extra nodes gets the same
        element density in each of its pieces.
    nodes_at : tuple of float
        Positions in m where nodes must lie (wheels, observation points).
    absorber_spans : int
        Number of bays at each end with graded extra pad damping (>= 0).
    absorber_damping : float
        Extra pad damping at the outermost sleeper in N s/m (>= 0); it grows
        quadratically from 0 at the inner edge of each layer.
    pad_temperature : float, optional
        Pad temperature in degrees Celsius, passed to the pad (and layer) models.
    ballast : PadModel, optional
        Given: a sleeper DOF of mass `sleeper_mass` under every pad, on this ballast
        (complex stiffness per rail seat, N/m) to a rigid ground. None: the pad stands
        on a rigid base.
    sleeper_mass : float
        Sleeper mass per rail seat in kg (>= 0), with `ballast`.
    subgrade : PadModel, optional
        With `ballast`: a ballast-mass DOF of mass `ballast_mass` under the ballast,
        on this subgrade (N/m) to the ground (the three-layer model).
    ballast_mass : float
        Ballast mass per rail seat in kg (> 0), with `subgrade`.
    """

    rail: Rail
    pad: PadModel
    sleeper_spacing: float
    first_sleeper: int
    last_sleeper: int
    elements_per_span: int = 8
    nodes_at: tuple[float, ...] = ()
    absorber_spans: int = 0
    absorber_damping: float = 0.0
    pad_temperature: float | None = None
    ballast: PadModel | None = None
    sleeper_mass: float = 0.0
    subgrade: PadModel | None = None
    ballast_mass: float = 0.0

    def __post_init__(self) -> None:
        if not (np.isfinite(self.sleeper_mass) and self.sleeper_mass >= 0):
            raise CaseError("finite_track.sleeper_mass", self.sleeper_mass, ">= 0 (kg)")
        if self.subgrade is not None and not (
            self.ballast is not None and np.isfinite(self.ballast_mass) and self.ballast_mass > 0
        ):
            raise CaseError(
                "finite_track.ballast_mass", self.ballast_mass, "> 0 (kg), with a ballast"
            )
        d = self.sleeper_spacing
        if not (np.isfinite(d) and d > 0):
            raise CaseError("track.sleeper_spacing", d, "must be > 0 (m)")
        check_rail(self.rail, time_domain=False)
        if self.last_sleeper - self.first_sleeper < 1:
            raise CaseError("finite_track.last_sleeper", self.last_sleeper, "> first_sleeper")
        if int(self.elements_per_span) < 1:
            raise CaseError("finite_track.elements_per_span", self.elements_per_span, ">= 1")
        lo, hi = self.first_sleeper * d, self.last_sleeper * d
        for x in self.nodes_at:
            if not (np.isfinite(x) and lo <= x <= hi):
                raise CaseError("finite_track.nodes_at", x, f"inside [{lo}, {hi}] (m)")
        n_bays = self.last_sleeper - self.first_sleeper
        if self.absorber_spans < 0 or 2 * self.absorber_spans > n_bays:
            raise CaseError("finite_track.absorber_spans", self.absorber_spans, ">= 0, fits twice")
        if not (np.isfinite(self.absorber_damping) and self.absorber_damping >= 0):
            raise CaseError("finite_track.absorber_damping", self.absorber_damping, ">= 0 (N s/m)")

    @classmethod
    def around(
        cls,
        positions: ArrayLike,
        rail: Rail,
        pad: PadModel,
        sleeper_spacing: float,
        *,
        margin_spans: int = 60,
        elements_per_span: int = 8,
        absorber_spans: int = 0,
        absorber_damping: float = 0.0,
        pad_temperature: float | None = None,
        ballast: PadModel | None = None,
        sleeper_mass: float = 0.0,
        subgrade: PadModel | None = None,
        ballast_mass: float = 0.0,
    ) -> FiniteTrack:
        """Build a track with nodes at `positions` (m) and `margin_spans` bays beyond them.

        The absorbing layers (if any) lie inside the margins, at the very ends.

        Parameters
        ----------
        positions : array_like
            Positions along the rail in m where nodes must lie (wheels, observation points).
        rail : Rail
            Rail beam (EI in N m^2, m in kg/m); Euler-Bernoulli only.
        pad : PadModel
            Railpad, complex stiffness per rail seat in N/m.
        sleeper_spacing : float
            Sleeper spacing d in m (> 0).
        margin_spans : int
            Bays of finite track beyond the outermost positions on each side.
        elements_per_span : int
            Hermite elements per bay (8: 1.7e-5 relative receptance error at 1 kHz).
        absorber_spans : int
            Bays with graded extra pad damping at each end, inside the margins.
        absorber_damping : float
            Extra pad damping at the outermost sleepers, N s/m (>= 0).
        pad_temperature : float, optional
            Pad temperature in degrees Celsius (degC), passed to the pad model.
        ballast, sleeper_mass, subgrade, ballast_mass
            The layers under the pads (N/m, kg), as in :class:`FiniteTrack`.

        Returns
        -------
        FiniteTrack
            Sleepers from ``floor(min(positions) / d) - margin_spans`` to
            ``ceil(max(positions) / d) + margin_spans``.
        """
        x = np.atleast_1d(np.asarray(positions, dtype=float))
        d = sleeper_spacing
        first = int(np.floor(x.min() / d)) - int(margin_spans)
        last = int(np.ceil(x.max() / d)) + int(margin_spans)
        return cls(
            rail,
            pad,
            d,
            first,
            last,
            elements_per_span=int(elements_per_span),
            nodes_at=tuple(float(v) for v in x),
            absorber_spans=int(absorber_spans),
            absorber_damping=float(absorber_damping),
            pad_temperature=pad_temperature,
            ballast=ballast,
            sleeper_mass=float(sleeper_mass),
            subgrade=subgrade,
            ballast_mass=float(ballast_mass),
        )

    # -- mesh -------------------------------------------------------------------------------
    @cached_property
    def nodes(self) -> NDArray[np.float64]:
        """Node positions in m, increasing."""
        d = self.sleeper_spacing
        extra = np.sort(np.asarray(self.nodes_at, dtype=float))
        pts = []
        for n in range(self.first_sleeper, self.last_sleeper):
            a, b = n * d, (n + 1) * d
            inside = extra[(extra > a + _MERGE_TOLERANCE * d) & (extra < b - _MERGE_TOLERANCE * d)]
            breaks = np.concatenate([[a], np.unique(inside), [b]])
            for lo, hi in zip(breaks[:-1], breaks[1:], strict=True):
                n_el = max(1, int(np.ceil(self.elements_per_span * (hi - lo) / d - 1e-9)))
                pts.append(np.linspace(lo, hi, n_el + 1)[:-1])
        pts.append(np.array([self.last_sleeper * d]))
        return np.concatenate(pts)

    @property
    def n_layers(self) -> int:
        """Layers of explicit DOFs under the pads: 0 (rigid base), 1 (sleepers), 2 (+ ballast)."""
        return 0 if self.ballast is None else (1 if self.subgrade is None else 2)

    @property
    def n_dof(self) -> int:
        """Number of DOFs: ``2 n_nodes`` (w, theta at each node), then one per sleeper and layer."""
        n_sl = self.last_sleeper - self.first_sleeper + 1
        return 2 * self.nodes.size + self.n_layers * n_sl

    def node_index(self, x: ArrayLike) -> NDArray[np.intp]:
        """Index of the node at each position `x` (m); raises if a position is not a node."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        idx = np.searchsorted(self.nodes, x)
        idx = np.clip(idx, 0, self.nodes.size - 1)
        left = np.clip(idx - 1, 0, self.nodes.size - 1)
        best = np.where(np.abs(self.nodes[left] - x) < np.abs(self.nodes[idx] - x), left, idx)
        if np.any(np.abs(self.nodes[best] - x) > _MERGE_TOLERANCE * self.sleeper_spacing * 10):
            raise CaseError("finite_track.position", list(x), "positions listed in nodes_at (m)")
        return best

    def w_dof(self, x: ArrayLike) -> NDArray[np.intp]:
        """DOF index of the vertical displacement at each position `x` (m)."""
        return 2 * self.node_index(x)

    @cached_property
    def sleeper_dofs(self) -> NDArray[np.intp]:
        """DOF index of w at every sleeper, left to right."""
        d = self.sleeper_spacing
        return self.w_dof(np.arange(self.first_sleeper, self.last_sleeper + 1) * d)

    @cached_property
    def absorber_profile(self) -> NDArray[np.float64]:
        """Extra pad damping at every sleeper in N s/m (graded quadratically, 0 inside)."""
        n_sl = self.last_sleeper - self.first_sleeper + 1
        out = np.zeros(n_sl)
        n_abs = self.absorber_spans
        if n_abs > 0 and self.absorber_damping > 0:
            ramp = self.absorber_damping * (np.arange(1, n_abs + 1) / n_abs) ** 2
            out[:n_abs] = ramp[::-1]
            out[n_sl - n_abs :] = ramp
        return out

    # -- matrices ---------------------------------------------------------------------------
    def _assemble(self, blocks: NDArray[np.float64]) -> sp.csc_matrix:
        n_el = self.nodes.size - 1
        dofs = 2 * np.arange(n_el)[:, None] + np.arange(4)[None, :]
        rows = np.broadcast_to(dofs[:, :, None], (n_el, 4, 4)).ravel()
        cols = np.broadcast_to(dofs[:, None, :], (n_el, 4, 4)).ravel()
        return sp.csc_matrix((blocks.ravel(), (rows, cols)), shape=(self.n_dof, self.n_dof))

    @cached_property
    def _element_matrices(self) -> tuple[sp.csc_matrix, sp.csc_matrix]:
        k, m = hermite_element_matrices(
            np.diff(self.nodes), self.rail.bending_stiffness, self.rail.mass_per_length
        )
        return self._assemble(k), self._assemble(m)

    @property
    def rail_stiffness_matrix(self) -> sp.csc_matrix:
        """Rail bending stiffness matrix (real EI), N/m-type units, ``(n_dof, n_dof)``."""
        return self._element_matrices[0]

    @property
    def mass_matrix(self) -> sp.csc_matrix:
        """Consistent rail mass matrix, kg-type units, ``(n_dof, n_dof)``."""
        return self._element_matrices[1]

    def _sleeper_diagonal(self, values: NDArray) -> sp.csc_matrix:
        diag = np.zeros(self.n_dof, dtype=values.dtype)
        diag[self.sleeper_dofs] = values
        return sp.diags(diag, format="csc")

    def _layer(self, model: PadModel, f: float) -> complex:
        return complex(np.asarray(model.stiffness(np.array([f]), self.pad_temperature)).ravel()[0])

    def pad_matrix(self, f: float) -> sp.csc_matrix:
        """Complex support matrix at frequency `f` (Hz), N/m, ``(n_dof, n_dof)``.

        Rigid base: the pad (and absorber) stiffness on the diagonal at the sleepers.
        Ballasted: the pad spring between each rail sleeper node and its sleeper DOF, the
        absorber from the rail node to the ground, the sleeper's ``-omega^2 m_s``, the
        ballast spring to the ground (or, for three layers, to the ballast-mass DOF with
        its ``-omega^2 m_b`` on the subgrade spring to the ground).

        Parameters
        ----------
        f : float
            Frequency in Hz.

        Returns
        -------
        scipy.sparse.csc_matrix
            Complex, N/m.
        """
        kp = self._layer(self.pad, f)
        omega = 2.0 * np.pi * f
        values = kp + 1j * omega * self.absorber_profile
        diagonal = self._sleeper_diagonal(values.astype(complex))
        if self.ballast is None:
            return diagonal
        n_sl = self.sleeper_dofs.size
        rail = self.sleeper_dofs
        first = 2 * self.nodes.size
        sleeper = first + np.arange(n_sl)
        kb = self._layer(self.ballast, f)
        rows = [rail, sleeper, sleeper]
        cols = [sleeper, rail, sleeper]
        vals = [np.full(n_sl, -kp), np.full(n_sl, -kp), np.full(n_sl, kp + kb)]
        vals[2] = vals[2] - omega**2 * self.sleeper_mass
        if self.subgrade is not None:
            ballast = sleeper + n_sl
            kg = self._layer(self.subgrade, f)
            rows += [sleeper, ballast, ballast]
            cols += [ballast, sleeper, ballast]
            vals += [
                np.full(n_sl, -kb),
                np.full(n_sl, -kb),
                np.full(n_sl, kb + kg - omega**2 * self.ballast_mass),
            ]
        layers = sp.csc_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(self.n_dof, self.n_dof),
        )
        return (diagonal + layers).tocsc()

    def time_domain_matrices(self) -> tuple[sp.csc_matrix, sp.csc_matrix, sp.csc_matrix]:
        """Real ``(M, C, K)`` for time integration (viscous or generalised Maxwell layers).

        A ballasted track's sleepers (and ballast masses) are explicit DOFs, as in
        :meth:`pad_matrix`: the pad spring-damper between each rail sleeper node and its
        sleeper of mass ``m_s``, the ballast from the sleeper to the ground (or to the
        ballast mass of ``m_b`` on the subgrade); the absorber from the rail to the ground.
        A generalised Maxwell layer's branches add one massless DOF each per sleeper, after
        the track's :attr:`n_dof` (:mod:`railvib.validation.maxwell`).

        Returns
        -------
        tuple of scipy.sparse.csc_matrix
            Mass (kg), damping (N s/m) and stiffness (N/m) matrices, ``n_dof`` plus the
            branches' DOFs square.

        Raises
        ------
        CaseError
            If the pad, ballast or subgrade is neither a spring-damper nor a generalised
            Maxwell model (or the two-rail doubling of one) or the rail has a loss factor,
            which have no exact time-domain counterpart here.
        """
        check_rail(self.rail, time_domain=True)
        pad = layer_branches(self.pad, "track.pad")
        rail = self.sleeper_dofs
        n_sl = rail.size
        layers = sp.csc_matrix((self.n_dof, self.n_dof))
        k_lay, c_lay, m_lay = layers, layers, layers
        # (top DOFs, bottom DOFs or None for the ground, elements) of each layer
        stack: list[tuple[NDArray[np.intp], NDArray[np.intp] | None, Branches]] = []
        if self.ballast is None:
            k_lay = self._sleeper_diagonal(np.full(n_sl, pad[0][0]))
            c_lay = self._sleeper_diagonal(np.full(n_sl, pad[0][1]))
            stack.append((rail, None, pad))
        else:
            sleeper = 2 * self.nodes.size + np.arange(n_sl)
            ballast = layer_branches(self.ballast, "track.ballast")
            chain = [(rail, sleeper, pad[0])]
            ground = [(sleeper, ballast[0])]
            masses = [(sleeper, self.sleeper_mass)]
            stack += [(rail, sleeper, pad), (sleeper, None, ballast)]
            if self.subgrade is not None:
                mass = sleeper + n_sl
                subgrade = layer_branches(self.subgrade, "track.subgrade")
                chain.append((sleeper, mass, ground.pop()[1]))
                ground.append((mass, subgrade[0]))
                masses.append((mass, self.ballast_mass))
                stack[-1] = (sleeper, mass, ballast)
                stack.append((mass, None, subgrade))
            k_lay = self._springs(chain, ground, 0)
            c_lay = self._springs(chain, ground, 1)
            m_lay = self._springs([], [(dofs, (mass, mass)) for dofs, mass in masses], 0)
        k = self.rail_stiffness_matrix + k_lay
        c = c_lay + self._sleeper_diagonal(self.absorber_profile)
        m = self.mass_matrix + m_lay
        # the layers' Maxwell branches: internal DOFs after the track's own
        rows: list[NDArray] = []
        cols: list[NDArray] = []
        k_vals: list[NDArray] = []
        c_vals: list[NDArray] = []
        n = self.n_dof
        for top, bottom, elements in stack:
            r, cc, kv, cv, added = branch_matrices(top, bottom, elements, n)
            rows, cols, k_vals, c_vals, n = rows + r, cols + cc, k_vals + kv, c_vals + cv, n + added
        if n == self.n_dof:
            return m.tocsc(), c.tocsc(), k.tocsc()
        at = (np.concatenate(rows), np.concatenate(cols))
        k_br = sp.csc_matrix((np.concatenate(k_vals), at), shape=(n, n))
        c_br = sp.csc_matrix((np.concatenate(c_vals), at), shape=(n, n))
        return padded(m, n), (padded(c, n) + c_br).tocsc(), (padded(k, n) + k_br).tocsc()

    def _springs(
        self,
        chain: list[tuple[NDArray[np.intp], NDArray[np.intp], tuple[float, float]]],
        ground: list[tuple[NDArray[np.intp], tuple[float, float]]],
        part: int,
    ) -> sp.csc_matrix:
        """Real springs (``part`` 0: stiffness, 1: damping) between DOF pairs and to the ground."""
        rows, cols, vals = [], [], []
        for a, b, values in chain:
            v = np.full(a.size, values[part])
            rows += [a, b, a, b]
            cols += [a, b, b, a]
            vals += [v, v, -v, -v]
        for a, values in ground:
            rows.append(a)
            cols.append(a)
            vals.append(np.full(a.size, values[part]))
        return sp.csc_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(self.n_dof, self.n_dof),
        )

    def dynamic_stiffness(self, f: float) -> sp.csc_matrix:
        """``K (1 + i eta_r) + K_pad(f) - omega^2 M`` at one frequency `f` (Hz), complex, N/m."""
        omega = 2.0 * np.pi * f
        k_rail = self.rail_stiffness_matrix * (1.0 + 1j * self.rail.loss_factor)
        return (k_rail - omega**2 * self.mass_matrix + self.pad_matrix(f)).tocsc()

    def receptance(self, f: ArrayLike, x_load: ArrayLike, x_obs: ArrayLike) -> NDArray:
        """Rail receptance between nodes by a direct sparse solve per frequency.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, ``(n_freq,)``.
        x_load, x_obs : array_like
            Load and observation positions in m; each must be a node.

        Returns
        -------
        numpy.ndarray
            Complex receptance in m/N, ``(n_freq, n_obs, n_load)``.
        """
        from scipy.sparse.linalg import splu

        f = np.atleast_1d(np.asarray(f, dtype=float))
        jl = self.w_dof(x_load)
        jo = self.w_dof(x_obs)
        rhs = np.zeros((self.n_dof, jl.size), dtype=complex)
        rhs[jl, np.arange(jl.size)] = 1.0
        out = np.empty((f.size, jo.size, jl.size), dtype=complex)
        for k, fk in enumerate(f):
            out[k] = splu(self.dynamic_stiffness(fk)).solve(rhs)[jo]
        return out
