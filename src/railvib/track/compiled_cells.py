"""The cell solver's dense steps compiled (numba), one pass over the frequencies of a block.

The same algorithm as :mod:`railvib.track.cells` (the reference, and the fallback),
written frequency by frequency: the Euler spans' exact stiffness, the assembly, the
condensation of a cell's interior DOFs, the doubling of its boundary blocks (the
symmetric step of a reciprocal cell, ``C = B^T``: three products instead of the
reference's four), the wave steps ``R`` and ``L``, and the loaded cell's solve at its
load and observation points with both semi-infinite chains attached. Each dense solve
is the reference's equilibrated one (rows and columns scaled by ``|diag|^(-1/2)``) by
Gaussian elimination with partial pivoting on ``|Re| + |Im|`` (LAPACK's choice), so
results agree with the reference to rounding. NumPy's stacked solve costs about a
microsecond per small matrix whatever its size; here a 4 x 4 solve is a few dozen
nanoseconds, and no intermediate array of the block is formed.

The kernel is used only in a process that has loaded the compiled kernels already (a
large sweep, or :func:`railvib.track.compiled.compile_kernel`): a single case's run
never imports numba itself. ``RAILVIB_COMPILED=0`` keeps everything on NumPy.
"""

from __future__ import annotations

import math
import os
from typing import Any

import numpy as np
from numpy.typing import NDArray

from railvib.jit import numba_jit
from railvib.track import compiled
from railvib.track.slab_kernel import slab_kernel

__all__ = [
    "assembled",
    "cell_kernel",
    "euler_span",
    "fused_kernel",
    "loaded_points",
    "propagated",
    "use_compiled_cells",
    "wave_chain",
]

_CELL_KERNEL: list[Any] = []

#: ``1 / (4k + j)!`` for ``k < 16``, ``j < 4``: the Krylov series' coefficients (a series
#: span has ``|beta L| < 2``, and 10 terms at most)
_INVERSE_FACTORIALS = np.array(
    [[1.0 / math.factorial(4 * k + j) for j in range(4)] for k in range(16)]
)

#: the point functions compiled, helpers first (each calls only those before it)
_FUNCTIONS = (
    "_abs2",
    "_lu_solve",
    "_eq_solve",
    "_waves_points",
    "_loaded_points",
    "_propagate_points",
    "_assemble_points",
    "_span_points",
)


def use_compiled_cells() -> bool:
    """Tell whether the cell solver runs on the compiled kernel in this process.

    Returns
    -------
    bool
        True where ``RAILVIB_COMPILED`` is not ``0`` and the process has loaded the
        compiled kernels (this one, or the rigid-base one of
        :mod:`railvib.track.compiled`, in which case this one is loaded now).
    """
    if os.environ.get("RAILVIB_COMPILED", "1") == "0":
        return False
    if _CELL_KERNEL:
        return _CELL_KERNEL[0] is not None
    if not compiled._KERNEL or compiled._KERNEL[0] is None:
        return False
    return cell_kernel() is not None


def cell_kernel() -> Any:
    """The compiled functions (numba, cached), or None.

    ``(waves, loaded, propagate, assemble, span, fused)``: the entry points of this module
    and the slab track's fused kernel (:func:`railvib.track.slab_kernel.slab_kernel`).
    """
    if not _CELL_KERNEL:
        jit = numba_jit()
        if jit is None:
            _CELL_KERNEL.append(None)
        else:
            space = globals()
            for name in _FUNCTIONS:  # compiled at first call: callees resolve to these
                space[name] = jit(_PLAIN[name])
            entries = tuple(space[name] for name in _FUNCTIONS[3:])
            _CELL_KERNEL.append((*entries, slab_kernel()))  # the entry points, the fused one
    return _CELL_KERNEL[0]


def fused_kernel() -> Any:
    """The slab track's fused kernel (:mod:`railvib.track.slab_kernel`) where it is in use.

    Returns
    -------
    callable or None
        The compiled kernel where :func:`use_compiled_cells` says so and the loaded cell
        kernel carries it, else None (the cell solver's steps are taken one by one).
    """
    if not use_compiled_cells():
        return None
    kernel = _CELL_KERNEL[0]
    return kernel[5] if len(kernel) > 5 else None


