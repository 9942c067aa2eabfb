"""The slab cell solver's fewer operations: waves on the cell without the points' nodes,
the loaded cell solved by condensing its interior, and the compiled Euler span.

Each is a different computation of the same quantity as the path it replaces: the
receptance with the waves found on the cell that also holds the load and observation
nodes (the previous path, still :func:`railvib.track.cells.cell_receptance` without a
`cell`), and the span stiffness of the NumPy functions of :mod:`railvib.track.beam`.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.track import cells, compiled_cells
from railvib.track.slab import _rail_dofs

from .test_slabspeed_compiled import PLAIN, TRACKS, X

#: two roundings of the same algorithm. The doubling of the slab's slowly decaying waves
#: amplifies rounding near the slab-on-foundation resonance: a 1-ulp random perturbation of
#: the spans' stiffness moves the receptance there by up to 1.1e-9 of its peak (measured,
#: 7-14 Hz); at these frequencies, away from it, the paths agree to ~1e-12
RTOL = 5e-10

#: the span's entries are the same formulas in the same order, but for the 2 x 2 inverse of
#: the transfer matrix's block (closed form here, LU in LAPACK): a few ulp of the block's
#: condition number, at most cosh(2)^2 = 14 below CLOSED_FORM_WAVENUMBER (measured 1.1e-15)
SPAN_RTOL = 1e-13

#: the same chains on both sides, so only the rounding of two solves of the 20-DOF loaded
#: cell: measured 1.8e-12 (NumPy) and 9.4e-12 (kernel) of the peak, with 10x margin
SOLVE_RTOL = 1e-10


def _peak_error(got, ref):
    scale = np.abs(ref).max(axis=tuple(range(1, ref.ndim)), keepdims=True)
    return float(np.max(np.abs(got - ref) / scale))


def _both_cells(track, f):
    """The receptance between the points X with the waves on each of the two cells."""
    layers = track.layer_stiffness(f)
    load_cell, local = track._locate(X)
    extra = np.concatenate([local, local])
    cell, rail_nodes = track._cell(f, extra, layers)
    minimal = track._cell(f, np.zeros(0), layers)[0]
    points = (load_cell, _rail_dofs(rail_nodes, local))
    with_nodes = cells.cell_receptance(cells.cell_waves(cell), points, points)
    without = cells.cell_receptance(cells.cell_waves(minimal), points, points, cell)
    return with_nodes, without, minimal, cell


@pytest.mark.parametrize("name", list(TRACKS))
def test_waves_on_the_cell_without_the_points_give_the_same_receptance(monkeypatch, name):
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    f = np.array([3.0, 85.0, 1500.0])  # below the slab resonance, mid band, high
    with_nodes, without, minimal, cell = _both_cells(TRACKS[name], f)
    assert minimal.interior.size < cell.interior.size  # fewer DOFs condensed for the waves
    assert _peak_error(without, with_nodes) <= RTOL


@pytest.mark.parametrize("kernel", ["numpy", "plain"])
def test_the_loaded_cell_at_its_points_equals_its_full_solve(monkeypatch, kernel):
    """The points' solve against the loaded cell solved whole with both chains attached."""
    track = TRACKS["bearings"]
    f = np.array([0.05, 12.0, 400.0])
    if kernel == "numpy":
        monkeypatch.setenv("RAILVIB_COMPILED", "0")
    else:
        monkeypatch.delenv("RAILVIB_COMPILED", raising=False)
        monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [PLAIN])
    layers = track.layer_stiffness(f)
    _, local = track._locate(X)
    cell, rail_nodes = track._cell(f, local, layers)
    waves = cells.cell_waves(track._cell(f, np.zeros(0), layers)[0])
    dofs = _rail_dofs(rail_nodes, local)
    # every wheel in one cell (offset 0): the points' displacements are the cell's own
    same = (np.zeros(X.size, dtype=np.int64), dofs)
    got = cells.cell_receptance(waves, same, same, cell)
    k = cell.stiffness()
    bnd = cell.boundary
    m = bnd.size // 2
    k[:, bnd[:m, None], bnd[None, :m]] += waves.left_chain
    k[:, bnd[m:, None], bnd[None, m:]] += waves.right_chain
    unit = np.zeros((f.size, k.shape[1], dofs.size), dtype=complex)
    unit[:, dofs, np.arange(dofs.size)] = 1.0
    ref = np.linalg.solve(k, unit)[:, dofs, :]
    assert _peak_error(got, ref) <= SOLVE_RTOL


def test_a_receptance_is_symmetric_between_its_points(monkeypatch):
    """Reciprocity: the symmetric doubling (kernel) and the full one (NumPy) both keep it."""
    track = TRACKS["unit_jointed"]
    f = np.array([2.0, 60.0, 900.0])
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    ref = track.receptance(f, X, X)
    monkeypatch.delenv("RAILVIB_COMPILED")
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [PLAIN])
    got = track.receptance(f, X, X)
    for r in (ref, got):
        assert _peak_error(r.transpose(0, 2, 1), r) <= RTOL


@pytest.mark.parametrize("loss", [0.0, 0.02])
@pytest.mark.parametrize("length", [0.15, 0.6, 2.4])
def test_the_compiled_euler_span_gives_the_numpy_span(monkeypatch, loss, length):
    # both branches: the series below |beta L| = 2, the closed form above; and a slab on a
    # foundation below its cut-on (beta4 < 0)
    omega2 = (2.0 * np.pi * np.geomspace(0.1, 5000.0, 40)) ** 2
    ei = 1.2e8 * (1.0 + 1j * max(loss, 1e-9))
    beta4 = np.concatenate([1750.0 * omega2, 1750.0 * omega2[:10] - 7e6]) * length**4 / ei
    closed = np.abs(beta4) >= cells.CLOSED_FORM_WAVENUMBER**4
    assert closed.any() or length < 0.6
    assert (~closed).any()
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    ref = cells.span_stiffness(beta4, length, ei)
    monkeypatch.delenv("RAILVIB_COMPILED")
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [PLAIN])
    assert _peak_error(cells.span_stiffness(beta4, length, ei), ref) <= SPAN_RTOL
