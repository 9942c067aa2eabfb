"""Stacked small-matrix kernels: one contiguous array over the stack per matrix entry.

A stack is the leading axis of every array of a solve: frequencies of one case, or
(case, frequency) points of many cases laid end to end (``docs/design/0006-stacked-batches.md``).
Small matrices (the 4x4 wave matching, the wheel condensation, the coupled 4x4 solve)
are held as nested lists of their entries, each entry an ``(n,)`` array over the stack
(or ``(n, k)`` for ``k`` right-hand sides), so every operation is one elementwise pass:
no loop over tiny matrices, no LAPACK call per point, and nothing but ``+ - * /``,
``abs`` and ``where`` of the array API, so the same code runs on NumPy, CuPy or JAX.

The array namespace of a computation is chosen by name (:func:`namespace`); NumPy is
the default and the other libraries are imported only when asked for.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from railvib.errors import CaseError

__all__ = [
    "BACKENDS",
    "PIVOT_THRESHOLD",
    "dot",
    "entries",
    "inverse",
    "namespace",
    "put",
    "solve",
    "stacked",
    "to_numpy",
]

#: array libraries a stacked computation can run on (``backend`` names)
BACKENDS = ("numpy", "cupy", "jax")

#: threshold of the pivot test: a diagonal pivot at least this fraction of the largest
#: entry below it in its column bounds the growth of the elimination as partial
#: pivoting does (``(1 + 1/threshold)^(n-1)``); points failing it are solved by LAPACK
PIVOT_THRESHOLD = 0.1


def namespace(backend: str = "numpy") -> Any:
    """The array namespace of `backend`: NumPy, CuPy or JAX (64-bit) in array-API form.

    Parameters
    ----------
    backend : {"numpy", "cupy", "jax"}
        Library name; CuPy and JAX are imported on first use.

    Returns
    -------
    module
        ``numpy``, ``cupy`` or ``jax.numpy`` (with ``jax_enable_x64`` set, so
        complex128 stays complex128).

    Raises
    ------
    CaseError
        ``backend = 'name': one of numpy, cupy, jax (installed)``.
    """
    if backend == "numpy":
        return np
    if backend not in BACKENDS:
        raise CaseError("backend", backend, f"one of {', '.join(BACKENDS)}")
    try:
        if backend == "cupy":
            import cupy

            return cupy
        import jax

        jax.config.update("jax_enable_x64", True)
        import jax.numpy as jnp

        return jnp
    except ImportError:
        raise CaseError(
            "backend", backend, f"{backend} is not installed (pip install {backend})"
        ) from None


def entries(a: Any, xp: Any = np) -> Any:
    """Entries of a stack ``(n, *shape)`` as contiguous ``(n,)`` arrays, nested by `shape`.

    Parameters
    ----------
    a : array
        Stack of small arrays, stack axis first.
    xp : module
        Array namespace of `a`.

    Returns
    -------
    list or array
        ``a`` itself for a 1-D stack, else a list (nested ``len(shape)`` deep) of the
        entries ``a[:, i, j, ...]``, each contiguous.
    """
    if a.ndim == 1:
        return a
    moved = xp.moveaxis(a, 0, -1)
    if xp is np:
        moved = np.ascontiguousarray(moved)
    return _nest(moved)


def _nest(a: Any) -> Any:
    return a if a.ndim == 1 else [_nest(a[i]) for i in range(a.shape[0])]


def stacked(e: Any, xp: Any = np) -> Any:
    """Inverse of :func:`entries`: nested entry lists back to one ``(n, *shape)`` array.

    Parameters
    ----------
    e : list or array
        Nested lists of entry arrays ``(n,)`` (or ``(n, k)``, giving ``(n, *shape, k)``).
    xp : module
        Array namespace of the entries.

    Returns
    -------
    array
        The stack, stack axis first.
    """
    if not isinstance(e, list):
        return e
    if xp is np:  # filled in place: np.stack on axis 1 copies through strided concatenation,
        return _filled(e)  # ~10x slower for the small matrices of a 4096-point block
    return xp.stack([stacked(x, xp) for x in e], axis=1)


def _leaves(e: Any) -> list[Any]:
    return [leaf for x in e for leaf in _leaves(x)] if isinstance(e, list) else [e]


def _filled(e: list[Any]) -> NDArray[Any]:
    """:func:`stacked` on NumPy: one preallocated array, each entry written into its place."""
    leaves = [np.asarray(x) for x in _leaves(e)]
    shape: list[int] = []
    level: Any = e
    while isinstance(level, list):
        shape.append(len(level))
        level = level[0]
    first = leaves[0]
    out = np.empty((first.shape[0], *shape, *first.shape[1:]), dtype=np.result_type(*leaves))
    flat = out.reshape(first.shape[0], -1, *first.shape[1:])
    for k, leaf in enumerate(leaves):
        flat[:, k] = leaf
    return out


def dot(u: list[Any], v: list[Any]) -> Any:
    """``sum_k u[k] v[k]`` of two lists of entry arrays.

    Parameters
    ----------
    u, v : list of array
        Entries of equal length (broadcastable arrays over the stack).

    Returns
    -------
    array
        The sum of the products, over the stack.
    """
    out = u[0] * v[0]
    for x, y in zip(u[1:], v[1:], strict=True):
        out = out + x * y
    return out


def solve(a: list[list[Any]], b: list[Any], xp: Any = np) -> tuple[list[Any], Any]:
    """Solve ``A x = b`` at every point of the stack by Gaussian elimination on entries.

    No row is exchanged; where a pivot fails the test of :data:`PIVOT_THRESHOLD`, the
    point is flagged and the caller solves it again with pivoting (LAPACK), so the
    result is as accurate as partial pivoting everywhere.

    Parameters
    ----------
    a : list of list of array
        ``n x n`` entries, each ``(N,)`` (or broadcastable against `b`).
    b : list of array
        ``n`` entries of the right-hand side(s), ``(N,)`` or ``(N, k)``.
    xp : module
        Array namespace.

    Returns
    -------
    x : list of array
        The solution's entries, shaped as `b`'s.
    bad : array of bool
        ``(N,)``: points whose pivots failed the test (their `x` is not to be used).
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return _solve(a, b, xp)