def wave_chain(
    k: NDArray[np.complex128],
    bnd: NDArray[np.intp],
    inner: NDArray[np.intp],
    max_doublings: int,
    converged: float,
) -> tuple[NDArray[np.complex128], ...]:
    """The condensed cell, its chains and wave steps (as :func:`railvib.track.cells.cell_waves`).

    Parameters
    ----------
    k : numpy.ndarray
        Assembled cell stiffness, ``(n_freq, n_dof, n_dof)``, SI units.
    bnd, inner : numpy.ndarray
        Boundary DOFs (left then right, ``2 m``) and interior DOFs (indices, dimensionless).
    max_doublings : int
        Doublings at most (dimensionless count).
    converged : float
        ``max|B_k| / max|A_k|`` below which a frequency has converged (dimensionless).

    Returns
    -------
    tuple of numpy.ndarray
        ``(A, B, C, E, P_r, P_l, R, L, unconverged)``: blocks ``(n_freq, m, m)`` and a bool
        ``(n_freq,)`` of the frequencies the doubling did not converge at.
    """
    n_freq = k.shape[0]
    m = bnd.size // 2
    blocks = np.empty((8, n_freq, m, m), dtype=np.complex128)
    unconverged = np.zeros(n_freq, dtype=np.bool_)
    cell_kernel()[0](
        np.ascontiguousarray(k),
        bnd.astype(np.int64),
        inner.astype(np.int64),
        int(max_doublings),
        float(converged),
        blocks,
        unconverged,
    )
    return (*blocks, unconverged)


