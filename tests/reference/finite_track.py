"""An independent brute-force model for the tests: a long FINITE rail on discrete pads.

Hermite cubic Euler-Bernoulli elements (consistent mass), ``n_sub`` elements per
sleeper bay, full pad impedance at every sleeper node, free ends softened by
absorbing end zones whose pad damping grows smoothly towards the ends. One
sparse direct solve per frequency. Shares no code with ``railvib.track``.

Discretisation error of Hermite elements on this track (physics.md §3.1 table):
4.4e-4 at 2 kHz with 4 elements per bay, 2.7e-5 with 8; the tests use 12.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def hermite_element(ei: complex, m: float, length: float) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness and consistent mass of a Hermite beam element (w1, t1, w2, t2)."""
    L = length
    k = (
        ei
        / L**3
        * np.array(
            [
                [12, 6 * L, -12, 6 * L],
                [6 * L, 4 * L**2, -6 * L, 2 * L**2],
                [-12, -6 * L, 12, -6 * L],
                [6 * L, 2 * L**2, -6 * L, 4 * L**2],
            ]
        )
    )
    mm = (
        m
        * L
        / 420
        * np.array(
            [
                [156, 22 * L, 54, -13 * L],
                [22 * L, 4 * L**2, 13 * L, -3 * L**2],
                [54, 13 * L, 156, -22 * L],
                [-13 * L, -3 * L**2, -22 * L, 4 * L**2],
            ]
        )
    )
    return k, mm


class FiniteTrack:
    """Rail from sleeper ``-n_bays`` to ``+n_bays`` (at ``n d``), with pads at the sleepers."""

    def __init__(self, ei, m, pad_k, pad_c, d, n_bays=300, n_sub=12, absorber_bays=100):
        self.d, self.n_sub = d, n_sub
        self.h = d / n_sub
        n_el = 2 * n_bays * n_sub
        self.x0 = -n_bays * d
        self.n_nodes = n_el + 1
        ke, me = hermite_element(ei, m, self.h)
        rows, cols, kv, mv = [], [], [], []
        for e in range(n_el):
            dofs = np.arange(2 * e, 2 * e + 4)
            rows.append(np.repeat(dofs, 4))
            cols.append(np.tile(dofs, 4))
            kv.append(ke.ravel())
            mv.append(me.ravel())
        shape = (2 * self.n_nodes, 2 * self.n_nodes)
        r, c = np.concatenate(rows), np.concatenate(cols)
        self.K = sp.csc_matrix((np.concatenate(kv), (r, c)), shape=shape)
        self.M = sp.csc_matrix((np.concatenate(mv), (r, c)), shape=shape)
        sleepers = np.arange(0, self.n_nodes, n_sub)
        # distance of each sleeper into the absorbing end zone, 0..1
        depth = np.zeros(sleepers.size)
        idx = np.arange(sleepers.size)
        edge = np.minimum(idx, sleepers.size - 1 - idx)
        zone = edge < absorber_bays
        depth[zone] = 1.0 - edge[zone] / absorber_bays
        extra_c = pad_c * 40.0 * depth**3
        self.pad_dofs = 2 * sleepers
        self.pad_k = pad_k
        self.pad_c = pad_c + extra_c
        self.pad_k_is_callable = callable(pad_k)

    def node_of(self, x: float) -> int:
        i = (x - self.x0) / self.h
        n = int(round(i))
        if abs(i - n) > 1e-9:
            raise ValueError(f"x = {x} is not a node")
        return n

    def receptance(self, f, x_load, x_obs):
        """Displacement at x_obs per unit force at x_load, (n_freq, n_obs, n_load)."""
        f = np.atleast_1d(f)
        load = [2 * self.node_of(x) for x in x_load]
        obs = [2 * self.node_of(x) for x in x_obs]
        out = np.empty((f.size, len(obs), len(load)), dtype=complex)
        rhs = np.zeros((self.K.shape[0], len(load)), dtype=complex)
        for j, dof in enumerate(load):
            rhs[dof, j] = 1.0
        for i, fi in enumerate(f):
            w = 2 * np.pi * fi
            kp = self.pad_k(fi) if self.pad_k_is_callable else self.pad_k
            pad = sp.csc_matrix(
                (kp + 1j * w * self.pad_c, (self.pad_dofs, self.pad_dofs)), shape=self.K.shape
            )
            a = (self.K - w**2 * self.M + pad).tocsc()
            sol = spla.splu(a).solve(rhs)
            out[i] = sol[obs, :]
        return out
