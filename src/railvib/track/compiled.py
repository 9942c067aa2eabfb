"""The Euler rail's waves and receptance compiled (numba), one pass over the points of a stack.

The same algorithm as :mod:`railvib.track.stacked` (the reference, and the fallback),
written for a batch of points in structure-of-arrays form (real and imaginary parts in
rows of float64, a point a lane) so that each stage is one branch-free loop over the
batch which LLVM turns into vector instructions, eight points at a time with AVX-512
(``docs/design/0006-stacked-batches.md``). The points where the reference takes a dense
fallback (a Bloch vector from an SVD near a band edge of a lossless rail, a wave
matching with a weak pivot) are flagged and solved again by the NumPy kernel, so results
agree with it to rounding everywhere.

numba is optional (``pip install railvib[fast]``): a sweep whose work reaches
:data:`COMPILED_MIN_POINTS` points imports it and loads the kernel in each worker
(compiled the first time, then from numba's on-disk cache); :func:`compile_kernel` loads
it into any process. Once loaded it serves every stack of :data:`LOADED_MIN_POINTS`
points or more. A single case's run never loads it itself (at 10^6 frequencies loading
costs about what it saves, and 160 MB of memory), so ``railvib run`` never imports numba.
Elsewhere, and with ``RAILVIB_COMPILED=0``, everything runs on NumPy.
"""

from __future__ import annotations

import functools
import math
import os
from typing import Any

import numpy as np
from numpy.typing import NDArray

from railvib.jit import numba_jit
from railvib.track.stacked import (
    ENERGY_FLOW_TOLERANCE,
    WEAK_CROSS_PRODUCT,
    _distinct,
    _nearest_sleeper,
)

__all__ = [
    "COMPILED_MIN_POINTS",
    "LOADED_MIN_POINTS",
    "compile_kernel",
    "compiled_receptance",
    "use_compiled",
]

#: work (points a process solves) from which a sweep loads the compiled kernel: importing
#: numba and loading its cached machine code costs 0.4-1 s, the kernel saves ~1 us a point
COMPILED_MIN_POINTS = 2**19

#: once the kernel is loaded, stacks of at least this many points use it
LOADED_MIN_POINTS = 2048

#: ``1 / m!`` for the Krylov series (a point needing more terms is solved on NumPy)
_INV_FACTORIAL = np.array([1.0 / math.factorial(m) for m in range(171)])

#: the pivot test of railvib.stack.PIVOT_THRESHOLD
_PIVOT = 0.1

_KERNEL: list[Any] = []


def use_compiled(n_points: int, *, work: int | None = None, load: bool = True) -> bool:
    """Tell whether a stack of `n_points` points runs on the compiled kernel.

    Parameters
    ----------
    n_points : int
        Points of the stack.
    work : int, optional
        Points the process is about to solve in all (a sweep's cases x frequencies);
        default `n_points`.
    load : bool
        Whether the kernel may be loaded now (numba imported, the kernel loaded from its
        cache or compiled, seconds the first time) if it is not loaded yet; False: only a
        kernel already loaded in this process is used (a single case's run: at 10^6
        frequencies loading costs about what it saves, and 160 MB).

    Returns
    -------
    bool
        True where numba is installed, the environment variable ``RAILVIB_COMPILED`` is not
        ``0`` and the stack holds at least :data:`LOADED_MIN_POINTS` points, if the kernel
        is loaded already, or `load` and the work reaches :data:`COMPILED_MIN_POINTS` (it
        is loaded then).
    """
    if os.environ.get("RAILVIB_COMPILED", "1") == "0" or n_points < LOADED_MIN_POINTS:
        return False
    if _KERNEL:
        return _KERNEL[0] is not None
    if not load or (n_points if work is None else work) < COMPILED_MIN_POINTS:
        return False
    return _kernel() is not None


def compile_kernel() -> bool:
    """Load the kernel into this process (compiling it if numba has not cached it).

    Afterwards every stack of :data:`LOADED_MIN_POINTS` points or more in this process,
    a single case's run included, uses it.

    Returns
    -------
    bool
        False where numba is not installed.
    """
    kernel = _kernel()
    if kernel is None:
        return False
    x = np.array([0.3, -0.8])
    compiled_receptance(np.array([1.0 + 0.1j]), np.array([2.0 + 0.1j]), x, x)
    return True


def _kernel() -> Any:
    """The compiled kernel (numba, cached on disk), or None where numba is not installed."""
    if not _KERNEL:
        # error_model="numpy": a division by zero gives inf instead of raising, so the
        # divisions carry no branch (one would stop LLVM vectorising the stage); fastmath
        # "contract" only: a * b + c may be one FMA, rounded once instead of twice (no
        # reassociation, no finite-math or signed-zero assumptions)
        jit = numba_jit(error_model="numpy", fastmath={"contract"})
        _KERNEL.append(None if jit is None else jit(_points))
    return _KERNEL[0]


def compiled_receptance(
    beta4: NDArray[np.complex128],
    pad: NDArray[np.complex128],
    x_load: NDArray[np.float64],
    x_obs: NDArray[np.float64],
    kernel: Any = None,
) -> tuple[NDArray[np.complex128], NDArray[np.float64], NDArray[np.bool_]]:
    """Dimensionless receptance ``[point, obs, load]`` of the Euler bay at every point.

    Multiplied by ``d^3 / EI*`` it is the receptance in m/N. The points flagged in `bad`
    hold no result: the caller solves them with :mod:`railvib.track.stacked`.

    Parameters
    ----------
    beta4, pad : numpy.ndarray
        ``m omega^2 d^4 / EI*`` and ``K* d^3 / EI*`` per point (dimensionless), ``(N,)``.
    x_load, x_obs : numpy.ndarray
        Dimensionless positions ``x / d`` of the loads and observation points.
    kernel : callable, optional
        The point kernel (default: the compiled one; the plain Python function
        ``_points`` gives the same numbers, slowly).

    Returns
    -------
    receptance : numpy.ndarray
        ``(N, n_obs, n_load)``, complex.
    condition : numpy.ndarray
        Estimate of the wave matching's condition number, ``(N,)``.
    bad : numpy.ndarray of bool
        ``(N,)``: points left to the NumPy kernel.
    """
    geometry = _geometry(
        tuple(np.asarray(x_load, dtype=float)), tuple(np.asarray(x_obs, dtype=float))
    )
    n = beta4.shape[0]
    out = np.empty((n, x_obs.size, x_load.size), dtype=np.complex128)
    condition = np.empty(n)
    bad = np.zeros(n, dtype=np.bool_)
    run = _kernel() if kernel is None else kernel
    run(
        np.ascontiguousarray(beta4, dtype=np.complex128),
        np.ascontiguousarray(pad, dtype=np.complex128),
        *geometry,
        _INV_FACTORIAL,
        ENERGY_FLOW_TOLERANCE,
        WEAK_CROSS_PRODUCT,
        _PIVOT,
        out,
        condition,
        bad,
    )
    return out, condition, bad


