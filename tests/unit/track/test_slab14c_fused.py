"""The slab track's fused kernel (railvib.track.slab_kernel) against the NumPy cell solver.

The kernel is the cell solver's algorithm in one pass over batches of frequencies, its
solves without row exchanges (a frequency with a weak pivot, or a doubling not converged,
is solved again by the cell solver). The plain Python functions (fast tests, a few
frequencies) and the numba-compiled ones (slow: numba compiles them on first use) must
give the NumPy path's numbers to rounding, and the fallback must give the cell solver's.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from railvib.errors import SolverWarning
from railvib.track import cells, compiled_cells, slab, slab_kernel

from .test_slabspeed_compiled import PLAIN, TRACKS, X

#: the tracks the fused kernel serves (Euler rails; a Timoshenko rail keeps the cell solver)
EULER = [name for name, track in TRACKS.items() if track.rail.shear_stiffness is None]

#: as railvib's own compiled/NumPy bound (test_slabspeed_compiled.RTOL): the same
#: algorithm, rounded differently (no row exchanges, sums in another order, FMA), which
#: the doubling of slowly decaying waves amplifies: measured up to 1.4e-11 of the peak on
#: these tracks over 0.1 Hz - 2 kHz, the cell kernel of main up to 1.3e-10
RTOL = 5e-10


def _peak_error(got, ref):
    scale = np.abs(ref).max(axis=(1, 2), keepdims=True)
    return float(np.max(np.abs(got - ref) / scale))


def _numpy(monkeypatch, fn):
    with monkeypatch.context() as patch:
        patch.setenv("RAILVIB_COMPILED", "0")
        return fn()


def _fused(monkeypatch, kernel, fn, calls=None):
    """`fn` with the cell kernel `kernel` loaded and the fused kernel's calls counted."""
    seen = [] if calls is None else calls
    original = slab.slab_receptance

    def counted(*args, **kwargs):
        seen.append(args[0].shape[1])
        return original(*args, **kwargs)

    with monkeypatch.context() as patch:
        patch.delenv("RAILVIB_COMPILED", raising=False)
        patch.setattr(compiled_cells, "_CELL_KERNEL", [kernel])
        patch.setattr(slab, "slab_receptance", counted)
        return fn()


def _plain(monkeypatch):
    """The plain Python kernels (the fused one's callees too, not numba's if loaded)."""
    for name in slab_kernel._FUNCTIONS:
        monkeypatch.setattr(slab_kernel, name, slab_kernel._PLAIN[name])
    return (*PLAIN, slab_kernel._PLAIN["_batches"])


@pytest.mark.parametrize("name", EULER)
def test_plain_fused_kernel_gives_the_numpy_receptance(monkeypatch, name):
    track = TRACKS[name]
    f = np.array([3.0, 85.0, 1500.0])  # below the slab resonance, mid band, high
    ref = _numpy(monkeypatch, lambda: track.receptance(f, X, X))
    calls = []
    got = _fused(monkeypatch, _plain(monkeypatch), lambda: track.receptance(f, X, X), calls)
    assert calls == [f.size]  # the fused kernel ran, once, on every frequency
    assert _peak_error(got, ref) <= RTOL


def test_flagged_frequencies_are_the_cell_solvers(monkeypatch):
    """Every pivot weak: every frequency is solved again by the cell solver, exactly."""
    track = TRACKS["bearings"]
    f = np.array([0.3, 11.0, 700.0])
    kernel = _plain(monkeypatch)
    cell_path = _fused(monkeypatch, PLAIN, lambda: track.receptance(f, X, X))
    monkeypatch.setattr(slab_kernel, "PIVOT_THRESHOLD", 1e100)
    calls = []
    got = _fused(monkeypatch, kernel, lambda: track.receptance(f, X, X), calls)
    assert calls == [f.size]
    np.testing.assert_array_equal(got, cell_path)


def test_unconverged_doubling_warns_on_the_fused_kernel_as_on_numpy(monkeypatch):
    track = TRACKS["floating"]
    f = np.array([50.0, 900.0])
    kernel = _plain(monkeypatch)
    monkeypatch.setattr(cells, "MAX_DOUBLINGS", 1)  # one doubling: two cells, no decay yet
    with pytest.warns(SolverWarning, match="2 frequencies"):
        _numpy(monkeypatch, lambda: track.receptance(f, X, X))
    calls = []
    with pytest.warns(SolverWarning, match="2 frequencies"):
        _fused(monkeypatch, kernel, lambda: track.receptance(f, X, X), calls)
    assert calls == [f.size]


def test_the_fused_kernel_is_used_only_with_the_loaded_cell_kernel(monkeypatch):
    kernel = (*PLAIN, slab_kernel._PLAIN["_batches"])
    monkeypatch.delenv("RAILVIB_COMPILED", raising=False)
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [kernel])
    assert compiled_cells.fused_kernel() is kernel[5]
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [PLAIN])  # a cell kernel without it
    assert compiled_cells.fused_kernel() is None
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [kernel])
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    assert compiled_cells.fused_kernel() is None


def test_a_timoshenko_rail_keeps_the_cell_solver(monkeypatch):
    track = TRACKS["timoshenko"]
    f = np.array([85.0])
    kernel = _plain(monkeypatch)
    calls = []
    _fused(monkeypatch, kernel, lambda: track.receptance(f, X, X), calls)
    assert calls == []


@pytest.mark.slow  # numba compiles the kernel on its first use (seconds), then caches it
@pytest.mark.parametrize("name", EULER)
def test_compiled_fused_kernel_gives_the_numpy_receptance(monkeypatch, name):
    pytest.importorskip("numba")
    track = TRACKS[name]
    f = np.geomspace(0.1, 2000.0, 600)
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [])  # loaded for this test only
    kernel = compiled_cells.cell_kernel()
    assert kernel[5] is not None
    ref = _numpy(monkeypatch, lambda: track.receptance(f, X, X))
    calls = []
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the kernel converges where NumPy does
        got = _fused(monkeypatch, kernel, lambda: track.receptance(f, X, X), calls)
    assert calls == [f.size]
    assert _peak_error(got, ref) <= RTOL


@pytest.mark.parametrize("name", ["floating", "bearings"])  # bays of a foundation, bearings
def test_plain_fused_kernel_gives_the_numpy_support_forces(monkeypatch, name):
    track = TRACKS[name]
    f = np.array([0.05, 12.0, 400.0])
    ref = _numpy(monkeypatch, lambda: track.support_response(f, 0.45, 3))
    calls = []
    got = _fused(
        monkeypatch, _plain(monkeypatch), lambda: track.support_response(f, 0.45, 3), calls
    )
    assert calls == [f.size]
    for layer in ref.force:
        assert _peak_error(got.force[layer][..., None], ref.force[layer][..., None]) <= RTOL
    for mass in ref.displacement:
        got_d, ref_d = got.displacement[mass][..., None], ref.displacement[mass][..., None]
        assert _peak_error(got_d, ref_d) <= RTOL
