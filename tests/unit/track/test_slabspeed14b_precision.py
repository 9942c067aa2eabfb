"""The slab cell solver against its own algorithm run in extended precision.

Near the slab-on-foundation resonance the doubling of the slab's slowly decaying waves
amplifies rounding (a 1-ulp random perturbation of the spans' stiffness moves the
receptance by up to 1.1e-9 of its peak at 7-14 Hz), so agreement between two double
precision paths says little about which is right there. The reference here is the
compiled kernel's plain Python functions run on ``numpy.clongdouble`` arrays (on x86-64
an 80-bit long double: a 64-bit mantissa, 2048 times finer rounding), from the same
double precision inputs (pads, foundation, ``beta^4`` of each span).
"""

from __future__ import annotations

import importlib.util
import math
from typing import Any

import numpy as np
import pytest

from railvib.track import compiled_cells

from .test_slabspeed_compiled import PLAIN, TRACKS, X

#: measured against this reference at 7-14 Hz: up to 4.6e-12 of the peak on this grid and
#: 1.1e-11 on a finer one (150 points, NumPy and compiled paths alike); the waves found on
#: the cell with the wheels' nodes (the path before) were 4.6e-10 (floating) and 4.4e-11
#: (bearings) off on this grid, which this bound rejects
RTOL = 3e-11


class _LongNumpy:
    """numpy, with ``complex128`` meaning ``clongdouble`` (the kernel's allocations)."""

    complex128 = np.clongdouble

    def __getattr__(self, name: str) -> Any:
        return getattr(np, name)


def _extended(monkeypatch, fn):
    with monkeypatch.context() as patch:
        patch.delenv("RAILVIB_COMPILED", raising=False)
        patch.setattr(compiled_cells, "np", _LongNumpy())
        patch.setattr(
            compiled_cells,
            "_INVERSE_FACTORIALS",
            np.array(
                [
                    [np.longdouble(1) / np.longdouble(math.factorial(4 * k + j)) for j in range(4)]
                    for k in range(16)
                ]
            ),
        )
        patch.setattr(compiled_cells, "_CELL_KERNEL", [PLAIN])
        for name in compiled_cells._FUNCTIONS:  # the callees plain too (not numba's, if loaded)
            patch.setattr(compiled_cells, name, compiled_cells._PLAIN[name])
        return fn()


@pytest.mark.slow  # the plain Python kernel: about 10 ms a frequency
@pytest.mark.parametrize("name", ["floating", "bearings", "unit_jointed"])
def test_receptance_near_the_slab_resonance_against_extended_precision(monkeypatch, name):
    if np.finfo(np.longdouble).nmant < 60:
        pytest.skip("long double is not extended precision on this platform")
    track = TRACKS[name]
    f = np.geomspace(7.0, 14.0, 24)  # the slab on its foundation or bearings resonates
    ref = _extended(monkeypatch, lambda: track.receptance(f, X, X))
    scale = np.abs(ref).max(axis=0)
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    assert np.max(np.abs(track.receptance(f, X, X) - ref) / scale) <= RTOL
    if importlib.util.find_spec("numba") is not None:  # the compiled kernel too
        monkeypatch.delenv("RAILVIB_COMPILED")
        monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [])  # loaded for this test only
        compiled_cells.cell_kernel()
        assert np.max(np.abs(track.receptance(f, X, X) - ref) / scale) <= RTOL