def _solve(a: list[list[Any]], b: list[Any], xp: Any) -> tuple[list[Any], Any]:
    """:func:`solve` (a zero pivot gives inf/nan at its points, which are flagged)."""
    n = len(b)
    a = [list(row) for row in a]
    b = list(b)
    bad = None
    for k in range(n):
        pivot = a[k][k]
        size = xp.abs(pivot)
        for i in range(k + 1, n):
            weak = size < PIVOT_THRESHOLD * xp.abs(a[i][k])
            bad = weak if bad is None else (bad | weak)
        inv = 1.0 / pivot
        a[k] = [None] * (k + 1) + [x * inv for x in a[k][k + 1 :]]
        b[k] = b[k] * _column(inv, b[k])
        for i in range(k + 1, n):
            lik = a[i][k]
            a[i] = [None] * (k + 1) + [a[i][j] - lik * a[k][j] for j in range(k + 1, n)]
            b[i] = b[i] - _column(lik, b[i]) * b[k]
    x: list[Any] = [None] * n
    for k in range(n - 1, -1, -1):
        acc = b[k]
        for j in range(k + 1, n):
            acc = acc - _column(a[k][j], acc) * x[j]
        x[k] = acc
    if bad is None:
        bad = xp.zeros(b[0].shape[:1], dtype=bool)
    return x, bad


