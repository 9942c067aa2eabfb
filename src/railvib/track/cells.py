"""A general periodic cell of beams and springs, solved as an infinite chain by doubling.

A cell of length ``L`` (the period) holds beam spans (the rail and, for a slab track, the
slab beam), each described by its exact dynamic stiffness (:func:`span_stiffness`), and
complex springs between nodes or from a node to the ground (railpads, slab bearings,
slab joints). Every node carries a displacement ``w`` (down) and a rotation ``theta =
dw/dx``. The cell's interior DOFs are condensed onto its ``m`` boundary DOFs on each
side: ``f_l = A q_l + B q_r``, ``f_r = C q_l + E q_r`` (forces on the cell).

The infinite chain of cells is solved through its semi-infinite dynamic stiffnesses,
found by the doubling (cyclic reduction) of the cell: two cells joined at a node and
the node condensed form a cell twice as long,

    S = E_k + A_k,  A_k+1 = A_k - B_k S^-1 C_k,  B_k+1 = -B_k S^-1 B_k,
    C_k+1 = -C_k S^-1 C_k,  E_k+1 = E_k - C_k S^-1 B_k,

so after ``k`` steps the blocks describe ``2^k`` cells; ``B_k`` and ``C_k`` shrink as
``mu^(2^k)`` of the least-attenuated wave and ``A_k``, ``E_k`` converge to the dynamic
stiffness ``P_r`` of the cells to the right of a node and ``P_l`` of the cells to its
left (a spring at a boundary node is counted by the one cell that holds it). This is the
structure-preserving doubling algorithm of the palindromic eigenproblem
``(mu^-1 C + A + E + mu B) q = 0`` of the Bloch waves (Chu, Hwang, Lin and Wu, "Vibration of
fast trains, palindromic eigenvalue problems and structure-preserving doubling
algorithms", J. Comput. Appl. Math. 219, 2008): it works with the cell's stiffness
blocks only, never with the cell's transfer matrix (whose entries reach
``exp(beta L)``, 1e21 for a 5 m slab at 5 kHz), and picks the decaying (in the limit of
vanishing loss, power-carrying outward) waves by construction. The waves' propagation
operator ``q_n+1 = R q_n``, ``R = -(E + P_r)^-1 C``, has the right-going propagation
constants ``mu`` (``|mu| < 1``) as its eigenvalues; ``q_n-1 = L q_n``,
``L = -(P_l + A)^-1 B``, carries the left-going ones.

A point load in a cell is solved in that cell with the two semi-infinite chains attached
at its ends; the response in another cell follows from its boundary displacements
(``R^k`` or ``L^k`` of the loaded cell's) through the cell's interior response to them.
The waves are best found on the cell without the load and observation nodes (fewer
interior DOFs to condense; the nodes only split spans, so its boundary blocks are the
same), and the loaded cell, which has them, is solved at those points only:
``K_ii^-1`` at the points (a column each), their rows of the interior response
``-(K_ii^-1 K_ib)`` by the symmetry of ``K_ii``, and the boundary with the condensed
cell and the chains.
Everything is stacked over frequency (no loop over frequencies). Every dense solve is
equilibrated (rows and columns scaled by the square root of the diagonal), so that a
slab thousands of times stiffer than the rail costs no digits.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from railvib.errors import SolverWarning
from railvib.track.beam import dynamic_stiffness, field_transfer, timoshenko_transfer
from railvib.track.compiled_cells import (
    assembled,
    euler_span,
    loaded_points,
    propagated,
    use_compiled_cells,
    wave_chain,
)

__all__ = [
    "CLOSED_FORM_WAVENUMBER",
    "MAX_DOUBLINGS",
    "Cell",
    "CellWaves",
    "cell_receptance",
    "cell_waves",
    "span_stiffness",
]

#: ``|beta L|`` of a span from which its dynamic stiffness is taken from the closed form
#: (below it, from the pole-free series transfer matrix): the closed form loses
#: ``1 / |beta L|^4`` of its digits to ``1 - cos cosh`` (1/16 here), the transfer route
#: ``cosh(beta L)^2`` (14 here)
CLOSED_FORM_WAVENUMBER = 2.0

#: doublings at most: ``2^80`` cells, beyond the decay of any wave with the vanishing
#: loss factor ``1e-12`` of an undamped beam
MAX_DOUBLINGS = 80

#: ``max|B_k| / max|A_k|`` (equilibrated) below which the doubling has converged: the
#: next step changes ``A_k`` by its square, 1e-20
CONVERGED = 1e-10


def span_stiffness(
    beta4: NDArray[np.complex128],
    length: float,
    bending_stiffness: complex,
    shear_flexibility: complex | None = None,
    rotary: NDArray[np.complex128] | None = None,
) -> NDArray[np.complex128]:
    """Exact dynamic stiffness of a uniform beam span in SI units, ``(n_freq, 4, 4)``.

    DOFs ``(w_a, theta_a, w_b, theta_b)`` (m, rad), end forces and moments on the span
    (N, N m). An Euler span with ``|beta L| >= CLOSED_FORM_WAVENUMBER`` uses the closed
    form (:func:`railvib.track.beam.dynamic_stiffness`); a shorter one, and every
    Timoshenko span, inverts blocks of the pole-free transfer matrix. An Euler span is
    computed by the compiled kernel where :func:`use_compiled_cells` says so.

    Parameters
    ----------
    beta4 : numpy.ndarray
        ``(m omega^2 - k_f) L^4 / EI*`` per frequency (dimensionless), ``(n_freq,)``;
        ``k_f`` is an elastic foundation per unit length (N/m^2), 0 for none.
    length : float
        Span length L in m (> 0).
    bending_stiffness : complex
        ``EI*`` in N m^2.
    shear_flexibility : complex, optional
        ``EI* / (kappa G A* L^2)`` of a Timoshenko span (dimensionless).
    rotary : numpy.ndarray, optional
        ``rho_I omega^2 L^2 / EI*`` of a Timoshenko span (dimensionless), ``(n_freq,)``.

    Returns
    -------
    numpy.ndarray
        Complex dynamic stiffness, ``(n_freq, 4, 4)``.
    """
    beta4 = np.asarray(beta4, dtype=np.complex128)
    if shear_flexibility is None and use_compiled_cells():
        return euler_span(beta4, CLOSED_FORM_WAVENUMBER**4, length, bending_stiffness)
    scale = np.array([1.0, length, 1.0, length])
    out = np.empty(beta4.shape + (4, 4), dtype=np.complex128)
    closed = np.abs(beta4) >= CLOSED_FORM_WAVENUMBER**4
    if shear_flexibility is not None:
        closed[:] = False
    if np.any(closed):
        out[closed] = dynamic_stiffness(beta4[closed], 1.0)
    series = ~closed
    if np.any(series):
        if shear_flexibility is None:
            t = field_transfer(beta4[series], 1.0)
        else:
            assert rotary is not None, "a Timoshenko span has its rotary term"
            t = timoshenko_transfer(beta4[series], shear_flexibility, rotary[series], 1.0)
        out[series] = _stiffness_from_transfer(t)
    return np.asarray(
        out * (scale[:, None] * scale[None, :]) * (bending_stiffness / length**3),
        dtype=np.complex128,
    )


def _stiffness_from_transfer(t: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """Dimensionless span stiffness (EI = L = 1) from its state transfer matrix.

    The state ``(w, psi, psi', v)`` maps to ``u = (w, theta) = (y0, y1)`` and ``p =
    (shear, moment) = (y3, -y2)``, the force across a section on the part to its right;
    with ``p_b = s21 u_a + s22 p_a``, ``u_b = s11 u_a + s12 p_a`` the forces on the span
    are ``f_a = p_a`` and ``f_b = -p_b``.
    """
    # s = c t c^-1 with the signed permutation c: rows and columns permuted, row and
    # column 3 negated (exactly what the product with c gives, without the products)
    perm = np.array([0, 1, 3, 2])
    sign = np.array([1.0, 1.0, 1.0, -1.0])
    s = t[:, perm[:, None], perm[None, :]] * (sign[:, None] * sign[None, :])
    k_ab = np.linalg.inv(s[:, :2, 2:])
    k_aa = -k_ab @ s[:, :2, :2]
    k_bb = -s[:, 2:, 2:] @ k_ab
    k_ba = -s[:, 2:, :2] - k_bb @ s[:, :2, :2]
    top = np.concatenate([k_aa, k_ab], axis=2)
    return np.concatenate([top, np.concatenate([k_ba, k_bb], axis=2)], axis=1)


@dataclass(frozen=True, eq=False)
class Cell:
    """One period of a track: beam spans and springs between nodes, at every frequency.

    Parameters
    ----------
    period : float
        Cell length L in m.
    n_nodes : int
        Number of nodes; node ``k`` has DOFs ``2k`` (w, m) and ``2k+1`` (theta, rad).
    spans : list of (int, int, numpy.ndarray)
        ``(node_a, node_b, K)``: a beam span's dynamic stiffness ``(n_freq, 4, 4)`` in SI
        units (:func:`span_stiffness`) between the two nodes.
    springs : list of (int, int or None, int, numpy.ndarray)
        ``(node_a, node_b, dof, k)``: a complex spring ``(n_freq,)`` on DOF `dof` (0: w in
        N/m, 1: theta in N m/rad) between two nodes, or from `node_a` to the ground
        (`node_b` None).
    left, right : tuple of int
        The boundary nodes at ``x = 0`` and at ``x = L``, in matching order (the right
        ones are the left ones of the next cell).
    """

    period: float
    n_nodes: int
    spans: list[tuple[int, int, NDArray[np.complex128]]]
    springs: list[tuple[int, int | None, int, NDArray[np.complex128]]]
    left: tuple[int, ...]
    right: tuple[int, ...]

    @property
    def boundary(self) -> NDArray[np.intp]:
        """DOF indices of the left then the right boundary, ``(2 m,)``."""
        nodes = np.array(self.left + self.right)
        return np.stack([2 * nodes, 2 * nodes + 1], axis=1).ravel()

    @property
    def interior(self) -> NDArray[np.intp]:
        """DOF indices of the interior (condensed), ascending."""
        return np.setdiff1d(np.arange(2 * self.n_nodes), self.boundary)

    def stiffness(self) -> NDArray[np.complex128]:
        """The assembled cell dynamic stiffness, ``(n_freq, 2 n_nodes, 2 n_nodes)``, SI."""
        n_freq = self.spans[0][2].shape[0]
        n = 2 * self.n_nodes
        if use_compiled_cells():
            ground = [
                (2 * a + dof, -1 if b is None else 2 * b + dof) for a, b, dof, _ in self.springs
            ]
            return assembled(
                n,
                np.array([(a, b) for a, b, _ in self.spans], dtype=np.int64).reshape(-1, 2),
                np.stack([block for _, _, block in self.spans]),
                np.array(ground, dtype=np.int64).reshape(-1, 2),
                np.array([v for *_, v in self.springs], dtype=np.complex128).reshape(-1, n_freq),
            )
        k = np.zeros((n_freq, n, n), dtype=np.complex128)
        for a, b, block in self.spans:
            if b == a + 1:  # consecutive nodes: a contiguous 4 x 4 block (a view, no copy)
                k[:, 2 * a : 2 * a + 4, 2 * a : 2 * a + 4] += block
                continue
            dofs = np.array([2 * a, 2 * a + 1, 2 * b, 2 * b + 1])
            k[:, dofs[:, None], dofs[None, :]] += block
        for a, other, dof, value in self.springs:
            i = 2 * a + dof
            k[:, i, i] += value
            if other is not None:
                j = 2 * other + dof
                k[:, j, j] += value
                k[:, i, j] -= value
                k[:, j, i] -= value
        return k


def _solve(k: NDArray[np.complex128], rhs: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """``k^-1 rhs`` stacked, with rows and columns scaled by ``|diag k|^(-1/2)``."""
    s = 1.0 / np.sqrt(np.abs(np.einsum("fii->fi", k)))
    scaled = k * s[:, :, None]
    scaled *= s[:, None, :]
    out = np.linalg.solve(scaled, rhs * s[:, :, None])
    out *= s[:, :, None]
    return np.asarray(out)


@dataclass(frozen=True, eq=False)
class CellWaves:
    """The infinite chain of one cell, at each frequency (SI units).

    Attributes
    ----------
    cell : Cell
        The cell.
    stiffness : numpy.ndarray
        Its assembled dynamic stiffness, ``(n_freq, n_dof, n_dof)``.
    blocks : tuple of numpy.ndarray
        ``(A, B, C, E)``, the condensed cell, each ``(n_freq, m, m)``.
    right_chain, left_chain : numpy.ndarray
        ``P_r`` and ``P_l``, ``(n_freq, m, m)``: dynamic stiffness of the cells to the
        right of a node and of those to its left.
    right_step, left_step : numpy.ndarray
        ``R`` (``q_n+1 = R q_n``) and ``L`` (``q_n-1 = L q_n``), ``(n_freq, m, m)``.
    """

    cell: Cell
    stiffness: NDArray[np.complex128]
    blocks: tuple[NDArray[np.complex128], ...]
    right_chain: NDArray[np.complex128]
    left_chain: NDArray[np.complex128]
    right_step: NDArray[np.complex128]
    left_step: NDArray[np.complex128]

    def propagation_constants(self) -> NDArray[np.complex128]:
        """``mu`` of the right-going waves per period, ``(n_freq, m)``, least attenuated first."""
        mu = np.linalg.eigvals(self.right_step)
        order = np.argsort(-np.abs(mu), axis=1, kind="stable")
        return np.asarray(np.take_along_axis(mu, order, axis=1), dtype=np.complex128)


def cell_waves(cell: Cell) -> CellWaves:
    """Condense `cell` onto its boundary and solve its infinite chain by doubling.

    Parameters
    ----------
    cell : Cell
        The period (springs and spans at every frequency).

    Returns
    -------
    CellWaves
        The chain's semi-infinite stiffnesses and wave steps.

    Warns
    -----
    SolverWarning
        If the doubling has not converged after :data:`MAX_DOUBLINGS` steps at some
        frequency (a wave that does not decay over ``2^80`` cells).
    """
    k = cell.stiffness()
    bnd, inner = cell.boundary, cell.interior
    if use_compiled_cells():
        *parts, unconverged = wave_chain(k, bnd, inner, MAX_DOUBLINGS, CONVERGED)
        if np.any(unconverged):
            _warn_unconverged(int(unconverged.sum()))
        a, b, c, e, p_r, p_l, r_step, l_step = parts
        return CellWaves(cell, k, (a, b, c, e), p_r, p_l, r_step, l_step)
    k_bb = k[:, bnd[:, None], bnd[None, :]]
    if inner.size:
        k_ib = k[:, inner[:, None], bnd[None, :]]
        k_bi = k[:, bnd[:, None], inner[None, :]]
        k_bb = k_bb - k_bi @ _solve(k[:, inner[:, None], inner[None, :]], k_ib)
    m = bnd.size // 2
    a, b, c, e = k_bb[:, :m, :m], k_bb[:, :m, m:], k_bb[:, m:, :m], k_bb[:, m:, m:]
    p_r, p_l = _doubling(a, b, c, e)
    r_step = -_solve(e + p_r, c)
    l_step = -_solve(p_l + a, b)
    return CellWaves(cell, k, (a, b, c, e), p_r, p_l, r_step, l_step)


def _doubling(
    a: NDArray[np.complex128],
    b: NDArray[np.complex128],
    c: NDArray[np.complex128],
    e: NDArray[np.complex128],
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """``(P_r, P_l)``: the limits of ``A_k`` and ``E_k`` of the doubling (module docstring).

    The blocks are equilibrated by the boundary DOFs' diagonal (the same DOFs on both
    sides), and each frequency leaves the iteration once converged.
    """
    s = 1.0 / np.sqrt(np.abs(np.einsum("fii->fi", a + e)))
    scale = s[:, :, None] * s[:, None, :]
    a, b, c, e = (x * scale for x in (a, b, c, e))
    p_r, p_l = a.copy(), e.copy()
    active = np.arange(a.shape[0])  # the frequencies still iterated, held compacted
    m = a.shape[1]
    for _ in range(MAX_DOUBLINGS):
        x = np.linalg.solve(e + a, np.concatenate([c, b], axis=2))
        x_c, x_b = x[:, :, :m], x[:, :, m:]
        a, e, b, c = a - b @ x_c, e - c @ x_b, -b @ x_b, -c @ x_c
        size = np.maximum(np.abs(a).max(axis=(1, 2)), np.abs(e).max(axis=(1, 2)))
        coupling = np.maximum(np.abs(b).max(axis=(1, 2)), np.abs(c).max(axis=(1, 2)))
        done = coupling <= CONVERGED * size
        p_r[active[done]], p_l[active[done]] = a[done], e[done]
        if np.all(done):
            break
        keep = ~done
        active, a, b, c, e = active[keep], a[keep], b[keep], c[keep], e[keep]
    else:
        p_r[active], p_l[active] = a, e
        _warn_unconverged(active.size)
    return p_r / scale, p_l / scale


def _warn_unconverged(n_freq: int) -> None:
    """Warn that the doubling has not converged at `n_freq` frequencies."""
    warnings.warn(
        f"{n_freq} frequencies: the cell's waves did not decay over 2^{MAX_DOUBLINGS} "
        "cells; the semi-infinite track stiffness there is not converged",
        SolverWarning,
        stacklevel=4,
    )


def cell_receptance(
    waves: CellWaves,
    load: tuple[NDArray[np.int64], NDArray[np.intp]],
    obs: tuple[NDArray[np.int64], NDArray[np.intp]],
    cell: Cell | None = None,
) -> NDArray[np.complex128]:
    """Displacement of DOFs per unit force on DOFs of the chain, ``(n_freq, n_obs, n_load)``.

    Parameters
    ----------
    waves : CellWaves
        The chain (:func:`cell_waves`).
    load, obs : (numpy.ndarray, numpy.ndarray)
        For each load (observation point): the index of its cell and its DOF in `cell`
        (a DOF of the cell's left boundary stands for the cell's left node).
    cell : Cell, optional
        The cell the loads and observation points are nodes of: the waves' cell with
        further nodes (its spans split there), the same boundary nodes in the same order.
        Default: the waves' cell. The waves are best found on the cell without them
        (fewer interior DOFs to condense), the loads placed here.

    Returns
    -------
    numpy.ndarray
        Complex receptance in SI units (m/N for displacement DOFs).
    """
    if cell is None or cell is waves.cell:
        cell, k = waves.cell, waves.stiffness
    else:
        assert cell.boundary.size == waves.cell.boundary.size, "the waves' boundary"
        k = cell.stiffness()
    bnd, inner = cell.boundary, cell.interior
    m = bnd.size // 2
    load_cell, load_dof = load
    obs_cell, obs_dof = obs
    n_freq = k.shape[0]
    a, b, c, e = waves.blocks
    condensed = np.concatenate(
        [
            np.concatenate([a + waves.left_chain, b], axis=2),
            np.concatenate([c, e + waves.right_chain], axis=2),
        ],
        axis=1,
    )
    where = _where(bnd, inner, load_dof, obs_dof)
    solve = loaded_points if use_compiled_cells() else _loaded_points
    u, u_b, rows = solve(k, bnd, inner, condensed, *where)
    offsets = obs_cell[:, None] - load_cell[None, :]
    # boundary displacements of the cells n = 1, 2, ... to the right of the loaded one
    # (q_n+1 = R q_n from its right end) and to its left (q_n-1 = L q_n from its left end),
    # as far as each load's farthest observed cell
    chain = propagated if use_compiled_cells() else _propagate
    out = np.empty((n_freq, obs_dof.size, load_dof.size), dtype=np.complex128)
    for j in range(load_dof.size):
        steps = int(max(offsets[:, j].max(), 0)), int(max(-offsets[:, j].min(), 0))
        right_q = chain(waves.right_step, u_b[:, m:, j : j + 1], steps[0])
        left_q = chain(waves.left_step, u_b[:, :m, j : j + 1], steps[1])
        for i in range(obs_dof.size):
            n = int(offsets[i, j])
            if n == 0:
                out[:, i, j] = u[:, i, j]
                continue
            if n > 0:  # the observed cell's ends: n - 1 and n steps from the loaded cell's
                q = np.concatenate([right_q[n - 1][:, :, 0], right_q[n][:, :, 0]], axis=1)
            else:
                q = np.concatenate([left_q[-n][:, :, 0], left_q[-n - 1][:, :, 0]], axis=1)
            out[:, i, j] = np.einsum("fa,fa->f", rows[:, i], q)
    return out


def _where(
    bnd: NDArray[np.intp],
    inner: NDArray[np.intp],
    load_dof: NDArray[np.intp],
    obs_dof: NDArray[np.intp],
) -> tuple[NDArray[np.int64], ...]:
    """Where the loads' and observation points' DOFs are in the cell.

    Returns ``(points, load_b, load_p, obs_b, obs_p)``: the interior DOFs that are a load
    or an observation point (their indices in `inner`), and for each load and observation
    point its index in `bnd` and in ``points`` (-1 where it is not one).
    """
    in_bnd = {int(d): i for i, d in enumerate(bnd)}
    in_inner = {int(d): i for i, d in enumerate(inner)}
    points = sorted({in_inner[int(d)] for d in (*load_dof, *obs_dof) if int(d) in in_inner})
    in_points = {i: p for p, i in enumerate(points)}

    def place(dofs: NDArray[np.intp]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        at_b = [in_bnd.get(int(d), -1) for d in dofs]
        at_p = [in_points.get(in_inner.get(int(d), -1), -1) for d in dofs]
        return np.array(at_b, dtype=np.int64), np.array(at_p, dtype=np.int64)

    return (np.array(points, dtype=np.int64), *place(load_dof), *place(obs_dof))


def _loaded_points(
    k: NDArray[np.complex128],
    bnd: NDArray[np.intp],
    inner: NDArray[np.intp],
    condensed: NDArray[np.complex128],
    points: NDArray[np.int64],
    load_b: NDArray[np.int64],
    load_p: NDArray[np.int64],
    obs_b: NDArray[np.int64],
    obs_p: NDArray[np.int64],
) -> tuple[NDArray[np.complex128], ...]:
    """The loaded cell with both chains, solved at its load and observation points only.

    With ``X = K_ii^-1`` at the interior points (one solve, a column per point), a point's
    row of the interior response to the boundary is ``-X^T K_ib`` (``K_ii`` is symmetric),
    an interior load's boundary load is the transpose of its row, the boundary is solved
    with the condensed cell and the chains (`condensed`, ``(n_freq, 2 m, 2 m)``), and an
    observation point's displacement is its row times the boundary's plus ``X`` between
    it and an interior load. Returns the points' DOFs per unit load ``(n_freq, n_obs,
    n_load)``, the boundary's ``(n_freq, 2 m, n_load)`` and the observation points' rows
    ``(n_freq, n_obs, 2 m)``.
    """
    n_freq = k.shape[0]
    unit_b = np.eye(bnd.size, dtype=np.complex128)
    x = np.zeros((n_freq, inner.size, points.size), dtype=np.complex128)
    rows_p = np.zeros((n_freq, points.size, bnd.size), dtype=np.complex128)
    if points.size:
        unit = np.zeros((n_freq, inner.size, points.size), dtype=np.complex128)
        unit[:, points, np.arange(points.size)] = 1.0
        x = _solve(k[:, inner[:, None], inner[None, :]], unit)
        rows_p = -np.einsum("fip,fib->fpb", x, k[:, inner[:, None], bnd[None, :]])

    def rows(at_b: NDArray[np.int64], at_p: NDArray[np.int64]) -> NDArray[np.complex128]:
        out = np.empty((n_freq, at_b.size, bnd.size), dtype=np.complex128)
        for i, (ib, ip) in enumerate(zip(at_b, at_p, strict=True)):
            out[:, i] = unit_b[ib] if ib >= 0 else rows_p[:, ip]
        return out

    rows_obs = rows(obs_b, obs_p)
    u_b = _solve(condensed, rows(load_b, load_p).transpose(0, 2, 1))
    u = rows_obs @ u_b
    for i, ip in enumerate(obs_p):
        for j, jp in enumerate(load_p):
            if ip >= 0 and jp >= 0:
                u[:, i, j] += x[:, points[ip], jp]
    return u, u_b, rows_obs


def _propagate(
    step: NDArray[np.complex128], q: NDArray[np.complex128], n: int
) -> list[NDArray[np.complex128]]:
    """``[q, step q, ..., step^n q]`` for the columns of `q` ``(n_freq, m, n_load)``."""
    out = [q]
    for _ in range(n):
        out.append(step @ out[-1])
    return out
