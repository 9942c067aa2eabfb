"""The doubling's stop test: the chains it leaves are those of the iteration run on.

:data:`railvib.track.cells.CONVERGED` stops the doubling once ``max|B_k| / max|A_k|`` is
below 1e-10. The doubling converges quadratically (``B_k+1 = -B_k S^-1 B_k``), so the steps
left would change ``A_k`` and ``E_k`` by about the square, 1e-20 of their size: below
rounding. Run on until ``B_k`` has all but vanished (a ratio of 1e-150: about four more
steps), the semi-infinite stiffnesses ``P_r`` and ``P_l`` must therefore be the same to
rounding, on the NumPy path and on the cell kernel's plain functions (measured: bit for bit
on the six tracks). Stopping at a ratio ``r`` neglects about ``r^2``: a stop at 1e-5 is
measured 2.6e-14 to 1.9e-9 off, at 1e-3 4.9e-7 to 1.9e-5, which this test rejects. So no
step can be saved by the stop test without losing digits beyond rounding: at most the one
that ends between ``r = 1e-8`` (the rounding bound, ``r^2 = 1e-16``) and 1e-10, 0.3 of the
preset's 9.9 steps on average.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.track import cells, compiled_cells

from .test_slabspeed_compiled import PLAIN, TRACKS

#: a few roundings of ``A_k + E_k``-sized sums: the neglected updates (about 1e-20 of the
#: blocks) change no digit, and the extra steps' own updates are as small (measured 0.0)
RTOL = 1e-14

#: a stop test that leaves about 1e-6 of the chains (``r^2``) unconverged
LOOSE = 1e-3

#: run on until ``B_k`` is 1e-150 of ``A_k`` (or underflows): the chains to the last digit
EXHAUSTED = 1e-150

#: below the slab-on-foundation resonance, at it, mid band and high (Hz)
FREQUENCIES = np.array([3.0, 10.0, 85.0, 1500.0])


def _peak_error(got, ref):
    scale = np.abs(ref).max(axis=(1, 2), keepdims=True)
    return float(np.max(np.abs(got - ref) / scale))


def _cell(track):
    return track._cell(FREQUENCIES, np.zeros(0), track.layer_stiffness(FREQUENCIES))[0]


@pytest.mark.parametrize("name", list(TRACKS))
def test_numpy_doubling_stops_when_the_rest_is_below_rounding(monkeypatch, name):
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    cell = _cell(TRACKS[name])
    stopped = cells.cell_waves(cell)
    monkeypatch.setattr(cells, "CONVERGED", EXHAUSTED)
    exhausted = cells.cell_waves(cell)
    assert _peak_error(stopped.right_chain, exhausted.right_chain) <= RTOL
    assert _peak_error(stopped.left_chain, exhausted.left_chain) <= RTOL
    # and the stop test does stop it: a looser one changes the chains
    monkeypatch.setattr(cells, "CONVERGED", LOOSE)
    loose = cells.cell_waves(cell)
    assert _peak_error(loose.right_chain, exhausted.right_chain) > RTOL


@pytest.mark.parametrize("name", list(TRACKS))
def test_kernel_doubling_stops_when_the_rest_is_below_rounding(monkeypatch, name):
    monkeypatch.setattr(compiled_cells, "_CELL_KERNEL", [PLAIN])
    cell = _cell(TRACKS[name])
    k = cell.stiffness()
    bnd, inner = cell.boundary, cell.interior
    stopped = compiled_cells.wave_chain(k, bnd, inner, cells.MAX_DOUBLINGS, cells.CONVERGED)
    exhausted = compiled_cells.wave_chain(k, bnd, inner, cells.MAX_DOUBLINGS, EXHAUSTED)
    assert not stopped[-1].any()
    for side in (4, 5):  # P_r, P_l
        assert _peak_error(stopped[side], exhausted[side]) <= RTOL
    loose = compiled_cells.wave_chain(k, bnd, inner, cells.MAX_DOUBLINGS, LOOSE)
    assert _peak_error(loose[4], exhausted[4]) > RTOL