@functools.lru_cache(maxsize=64)
def _geometry(x_load: tuple[float, ...], x_obs: tuple[float, ...]) -> tuple[NDArray[Any], ...]:
    """The kernel's index tables for loads at `x_load` seen at `x_obs` (``x / d``).

    Kept per geometry: every block of a run or a sweep has the same few (about 80 us of
    NumPy calls each time otherwise). Returns ``x_pow, series, xi_u, load_u, eta_u, obs_u,
    side, power, exponents, entry`` as :func:`_points` takes them (read only). ``entry[i, j]``
    is the first entry (row-major index) of the same load coordinate, observation
    coordinate, side and bay count as ``(i, j)``: the same operations on the same values,
    so it is formed once and copied (the wheels of two bogies a whole number of bays apart,
    and the seats under them: 24 distinct of the default case's 32 entries).
    """
    load, obs = np.array(x_load), np.array(x_obs)
    ref_load, xi = _nearest_sleeper(load)
    ref_obs, eta = _nearest_sleeper(obs)
    xi_u, load_u = np.unique(_distinct(xi), return_inverse=True)
    eta_u, obs_u = np.unique(_distinct(eta), return_inverse=True)
    # the Krylov functions at each distinct |x| (the half bay's 1/2 among them) once a point:
    # the loads' and the observation points' coordinates are mostly the same few values
    x_abs, series = np.unique(
        np.concatenate([[0.5], np.abs(xi_u), np.abs(eta_u)]), return_inverse=True
    )
    side = (obs[:, None] < load[None, :]).astype(np.int64)  # 0: right-going waves
    exponents, power = np.unique(np.abs(ref_obs[:, None] - ref_load[None, :]), return_inverse=True)
    power = power.reshape(side.shape)
    keys = np.stack(
        np.broadcast_arrays(load_u.ravel()[None, :], obs_u.ravel()[:, None], side, power), axis=-1
    ).reshape(-1, 4)
    first: dict[tuple[int, ...], int] = {}
    entry = np.array([first.setdefault(tuple(key), e) for e, key in enumerate(keys.tolist())])
    tables = (
        np.stack([x_abs, x_abs**2, x_abs**3, x_abs**4], axis=1),
        series.ravel().astype(np.int64),
        xi_u.astype(float),
        load_u.ravel().astype(np.int64),
        eta_u.astype(float),
        obs_u.ravel().astype(np.int64),
        side,
        power.astype(np.int64),
        exponents.astype(np.int64),
        entry.reshape(side.shape).astype(np.int64),
    )
    for table in tables:
        table.flags.writeable = False
    return tables


#: points a batch: each stage of the kernel is a loop over the batch's points that LLVM
#: vectorises (8 lanes with AVX-512; the points past the last full vector run scalar)
_B = 32

# rows of the kernel's work array, each `_B` lanes wide (row r of lane i at r * _B + i; a
# complex value takes two rows, its real then its imaginary part). Constant offsets keep
# the stages' loads and stores provably apart, so LLVM vectorises them without checks.
_BETA = 0 * _B  # beta4
_PAD = 2 * _B  # K* d^3 / EI*
_ROOT4 = 4 * _B  # |beta4|^(1/4)
_FLAG = 5 * _B  # 1: the point is left to the NumPy kernel
_C1 = 6 * _B  # the characteristic polynomial's c1
_C2 = 8 * _B  # and its c2 - 2
_ACC = 10 * _B  # Horner sums and binary powers (4 complex)
_ZETA = 18 * _B  # a series' argument
_INV = 20 * _B  # entry (r, c) of the matching's inverse at _INV + 2 (4 r + c) _B
_COND = 52 * _B  # the matching's condition estimate
_WAVE_MU = 53 * _B  # the current wave's two candidates (mu, 1/mu)
_WAVE_OUT = 57 * _B  # its propagation constant and vector (as a wave's rows)
_ROWS = 67
# rows of the two waves' candidates (wave v from v * _CAND) and of the right-going waves
# (from v * _WAVE), two arrays: a stage reading one and writing the other vectorises
_MS = 0 * _B  # the |mu| <= 1 candidate
_MB = 2 * _B  # and its inverse
_CAND = 4 * _B
_MU = 0 * _B  # the right-going wave's propagation constant
_RV = 2 * _B  # component c of the right-going wave at _RV + 2 c _B
_WAVE = 10 * _B


