"""A slab track's whole receptance path compiled (numba), one pass over batches of frequencies.

:mod:`railvib.track.compiled_cells` compiles the cell solver's steps one by one, a
frequency at a time; between them the cell matrices of a block of frequencies go through
memory and through Python, and each step on 4 x 4 blocks waits on its own latency. Here
the whole path of :meth:`railvib.track.slab.SlabTrack.receptance` is one kernel, over
batches of :data:`BATCH` frequencies in structure-of-arrays form (a frequency a lane, the
lane the innermost, contiguous axis of every array, so that each operation is a loop over
the batch that LLVM turns into vector instructions, as in :mod:`railvib.track.compiled`):

1. the spans' exact Euler stiffness, once per distinct (beam, length) of the two cells
   (the closed form, or the Krylov series of the transfer matrix below ``|beta L| = 2``,
   as :func:`railvib.track.cells.span_stiffness`);
2. the cell without the load and observation nodes assembled and condensed onto its
   boundary, the doubling of the boundary blocks to the semi-infinite chains (the
   symmetric step of a reciprocal cell, as the compiled cell kernel) and the wave steps
   ``R``, ``L``;
3. the loaded cell (with the points' nodes) assembled and solved at its points with both
   chains attached, the boundary displacements propagated cell by cell, and the
   receptance between the points.

The dense solves are the reference's equilibrated ones (rows and columns scaled by
``|diag|^(-1/2)``) by elimination without row exchanges, on the structural nonzeros of
the matrix (a cell's matrices are nearly banded). A frequency where a pivot is weaker than
:data:`PIVOT_THRESHOLD` of its column, or where the doubling has not converged, is flagged
and solved again by the reference (:mod:`railvib.track.cells`, with partial pivoting), so
that every result is the pivoted algorithm's to rounding.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from railvib.jit import numba_jit

__all__ = ["BATCH", "PIVOT_THRESHOLD", "slab_kernel", "slab_receptance"]

#: frequencies a batch (the lanes of each operation)
BATCH = 32

#: a pivot smaller than this fraction of the largest entry below it in its column sends
#: the frequency to the pivoted reference (elimination without row exchanges grows its
#: entries by at most ``1 + 1 / threshold`` a step then)
PIVOT_THRESHOLD = 0.1

#: ``1 / (4k + j)!`` for ``k < 16``, ``j < 4``: the Krylov series' coefficients (a series
#: span has ``|beta L| < 2``: 10 terms at most)
_INVERSE_FACTORIALS = np.array(
    [[1.0 / math.factorial(4 * k + j) for j in range(4)] for k in range(16)]
)

_KERNEL: list[Any] = []

#: the point functions compiled, helpers first (each calls only those before it)
_FUNCTIONS = (
    "_pattern",
    "_solve",
    "_span_lane",
    "_assemble",
    "_doubling",
    "_propagate",
    "_batches",
)


def slab_kernel() -> Any:
    """The compiled kernel (numba, cached on disk), or None where numba is not installed."""
    if not _KERNEL:
        # the options of the rigid-base kernel (railvib.track.compiled._kernel): divisions
        # without a zero test (no branch in a vector loop), a * b + c as one FMA at most
        jit = numba_jit(error_model="numpy", fastmath={"contract"})
        if jit is None:
            _KERNEL.append(None)
        else:
            space = globals()
            for name in _FUNCTIONS:  # compiled at first call: callees resolve to these
                space[name] = jit(_PLAIN[name])
            _KERNEL.append(space[_FUNCTIONS[-1]])
    return _KERNEL[0]


def slab_receptance(
    beam_load: NDArray[np.complex128],
    beam_ei: NDArray[np.complex128],
    spring_values: NDArray[np.complex128],
    kinds: tuple[NDArray[np.int64], NDArray[np.float64]],
    waves_cell: tuple[NDArray[np.int64], ...],
    loaded_cell: tuple[NDArray[np.int64], ...],
    where: tuple[NDArray[np.int64], ...],
    offsets: NDArray[np.int64],
    max_doublings: int,
    converged: float,
    closed_from: float,
    kernel: Any = None,
) -> tuple[NDArray[np.complex128], NDArray[np.bool_]]:
    """Receptance between the points of a slab track at each frequency (module docstring).

    Parameters
    ----------
    beam_load : numpy.ndarray
        ``(2, n_freq)``: ``m omega^2 - k_f`` of the rail (row 0) and the slab (row 1), N/m^2.
    beam_ei : numpy.ndarray
        ``(2, n_freq)``: their ``EI*``, N m^2.
    spring_values : numpy.ndarray
        ``(n_values, n_freq)``: the springs' complex stiffness (N/m or N m/rad).
    kinds : (numpy.ndarray, numpy.ndarray)
        The distinct spans: each one's beam (0 rail, 1 slab; dimensionless) and length (m).
    waves_cell, loaded_cell : tuple of numpy.ndarray
        ``(spans, springs, boundary, interior)`` of the cell without the points and of the
        cell with them: ``spans (n_span, 3)``: the nodes and the kind of each span;
        ``springs (n_spring, 3)``: the two DOFs (-1: the ground) and the value row of each
        spring; the boundary DOFs (left then right) and the interior ones (indices,
        dimensionless).
    where : tuple of numpy.ndarray
        ``(points, load_b, load_p, obs_b, obs_p)`` of the loaded cell
        (``railvib.track.cells._where``; indices, dimensionless).
    offsets : numpy.ndarray
        ``(n_obs, n_load)``: cells from each load's to each observation point's (count).
    max_doublings : int
        Doublings at most (count).
    converged : float
        ``max|B_k| / max|A_k|`` below which a frequency's doubling has converged (-).
    closed_from : float
        ``|beta4|`` of a span from which its closed form is used (dimensionless).
    kernel : callable, optional
        The batch kernel (default: the compiled one; the plain Python ``_batches`` gives
        the same numbers, slowly).

    Returns
    -------
    receptance : numpy.ndarray
        ``(n_freq, n_obs, n_load)``, m/N (per unit load on the points' DOFs).
    bad : numpy.ndarray of bool
        ``(n_freq,)``: frequencies left to the reference (a weak pivot, or a doubling not
        converged); their receptance here is not a result.
    """
    n_freq = beam_load.shape[1]
    out = np.empty((n_freq, where[3].size, where[1].size), dtype=np.complex128)
    bad = np.zeros(n_freq, dtype=np.bool_)
    run = slab_kernel() if kernel is None else kernel
    run(
        np.ascontiguousarray(beam_load, dtype=np.complex128),
        np.ascontiguousarray(beam_ei, dtype=np.complex128),
        np.ascontiguousarray(spring_values, dtype=np.complex128).reshape(-1, n_freq),
        kinds[0].astype(np.int64),
        kinds[1].astype(np.float64),
        *(np.ascontiguousarray(a, dtype=np.int64) for a in waves_cell),
        *(np.ascontiguousarray(a, dtype=np.int64) for a in loaded_cell),
        *(np.ascontiguousarray(a, dtype=np.int64) for a in where),
        np.ascontiguousarray(offsets, dtype=np.int64),
        int(max_doublings),
        float(converged),
        float(closed_from),
        PIVOT_THRESHOLD,
        _INVERSE_FACTORIALS,
        out,
        bad,
    )
    return out, bad


def _pattern(n_dof: Any, spans: Any, springs: Any, rows: Any, cols: Any) -> Any:
    """Structural nonzeros of the cell matrix's ``[rows, cols]`` after elimination.

    The pattern of the spans' 4 x 4 blocks and the springs, restricted to `rows` x `cols`
    (the same set for a square one), with the fill-in of elimination in their order.
    """
    full = np.zeros((n_dof, n_dof), dtype=np.bool_)
    for s in range(spans.shape[0]):
        for i in range(4):
            for j in range(4):
                full[2 * spans[s, i // 2] + i % 2, 2 * spans[s, j // 2] + j % 2] = True
    for s in range(springs.shape[0]):
        i, j = springs[s, 0], springs[s, 1]
        full[i, i] = True
        if j >= 0:
            full[j, j] = full[i, j] = full[j, i] = True
    nz = np.zeros((rows.size, cols.size), dtype=np.bool_)
    for i in range(rows.size):
        for j in range(cols.size):
            nz[i, j] = full[rows[i], cols[j]]
    if rows.size == cols.size:
        for j in range(rows.size):  # the fill-in of the elimination
            for i in range(j + 1, rows.size):
                if nz[i, j]:
                    for q in range(j + 1, rows.size):
                        if nz[j, q]:
                            nz[i, q] = True
    return nz


def _solve(a: Any, b: Any, nz: Any, n: int, flag: Any, pivot2: float, s: Any) -> None:
    """``b <- a^-1 b`` of each lane, equilibrated, by elimination without row exchanges.

    `a` ``(k, k, BATCH)`` is left as it is, `b` ``(k, r, BATCH)`` overwritten; `nz` the
    structural nonzeros of `a` with its fill-in (:func:`_pattern`); `n` lanes in use. A
    lane with a pivot below ``sqrt(pivot2)`` of an entry under it gets ``flag = 1``. `s`
    ``(k, BATCH)`` is scratch. The real and imaginary parts are held apart (each
    update a loop of real operations over the lanes, which LLVM vectorises).
    """
    k = a.shape[0]
    r = b.shape[1]
    lanes = a.shape[2]
    ur = np.empty((k, k, lanes))
    ui = np.empty((k, k, lanes))
    xr = np.empty((k, r, lanes))
    xi = np.empty((k, r, lanes))
    ivr = np.empty((k, lanes))
    ivi = np.empty((k, lanes))
    for i in range(k):
        for lane in range(n):
            d = a[i, i, lane]
            s[i, lane] = 1.0 / math.sqrt(math.sqrt(d.real * d.real + d.imag * d.imag))
    for i in range(k):
        for j in range(k):
            if nz[i, j]:
                for lane in range(n):
                    w = s[i, lane] * s[j, lane]
                    ur[i, j, lane] = a[i, j, lane].real * w
                    ui[i, j, lane] = a[i, j, lane].imag * w
        for q in range(r):
            for lane in range(n):
                xr[i, q, lane] = b[i, q, lane].real * s[i, lane]
                xi[i, q, lane] = b[i, q, lane].imag * s[i, lane]
    for j in range(k):
        for lane in range(n):
            pr, pi = ur[j, j, lane], ui[j, j, lane]
            den = 1.0 / (pr * pr + pi * pi)
            ivr[j, lane] = pr * den
            ivi[j, lane] = -pi * den
        for i in range(j + 1, k):
            if not nz[i, j]:
                continue
            for lane in range(n):
                pr, pi = ur[j, j, lane], ui[j, j, lane]
                gr, gi = ur[i, j, lane], ui[i, j, lane]
                weak = (gr * gr + gi * gi) * pivot2 > pr * pr + pi * pi
                flag[lane] = max(flag[lane], 1.0 if weak else 0.0)
                ur[i, j, lane] = gr * ivr[j, lane] - gi * ivi[j, lane]
                ui[i, j, lane] = gr * ivi[j, lane] + gi * ivr[j, lane]
            for q in range(j + 1, k):
                if nz[j, q]:
                    for lane in range(n):
                        gr, gi = ur[i, j, lane], ui[i, j, lane]
                        vr, vi = ur[j, q, lane], ui[j, q, lane]
                        ur[i, q, lane] = ur[i, q, lane] - (gr * vr - gi * vi)
                        ui[i, q, lane] = ui[i, q, lane] - (gr * vi + gi * vr)
            for q in range(r):
                for lane in range(n):
                    gr, gi = ur[i, j, lane], ui[i, j, lane]
                    vr, vi = xr[j, q, lane], xi[j, q, lane]
                    xr[i, q, lane] = xr[i, q, lane] - (gr * vr - gi * vi)
                    xi[i, q, lane] = xi[i, q, lane] - (gr * vi + gi * vr)
    for j in range(k - 1, -1, -1):
        for q in range(r):
            for i in range(j + 1, k):
                if nz[j, i]:
                    for lane in range(n):
                        gr, gi = ur[j, i, lane], ui[j, i, lane]
                        vr, vi = xr[i, q, lane], xi[i, q, lane]
                        xr[j, q, lane] = xr[j, q, lane] - (gr * vr - gi * vi)
                        xi[j, q, lane] = xi[j, q, lane] - (gr * vi + gi * vr)
            for lane in range(n):
                vr, vi = xr[j, q, lane], xi[j, q, lane]
                xr[j, q, lane] = vr * ivr[j, lane] - vi * ivi[j, lane]
                xi[j, q, lane] = vr * ivi[j, lane] + vi * ivr[j, lane]
    for i in range(k):
        for q in range(r):
            for lane in range(n):
                b[i, q, lane] = complex(xr[i, q, lane] * s[i, lane], xi[i, q, lane] * s[i, lane])


def _propagate(step: Any, q: Any, steps: int, n: int) -> None:
    """``q[t + 1] = step q[t]`` for ``t < steps`` in each lane (`q` ``(steps + 1, m, BATCH)``).

    Real and imaginary parts apart, as :func:`_solve`.
    """
    m = step.shape[0]
    lanes = step.shape[2]
    sr = np.empty((m, m, lanes))
    si = np.empty((m, m, lanes))
    vr = np.empty((steps + 1, m, lanes))
    vi = np.empty((steps + 1, m, lanes))
    for i in range(m):
        for j in range(m):
            for lane in range(n):
                sr[i, j, lane] = step[i, j, lane].real
                si[i, j, lane] = step[i, j, lane].imag
        for lane in range(n):
            vr[0, i, lane] = q[0, i, lane].real
            vi[0, i, lane] = q[0, i, lane].imag
    for t in range(steps):
        for i in range(m):
            for lane in range(n):
                vr[t + 1, i, lane] = 0.0
                vi[t + 1, i, lane] = 0.0
            for j in range(m):
                for lane in range(n):
                    gr, gi = sr[i, j, lane], si[i, j, lane]
                    ur, ui = vr[t, j, lane], vi[t, j, lane]
                    vr[t + 1, i, lane] = vr[t + 1, i, lane] + (gr * ur - gi * ui)
                    vi[t + 1, i, lane] = vi[t + 1, i, lane] + (gr * ui + gi * ur)
        for i in range(m):
            for lane in range(n):
                q[t + 1, i, lane] = complex(vr[t + 1, i, lane], vi[t + 1, i, lane])


def _span_lane(b4: complex, closed_from: float, n_terms: int, coeff: Any, k: Any) -> None:
    """The dimensionless span stiffness (EI = L = 1) of one frequency into `k` ``(4, 4)``.

    As ``railvib.track.compiled_cells._span_points``: the closed form where ``|beta4| >=
    closed_from`` (its ``cos``, ``cosh``, ... of ``z = beta4^(1/4)``, the principal root,
    from real ones), else the blocks of the Krylov series transfer matrix inverted.
    """
    if abs(b4) >= closed_from:
        br, bi = b4.real, b4.imag
        r = math.sqrt(0.5 * (abs(br) + math.sqrt(br * br + bi * bi)))  # two principal roots
        h = 0.5 * bi / r
        zr, zi = (r, h) if br >= 0.0 else (abs(h), math.copysign(r, bi))
        r = math.sqrt(0.5 * (abs(zr) + math.sqrt(zr * zr + zi * zi)))
        h = 0.5 * zi / r
        x, y = (r, h) if zr >= 0.0 else (abs(h), math.copysign(r, zi))
        cx, sx, cy, sy = math.cos(x), math.sin(x), math.cos(y), math.sin(y)
        chx, shx, chy, shy = math.cosh(x), math.sinh(x), math.cosh(y), math.sinh(y)
        c = complex(cx * chy, -sx * shy)
        sn = complex(sx * chy, cx * shy)
        ch = complex(chx * cy, shx * sy)
        sh = complex(shx * cy, chx * sy)
        b = complex(x, y)
        d = 1.0 - c * ch
        den = 1.0 / (d.real * d.real + d.imag * d.imag)
        inv = complex(d.real * den, -d.imag * den)  # 1 / D, one division for the six
        b2 = b * b
        k11 = b2 * b * (c * sh + sn * ch) * inv
        k12 = b2 * sn * sh * inv
        k13 = -(b2 * b) * (sh + sn) * inv
        k14 = b2 * (ch - c) * inv
        k22 = b * (sn * ch - c * sh) * inv
        k24 = b * (sh - sn) * inv
        k[0, 0], k[0, 1], k[0, 2], k[0, 3] = k11, k12, k13, k14
        k[1, 0], k[1, 1], k[1, 2], k[1, 3] = k12, k22, -k14, k24
        k[2, 0], k[2, 1], k[2, 2], k[2, 3] = k13, -k14, k11, -k12
        k[3, 0], k[3, 1], k[3, 2], k[3, 3] = k14, k24, -k12, k22
        return
    a0 = a1 = a2 = a3 = 0.0j  # Horner in beta4 for the four sums
    for q in range(n_terms - 1, -1, -1):
        a0 = a0 * b4 + coeff[q, 0]
        a1 = a1 * b4 + coeff[q, 1]
        a2 = a2 * b4 + coeff[q, 2]
        a3 = a3 * b4 + coeff[q, 3]
    # the transfer matrix t[r, c] = acc[c - r] (c >= r), b4 acc[c - r + 4] below; its
    # rows and columns 2, 3 exchanged and row and column 3 negated: s
    s00, s01, s02, s03 = a0, a1, a3, -a2
    s10, s11, s12, s13 = b4 * a3, a0, a2, -a1
    s20, s21, s22, s23 = b4 * a1, b4 * a2, a0, -b4 * a3
    s30, s31, s32, s33 = -b4 * a2, -b4 * a3, -a1, a0
    det = s02 * s13 - s03 * s12
    den = 1.0 / (det.real * det.real + det.imag * det.imag)
    inv = complex(det.real * den, -det.imag * den)
    k[0, 2] = s13 * inv  # k_ab = s_ab^-1
    k[0, 3] = -s03 * inv
    k[1, 2] = -s12 * inv
    k[1, 3] = s02 * inv
    k[0, 0] = -(k[0, 2] * s00 + k[0, 3] * s10)  # k_aa = -k_ab s_aa
    k[0, 1] = -(k[0, 2] * s01 + k[0, 3] * s11)
    k[1, 0] = -(k[1, 2] * s00 + k[1, 3] * s10)
    k[1, 1] = -(k[1, 2] * s01 + k[1, 3] * s11)
    k[2, 2] = -(s22 * k[0, 2] + s23 * k[1, 2])  # k_bb = -s_bb k_ab
    k[2, 3] = -(s22 * k[0, 3] + s23 * k[1, 3])
    k[3, 2] = -(s32 * k[0, 2] + s33 * k[1, 2])
    k[3, 3] = -(s32 * k[0, 3] + s33 * k[1, 3])
    k[2, 0] = -s20 - (k[2, 2] * s00 + k[2, 3] * s10)  # k_ba = -s_ba - k_bb s_aa
    k[2, 1] = -s21 - (k[2, 2] * s01 + k[2, 3] * s11)
    k[3, 0] = -s30 - (k[3, 2] * s00 + k[3, 3] * s10)
    k[3, 1] = -s31 - (k[3, 2] * s01 + k[3, 3] * s11)


def _assemble(out: Any, spans: Any, span_k: Any, springs: Any, values: Any, n: int) -> None:
    """The cell matrix of each lane into `out` ``(n_dof, n_dof, BATCH)`` (zeroed first).

    `span_k` ``(n_kind, 4, 4, BATCH)`` holds each span kind's stiffness, `values`
    ``(n_values, BATCH)`` the springs'.
    """
    for i in range(out.shape[0]):
        for j in range(out.shape[1]):
            for lane in range(n):
                out[i, j, lane] = 0.0
    for s in range(spans.shape[0]):
        kind = spans[s, 2]
        for i in range(4):
            di = 2 * spans[s, i // 2] + i % 2
            for j in range(4):
                dj = 2 * spans[s, j // 2] + j % 2
                for lane in range(n):
                    out[di, dj, lane] = out[di, dj, lane] + span_k[kind, i, j, lane]
    for s in range(springs.shape[0]):
        i, j, v = springs[s, 0], springs[s, 1], springs[s, 2]
        for lane in range(n):
            out[i, i, lane] = out[i, i, lane] + values[v, lane]
        if j >= 0:
            for lane in range(n):
                out[j, j, lane] = out[j, j, lane] + values[v, lane]
                out[i, j, lane] = out[i, j, lane] - values[v, lane]
                out[j, i, lane] = out[j, i, lane] - values[v, lane]


def _doubling(  # noqa: C901, PLR0912, PLR0913, PLR0915 - the step written out
    a: Any,
    b: Any,
    e: Any,
    p_r: Any,
    p_l: Any,
    n: int,
    max_doublings: int,
    conv2: float,
    pivot2: float,
    flag: Any,
) -> None:
    """The doubling of each lane's equilibrated boundary blocks (``(m, m, BATCH)`` each).

    The symmetric step of a reciprocal cell (``C = B^T``): ``A' = A - B S^-1 B^T``, ``E' =
    E - B^T S^-1 B`` (upper triangles), ``B' = -B S^-1 B``, ``S = A + E`` solved by
    elimination without row exchanges (`flag` = 1 at a weak pivot), until ``max|B'|^2 <=
    conv2 max(|A'|^2, |E'|^2)`` in every lane (or `max_doublings`; `flag` = 1 for a lane
    not converged). `P_r`, `P_l` receive each lane's ``A'``, ``E'`` at its convergence. The
    real and imaginary parts are held apart here (each update a loop of real operations
    over the lanes, which LLVM vectorises); `a`, `b`, `e` are not changed.
    """
    m = a.shape[0]
    lanes = a.shape[2]
    ar = np.empty((m, m, lanes))
    ai = np.empty((m, m, lanes))
    br = np.empty((m, m, lanes))
    bi = np.empty((m, m, lanes))
    er = np.empty((m, m, lanes))
    ei = np.empty((m, m, lanes))
    sr = np.empty((m, m, lanes))
    si = np.empty((m, m, lanes))
    yr = np.empty((m, 2 * m, lanes))
    yi = np.empty((m, 2 * m, lanes))
    ivr = np.empty((m, lanes))
    ivi = np.empty((m, lanes))
    size = np.empty(lanes)
    coupling = np.empty(lanes)
    done = np.zeros(lanes)
    for i in range(m):
        for j in range(m):
            for lane in range(n):
                ar[i, j, lane] = a[i, j, lane].real
                ai[i, j, lane] = a[i, j, lane].imag
                br[i, j, lane] = b[i, j, lane].real
                bi[i, j, lane] = b[i, j, lane].imag
                er[i, j, lane] = e[i, j, lane].real
                ei[i, j, lane] = e[i, j, lane].imag
    for _ in range(max_doublings):
        for i in range(m):
            for j in range(m):
                for lane in range(n):
                    sr[i, j, lane] = er[i, j, lane] + ar[i, j, lane]
                    si[i, j, lane] = ei[i, j, lane] + ai[i, j, lane]
                    yr[i, j, lane] = br[j, i, lane]
                    yi[i, j, lane] = bi[j, i, lane]
                    yr[i, m + j, lane] = br[i, j, lane]
                    yi[i, m + j, lane] = bi[i, j, lane]
        for j in range(m):  # y = S^-1 [B^T, B]: the elimination, the right-hand sides along
            for lane in range(n):
                pr, pi = sr[j, j, lane], si[j, j, lane]
                den = 1.0 / (pr * pr + pi * pi)
                ivr[j, lane] = pr * den
                ivi[j, lane] = -pi * den
            for i in range(j + 1, m):
                for lane in range(n):
                    pr, pi = sr[j, j, lane], si[j, j, lane]
                    xr, xi = sr[i, j, lane], si[i, j, lane]
                    weak = (xr * xr + xi * xi) * pivot2 > pr * pr + pi * pi
                    flag[lane] = max(flag[lane], 1.0 if weak else 0.0)
                    sr[i, j, lane] = xr * ivr[j, lane] - xi * ivi[j, lane]
                    si[i, j, lane] = xr * ivi[j, lane] + xi * ivr[j, lane]
                for q in range(j + 1, m):
                    for lane in range(n):
                        gr, gi = sr[i, j, lane], si[i, j, lane]
                        ur, ui = sr[j, q, lane], si[j, q, lane]
                        sr[i, q, lane] = sr[i, q, lane] - (gr * ur - gi * ui)
                        si[i, q, lane] = si[i, q, lane] - (gr * ui + gi * ur)
                for q in range(2 * m):
                    for lane in range(n):
                        gr, gi = sr[i, j, lane], si[i, j, lane]
                        ur, ui = yr[j, q, lane], yi[j, q, lane]
                        yr[i, q, lane] = yr[i, q, lane] - (gr * ur - gi * ui)
                        yi[i, q, lane] = yi[i, q, lane] - (gr * ui + gi * ur)
        for j in range(m - 1, -1, -1):
            for q in range(2 * m):
                for i in range(j + 1, m):
                    for lane in range(n):
                        gr, gi = sr[j, i, lane], si[j, i, lane]
                        ur, ui = yr[i, q, lane], yi[i, q, lane]
                        yr[j, q, lane] = yr[j, q, lane] - (gr * ur - gi * ui)
                        yi[j, q, lane] = yi[j, q, lane] - (gr * ui + gi * ur)
                for lane in range(n):
                    ur, ui = yr[j, q, lane], yi[j, q, lane]
                    yr[j, q, lane] = ur * ivr[j, lane] - ui * ivi[j, lane]
                    yi[j, q, lane] = ur * ivi[j, lane] + ui * ivr[j, lane]
        for lane in range(n):
            size[lane] = 0.0
            coupling[lane] = 0.0
        # the new A and E (upper triangles) into s, the new B into the B^T columns of y
        # (after they are used): A' = A - B y1, E' = E - B^T y2, B' = -B y2
        for i in range(m):
            for j in range(i, m):
                for lane in range(n):
                    sr[i, j, lane] = ar[i, j, lane]
                    si[i, j, lane] = ai[i, j, lane]
                    ivr[0, lane] = er[i, j, lane]  # (ivr, ivi: scratch now)
                    ivi[0, lane] = ei[i, j, lane]
                for q in range(m):
                    for lane in range(n):
                        gr, gi = br[i, q, lane], bi[i, q, lane]
                        ur, ui = yr[q, j, lane], yi[q, j, lane]
                        sr[i, j, lane] = sr[i, j, lane] - (gr * ur - gi * ui)
                        si[i, j, lane] = si[i, j, lane] - (gr * ui + gi * ur)
                        gr, gi = br[q, i, lane], bi[q, i, lane]
                        ur, ui = yr[q, m + j, lane], yi[q, m + j, lane]
                        ivr[0, lane] = ivr[0, lane] - (gr * ur - gi * ui)
                        ivi[0, lane] = ivi[0, lane] - (gr * ui + gi * ur)
                for lane in range(n):
                    er[i, j, lane] = ivr[0, lane]  # E's upper triangle: no longer read
                    ei[i, j, lane] = ivi[0, lane]
                    v = max(
                        sr[i, j, lane] * sr[i, j, lane] + si[i, j, lane] * si[i, j, lane],
                        ivr[0, lane] * ivr[0, lane] + ivi[0, lane] * ivi[0, lane],
                    )
                    size[lane] = max(size[lane], v)
        for i in range(m):
            for j in range(m):
                for lane in range(n):
                    yr[j, i, lane] = 0.0  # column i of y1 (= S^-1 B^T) is done with
                    yi[j, i, lane] = 0.0
                for q in range(m):
                    for lane in range(n):
                        gr, gi = br[i, q, lane], bi[i, q, lane]
                        ur, ui = yr[q, m + j, lane], yi[q, m + j, lane]
                        yr[j, i, lane] = yr[j, i, lane] - (gr * ur - gi * ui)
                        yi[j, i, lane] = yi[j, i, lane] - (gr * ui + gi * ur)
                for lane in range(n):
                    v = yr[j, i, lane] * yr[j, i, lane] + yi[j, i, lane] * yi[j, i, lane]
                    coupling[lane] = max(coupling[lane], v)
        for i in range(m):
            for j in range(m):
                lo, hi = min(i, j), max(i, j)
                for lane in range(n):
                    ar[i, j, lane] = sr[lo, hi, lane]
                    ai[i, j, lane] = si[lo, hi, lane]
                    br[i, j, lane] = yr[j, i, lane]
                    bi[i, j, lane] = yi[j, i, lane]
        for i in range(m):
            for j in range(i + 1, m):
                for lane in range(n):
                    er[j, i, lane] = er[i, j, lane]
                    ei[j, i, lane] = ei[i, j, lane]
        all_done = True
        for lane in range(n):
            if done[lane] == 0.0 and coupling[lane] <= conv2 * size[lane]:
                done[lane] = 1.0
                for i in range(m):
                    for j in range(m):
                        p_r[i, j, lane] = complex(ar[i, j, lane], ai[i, j, lane])
                        p_l[i, j, lane] = complex(er[i, j, lane], ei[i, j, lane])
            all_done = all_done and done[lane] != 0.0
        if all_done:
            break
    for lane in range(n):
        if done[lane] == 0.0:
            flag[lane] = 1.0  # not converged: the reference warns


def _batches(  # noqa: C901, PLR0912, PLR0913, PLR0915 - the stages of one batch, written out
    beam_load: Any,
    beam_ei: Any,
    spring_values: Any,
    kind_beam: Any,
    kind_length: Any,
    w_spans: Any,
    w_springs: Any,
    w_bnd: Any,
    w_inner: Any,
    l_spans: Any,
    l_springs: Any,
    l_bnd: Any,
    l_inner: Any,
    points: Any,
    load_b: Any,
    load_p: Any,
    obs_b: Any,
    obs_p: Any,
    offsets: Any,
    max_doublings: int,
    converged: float,
    closed_from: float,
    pivot_threshold: float,
    coeff: Any,
    out: Any,
    bad: Any,
) -> None:
    """The kernel: each batch's spans, waves and receptance (:func:`slab_receptance`)."""
    lanes = BATCH
    n_freq = beam_load.shape[1]
    n_kind = kind_beam.size
    n_val = spring_values.shape[0]
    nb = w_bnd.size
    m = nb // 2
    nwi = w_inner.size
    nli = l_inner.size
    n_p = points.size
    n_load = load_b.size
    n_obs = obs_b.size
    pivot2 = pivot_threshold * pivot_threshold
    conv2 = converged * converged
    n_dof_w = nb + nwi  # the boundary and the interior: every DOF of a cell
    n_dof_l = l_bnd.size + nli
    # the structural patterns: the interiors (with fill-in) and their coupling to the boundary
    nz_wi = _pattern(n_dof_w, w_spans, w_springs, w_inner, w_inner)
    nz_li = _pattern(n_dof_l, l_spans, l_springs, l_inner, l_inner)
    dense_m = np.ones((m, m), dtype=np.bool_)
    dense_b = np.ones((nb, nb), dtype=np.bool_)
    # steps of each load's boundary displacements: right and left, to its farthest point
    right_steps = np.zeros(n_load, dtype=np.int64)
    left_steps = np.zeros(n_load, dtype=np.int64)
    for j in range(n_load):
        for i in range(n_obs):
            right_steps[j] = max(right_steps[j], offsets[i, j])
            left_steps[j] = max(left_steps[j], -offsets[i, j])
    max_steps = max(right_steps.max(), left_steps.max()) if n_load else 0
    # the batch's arrays, the lane last
    c16 = np.complex128
    span_k = np.empty((n_kind, 4, 4, lanes), dtype=c16)
    values = np.empty((n_val, lanes), dtype=c16)
    kw = np.empty((n_dof_w, n_dof_w, lanes), dtype=c16)
    kl = np.empty((n_dof_l, n_dof_l, lanes), dtype=c16)
    kii_w = np.empty((nwi, nwi, lanes), dtype=c16)
    kii_l = np.empty((nli, nli, lanes), dtype=c16)
    xw = np.empty((nwi, nb, lanes), dtype=c16)
    kbb = np.empty((nb, nb, lanes), dtype=c16)
    a = np.empty((m, m, lanes), dtype=c16)
    b = np.empty((m, m, lanes), dtype=c16)
    e = np.empty((m, m, lanes), dtype=c16)
    sm = np.empty((m, m, lanes), dtype=c16)
    p_r = np.empty((m, m, lanes), dtype=c16)
    p_l = np.empty((m, m, lanes), dtype=c16)
    r_step = np.empty((m, m, lanes), dtype=c16)
    l_step = np.empty((m, m, lanes), dtype=c16)
    xl = np.empty((nli, n_p, lanes), dtype=c16)
    rp = np.empty((n_p, nb, lanes), dtype=c16)
    cond = np.empty((nb, nb, lanes), dtype=c16)
    ub = np.empty((nb, n_load, lanes), dtype=c16)
    rows = np.empty((n_obs, nb, lanes), dtype=c16)
    qr = np.empty((max_steps + 1, m, lanes), dtype=c16)
    ql = np.empty((max_steps + 1, m, lanes), dtype=c16)
    res = np.empty((n_obs, n_load, lanes), dtype=c16)
    s = np.empty((max(nb, nwi, nli), lanes))
    flag = np.empty(lanes)
    bs = np.empty((m, lanes))
    kl4 = np.empty((4, 4), dtype=c16)
    for start in range(0, n_freq, lanes):
        n = min(lanes, n_freq - start)
        for lane in range(n):
            flag[lane] = 0.0
        # -- 1. the spans of each kind, lane by lane (libm's cos, cosh: scalar)
        for kind in range(n_kind):
            beam = kind_beam[kind]
            length = kind_length[kind]
            l4 = length**4
            top = 0.0  # the series' longest term count, from its largest |beta4|
            for lane in range(n):
                v = abs(beam_load[beam, start + lane] * l4 / beam_ei[beam, start + lane])
                if v < closed_from and v > top:
                    top = v
            n_terms = max(6, math.ceil((2.72 * top**0.25 + 34.0) / 4.0))
            scale = (1.0, length, 1.0, length)
            for lane in range(n):
                ei = beam_ei[beam, start + lane]
                _span_lane(
                    beam_load[beam, start + lane] * l4 / ei, closed_from, n_terms, coeff, kl4
                )
                factor = ei / length**3
                for i in range(4):
                    for j in range(4):
                        span_k[kind, i, j, lane] = kl4[i, j] * (scale[i] * scale[j]) * factor
        for v in range(n_val):
            for lane in range(n):
                values[v, lane] = spring_values[v, start + lane]
        # -- 2. the waves' cell, condensed onto its boundary
        _assemble(kw, w_spans, span_k, w_springs, values, n)
        for i in range(nwi):
            for j in range(nwi):
                for lane in range(n):
                    kii_w[i, j, lane] = kw[w_inner[i], w_inner[j], lane]
            for j in range(nb):
                for lane in range(n):
                    xw[i, j, lane] = kw[w_inner[i], w_bnd[j], lane]
        if nwi:
            _solve(kii_w, xw, nz_wi, n, flag, pivot2, s)
        for i in range(nb):
            for j in range(nb):
                for lane in range(n):
                    kbb[i, j, lane] = kw[w_bnd[i], w_bnd[j], lane]
                for q in range(nwi):
                    kq = w_inner[q]
                    for lane in range(n):
                        kbb[i, j, lane] = kbb[i, j, lane] - kw[w_bnd[i], kq, lane] * xw[q, j, lane]
        # -- the doubling, equilibrated by the boundary's diagonal of A + E (symmetric step)
        for i in range(m):
            for lane in range(n):
                d = kbb[i, i, lane] + kbb[m + i, m + i, lane]
                bs[i, lane] = 1.0 / math.sqrt(math.sqrt(d.real * d.real + d.imag * d.imag))
        for i in range(m):
            for j in range(m):
                for lane in range(n):
                    w = bs[i, lane] * bs[j, lane]
                    a[i, j, lane] = 0.5 * (kbb[i, j, lane] + kbb[j, i, lane]) * w
                    b[i, j, lane] = kbb[i, m + j, lane] * w
                    e[i, j, lane] = 0.5 * (kbb[m + i, m + j, lane] + kbb[m + j, m + i, lane]) * w
        _doubling(a, b, e, p_r, p_l, n, max_doublings, conv2, pivot2, flag)
        for i in range(m):
            for j in range(m):
                for lane in range(n):
                    w = bs[i, lane] * bs[j, lane]
                    p_r[i, j, lane] = p_r[i, j, lane] / w
                    p_l[i, j, lane] = p_l[i, j, lane] / w
        # R = -(E + P_r)^-1 C, L = -(P_l + A)^-1 B (C = B^T of the cell, unscaled)
        for i in range(m):
            for j in range(m):
                for lane in range(n):
                    sm[i, j, lane] = kbb[m + i, m + j, lane] + p_r[i, j, lane]
                    r_step[i, j, lane] = -kbb[m + i, j, lane]
        _solve(sm, r_step, dense_m, n, flag, pivot2, s)
        for i in range(m):
            for j in range(m):
                for lane in range(n):
                    sm[i, j, lane] = p_l[i, j, lane] + kbb[i, j, lane]
                    l_step[i, j, lane] = -kbb[i, m + j, lane]
        _solve(sm, l_step, dense_m, n, flag, pivot2, s)
        # -- 3. the loaded cell at its points, with both chains
        _assemble(kl, l_spans, span_k, l_springs, values, n)
        if n_p:
            for i in range(nli):
                for j in range(nli):
                    for lane in range(n):
                        kii_l[i, j, lane] = kl[l_inner[i], l_inner[j], lane]
                for p in range(n_p):
                    for lane in range(n):
                        xl[i, p, lane] = 1.0 if points[p] == i else 0.0
            _solve(kii_l, xl, nz_li, n, flag, pivot2, s)  # K_ii^-1 at the points
        for p in range(n_p):  # their rows: -X^T K_ib
            for j in range(nb):
                for lane in range(n):
                    rp[p, j, lane] = 0.0
                for i in range(nli):
                    ki = l_inner[i]
                    kj = l_bnd[j]
                    for lane in range(n):
                        rp[p, j, lane] = rp[p, j, lane] - xl[i, p, lane] * kl[ki, kj, lane]
        for i in range(m):
            for j in range(m):
                for lane in range(n):
                    cond[i, j, lane] = kbb[i, j, lane] + p_l[i, j, lane]
                    cond[i, m + j, lane] = kbb[i, m + j, lane]
                    cond[m + i, j, lane] = kbb[m + i, j, lane]
                    cond[m + i, m + j, lane] = kbb[m + i, m + j, lane] + p_r[i, j, lane]
        for i in range(nb):
            for q in range(n_load):
                if load_b[q] >= 0:
                    for lane in range(n):
                        ub[i, q, lane] = 1.0 if load_b[q] == i else 0.0
                else:
                    for lane in range(n):
                        ub[i, q, lane] = rp[load_p[q], i, lane]
        _solve(cond, ub, dense_b, n, flag, pivot2, s)
        for o in range(n_obs):
            for j in range(nb):
                if obs_b[o] >= 0:
                    for lane in range(n):
                        rows[o, j, lane] = 1.0 if obs_b[o] == j else 0.0
                else:
                    for lane in range(n):
                        rows[o, j, lane] = rp[obs_p[o], j, lane]
        # -- the boundary displacements carried cell by cell, and the receptance
        for q in range(n_load):
            for i in range(m):
                for lane in range(n):
                    qr[0, i, lane] = ub[m + i, q, lane]
                    ql[0, i, lane] = ub[i, q, lane]
            _propagate(r_step, qr, right_steps[q], n)
            _propagate(l_step, ql, left_steps[q], n)
            for o in range(n_obs):
                cells = offsets[o, q]
                for lane in range(n):
                    res[o, q, lane] = 0.0
                if cells == 0:  # the loaded cell: its rows times its boundary, and X
                    for j in range(nb):
                        for lane in range(n):
                            res[o, q, lane] = res[o, q, lane] + rows[o, j, lane] * ub[j, q, lane]
                    if obs_p[o] >= 0 and load_p[q] >= 0:
                        at, col = points[obs_p[o]], load_p[q]
                        for lane in range(n):
                            res[o, q, lane] = res[o, q, lane] + xl[at, col, lane]
                    continue
                for j in range(m):  # the observed cell's ends: its left then its right
                    if cells > 0:
                        for lane in range(n):
                            res[o, q, lane] = (
                                res[o, q, lane]
                                + rows[o, j, lane] * qr[cells - 1, j, lane]
                                + rows[o, m + j, lane] * qr[cells, j, lane]
                            )
                    else:
                        for lane in range(n):
                            res[o, q, lane] = (
                                res[o, q, lane]
                                + rows[o, j, lane] * ql[-cells, j, lane]
                                + rows[o, m + j, lane] * ql[-cells - 1, j, lane]
                            )
        for lane in range(n):
            bad[start + lane] = flag[lane] > 0.0
            for o in range(n_obs):
                for q in range(n_load):
                    out[start + lane, o, q] = res[o, q, lane]


#: the plain Python functions (the kernel before compilation: the same numbers, slowly)
_PLAIN = {name: globals()[name] for name in _FUNCTIONS}
