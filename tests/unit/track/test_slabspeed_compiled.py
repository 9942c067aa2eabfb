"""The compiled cell kernel (railvib.track.compiled_cells) against the NumPy cell solver.

The kernel is the same algorithm written frequency by frequency: the plain Python
functions (fast tests, a few frequencies) and the numba-compiled ones (slow: numba
compiles them on first use) must give the NumPy path's numbers to rounding.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from railvib.errors import SolverWarning
from railvib.pads import Hysteretic, SpringDamper
from railvib.track import FloatingSlabTrack, Rail, UnitSlabTrack, cells, compiled, compiled_cells

UIC60 = Rail(6.42e6, 60.0, 0.01)
TIMOSHENKO = Rail(6.42e6, 60.0, 0.01, 2.45e8, 0.25)
UNDAMPED = Rail(6.42e6, 60.0, 0.0)
PAD = Hysteretic(3e8, 0.25)
SLAB = {"slab_bending_stiffness": 1.2e8, "slab_mass_per_length": 1750.0, "slab_loss_factor": 0.05}
FOUNDATION = Hysteretic(7e6, 0.2)
BEARING = SpringDamper(2e7, 2e4)
X = np.array([0.0, 0.3, 1.1, -2.7, 7.45])
#: the same algorithm with the same elimination order as LAPACK's (partial pivoting on
#: |Re| + |Im|): only the order of the sums differs, ~1e-16 each, which the doubling of the
#: slowly decaying slab waves near the slab-on-foundation resonance (7-12 Hz) amplifies:
#: measured up to 1.6e-10 of the peak there (changing only the rounding of the spans' 2 x 2
#: inverse on the NumPy path moves it by 1.3e-10 as well), ~1e-13 elsewhere
RTOL = 5e-10

TRACKS = {
    "floating": FloatingSlabTrack(UIC60, PAD, 0.6, foundation=FOUNDATION, **SLAB),
    "bearings": FloatingSlabTrack(
        UIC60, PAD, 0.6, bearing=BEARING, bearing_spacing_fasteners=2, **SLAB
    ),
    "timoshenko": FloatingSlabTrack(TIMOSHENKO, PAD, 0.6, foundation=FOUNDATION, **SLAB),
    "undamped_rail": FloatingSlabTrack(UNDAMPED, PAD, 0.6, bearing=BEARING, **SLAB),
    "unit_free": UnitSlabTrack(
        UIC60, PAD, 0.6, foundation=FOUNDATION, slab_length=2.4, fasteners_per_slab=4, **SLAB
    ),
    "unit_jointed": UnitSlabTrack(
        UIC60,
        PAD,
        0.6,
        bearing=BEARING,
        slab_length=2.4,
        fasteners_per_slab=4,
        joint_shear_stiffness=1e8,
        joint_bending_stiffness=1e6,
        **SLAB,
    ),
}

#: the entry points' plain Python functions, in the order of cell_kernel()'s tuple
PLAIN = tuple(compiled_cells._PLAIN[name] for name in compiled_cells._FUNCTIONS[3:])


def _numpy(monkeypatch, fn):
    with monkeypatch.context() as patch:
        patch.setenv("RAILVIB_COMPILED", "0")
        return fn()


def _kernel(monkeypatch, kernel, fn):
    with monkeypatch.context() as patch:
        patch.delenv("RAILVIB_COMPILED", raising=False)
        patch.setattr(compiled_cells, "_CELL_KERNEL", [kernel])
        assert compiled_cells.use_compiled_cells()
        return fn()


def _peak_error(got, ref):
    scale = np.abs(ref).max(axis=tuple(range(1, ref.ndim)), keepdims=True)
    return float(np.max(np.abs(got - ref) / scale))


@pytest.mark.parametrize("name", list(TRACKS))
def test_plain_kernel_gives_the_numpy_receptance(monkeypatch, name):
    track = TRACKS[name]
    f = np.array([3.0, 85.0, 1500.0])  # below the slab resonance, mid band, high
    ref = _numpy(monkeypatch, lambda: track.receptance(f, X, X))
    got = _kernel(monkeypatch, PLAIN, lambda: track.receptance(f, X, X))
    assert _peak_error(got, ref) <= RTOL


def test_plain_kernel_gives_the_numpy_waves_and_bearing_forces(monkeypatch):
    track = TRACKS["bearings"]
    f = np.array([0.05, 12.0, 400.0])
    ref = _numpy(monkeypatch, lambda: track.support_response(f, 0.45, 3))
    got = _kernel(monkeypatch, PLAIN, lambda: track.support_response(f, 0.45, 3))
    for layer in ("pad", "bearing"):
        assert _peak_error(got.force[layer], ref.force[layer]) <= RTOL
    mu_ref = _numpy(monkeypatch, lambda: track.propagation_constants(f))
    mu = _kernel(monkeypatch, PLAIN, lambda: track.propagation_constants(f))
    assert np.max(np.abs(mu - mu_ref)) <= RTOL  # |mu| <= 1: absolute


def test_unconverged_doubling_warns_on_the_kernel_as_on_numpy(monkeypatch):
    track = TRACKS["floating"]
    f = np.array([50.0, 900.0])
    monkeypatch.setattr(cells, "MAX_DOUBLINGS", 1)  # one doubling: two cells, no decay yet
    for run in (_numpy, lambda mp, fn: _kernel(mp, PLAIN, fn)):
        with pytest.warns(SolverWarning, match="2 frequencies"):
            run(monkeypatch, lambda: track.propagation_constants(f))


def test_the_kernel_is_used_only_where_the_compiled_kernels_are_loaded(monkeypatch):
    monkeypatch.delenv("RAILVIB_COMPILED", raising=False)
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [])
    monkeypatch.setattr(compiled, "_KERNEL", [])
    assert not compiled_cells.use_compiled_cells()  # a single run: NumPy, numba not imported
    assert compiled_cells._CELL_KERNEL == []
    monkeypatch.setattr(compiled, "_KERNEL", [None])  # numba missing
    assert not compiled_cells.use_compiled_cells()
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [PLAIN])
    assert compiled_cells.use_compiled_cells()
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    assert not compiled_cells.use_compiled_cells()


@pytest.mark.slow  # numba compiles the kernel on its first use (seconds), then caches it
@pytest.mark.parametrize("name", list(TRACKS))
def test_compiled_kernel_gives_the_numpy_receptance(monkeypatch, name):
    pytest.importorskip("numba")
    track = TRACKS[name]
    f = np.geomspace(0.1, 2000.0, 600)
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [])  # loaded for this test only
    kernel = compiled_cells.cell_kernel()
    ref = _numpy(monkeypatch, lambda: track.receptance(f, X, X))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the kernel converges where NumPy does
        got = _kernel(monkeypatch, kernel, lambda: track.receptance(f, X, X))
    assert _peak_error(got, ref) <= RTOL
