"""The periodic Euler rail's receptance over a stack, in the stacked layout, on any array library.

The same wave solution as :class:`railvib.track.PeriodicTrack` (the symplectic method,
``docs/design/0002-track-solver.md``: half-bay transfer matrices, the closed-form
characteristic polynomial of the Euler bay, Bloch vectors from the half-bay pencil,
mirrored left waves, the row-equilibrated wave matching, points referred to their nearest
sleeper), written on entry arrays (:mod:`railvib.stack`): every small matrix is a nested
list of ``(N,)`` arrays over the stack, so each step is a few elementwise passes and the
only dense linear algebra is the LAPACK fallback of the few points that need it (weak
pivots, a singular-value decomposition near a band edge of a lossless rail). It runs on
NumPy, CuPy or JAX alike; each point of the stack may have its own frequency, rail
(through ``beta4``) and pad.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from railvib.stack import dot, put, to_numpy
from railvib.stack import inverse as lu_inverse

__all__ = ["StackedWaves", "receptance_entries", "stacked_waves"]

#: where ``| |mu| - 1 |`` is below this, waves are sorted by energy flow, not modulus
ENERGY_FLOW_TOLERANCE = 1e-6

#: below this volume of the three unit rows, a Bloch vector is taken from an SVD
WEAK_CROSS_PRODUCT = 1e-3

#: mirror image ``x -> -x`` of a state ``(w, d psi, d^2 psi', d^3 v)``
_MIRROR = (1.0, -1.0, 1.0, -1.0)

#: the column pairs of a 4-vector, for its 2x2 minors
_PAIRS = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))


class StackedWaves:
    """The decaying waves of the bay at every point of a stack, as entry arrays.

    Attributes
    ----------
    beta4, pad : array
        ``m omega^2 d^4 / EI*`` and ``K* d^3 / EI*`` (dimensionless), ``(N,)``.
    mu : list of array
        Propagation constants of the two right-going waves, each ``(N,)``.
    right, left : list of list of array
        Wave states ``[component][wave]`` just right of a sleeper (``4 x 2`` entries).
    matching_inv : list of list of array
        ``[R, -L]^-1`` (``4 x 4`` entries).
    condition : array
        Estimate of the wave matching's condition number, ``(N,)``.
    """

    def __init__(self, **kw: Any) -> None:
        self.__dict__.update(kw)

    beta4: Any
    pad: Any
    mu: list[Any]
    right: list[list[Any]]
    left: list[list[Any]]
    matching_inv: list[list[Any]]
    condition: Any


def krylov(beta4: Any, length: float, xp: Any = np) -> list[Any]:
    """Scaled Krylov functions ``(s0, s1, s2, s3)`` at `length`, as ``krylov_series``.

    Parameters
    ----------
    beta4 : array
        ``beta^4`` (dimensionless), ``(N,)``.
    length : float
        Signed dimensionless length x.
    xp : module
        Array namespace.

    Returns
    -------
    list of array
        ``s_j = x^j sum_k (beta4 x^4)^k / (4k + j)!``, each ``(N,)``.
    """
    x = float(length)
    zeta = beta4 * x**4
    big = float(to_numpy(xp.max(xp.abs(beta4)))) if beta4.shape[0] else 0.0
    n = max(6, math.ceil((2.72 * big**0.25 * abs(x) + 34.0) / 4.0))
    acc = [xp.zeros_like(zeta) for _ in range(4)]
    for k in range(n - 1, -1, -1):  # Horner in zeta for all four sums at once
        acc = [a * zeta + 1.0 / math.factorial(4 * k + j) for j, a in enumerate(acc)]
    return [a * x**j for j, a in enumerate(acc)]


def stacked_waves(beta4: Any, pad: Any, xp: Any = np) -> StackedWaves:
    """Propagation constants and decaying waves of the Euler bay at every point.

    Parameters
    ----------
    beta4 : array
        ``m omega^2 d^4 / EI*`` per point (dimensionless, complex), ``(N,)``.
    pad : array
        ``K* d^3 / EI*`` per point (dimensionless, complex), ``(N,)``.
    xp : module
        Array namespace.

    Returns
    -------
    StackedWaves
    """
    with np.errstate(all="ignore"):  # the branches xp.where discards may overflow
        return _waves(beta4, pad, xp)


def _waves(beta4: Any, pad: Any, xp: Any) -> StackedWaves:
    basis = krylov(beta4, 0.5, xp)
    half = [
        [basis[c - r] if c >= r else beta4 * basis[c - r + 4] for c in range(4)] for r in range(4)
    ]
    mu_small, mu_big = _propagation_constants(*_characteristic(beta4, pad, xp), xp)
    vec = [_bloch_vector(half, pad, m, xp) for m in mu_small]  # [wave][component]
    partner = [_mirror(v, pad) for v in vec]
    mu, right = [], []
    for k in range(2):
        swap = (xp.abs(xp.abs(mu_small[k]) - 1.0) < ENERGY_FLOW_TOLERANCE) & (
            _energy_flux(vec[k], xp) < 0
        )
        mu.append(xp.where(swap, mu_big[k], mu_small[k]))
        right.append([xp.where(swap, p, v) for p, v in zip(partner[k], vec[k], strict=True)])
    left = [_mirror(r, pad) for r in right]
    # [R, -L], rows equilibrated: at a stiff pad the displacement row of the waves is small
    matching = [[right[0][i], right[1][i], -left[0][i], -left[1][i]] for i in range(4)]
    rows = [1.0 / _max_abs(row, xp) for row in matching]
    matching = [[e * rows[i] for e in matching[i]] for i in range(4)]
    inverse = _inverse(matching, xp)
    condition = _max_abs([e for row in matching for e in row], xp) * _max_abs(
        [e for row in inverse for e in row], xp
    )
    inverse = [[inverse[i][j] * rows[j] for j in range(4)] for i in range(4)]
    return StackedWaves(
        beta4=beta4,
        pad=pad,
        mu=mu,
        right=[[right[k][i] for k in range(2)] for i in range(4)],
        left=[[left[k][i] for k in range(2)] for i in range(4)],
        matching_inv=inverse,
        condition=4.0 * condition,
    )


def receptance_entries(
    waves: StackedWaves, x_load: Any, x_obs: Any, xp: Any = np
) -> list[list[Any]]:
    """Dimensionless receptance ``[obs][load]`` between points, each ``(N,)``.

    Multiplied by ``d^3 / EI*`` it is the receptance in m/N.

    Parameters
    ----------
    waves : StackedWaves
        From :func:`stacked_waves`.
    x_load, x_obs : array_like
        Dimensionless positions ``x / d`` of the loads and observation points (the same at
        every point of the stack), sleepers at integers.
    xp : module
        Array namespace.

    Returns
    -------
    list of list of array
        Displacement at ``x_obs[i]`` per unit force at ``x_load[j]``.
    """
    x_load = np.atleast_1d(np.asarray(x_load, dtype=float))
    x_obs = np.atleast_1d(np.asarray(x_obs, dtype=float))
    ref_load, xi = _nearest_sleeper(x_load)
    ref_obs, eta = _nearest_sleeper(x_obs)
    xi, eta = _distinct(xi), _distinct(eta)
    pad = waves.pad
    series: dict[float, list[Any]] = {}

    def beam(u: float) -> list[Any]:
        """``s_j(u)``, from ``s_j(|u|)``: ``s_j(-u) = (-1)^j s_j(u)`` (the same numbers)."""
        if abs(u) not in series:
            series[abs(u)] = krylov(waves.beta4, abs(u), xp)
        s = series[abs(u)]
        return list(s) if u >= 0 else [s[0], -s[1], s[2], -s[3]]

    amps = {}
    for u in np.unique(xi):  # wave amplitudes (a1, a2, b1, b2) of a load at coordinate u
        s = beam(-float(u))
        rhs = [s[3], s[2], s[1], s[0]]
        if u < 0:
            rhs[3] = rhs[3] - pad * rhs[0]
        amps[float(u)] = [dot(row, rhs) for row in waves.matching_inv]
    disp = {}
    for u in np.unique(eta):  # displacement of each wave at observation coordinate u
        row = beam(float(u))
        if u < 0:
            row[0] = row[0] + pad * row[3]
        disp[float(u)] = [
            [dot(row, [c[k] for c in side]) for k in range(2)] for side in (waves.right, waves.left)
        ]
    powers: dict[int, list[Any]] = {}
    # pairs with the same local coordinates, side and bay count are the same numbers (the
    # wheels of two bogies a whole number of bays apart): each formed once
    pairs: dict[tuple[float, float, int, int], Any] = {}
    out = []
    for i in range(x_obs.size):
        out_row = []
        for j in range(x_load.size):
            side = 0 if x_obs[i] >= x_load[j] else 1
            m = int(abs(ref_obs[i] - ref_load[j]))
            key = (float(eta[i]), float(xi[j]), side, m)
            if key not in pairs:
                if m not in powers:
                    powers[m] = [mu_k**m for mu_k in waves.mu]
                a = amps[float(xi[j])][2 * side : 2 * side + 2]
                d_k = disp[float(eta[i])][side]
                pairs[key] = a[0] * powers[m][0] * d_k[0] + a[1] * powers[m][1] * d_k[1]
            out_row.append(pairs[key])
        out.append(out_row)
    return out


def _nearest_sleeper(x: Any) -> tuple[Any, Any]:
    """Index of the nearest sleeper and the local coordinate in [-1/2, 1/2] from it."""
    bay = np.floor(x)
    ref = bay + ((x - bay) > 0.5)
    return ref.astype(np.int64), x - ref


def _distinct(x: Any, decimals: int = 12) -> Any:
    """`x` with the values equal to `decimals` places made equal (to the first of them).

    Wheel positions a whole number of bays apart give local coordinates that differ by
    float noise (``0.5`` and ``0.4999999999999991``); they are one coordinate, one
    evaluation of the beam field.
    """
    _, first, inverse = np.unique(np.round(x, decimals), return_index=True, return_inverse=True)
    return x[first][inverse.ravel()]


def _max_abs(values: list[Any], xp: Any) -> Any:
    out = xp.abs(values[0])
    for v in values[1:]:
        out = xp.maximum(out, xp.abs(v))
    return out


def _characteristic(beta4: Any, pad: Any, xp: Any) -> tuple[Any, Any]:
    """``c1`` and ``c2 - 2`` of the Euler bay in closed form (no cancellation)."""
    s = krylov(beta4, 1.0, xp)
    c1 = 4.0 * s[0] - pad * s[3]
    small = xp.abs(beta4) < 16.0  # |z| < 2: the alternating series loses < 2.3 ulp
    q = krylov(xp.where(small, -4.0 * beta4, 0.0 * beta4), 1.0, xp)
    series = 4.0 * (q[0] + pad * q[3])
    z = xp.where(small, 1.0 + 0.0 * beta4, beta4) ** 0.25
    cos, cosh, sin, sinh = xp.cos(z), xp.cosh(z), xp.sin(z), xp.sinh(z)
    closed = 4.0 * cos * cosh + pad * (cosh * sin - cos * sinh) / z**3
    return c1, xp.where(small, series, closed)


def _propagation_constants(c1: Any, c2m2: Any, xp: Any) -> tuple[list[Any], list[Any]]:
    """The two small (``|mu| <= 1``) eigenvalues and their large partners ``1/mu``."""
    disc = xp.sqrt(c1**2 - 4.0 * c2m2)
    disc = xp.where(xp.real(xp.conj(c1) * disc) >= 0, disc, -disc)
    lam_big = 0.5 * (c1 + disc)
    lam_big = xp.where(lam_big == 0, 1.0 + 0.0 * lam_big, lam_big)  # c1 = c2 - 2 = 0
    small, big = [], []
    for lam in (lam_big, c2m2 / lam_big):
        root = xp.sqrt((lam - 2.0) * (lam + 2.0))
        root = xp.where(xp.real(xp.conj(lam) * root) >= 0, root, -root)
        large = 0.5 * (lam + root)  # no cancellation in the larger root
        small.append(1.0 / large)
        big.append(large)
    return small, big


def _bloch_vector(half: list[list[Any]], pad: Any, mu: Any, xp: Any) -> list[Any]:
    """Unit null vector of the half-bay pencil ``B(1/2) - mu B(-1/2) P^-1`` (4 entries)."""
    back = [[half[r][c] * (_MIRROR[r] * _MIRROR[c]) for c in range(4)] for r in range(4)]
    for r in range(4):
        back[r][0] = back[r][0] + pad * back[r][3]
    m = [[half[r][c] - mu * back[r][c] for c in range(4)] for r in range(4)]
    m = [[e * inv for e in row] for row, inv in ((row, 1.0 / _norm(row, xp)) for row in m)]
    first = _cross(m[1], _minors(m[2], m[3]))
    second = _cross(m[2], _minors(m[0], m[1]))
    n1, n2 = _norm(first, xp), _norm(second, xp)
    better = n2 > n1
    norm = xp.where(better, n2, n1)
    best = [xp.where(better, b, a) / norm for a, b in zip(first, second, strict=True)]
    weak = norm < WEAK_CROSS_PRODUCT
    if bool(xp.any(weak)):  # near a band edge of a lossless rail: an SVD of those points
        mask = to_numpy(weak)
        dense = np.stack([np.stack([to_numpy(e)[mask] for e in row], -1) for row in m], -2)
        null = np.conj(np.linalg.svd(dense)[2][:, -1, :])
        best = [put(best[c], weak, null[:, c], xp) for c in range(4)]
    return best


def _norm(v: list[Any], xp: Any) -> Any:
    return xp.sqrt(sum((xp.real(e) ** 2 + xp.imag(e) ** 2 for e in v[1:]), xp.abs(v[0]) ** 2))


def _minors(b: list[Any], c: list[Any]) -> dict[tuple[int, int], Any]:
    return {(q, r): b[q] * c[r] - b[r] * c[q] for q, r in _PAIRS}


def _cross(a: list[Any], minors: dict[tuple[int, int], Any]) -> list[Any]:
    out = []
    for i in range(4):
        p, q, r = (k for k in range(4) if k != i)
        det = a[p] * minors[q, r] - a[q] * minors[p, r] + a[r] * minors[p, q]
        out.append(det if i % 2 == 0 else -det)
    return out


def _mirror(v: list[Any], pad: Any) -> list[Any]:
    """Mirror image ``x -> -x`` of a wave given just right of a sleeper (4 entries)."""
    return [v[0], -v[1], v[2], -v[3] - pad * v[0]]


def _energy_flux(v: list[Any], xp: Any) -> Any:
    """Sign-carrying power flow to the right, ``Im(w''' conj(w) - w'' conj(w'))``."""
    return xp.imag(v[3] * xp.conj(v[0]) - v[2] * xp.conj(v[1]))


def _inverse(a: list[list[Any]], xp: Any) -> list[list[Any]]:
    """``A^-1`` by elimination on entries; points with weak pivots inverted by LAPACK."""
    n = len(a)
    inverse, bad = lu_inverse(a, xp)
    if bool(xp.any(bad)):
        mask = to_numpy(bad)
        dense = np.stack([np.stack([to_numpy(e)[mask] for e in row], -1) for row in a], -2)
        inv = np.linalg.inv(dense)
        inverse = [[put(inverse[i][j], bad, inv[:, i, j], xp) for j in range(n)] for i in range(n)]
    return inverse