def _points(  # noqa: C901, PLR0912, PLR0915 - the stages of one batch, written out
    beta4: Any,
    pad: Any,
    x_pow: Any,
    series: Any,
    xi_u: Any,
    load_u: Any,
    eta_u: Any,
    obs_u: Any,
    side: Any,
    power: Any,
    exponents: Any,
    entry: Any,
    inv_fact: Any,
    energy_tol: float,
    weak_cross: float,
    pivot_threshold: float,
    out: Any,
    condition: Any,
    bad: Any,
) -> None:
    """The kernel: each point's waves, matching inverse and receptance (see module doc).

    `x_pow` holds ``|x|, x^2, x^3, x^4`` of each distinct local coordinate (row 0 and the
    entries of `series` say which row: first the half bay, then the loads' `xi_u`, then
    the observation points' `eta_u`); their Krylov functions are summed once a point, and
    each distinct entry is formed once (`entry`: the first of its repeats, :func:`_geometry`).

    The points go in batches of `_B`, structure of arrays: every stage is one loop over
    the batch's points without branches (a point that needs one, a weak pivot or a
    Krylov series longer than `inv_fact`, is flagged in `bad`), so that LLVM turns it into
    vector instructions, four or eight points at a time. The series are summed to the
    longest term count of the batch. Complex division and square roots are written out
    from real ones (the library's own are calls, which stop vectorisation); ``c2 - 2``
    above ``|beta4| = 16`` (real cos, sin, cosh, sinh: libm calls) is the one scalar stage.
    """
    n_points = beta4.shape[0]
    n_fact = inv_fact.shape[0]
    n_x, n_xi, n_eta, n_pow = x_pow.shape[0], xi_u.shape[0], eta_u.shape[0], exponents.shape[0]
    n_obs, n_load = out.shape[1], out.shape[2]
    w = np.zeros(_ROWS * _B)
    cand = np.zeros(2 * _CAND)
    wv = np.zeros(2 * _WAVE)
    # the geometry's rows: Krylov functions s_j at each coordinate, amplitudes of a load at
    # each load coordinate, each wave's displacement at each observation coordinate, mu^e
    kr = np.zeros(8 * n_x * _B)
    am = np.zeros(8 * n_xi * _B)
    dp = np.zeros(8 * n_eta * _B)
    mp = np.zeros(4 * n_pow * _B)
    n_ent = n_obs * n_load
    ent = np.zeros(2 * n_ent * _B)
    flat = out.reshape((n_points, n_ent))
    entry_of = entry.reshape(n_ent)
    pivot2 = pivot_threshold**2  # magnitudes compared squared: no hypot
    for start in range(0, n_points, _B):
        n = min(_B, n_points - start)
        # -- the batch's points, and the series' longest term counts
        for i in range(n):
            b, k = beta4[start + i], pad[start + i]
            w[_BETA + i], w[_BETA + _B + i] = b.real, b.imag
            w[_PAD + i], w[_PAD + _B + i] = k.real, k.imag
            w[_ROOT4 + i] = math.sqrt(math.sqrt(b.real * b.real + b.imag * b.imag))
            w[_FLAG + i] = 0.0
        root_max = 0.0  # the largest |beta|, and that of the c2 series' points
        root_series = 0.0
        trig = False  # a point of |beta4| >= 16 (c2 - 2 in closed form)
        for i in range(n):
            root4 = w[_ROOT4 + i]
            if 4 * max(6, math.ceil((2.72 * root4 + 34.0) / 4.0)) + 3 >= n_fact:
                w[_FLAG + i] = 1.0  # solved on NumPy; here a harmless stand-in point
                w[_BETA + i], w[_BETA + _B + i], w[_PAD + i], w[_PAD + _B + i] = 1, 0, 1, 0
                w[_ROOT4 + i] = root4 = 1.0
            root_max = max(root_max, root4)
            if root4 * root4 < 4.0:
                root_series = max(root_series, root4)
            else:
                trig = True
        terms = max(6, math.ceil((2.72 * root_max + 34.0) / 4.0))
        # -- characteristic polynomial: c1 (railvib.track.stacked._characteristic)
        for i in range(n):
            w[_ACC + i] = w[_ACC + _B + i] = w[_ACC + 2 * _B + i] = w[_ACC + 3 * _B + i] = 0.0
        for t in range(terms - 1, -1, -1):
            f0, f3 = inv_fact[4 * t], inv_fact[4 * t + 3]
            for i in range(n):
                zr, zi = w[_BETA + i], w[_BETA + _B + i]
                ar, ai = w[_ACC + i], w[_ACC + _B + i]
                w[_ACC + i], w[_ACC + _B + i] = ar * zr - ai * zi + f0, ar * zi + ai * zr
                ar, ai = w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i]
                w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i] = (
                    ar * zr - ai * zi + f3,
                    ar * zi + ai * zr,
                )
        for i in range(n):
            k = complex(w[_PAD + i], w[_PAD + _B + i])
            a0 = complex(w[_ACC + i], w[_ACC + _B + i])
            a3 = complex(w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i])
            c1 = complex(4.0 * a0.real, 4.0 * a0.imag) - k * a3
            w[_C1 + i], w[_C1 + _B + i] = c1.real, c1.imag
        # -- and c2 - 2: the series in -4 beta4 below |beta4| = 16
        if root_series > 0.0:
            tq = max(6, math.ceil((2.72 * math.sqrt(2.0) * root_series + 34.0) / 4.0))
            for i in range(n):
                w[_ACC + i] = w[_ACC + _B + i] = w[_ACC + 2 * _B + i] = w[_ACC + 3 * _B + i] = 0.0
            for t in range(tq - 1, -1, -1):
                f0, f3 = inv_fact[4 * t], inv_fact[4 * t + 3]
                for i in range(n):
                    zr, zi = -4.0 * w[_BETA + i], -4.0 * w[_BETA + _B + i]
                    ar, ai = w[_ACC + i], w[_ACC + _B + i]
                    w[_ACC + i], w[_ACC + _B + i] = ar * zr - ai * zi + f0, ar * zi + ai * zr
                    ar, ai = w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i]
                    w[_ACC + 2 * _B + i] = ar * zr - ai * zi + f3
                    w[_ACC + 3 * _B + i] = ar * zi + ai * zr
            for i in range(n):
                k = complex(w[_PAD + i], w[_PAD + _B + i])
                q = complex(w[_ACC + i], w[_ACC + _B + i])
                q = q + k * complex(w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i])
                w[_C2 + i], w[_C2 + _B + i] = 4.0 * q.real, 4.0 * q.imag
        if trig:  # and in closed form above, point by point (real cos, sin, cosh, sinh)
            for i in range(n):
                root4 = w[_ROOT4 + i]
                if root4 * root4 < 4.0:
                    continue
                br, bi = w[_BETA + i], w[_BETA + _B + i]
                k = complex(w[_PAD + i], w[_PAD + _B + i])
                # z = beta4^(1/4), the principal root, as two principal square roots
                r = math.sqrt(0.5 * (abs(br) + math.sqrt(br * br + bi * bi)))
                h = 0.5 * bi / r
                zr, zi = (r, h) if br >= 0.0 else (abs(h), math.copysign(r, bi))
                r = math.sqrt(0.5 * (abs(zr) + math.sqrt(zr * zr + zi * zi)))
                h = 0.5 * zi / r
                x, y = (r, h) if zr >= 0.0 else (abs(h), math.copysign(r, zi))
                cx, sx, cy, sy = math.cos(x), math.sin(x), math.cos(y), math.sin(y)
                chx, shx, chy, shy = math.cosh(x), math.sinh(x), math.cosh(y), math.sinh(y)
                cz = complex(cx * chy, -sx * shy)
                sz = complex(sx * chy, cx * shy)
                chz = complex(chx * cy, shx * sy)
                shz = complex(shx * cy, chx * sy)
                z = complex(x, y)
                z3 = z * z * z
                den = 1.0 / (z3.real * z3.real + z3.imag * z3.imag)
                c2 = 4.0 * cz * chz + k * (chz * sz - cz * shz) * complex(
                    z3.real * den, -z3.imag * den
                )
                w[_C2 + i], w[_C2 + _B + i] = c2.real, c2.imag
        # -- propagation constants (_propagation_constants); square roots principal
        for i in range(n):
            c1 = complex(w[_C1 + i], w[_C1 + _B + i])
            c2 = complex(w[_C2 + i], w[_C2 + _B + i])
            v = c1 * c1 - complex(4.0 * c2.real, 4.0 * c2.imag)
            r = math.sqrt(0.5 * (abs(v.real) + math.sqrt(v.real * v.real + v.imag * v.imag)))
            h = 0.5 * v.imag / (r if r > 0.0 else 1.0)
            disc = complex(r, h) if v.real >= 0.0 else complex(abs(h), math.copysign(r, v.imag))
            if (c1.conjugate() * disc).real < 0:
                disc = -disc
            lam_big = c1 + disc
            lam_big = complex(0.5 * lam_big.real, 0.5 * lam_big.imag)
            if lam_big == 0:
                lam_big = 1.0 + 0j
            den = 1.0 / (lam_big.real * lam_big.real + lam_big.imag * lam_big.imag)
            lam_small = c2 * complex(lam_big.real * den, -lam_big.imag * den)
            # wave 0: lam_big, wave 1: lam_small (written twice: a loop here stops LLVM)
            v = (lam_big - 2.0) * (lam_big + 2.0)
            r = math.sqrt(0.5 * (abs(v.real) + math.sqrt(v.real * v.real + v.imag * v.imag)))
            h = 0.5 * v.imag / (r if r > 0.0 else 1.0)
            root = complex(r, h) if v.real >= 0.0 else complex(abs(h), math.copysign(r, v.imag))
            if (lam_big.conjugate() * root).real < 0:
                root = -root
            large = lam_big + root
            lr, li = 0.5 * large.real, 0.5 * large.imag
            den = 1.0 / (lr * lr + li * li)
            cand[_MS + i], cand[_MS + _B + i], cand[_MB + i], cand[_MB + _B + i] = (
                lr * den,
                -li * den,
                lr,
                li,
            )
            v = (lam_small - 2.0) * (lam_small + 2.0)
            r = math.sqrt(0.5 * (abs(v.real) + math.sqrt(v.real * v.real + v.imag * v.imag)))
            h = 0.5 * v.imag / (r if r > 0.0 else 1.0)
            root = complex(r, h) if v.real >= 0.0 else complex(abs(h), math.copysign(r, v.imag))
            if (lam_small.conjugate() * root).real < 0:
                root = -root
            large = lam_small + root
            lr, li = 0.5 * large.real, 0.5 * large.imag
            den = 1.0 / (lr * lr + li * li)
            cand[_CAND + _MS + i], cand[_CAND + _MS + _B + i] = lr * den, -li * den
            cand[_CAND + _MB + i], cand[_CAND + _MB + _B + i] = lr, li
        # -- the Krylov functions at each local coordinate, the half bay's first
        for q in range(n_x):
            x = x_pow[q, 0]
            row = 8 * q * _B
            if x == 0.0:  # the series' exact value: s_0 = 1, the others 0
                for i in range(n):
                    kr[row + i] = 1.0
                    kr[row + _B + i] = kr[row + 2 * _B + i] = kr[row + 3 * _B + i] = 0.0
                    kr[row + 4 * _B + i] = kr[row + 5 * _B + i] = 0.0
                    kr[row + 6 * _B + i] = kr[row + 7 * _B + i] = 0.0
                continue
            tb = max(6, math.ceil((2.72 * root_max * x + 34.0) / 4.0))
            x4 = x_pow[q, 3]
            for i in range(n):
                w[_ZETA + i], w[_ZETA + _B + i] = w[_BETA + i] * x4, w[_BETA + _B + i] * x4
                w[_ACC + i] = w[_ACC + _B + i] = w[_ACC + 2 * _B + i] = w[_ACC + 3 * _B + i] = 0.0
                w[_ACC + 4 * _B + i] = w[_ACC + 5 * _B + i] = 0.0
                w[_ACC + 6 * _B + i] = w[_ACC + 7 * _B + i] = 0.0
            for t in range(tb - 1, -1, -1):
                f0, f1, f2, f3 = (
                    inv_fact[4 * t],
                    inv_fact[4 * t + 1],
                    inv_fact[4 * t + 2],
                    inv_fact[4 * t + 3],
                )
                for i in range(n):
                    zr, zi = w[_ZETA + i], w[_ZETA + _B + i]
                    ar, ai = w[_ACC + i], w[_ACC + _B + i]
                    w[_ACC + i], w[_ACC + _B + i] = ar * zr - ai * zi + f0, ar * zi + ai * zr
                    ar, ai = w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i]
                    w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i] = (
                        ar * zr - ai * zi + f1,
                        ar * zi + ai * zr,
                    )
                    ar, ai = w[_ACC + 4 * _B + i], w[_ACC + 5 * _B + i]
                    w[_ACC + 4 * _B + i], w[_ACC + 5 * _B + i] = (
                        ar * zr - ai * zi + f2,
                        ar * zi + ai * zr,
                    )
                    ar, ai = w[_ACC + 6 * _B + i], w[_ACC + 7 * _B + i]
                    w[_ACC + 6 * _B + i], w[_ACC + 7 * _B + i] = (
                        ar * zr - ai * zi + f3,
                        ar * zi + ai * zr,
                    )
            x2, x3 = x_pow[q, 1], x_pow[q, 2]
            for i in range(n):
                kr[row + i], kr[row + _B + i] = w[_ACC + i], w[_ACC + _B + i]
                kr[row + 2 * _B + i], kr[row + 3 * _B + i] = (
                    w[_ACC + 2 * _B + i] * x,
                    w[_ACC + 3 * _B + i] * x,
                )
                kr[row + 4 * _B + i], kr[row + 5 * _B + i] = (
                    w[_ACC + 4 * _B + i] * x2,
                    w[_ACC + 5 * _B + i] * x2,
                )
                kr[row + 6 * _B + i], kr[row + 7 * _B + i] = (
                    w[_ACC + 6 * _B + i] * x3,
                    w[_ACC + 7 * _B + i] * x3,
                )
        # -- Bloch vectors of the half-bay pencil (_bloch_vector), energy-flow sorting
        half = 8 * series[0] * _B
        for wave in range(2):
            o, oc = wave * _WAVE, wave * _CAND
            for i in range(n):  # its candidates at fixed rows: their loads then vectorise
                w[_WAVE_MU + i], w[_WAVE_MU + _B + i] = cand[oc + _MS + i], cand[oc + _MS + _B + i]
                w[_WAVE_MU + 2 * _B + i] = cand[oc + _MB + i]
                w[_WAVE_MU + 3 * _B + i] = cand[oc + _MB + _B + i]
            for i in range(n):
                b = complex(w[_BETA + i], w[_BETA + _B + i])
                k = complex(w[_PAD + i], w[_PAD + _B + i])
                s0 = complex(kr[half + i], kr[half + _B + i])
                s1 = complex(kr[half + 2 * _B + i], kr[half + 3 * _B + i])
                s2 = complex(kr[half + 4 * _B + i], kr[half + 5 * _B + i])
                s3 = complex(kr[half + 6 * _B + i], kr[half + 7 * _B + i])
                ms = complex(w[_WAVE_MU + i], w[_WAVE_MU + _B + i])
                bs1, bs2, bs3 = b * s1, b * s2, b * s3
                # m = B(1/2) - mu M B(1/2) M (M = diag(1, -1, 1, -1), the pad in column 0):
                # B(1/2) is Toeplitz (s_j above the diagonal, beta4 s_j below), so is m but
                # for its first column
                e0, e1, e2, e3 = s0 - ms * s0, s1 + ms * s1, s2 - ms * s2, s3 + ms * s3
                f2, f3 = bs2 - ms * bs2, bs3 + ms * bs3
                m00, m01, m02, m03 = s0 - ms * (s0 - k * s3), e1, e2, e3
                m10, m11, m12, m13 = bs3 - ms * (k * s2 - bs3), e0, e1, e2
                m20, m21, m22, m23 = bs2 - ms * (bs2 - k * s1), f3, e0, e1
                m30, m31, m32, m33 = bs1 - ms * (k * s0 - bs1), f2, f3, e0
                # rows scaled to unit norm
                sc = 1.0 / math.sqrt(
                    (m00.real**2 + m00.imag**2 + m01.real**2 + m01.imag**2)
                    + (m02.real**2 + m02.imag**2)
                    + (m03.real**2 + m03.imag**2)
                )
                m00, m01, m02, m03 = m00 * sc, m01 * sc, m02 * sc, m03 * sc
                sc = 1.0 / math.sqrt(
                    (m10.real**2 + m10.imag**2 + m11.real**2 + m11.imag**2)
                    + (m12.real**2 + m12.imag**2)
                    + (m13.real**2 + m13.imag**2)
                )
                m10, m11, m12, m13 = m10 * sc, m11 * sc, m12 * sc, m13 * sc
                sc = 1.0 / math.sqrt(
                    (m20.real**2 + m20.imag**2 + m21.real**2 + m21.imag**2)
                    + (m22.real**2 + m22.imag**2)
                    + (m23.real**2 + m23.imag**2)
                )
                m20, m21, m22, m23 = m20 * sc, m21 * sc, m22 * sc, m23 * sc
                sc = 1.0 / math.sqrt(
                    (m30.real**2 + m30.imag**2 + m31.real**2 + m31.imag**2)
                    + (m32.real**2 + m32.imag**2)
                    + (m33.real**2 + m33.imag**2)
                )
                m30, m31, m32, m33 = m30 * sc, m31 * sc, m32 * sc, m33 * sc
                # the null vector as the cofactors of row 0 (rows 1, 2, 3), or of row 1
                # (rows 2, 0, 1): the larger
                n01, n02, n03 = m20 * m31 - m21 * m30, m20 * m32 - m22 * m30, m20 * m33 - m23 * m30
                n12, n13, n23 = m21 * m32 - m22 * m31, m21 * m33 - m23 * m31, m22 * m33 - m23 * m32
                a0 = m11 * n23 - m12 * n13 + m13 * n12
                a1 = -(m10 * n23 - m12 * n03 + m13 * n02)
                a2 = m10 * n13 - m11 * n03 + m13 * n01
                a3 = -(m10 * n12 - m11 * n02 + m12 * n01)
                n01, n02, n03 = m00 * m11 - m01 * m10, m00 * m12 - m02 * m10, m00 * m13 - m03 * m10
                n12, n13, n23 = m01 * m12 - m02 * m11, m01 * m13 - m03 * m11, m02 * m13 - m03 * m12
                c0 = m21 * n23 - m22 * n13 + m23 * n12
                c1 = -(m20 * n23 - m22 * n03 + m23 * n02)
                c2 = m20 * n13 - m21 * n03 + m23 * n01
                c3 = -(m20 * n12 - m21 * n02 + m22 * n01)
                na = math.sqrt(
                    (a0.real**2 + a0.imag**2 + a1.real**2 + a1.imag**2)
                    + (a2.real**2 + a2.imag**2)
                    + (a3.real**2 + a3.imag**2)
                )
                nc = math.sqrt(
                    (c0.real**2 + c0.imag**2 + c1.real**2 + c1.imag**2)
                    + (c2.real**2 + c2.imag**2)
                    + (c3.real**2 + c3.imag**2)
                )
                if nc > na:
                    a0, a1, a2, a3, na = c0, c1, c2, c3, nc
                w[_FLAG + i] = max(w[_FLAG + i], 1.0 if na < weak_cross else 0.0)
                sc = 1.0 / na  # a real scale: multiplied, not a complex division
                v0, v1, v2, v3 = a0 * sc, a1 * sc, a2 * sc, a3 * sc
                # energy-flow sorting near |mu| = 1: the right-going wave of the pair
                flux = (v3 * v0.conjugate() - v2 * v1.conjugate()).imag
                mb = complex(w[_WAVE_MU + 2 * _B + i], w[_WAVE_MU + 3 * _B + i])
                flip = abs(math.sqrt(ms.real**2 + ms.imag**2) - 1.0) < energy_tol and flux < 0
                mu = mb if flip else ms
                v1, v3 = (-v1, -v3 - k * v0) if flip else (v1, v3)
                out_w = _WAVE_OUT
                w[out_w + _MU + i], w[out_w + _MU + _B + i] = mu.real, mu.imag
                w[out_w + _RV + i], w[out_w + _RV + _B + i] = v0.real, v0.imag
                w[out_w + _RV + 2 * _B + i], w[out_w + _RV + 3 * _B + i] = v1.real, v1.imag
                w[out_w + _RV + 4 * _B + i], w[out_w + _RV + 5 * _B + i] = v2.real, v2.imag
                w[out_w + _RV + 6 * _B + i], w[out_w + _RV + 7 * _B + i] = v3.real, v3.imag
            for r in range(10):
                for i in range(n):
                    wv[o + r * _B + i] = w[_WAVE_OUT + r * _B + i]
        # -- wave matching [R, -L] (L: the right-going waves mirrored), rows equilibrated,
        # inverted from its LU factors; a weak pivot leaves the point to NumPy
        for i in range(n):
            k = complex(w[_PAD + i], w[_PAD + _B + i])
            r00 = complex(wv[_RV + i], wv[_RV + _B + i])
            r10 = complex(wv[_RV + 2 * _B + i], wv[_RV + 3 * _B + i])
            r20 = complex(wv[_RV + 4 * _B + i], wv[_RV + 5 * _B + i])
            r30 = complex(wv[_RV + 6 * _B + i], wv[_RV + 7 * _B + i])
            r01 = complex(wv[_WAVE + _RV + i], wv[_WAVE + _RV + _B + i])
            r11 = complex(wv[_WAVE + _RV + 2 * _B + i], wv[_WAVE + _RV + 3 * _B + i])
            r21 = complex(wv[_WAVE + _RV + 4 * _B + i], wv[_WAVE + _RV + 5 * _B + i])
            r31 = complex(wv[_WAVE + _RV + 6 * _B + i], wv[_WAVE + _RV + 7 * _B + i])
            # -L = (-v0, v1, -v2, v3 + k v0) of each wave
            u00, u01, u02, u03 = r00, r01, -r00, -r01
            u10, u11, u12, u13 = r10, r11, r10, r11
            u20, u21, u22, u23 = r20, r21, -r20, -r21
            u30, u31, u32, u33 = r30, r31, r30 + k * r00, r31 + k * r01
            rows0 = 1.0 / math.sqrt(max(r00.real**2 + r00.imag**2, r01.real**2 + r01.imag**2))
            rows1 = 1.0 / math.sqrt(max(r10.real**2 + r10.imag**2, r11.real**2 + r11.imag**2))
            rows2 = 1.0 / math.sqrt(max(r20.real**2 + r20.imag**2, r21.real**2 + r21.imag**2))
            rows3 = 1.0 / math.sqrt(
                max(
                    max(r30.real**2 + r30.imag**2, r31.real**2 + r31.imag**2),
                    max(u32.real**2 + u32.imag**2, u33.real**2 + u33.imag**2),
                )
            )
            u00, u01, u02, u03 = u00 * rows0, u01 * rows0, u02 * rows0, u03 * rows0
            u10, u11, u12, u13 = u10 * rows1, u11 * rows1, u12 * rows1, u13 * rows1
            u20, u21, u22, u23 = u20 * rows2, u21 * rows2, u22 * rows2, u23 * rows2
            u30, u31, u32, u33 = u30 * rows3, u31 * rows3, u32 * rows3, u33 * rows3
            big_m = max(
                max(
                    max(u00.real**2 + u00.imag**2, u01.real**2 + u01.imag**2),
                    max(u10.real**2 + u10.imag**2, u11.real**2 + u11.imag**2),
                ),
                max(
                    max(u20.real**2 + u20.imag**2, u21.real**2 + u21.imag**2),
                    max(
                        max(u30.real**2 + u30.imag**2, u31.real**2 + u31.imag**2),
                        max(u32.real**2 + u32.imag**2, u33.real**2 + u33.imag**2),
                    ),
                ),
            )
            weak = w[_FLAG + i]
            big_inv = 0.0
            size = u00.real * u00.real + u00.imag * u00.imag
            weak = max(
                weak, 1.0 if size < pivot2 * (u10.real * u10.real + u10.imag * u10.imag) else 0.0
            )
            weak = max(
                weak, 1.0 if size < pivot2 * (u20.real * u20.real + u20.imag * u20.imag) else 0.0
            )
            weak = max(
                weak, 1.0 if size < pivot2 * (u30.real * u30.real + u30.imag * u30.imag) else 0.0
            )
            den = 1.0 / size
            d0 = complex(u00.real * den, -u00.imag * den)
            l10 = u10 * d0
            u11 = u11 - l10 * u01
            u12 = u12 - l10 * u02
            u13 = u13 - l10 * u03
            l20 = u20 * d0
            u21 = u21 - l20 * u01
            u22 = u22 - l20 * u02
            u23 = u23 - l20 * u03
            l30 = u30 * d0
            u31 = u31 - l30 * u01
            u32 = u32 - l30 * u02
            u33 = u33 - l30 * u03
            size = u11.real * u11.real + u11.imag * u11.imag
            weak = max(
                weak, 1.0 if size < pivot2 * (u21.real * u21.real + u21.imag * u21.imag) else 0.0
            )
            weak = max(
                weak, 1.0 if size < pivot2 * (u31.real * u31.real + u31.imag * u31.imag) else 0.0
            )
            den = 1.0 / size
            d1 = complex(u11.real * den, -u11.imag * den)
            l21 = u21 * d1
            u22 = u22 - l21 * u12
            u23 = u23 - l21 * u13
            l31 = u31 * d1
            u32 = u32 - l31 * u12
            u33 = u33 - l31 * u13
            size = u22.real * u22.real + u22.imag * u22.imag
            weak = max(
                weak, 1.0 if size < pivot2 * (u32.real * u32.real + u32.imag * u32.imag) else 0.0
            )
            den = 1.0 / size
            d2 = complex(u22.real * den, -u22.imag * den)
            l32 = u32 * d2
            u33 = u33 - l32 * u23
            size = u33.real * u33.real + u33.imag * u33.imag
            den = 1.0 / size
            d3 = complex(u33.real * den, -u33.imag * den)
            li10 = -l10
            li20 = -l20 - l21 * li10
            li30 = -l30 - l31 * li10 - l32 * li20
            li21 = -l21
            li31 = -l31 - l32 * li21
            li32 = -l32
            ui00 = d0
            ui11 = d1
            ui22 = d2
            ui33 = d3
            ui01 = -(u01 * ui11) * d0
            ui12 = -(u12 * ui22) * d1
            ui02 = -(u01 * ui12 + u02 * ui22) * d0
            ui23 = -(u23 * ui33) * d2
            ui13 = -(u12 * ui23 + u13 * ui33) * d1
            ui03 = -(u01 * ui13 + u02 * ui23 + u03 * ui33) * d0
            v = ui00 + ui01 * li10 + ui02 * li20 + ui03 * li30
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 0 * _B + i], w[_INV + 1 * _B + i] = v.real * rows0, v.imag * rows0
            v = ui01 + ui02 * li21 + ui03 * li31
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 2 * _B + i], w[_INV + 3 * _B + i] = v.real * rows1, v.imag * rows1
            v = ui02 + ui03 * li32
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 4 * _B + i], w[_INV + 5 * _B + i] = v.real * rows2, v.imag * rows2
            v = ui03
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 6 * _B + i], w[_INV + 7 * _B + i] = v.real * rows3, v.imag * rows3
            v = ui11 * li10 + ui12 * li20 + ui13 * li30
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 8 * _B + i], w[_INV + 9 * _B + i] = v.real * rows0, v.imag * rows0
            v = ui11 + ui12 * li21 + ui13 * li31
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 10 * _B + i], w[_INV + 11 * _B + i] = v.real * rows1, v.imag * rows1
            v = ui12 + ui13 * li32
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 12 * _B + i], w[_INV + 13 * _B + i] = v.real * rows2, v.imag * rows2
            v = ui13
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 14 * _B + i], w[_INV + 15 * _B + i] = v.real * rows3, v.imag * rows3
            v = ui22 * li20 + ui23 * li30
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 16 * _B + i], w[_INV + 17 * _B + i] = v.real * rows0, v.imag * rows0
            v = ui22 * li21 + ui23 * li31
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 18 * _B + i], w[_INV + 19 * _B + i] = v.real * rows1, v.imag * rows1
            v = ui22 + ui23 * li32
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 20 * _B + i], w[_INV + 21 * _B + i] = v.real * rows2, v.imag * rows2
            v = ui23
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 22 * _B + i], w[_INV + 23 * _B + i] = v.real * rows3, v.imag * rows3
            v = ui33 * li30
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 24 * _B + i], w[_INV + 25 * _B + i] = v.real * rows0, v.imag * rows0
            v = ui33 * li31
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 26 * _B + i], w[_INV + 27 * _B + i] = v.real * rows1, v.imag * rows1
            v = ui33 * li32
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 28 * _B + i], w[_INV + 29 * _B + i] = v.real * rows2, v.imag * rows2
            v = ui33
            big_inv = max(big_inv, (v.real * v.real + v.imag * v.imag))
            w[_INV + 30 * _B + i], w[_INV + 31 * _B + i] = v.real * rows3, v.imag * rows3
            w[_FLAG + i] = weak
            w[_COND + i] = 4.0 * math.sqrt(big_m * big_inv)
        # -- wave amplitudes of a load at each local coordinate (receptance_entries)
        for q in range(n_xi):
            row = 8 * series[1 + q] * _B
            at = 8 * q * _B
            sg = -1.0 if xi_u[q] > 0 else 1.0  # the field at -xi: s_j(-u) = (-1)^j s_j(u)
            left = 1.0 if xi_u[q] < 0 else 0.0  # the pad's reaction at a load left of it
            for i in range(n):
                k = complex(w[_PAD + i], w[_PAD + _B + i])
                h0 = complex(sg * kr[row + 6 * _B + i], sg * kr[row + 7 * _B + i])
                h1 = complex(kr[row + 4 * _B + i], kr[row + 5 * _B + i])
                h2 = complex(sg * kr[row + 2 * _B + i], sg * kr[row + 3 * _B + i])
                h3 = complex(kr[row + i], kr[row + _B + i])
                kh = k * h0
                h3 = h3 - complex(left * kh.real, left * kh.imag)
                v = (
                    complex(w[_INV + 0 * _B + i], w[_INV + 1 * _B + i]) * h0
                    + complex(w[_INV + 2 * _B + i], w[_INV + 3 * _B + i]) * h1
                    + complex(w[_INV + 4 * _B + i], w[_INV + 5 * _B + i]) * h2
                    + complex(w[_INV + 6 * _B + i], w[_INV + 7 * _B + i]) * h3
                )
                am[at + 0 * _B + i], am[at + 1 * _B + i] = v.real, v.imag
                v = (
                    complex(w[_INV + 8 * _B + i], w[_INV + 9 * _B + i]) * h0
                    + complex(w[_INV + 10 * _B + i], w[_INV + 11 * _B + i]) * h1
                    + complex(w[_INV + 12 * _B + i], w[_INV + 13 * _B + i]) * h2
                    + complex(w[_INV + 14 * _B + i], w[_INV + 15 * _B + i]) * h3
                )
                am[at + 2 * _B + i], am[at + 3 * _B + i] = v.real, v.imag
                v = (
                    complex(w[_INV + 16 * _B + i], w[_INV + 17 * _B + i]) * h0
                    + complex(w[_INV + 18 * _B + i], w[_INV + 19 * _B + i]) * h1
                    + complex(w[_INV + 20 * _B + i], w[_INV + 21 * _B + i]) * h2
                    + complex(w[_INV + 22 * _B + i], w[_INV + 23 * _B + i]) * h3
                )
                am[at + 4 * _B + i], am[at + 5 * _B + i] = v.real, v.imag
                v = (
                    complex(w[_INV + 24 * _B + i], w[_INV + 25 * _B + i]) * h0
                    + complex(w[_INV + 26 * _B + i], w[_INV + 27 * _B + i]) * h1
                    + complex(w[_INV + 28 * _B + i], w[_INV + 29 * _B + i]) * h2
                    + complex(w[_INV + 30 * _B + i], w[_INV + 31 * _B + i]) * h3
                )
                am[at + 6 * _B + i], am[at + 7 * _B + i] = v.real, v.imag
        # -- displacement of each wave, and of its mirror, at each observation coordinate
        for q in range(n_eta):
            row = 8 * series[1 + n_xi + q] * _B
            at = 8 * q * _B
            sg = -1.0 if eta_u[q] < 0 else 1.0
            left = 1.0 if eta_u[q] < 0 else 0.0
            for i in range(n):
                k = complex(w[_PAD + i], w[_PAD + _B + i])
                h0 = complex(kr[row + i], kr[row + _B + i])
                h1 = complex(sg * kr[row + 2 * _B + i], sg * kr[row + 3 * _B + i])
                h2 = complex(kr[row + 4 * _B + i], kr[row + 5 * _B + i])
                h3 = complex(sg * kr[row + 6 * _B + i], sg * kr[row + 7 * _B + i])
                kh = k * h3
                h0 = h0 + complex(left * kh.real, left * kh.imag)
                v0 = complex(wv[_RV + i], wv[_RV + _B + i])
                v1 = complex(wv[_RV + 2 * _B + i], wv[_RV + 3 * _B + i])
                v2 = complex(wv[_RV + 4 * _B + i], wv[_RV + 5 * _B + i])
                v3 = complex(wv[_RV + 6 * _B + i], wv[_RV + 7 * _B + i])
                d = h0 * v0 + h1 * v1 + h2 * v2 + h3 * v3
                dp[at + 0 * _B + i], dp[at + 1 * _B + i] = d.real, d.imag
                d = h0 * v0 + h1 * -v1 + h2 * v2 + h3 * (-v3 - k * v0)
                dp[at + 4 * _B + i], dp[at + 5 * _B + i] = d.real, d.imag
                v0 = complex(wv[_WAVE + _RV + i], wv[_WAVE + _RV + _B + i])
                v1 = complex(wv[_WAVE + _RV + 2 * _B + i], wv[_WAVE + _RV + 3 * _B + i])
                v2 = complex(wv[_WAVE + _RV + 4 * _B + i], wv[_WAVE + _RV + 5 * _B + i])
                v3 = complex(wv[_WAVE + _RV + 6 * _B + i], wv[_WAVE + _RV + 7 * _B + i])
                d = h0 * v0 + h1 * v1 + h2 * v2 + h3 * v3
                dp[at + 2 * _B + i], dp[at + 3 * _B + i] = d.real, d.imag
                d = h0 * v0 + h1 * -v1 + h2 * v2 + h3 * (-v3 - k * v0)
                dp[at + 6 * _B + i], dp[at + 7 * _B + i] = d.real, d.imag
        # -- mu^e by NumPy's binary powering (its integer-power path)
        for q in range(n_pow):
            e = exponents[q]
            at = 4 * q * _B
            if e <= 3:
                for i in range(n):
                    m0 = complex(wv[_MU + i], wv[_MU + _B + i])
                    m1 = complex(wv[_WAVE + _MU + i], wv[_WAVE + _MU + _B + i])
                    if e == 0:
                        m0, m1 = 1.0 + 0j, 1.0 + 0j
                    elif e == 2:
                        m0, m1 = m0 * m0, m1 * m1
                    elif e == 3:
                        m0, m1 = m0 * m0 * m0, m1 * m1 * m1
                    mp[at + i], mp[at + _B + i] = m0.real, m0.imag
                    mp[at + 2 * _B + i], mp[at + 3 * _B + i] = m1.real, m1.imag
                continue
            for i in range(n):  # the product (1 for now), then the powers mu^(2^j)
                mp[at + i], mp[at + 2 * _B + i] = 1.0, 1.0
                mp[at + _B + i] = mp[at + 3 * _B + i] = 0.0
                w[_ACC + i], w[_ACC + _B + i] = wv[_MU + i], wv[_MU + _B + i]
                w[_ACC + 2 * _B + i] = wv[_WAVE + _MU + i]
                w[_ACC + 3 * _B + i] = wv[_WAVE + _MU + _B + i]
            mask = 1
            while True:
                if e & mask:
                    for i in range(n):
                        m0 = complex(mp[at + i], mp[at + _B + i])
                        m0 = m0 * complex(w[_ACC + i], w[_ACC + _B + i])
                        m1 = complex(mp[at + 2 * _B + i], mp[at + 3 * _B + i])
                        m1 = m1 * complex(w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i])
                        mp[at + i], mp[at + _B + i] = m0.real, m0.imag
                        mp[at + 2 * _B + i], mp[at + 3 * _B + i] = m1.real, m1.imag
                mask <<= 1
                if e < mask:
                    break
                for i in range(n):
                    m0 = complex(w[_ACC + i], w[_ACC + _B + i])
                    m1 = complex(w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i])
                    m0, m1 = m0 * m0, m1 * m1
                    w[_ACC + i], w[_ACC + _B + i] = m0.real, m0.imag
                    w[_ACC + 2 * _B + i], w[_ACC + 3 * _B + i] = m1.real, m1.imag
        # -- the entries: each load's two waves carried to each observation point (into
        # the batch's rows, then copied point by point: a scattered store stops LLVM)
        for i_obs in range(n_obs):
            for j in range(n_load):
                if entry[i_obs, j] != i_obs * n_load + j:
                    continue  # a repeat of an entry formed before: copied below
                sd = side[i_obs, j]
                at_a = 8 * load_u[j] * _B + 4 * sd * _B
                at_m = 4 * power[i_obs, j] * _B
                at_d = 8 * obs_u[i_obs] * _B + 4 * sd * _B
                at = 2 * (i_obs * n_load + j) * _B
                for i in range(n):
                    v = complex(am[at_a + i], am[at_a + _B + i]) * complex(
                        mp[at_m + i], mp[at_m + _B + i]
                    ) * complex(dp[at_d + i], dp[at_d + _B + i]) + complex(
                        am[at_a + 2 * _B + i], am[at_a + 3 * _B + i]
                    ) * complex(mp[at_m + 2 * _B + i], mp[at_m + 3 * _B + i]) * complex(
                        dp[at_d + 2 * _B + i], dp[at_d + 3 * _B + i]
                    )
                    ent[at + i], ent[at + _B + i] = v.real, v.imag
        for i in range(n):
            for e in range(n_ent):
                r = entry_of[e]
                flat[start + i, e] = complex(ent[2 * r * _B + i], ent[(2 * r + 1) * _B + i])
        for i in range(n):
            bad[start + i] = w[_FLAG + i] > 0.0
            condition[start + i] = w[_COND + i]