def inverse(a: list[list[Any]], xp: Any = np) -> tuple[list[list[Any]], Any]:
    """``A^-1`` at every point of the stack from its LU factors on entries.

    ``A = L U`` without row exchanges (the pivot test of :func:`solve`), then
    ``A^-1 = U^-1 L^-1``, skipping the known zeros of the triangular factors: about
    ``n^3`` elementwise operations, against ``n^3 + n^2 n`` for :func:`solve` with the
    ``n`` columns of the identity.

    Parameters
    ----------
    a : list of list of array
        ``n x n`` entries, each ``(N,)``.
    xp : module
        Array namespace.

    Returns
    -------
    inv : list of list of array
        The inverse's entries.
    bad : array of bool
        ``(N,)``: points whose pivots failed the test (their `inv` is not to be used).
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        n = len(a)
        u = [list(row) for row in a]
        low: list[list[Any]] = [[None] * n for _ in range(n)]  # multipliers of L
        bad = xp.zeros(a[0][0].shape, dtype=bool)
        for k in range(n):
            size = xp.abs(u[k][k])
            for i in range(k + 1, n):
                bad = bad | (size < PIVOT_THRESHOLD * xp.abs(u[i][k]))
            inv_pivot = 1.0 / u[k][k]
            for i in range(k + 1, n):
                low[i][k] = u[i][k] * inv_pivot
                for j in range(k + 1, n):
                    u[i][j] = u[i][j] - low[i][k] * u[k][j]
        # L^-1: unit lower triangular, column by column
        linv: list[list[Any]] = [[None] * n for _ in range(n)]
        for j in range(n):
            for i in range(j + 1, n):
                acc = -low[i][j]
                for k in range(j + 1, i):
                    acc = acc - low[i][k] * linv[k][j]
                linv[i][j] = acc
        # U^-1: upper triangular
        diag = [1.0 / u[k][k] for k in range(n)]
        uinv: list[list[Any]] = [[None] * n for _ in range(n)]
        for j in range(n):
            uinv[j][j] = diag[j]
            for i in range(j - 1, -1, -1):
                acc = u[i][i + 1] * uinv[i + 1][j]
                for k in range(i + 2, j + 1):
                    acc = acc + u[i][k] * uinv[k][j]
                uinv[i][j] = -acc * diag[i]
        out = []
        for i in range(n):
            row = []
            for j in range(n):
                # (U^-1 L^-1)_ij = sum_{k >= max(i, j)} U^-1_ik L^-1_kj, L^-1_jj = 1
                start = max(i, j)
                acc = uinv[i][j] if start == j else uinv[i][start] * linv[start][j]
                for k in range(start + 1, n):
                    acc = acc + uinv[i][k] * linv[k][j]
                row.append(acc)
            out.append(row)
    return out, bad


def _column(coef: Any, like: Any) -> Any:
    """`coef` ``(N,)`` shaped to multiply `like` ``(N,)`` or ``(N, k)``."""
    return coef if coef.ndim == like.ndim else coef[:, None]


def to_numpy(a: Any) -> Any:
    """`a` as a NumPy array (CuPy arrays are copied from the device).

    Parameters
    ----------
    a : array
        A NumPy, CuPy or JAX array.

    Returns
    -------
    numpy.ndarray
        The same values on the host.
    """
    return a.get() if hasattr(a, "get") and not isinstance(a, np.ndarray) else np.asarray(a)


def put(a: Any, mask: Any, values: Any, xp: Any = np) -> Any:
    """`a` with the points `mask` replaced by `values`, as a new array.

    Parameters
    ----------
    a : array
        Entry array over the stack, ``(N, ...)``.
    mask : array of bool
        ``(N,)``: the points to replace.
    values : array_like
        The new values, ``(mask.sum(), ...)``.
    xp : module
        Array namespace of `a`.

    Returns
    -------
    array
        A copy of `a` with the points replaced.
    """
    values = xp.asarray(values)
    if hasattr(a, "at"):  # JAX arrays are immutable
        return a.at[mask].set(values)
    out = a.copy()
    out[mask] = values
    return out