def loaded_points(
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
    """The loaded cell at its load and observation points (as ``cells._loaded_points``).

    Parameters
    ----------
    k : numpy.ndarray
        Assembled cell stiffness, ``(n_freq, n_dof, n_dof)``, SI units.
    bnd, inner : numpy.ndarray
        Boundary DOFs (left then right, ``2 m``) and interior DOFs (indices, dimensionless).
    condensed : numpy.ndarray
        The condensed cell with both chains added, ``(n_freq, 2 m, 2 m)``, SI units.
    points : numpy.ndarray
        The interior DOFs that are a load or an observation point (indices in `inner`,
        dimensionless).
    load_b, load_p, obs_b, obs_p : numpy.ndarray
        Each load's and observation point's index in `bnd` and in `points` (dimensionless;
        -1: none).

    Returns
    -------
    tuple of numpy.ndarray
        The observation points' DOFs per unit load ``(n_freq, n_obs, n_load)`` and the
        boundary's ``(n_freq, 2 m, n_load)`` in m/N, and the observation points' rows of
        the interior response to the boundary ``(n_freq, n_obs, 2 m)`` (dimensionless for
        displacements).
    """
    n_freq = k.shape[0]
    u = np.empty((n_freq, obs_b.size, load_b.size), dtype=np.complex128)
    u_b = np.empty((n_freq, bnd.size, load_b.size), dtype=np.complex128)
    rows = np.empty((n_freq, obs_b.size, bnd.size), dtype=np.complex128)
    cell_kernel()[1](
        np.ascontiguousarray(k),
        bnd.astype(np.int64),
        inner.astype(np.int64),
        np.ascontiguousarray(condensed),
        points,
        load_b,
        load_p,
        obs_b,
        obs_p,
        u,
        u_b,
        rows,
    )
    return u, u_b, rows


def assembled(
    n_dof: int,
    span_nodes: NDArray[np.int64],
    span_blocks: NDArray[np.complex128],
    spring_dofs: NDArray[np.int64],
    spring_values: NDArray[np.complex128],
) -> NDArray[np.complex128]:
    """The cell stiffness assembled (as :meth:`railvib.track.cells.Cell.stiffness`).

    Parameters
    ----------
    n_dof : int
        DOFs of the cell (dimensionless count).
    span_nodes : numpy.ndarray
        ``(n_span, 2)``: the two nodes of each span (indices, dimensionless).
    span_blocks : numpy.ndarray
        ``(n_span, n_freq, 4, 4)``: their dynamic stiffness, SI units.
    spring_dofs : numpy.ndarray
        ``(n_spring, 2)``: the two DOFs of each spring (indices, dimensionless; -1: ground).
    spring_values : numpy.ndarray
        ``(n_spring, n_freq)``: their complex stiffness, SI units.

    Returns
    -------
    numpy.ndarray
        ``(n_freq, n_dof, n_dof)``, complex, SI units.
    """
    out = np.zeros((span_blocks.shape[1], n_dof, n_dof), dtype=np.complex128)
    cell_kernel()[3](span_nodes, span_blocks, spring_dofs, spring_values, out)
    return out


def propagated(
    step: NDArray[np.complex128], q: NDArray[np.complex128], n: int
) -> NDArray[np.complex128]:
    """``[q, step q, ..., step^n q]`` stacked, ``(n + 1, n_freq, m, n_load)``.

    Parameters
    ----------
    step : numpy.ndarray
        The wave step ``R`` or ``L``, ``(n_freq, m, m)``.
    q : numpy.ndarray
        Boundary displacements per load, ``(n_freq, m, n_load)``.
    n : int
        Steps (>= 0).

    Returns
    -------
    numpy.ndarray
        Complex, in the units of `q`.
    """
    out = np.empty((n + 1,) + q.shape, dtype=np.complex128)
    out[0] = q
    cell_kernel()[2](np.ascontiguousarray(step), int(n), out)
    return out


def euler_span(
    beta4: NDArray[np.complex128], closed_from: float, length: float, bending_stiffness: complex
) -> NDArray[np.complex128]:
    """An Euler span's exact dynamic stiffness (as :func:`railvib.track.cells.span_stiffness`).

    Parameters
    ----------
    beta4 : numpy.ndarray
        ``(m omega^2 - k_f) L^4 / EI*`` per frequency (dimensionless), ``(n_freq,)``.
    closed_from : float
        ``|beta4|`` from which the closed form is used (dimensionless); below it, the
        Krylov series of the transfer matrix.
    length : float
        Span length L in m.
    bending_stiffness : complex
        ``EI*`` in N m^2.

    Returns
    -------
    numpy.ndarray
        ``(n_freq, 4, 4)``, complex, SI units.
    """
    beta4 = np.ascontiguousarray(beta4, dtype=np.complex128)
    out = np.empty(beta4.shape + (4, 4), dtype=np.complex128)
    cell_kernel()[4](
        beta4,
        float(closed_from),
        float(length),
        complex(bending_stiffness),
        _INVERSE_FACTORIALS,
        out,
    )
    return out


def _abs2(z: complex) -> float:
    """``|z|^2``."""
    return z.real * z.real + z.imag * z.imag


def _lu_solve(a: Any, b: Any, hi: Any) -> None:
    """``b <- a^-1 b`` in place (`a` overwritten): elimination with partial pivoting.

    Each row's last nonzero column is tracked in the scratch `hi` (a cell's matrix is
    nearly banded), so that the products with exact zeros, which change nothing, are
    skipped.
    """
    n = a.shape[0]
    r = b.shape[1]
    for i in range(n):
        hi[i] = i
        for q in range(n - 1, i, -1):
            if a[i, q] != 0.0:
                hi[i] = q
                break
    for j in range(n):
        p = j
        best = abs(a[j, j].real) + abs(a[j, j].imag)
        for i in range(j + 1, n):
            v = abs(a[i, j].real) + abs(a[i, j].imag)
            if v > best:
                best = v
                p = i
        if p != j:
            for q in range(n):
                t = a[j, q]
                a[j, q] = a[p, q]
                a[p, q] = t
            for q in range(r):
                t = b[j, q]
                b[j, q] = b[p, q]
                b[p, q] = t
            t_hi = hi[j]
            hi[j] = hi[p]
            hi[p] = t_hi
        end = max(hi[j], j) + 1
        inv = 1.0 / a[j, j]
        for i in range(j + 1, n):
            g = a[i, j] * inv
            if g != 0.0:
                for q in range(j + 1, end):
                    a[i, q] -= g * a[j, q]
                for q in range(r):
                    b[i, q] -= g * b[j, q]
                if end - 1 > hi[i]:
                    hi[i] = end - 1
    for j in range(n - 1, -1, -1):
        inv = 1.0 / a[j, j]
        end = max(hi[j], j) + 1
        for q in range(r):
            v = b[j, q]
            for i in range(j + 1, end):
                v -= a[j, i] * b[i, q]
            b[j, q] = v * inv


def _eq_solve(a: Any, b: Any, s: Any, hi: Any) -> None:
    """``b <- a^-1 b`` in place, rows and columns scaled by ``|diag a|^(-1/2)`` (`a` overwritten).

    `s` and `hi` are scratch (at least as long as `a`).
    """
    n = a.shape[0]
    for i in range(n):
        s[i] = 1.0 / np.sqrt(abs(a[i, i]))
    for i in range(n):
        for j in range(n):
            a[i, j] *= s[i] * s[j]
        for q in range(b.shape[1]):
            b[i, q] *= s[i]
    _lu_solve(a, b, hi)
    for i in range(n):
        for q in range(b.shape[1]):
            b[i, q] *= s[i]


def _waves_points(  # noqa: C901, PLR0912, PLR0915 - one loop body per frequency
    k: Any,
    bnd: Any,
    inner: Any,
    max_doublings: int,
    converged: float,
    blocks: Any,
    unconverged: Any,
) -> None:
    """Condensation, doubling and wave steps of each frequency (:func:`wave_chain`)."""
    n_freq = k.shape[0]
    nb = bnd.size
    ni = inner.size
    m = nb // 2
    kii = np.empty((ni, ni), dtype=np.complex128)
    x = np.empty((ni, nb), dtype=np.complex128)
    kbb = np.empty((nb, nb), dtype=np.complex128)
    a = np.empty((m, m), dtype=np.complex128)
    b = np.empty((m, m), dtype=np.complex128)
    c = np.empty((m, m), dtype=np.complex128)
    e = np.empty((m, m), dtype=np.complex128)
    sm = np.empty((m, m), dtype=np.complex128)
    y = np.empty((m, 2 * m), dtype=np.complex128)
    s = np.empty(m)
    scratch = np.empty(max(ni, m))
    hi = np.empty(max(ni, m), dtype=np.int64)
    z = np.empty((m, m), dtype=np.complex128)
    for f in range(n_freq):
        for i in range(ni):
            for j in range(ni):
                kii[i, j] = k[f, inner[i], inner[j]]
            for j in range(nb):
                x[i, j] = k[f, inner[i], bnd[j]]
        if ni:
            _eq_solve(kii, x, scratch, hi)
        for i in range(nb):
            for j in range(nb):
                v = k[f, bnd[i], bnd[j]]
                for q in range(ni):
                    v -= k[f, bnd[i], inner[q]] * x[q, j]
                kbb[i, j] = v
        for i in range(m):
            for j in range(m):
                blocks[0, f, i, j] = kbb[i, j]
                blocks[1, f, i, j] = kbb[i, m + j]
                blocks[2, f, i, j] = kbb[m + i, j]
                blocks[3, f, i, j] = kbb[m + i, m + j]
        # the doubling, equilibrated by the boundary DOFs' diagonal of A + E; a cell is
        # reciprocal (C = B^T, A and E symmetric), so each step is A' = A - B S^-1 B^T,
        # E' = E - B^T S^-1 B (their upper triangles) and B' = -B S^-1 B: three products
        for i in range(m):
            s[i] = 1.0 / np.sqrt(abs(kbb[i, i] + kbb[m + i, m + i]))
        for i in range(m):
            for j in range(m):
                w = s[i] * s[j]
                a[i, j] = 0.5 * (kbb[i, j] + kbb[j, i]) * w
                b[i, j] = kbb[i, m + j] * w
                e[i, j] = 0.5 * (kbb[m + i, m + j] + kbb[m + j, m + i]) * w
        done = False
        for _ in range(max_doublings):
            for i in range(m):
                for j in range(m):
                    sm[i, j] = e[i, j] + a[i, j]
                    y[i, j] = b[j, i]
                    y[i, m + j] = b[i, j]
            _lu_solve(sm, y, hi)  # y = S^-1 [B^T, B]
            size = 0.0
            coupling = 0.0
            for i in range(m):  # the new B into c (scratch), A and E in place
                for j in range(m):
                    vb = 0.0j
                    for q in range(m):
                        vb -= b[i, q] * y[q, m + j]
                    c[i, j] = vb
                    coupling = max(coupling, _abs2(vb))
            for i in range(m):
                for j in range(i, m):
                    va = a[i, j]
                    ve = e[i, j]
                    for q in range(m):
                        va -= b[i, q] * y[q, j]
                        ve -= b[q, i] * y[q, m + j]
                    sm[i, j] = va
                    z[i, j] = ve
            for i in range(m):
                for j in range(i, m):
                    a[i, j] = sm[i, j]
                    a[j, i] = sm[i, j]
                    e[i, j] = z[i, j]
                    e[j, i] = z[i, j]
                    size = max(size, _abs2(sm[i, j]), _abs2(z[i, j]))
                for j in range(m):
                    b[i, j] = c[i, j]
            if coupling <= converged**2 * size:
                done = True
                break
        unconverged[f] = not done
        for i in range(m):
            for j in range(m):
                w = s[i] * s[j]
                blocks[4, f, i, j] = a[i, j] / w
                blocks[5, f, i, j] = e[i, j] / w
        # R = -(E + P_r)^-1 C, L = -(P_l + A)^-1 B
        for side in range(2):
            for i in range(m):
                for j in range(m):
                    if side == 0:
                        sm[i, j] = blocks[3, f, i, j] + blocks[4, f, i, j]
                        y[i, j] = blocks[2, f, i, j]
                    else:
                        sm[i, j] = blocks[5, f, i, j] + blocks[0, f, i, j]
                        y[i, j] = blocks[1, f, i, j]
            for i in range(m):
                for j in range(m):
                    z[i, j] = y[i, j]
            _eq_solve(sm, z, scratch, hi)
            for i in range(m):
                for j in range(m):
                    blocks[6 + side, f, i, j] = -z[i, j]


def _loaded_points(  # noqa: C901, PLR0912, PLR0913 - one loop body per frequency
    k: Any,
    bnd: Any,
    inner: Any,
    condensed: Any,
    points: Any,
    load_b: Any,
    load_p: Any,
    obs_b: Any,
    obs_p: Any,
    u: Any,
    u_b: Any,
    rows: Any,
) -> None:
    """The loaded cell at its points, frequency by frequency (:func:`loaded_points`)."""
    n_freq = k.shape[0]
    nb = bnd.size
    ni = inner.size
    n_p = points.size
    nl = load_b.size
    kii = np.empty((ni, ni), dtype=np.complex128)
    x = np.empty((ni, n_p), dtype=np.complex128)
    rp = np.empty((n_p, nb), dtype=np.complex128)
    s = np.empty((nb, nb), dtype=np.complex128)
    rhs = np.empty((nb, nl), dtype=np.complex128)
    scratch = np.empty(max(ni, nb))
    hi = np.empty(max(ni, nb), dtype=np.int64)
    for f in range(n_freq):
        if n_p:
            for i in range(ni):
                for j in range(ni):
                    kii[i, j] = k[f, inner[i], inner[j]]
                for p in range(n_p):
                    x[i, p] = 1.0 if points[p] == i else 0.0
            _eq_solve(kii, x, scratch, hi)  # K_ii^-1 at the points
        for p in range(n_p):  # their rows: -X^T K_ib
            for j in range(nb):
                v = 0.0j
                for i in range(ni):
                    v -= x[i, p] * k[f, inner[i], bnd[j]]
                rp[p, j] = v
        for i in range(nb):
            for j in range(nb):
                s[i, j] = condensed[f, i, j]
            for q in range(nl):
                if load_b[q] >= 0:
                    rhs[i, q] = 1.0 if load_b[q] == i else 0.0
                else:
                    rhs[i, q] = rp[load_p[q], i]
        _eq_solve(s, rhs, scratch, hi)
        for i in range(nb):
            for q in range(nl):
                u_b[f, i, q] = rhs[i, q]
        for o in range(obs_b.size):
            for j in range(nb):
                if obs_b[o] >= 0:
                    rows[f, o, j] = 1.0 if obs_b[o] == j else 0.0
                else:
                    rows[f, o, j] = rp[obs_p[o], j]
            for q in range(nl):
                v = 0.0j
                for j in range(nb):
                    v += rows[f, o, j] * rhs[j, q]
                if obs_p[o] >= 0 and load_p[q] >= 0:
                    v += x[points[obs_p[o]], load_p[q]]
                u[f, o, q] = v


def _propagate_points(step: Any, n: int, out: Any) -> None:
    """``out[k + 1] = step out[k]`` for ``k < n`` at each frequency (:func:`propagated`)."""
    m = step.shape[1]
    n_load = out.shape[3]
    for f in range(step.shape[0]):
        for k in range(n):
            for i in range(m):
                for q in range(n_load):
                    v = 0.0j
                    for j in range(m):
                        v += step[f, i, j] * out[k, f, j, q]
                    out[k + 1, f, i, q] = v


def _assemble_points(
    span_nodes: Any, span_blocks: Any, spring_dofs: Any, spring_values: Any, out: Any
) -> None:
    """Add the spans and springs into `out` at each frequency (:func:`assembled`)."""
    for f in range(out.shape[0]):
        for s in range(span_nodes.shape[0]):
            for i in range(4):
                di = 2 * span_nodes[s, i // 2] + i % 2
                for j in range(4):
                    out[f, di, 2 * span_nodes[s, j // 2] + j % 2] += span_blocks[s, f, i, j]
        for s in range(spring_dofs.shape[0]):
            i = spring_dofs[s, 0]
            j = spring_dofs[s, 1]
            v = spring_values[s, f]
            out[f, i, i] += v
            if j >= 0:
                out[f, j, j] += v
                out[f, i, j] -= v
                out[f, j, i] -= v


def _span_points(  # noqa: PLR0915 - one loop body per frequency
    beta4: Any, closed_from: float, length: float, ei: complex, coeff: Any, out: Any
) -> None:
    """Dimensionless span stiffness of each frequency, scaled to SI (:func:`euler_span`).

    The closed form of :func:`railvib.track.beam.dynamic_stiffness` where ``|beta4| >=
    closed_from``, else :func:`railvib.track.cells._stiffness_from_transfer` of the
    Krylov series :func:`railvib.track.beam.krylov_series`, whose number of terms is taken
    from the largest ``|beta4|`` of the series frequencies, as there.
    """
    top = 0.0
    for f in range(beta4.size):
        v = abs(beta4[f])
        if v < closed_from and v > top:
            top = v
    n_terms = max(6, math.ceil((2.72 * top**0.25 + 34.0) / 4.0))
    factor = ei / length**3
    scale = np.array([1.0, length, 1.0, length])
    perm = np.array([0, 1, 3, 2])
    sign = np.array([1.0, 1.0, 1.0, -1.0])
    acc = np.empty(4, dtype=np.complex128)
    t = np.empty((4, 4), dtype=np.complex128)
    s = np.empty((4, 4), dtype=np.complex128)
    k = np.empty((4, 4), dtype=np.complex128)
    for f in range(beta4.size):
        b4 = beta4[f]
        if abs(b4) >= closed_from:  # the closed form, D = 1 - cos cosh
            b = b4**0.25
            c, sn = np.cos(b), np.sin(b)
            ch, sh = np.cosh(b), np.sinh(b)
            d = 1.0 - c * ch
            b2 = b * b
            k11 = b2 * b * (c * sh + sn * ch) / d
            k12 = b2 * sn * sh / d
            k13 = -(b2 * b) * (sh + sn) / d
            k14 = b2 * (ch - c) / d
            k22 = b * (sn * ch - c * sh) / d
            k24 = b * (sh - sn) / d
            k[0, 0], k[0, 1], k[0, 2], k[0, 3] = k11, k12, k13, k14
            k[1, 0], k[1, 1], k[1, 2], k[1, 3] = k12, k22, -k14, k24
            k[2, 0], k[2, 1], k[2, 2], k[2, 3] = k13, -k14, k11, -k12
            k[3, 0], k[3, 1], k[3, 2], k[3, 3] = k14, k24, -k12, k22
        else:  # the series transfer matrix, its blocks inverted
            for j in range(4):
                acc[j] = 0.0
            for q in range(n_terms - 1, -1, -1):  # Horner in beta4 for the four sums
                for j in range(4):
                    acc[j] = acc[j] * b4 + coeff[q, j]
            for r in range(4):
                for col in range(4):
                    t[r, col] = acc[col - r] if col >= r else b4 * acc[col - r + 4]
            for i in range(4):
                for j in range(4):
                    s[i, j] = t[perm[i], perm[j]] * (sign[i] * sign[j])
            det = s[0, 2] * s[1, 3] - s[0, 3] * s[1, 2]
            k[0, 2] = s[1, 3] / det  # k_ab = s_ab^-1
            k[0, 3] = -s[0, 3] / det
            k[1, 2] = -s[1, 2] / det
            k[1, 3] = s[0, 2] / det
            for i in range(2):
                for j in range(2):
                    k[i, j] = -(k[i, 2] * s[0, j] + k[i, 3] * s[1, j])  # -k_ab s_aa
                    k[2 + i, 2 + j] = -(s[2 + i, 2] * k[0, 2 + j] + s[2 + i, 3] * k[1, 2 + j])
            for i in range(2):
                for j in range(2):  # k_ba = -s_ba - k_bb s_aa
                    k[2 + i, j] = -s[2 + i, j] - (k[2 + i, 2] * s[0, j] + k[2 + i, 3] * s[1, j])
        for i in range(4):
            for j in range(4):
                out[f, i, j] = k[i, j] * (scale[i] * scale[j]) * factor


#: the plain Python functions (the kernel before compilation: the same numbers, slowly)
_PLAIN = {name: globals()[name] for name in _FUNCTIONS}
