"""The harmonic-balance blocks of the moving vehicle, against their defining formulas.

:func:`railvib.moving.harmonic_blocks` gathers ``R`` from the table of moving-load
receptances with one index array, and :meth:`~railvib.moving.harmonic.HarmonicSystem.solve`
writes ``R S`` straight into the system matrix. Here both are checked against the module's
own equations, evaluated entry by entry with loops (another code path): ``R[q, m]_ji =
A_{q-m}(Omega + m Omega_s, r_ji) exp(i (q - m) phi_i)`` for ``|q - m| <= N`` and 0 outside,
and the solution satisfying ``u_w = r + R P + P / k_H`` with ``P = -S u_w``.
"""

from __future__ import annotations

import numpy as np

from railvib.coupling import CoupledSystem
from railvib.moving import MovingSettings, harmonic_blocks
from railvib.moving.harmonic import load_receptances
from railvib.pads import SpringDamper
from railvib.track import BallastedTrack, Rail
from railvib.vehicle.library import PitchPlaneParameters

D = 0.6
TRACK = BallastedTrack(
    Rail(6.4e6, 60.0, loss_factor=0.01),
    SpringDamper(2.0e8, 3.0e4),
    D,
    sleeper_mass=150.0,
    ballast=SpringDamper(1.0e8, 8.0e4),
)
#: Wang et al. (2017) Table 1 metro car, half of it on one rail
VEHICLE = (
    PitchPlaneParameters(
        21920.0, 617310.0, 2550.0, 1750.0, 1420.0, 1.7e6, 5.0e3, 2.75e5, 3.0e4, 6.3, 1.1
    )
    .vehicle()
    .scaled(0.5)
)
K_H = 1.0e9
#: 20 m/s: v / d = 33.3 Hz, so the lowest base frequency has negative load frequencies
SYSTEM = CoupledSystem(VEHICLE, TRACK, K_H, 0.17, 20.0)
SETTINGS = MovingSettings(2, 0.5)
F = np.array([5.0, 47.3, 120.0])


def test_blocks_are_the_defining_formula_entry_by_entry():
    blocks = harmonic_blocks(SYSTEM, F, SETTINGS)
    table = load_receptances(SYSTEM, F, SETTINGS)
    n = SETTINGS.harmonic_order
    x = SYSTEM.wheel_positions
    passing = SYSTEM.speed / D
    expected = np.zeros_like(blocks.receptance)
    for a, f in enumerate(F):
        for m in range(-n, n + 1):
            amp = table.signed([f + m * passing])[0]  # (n_r, 2 N + 1)
            for q in range(-n, n + 1):
                if abs(q - m) > n:
                    continue
                for j in range(x.size):
                    for i in range(x.size):
                        gap = np.flatnonzero(np.isclose(table.r, x[j] - x[i], atol=1e-9))
                        assert gap.size == 1
                        phase = np.exp(1j * (q - m) * 2.0 * np.pi * x[i] / D)
                        expected[a, q + n, j, m + n, i] = amp[gap[0], q - m + n] * phase
    # the same products of the same numbers: equal to rounding (a few ulp of the largest)
    scale = np.abs(expected).max()
    assert np.abs(blocks.receptance - expected).max() <= 1e-14 * scale
    # outside the band the blocks are exactly empty
    q, m = np.meshgrid(np.arange(-n, n + 1), np.arange(-n, n + 1), indexing="ij")
    outside = np.abs(q - m) > n
    assert np.all(blocks.receptance.transpose(0, 1, 3, 2, 4)[:, outside] == 0.0)


def test_solution_satisfies_the_harmonic_balance():
    blocks = harmonic_blocks(SYSTEM, F, SETTINGS)
    n_f, h, n_w = blocks.stiffness.shape[:3]
    rng = np.random.default_rng(17)
    rhs = rng.standard_normal((n_f, h, n_w, 3)) + 1j * rng.standard_normal((n_f, h, n_w, 3))
    rhs *= 1e-4
    for loads in (None, np.array([5.0e4, 6.0e4, 7.0e4, 8.0e4])[:n_w]):
        _, force, rail = blocks.solve(rhs, loads)
        size = h * n_w
        rec = blocks.receptance.reshape(n_f, size, size)
        p = force.reshape(n_f, size, -1)
        # the rail under the wheels is R P (the static loads' part of P included)
        assert np.allclose(
            rail.reshape(n_f, size, -1), rec @ p, rtol=0.0, atol=1e-12 * abs(rail).max()
        )
        dynamic = force.copy()
        if loads is not None:
            dynamic[:, h // 2] -= loads[None, :, None]
        # u_w = r + R P + P / k_H (wheel on rail through the Hertz spring), P_dyn = -S u_w
        u_w = rhs + rail + force / K_H
        back = -np.einsum("fmij,fmjc->fmic", blocks.stiffness, u_w)
        # a solve of 44 unknowns conditioned ~1e3-1e5: agreement to 1e-9 of the largest force
        assert np.abs(back - dynamic).max() <= 1e-9 * np.abs(force).max()
