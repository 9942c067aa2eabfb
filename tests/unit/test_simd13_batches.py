"""The wave kernel's batches of points (structure of arrays, issue 13) against the NumPy kernel.

The compiled kernel solves its points `compiled._B` at a time, each series summed to the
longest term count of the batch, `c2 - 2` in closed form point by point above
``|beta4| = 16``, and points that need a branch flagged instead of taken. These tests run
the same function uncompiled (plain Python, so they run without numba too) on stacks that
cross those seams: a partial last batch, both sides of the closed-form threshold in one
batch, a point alone or among much larger ones.
"""

import numpy as np
import pytest

from railvib.stack import stacked
from railvib.track import compiled
from railvib.track.stacked import receptance_entries, stacked_waves

#: reason: the same formulas in another order of operations, as
#: tests/unit/test_compiled_kernels.py holds the kernel to
RTOL = 1e-12


def _reference(beta4, pad, x_load, x_obs):
    waves = stacked_waves(beta4, pad)
    return np.asarray(stacked(receptance_entries(waves, x_load, x_obs))), waves.condition


def _max_rel(a, b):
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=0, keepdims=True)))


def _stack(n, lo=1e-3, hi=300.0, loss=2e-2):
    """`n` points of a lossy rail on a lossy pad, |beta4| from `lo` to `hi` (log spaced)."""
    beta4 = np.geomspace(lo, hi, n) * (1 - 1e-12j)
    pad = (2.0 + 0.3 * np.log1p(np.arange(n))) * (1 + loss * 1j)
    return beta4.astype(complex), pad.astype(complex)


def test_a_partial_batch_across_the_closed_form_threshold_equals_the_numpy_kernel():
    # 2 batches and 5 points; |beta4| = 16 falls inside the second batch
    n = 2 * compiled._B + 5
    beta4, pad = _stack(n)
    assert (np.abs(beta4[compiled._B : 2 * compiled._B]) < 16).any()
    assert (np.abs(beta4[compiled._B : 2 * compiled._B]) >= 16).any()
    x_load = np.array([0.3, -1.7, 4.5])
    x_obs = np.array([0.3, -1.7, 4.5, 0.0, -0.5, 2.25])
    rec, condition, bad = compiled.compiled_receptance(
        beta4, pad, x_load, x_obs, kernel=compiled._points
    )
    ref, ref_condition = _reference(beta4, pad, x_load, x_obs)
    assert not bad.any()
    assert rec.shape == (n, x_obs.size, x_load.size)
    assert _max_rel(rec, ref) < RTOL
    # reason: the same estimate from magnitudes squared (a few ulp)
    np.testing.assert_allclose(condition, ref_condition, rtol=1e-12)


def test_a_point_alone_equals_the_same_point_among_much_larger_ones():
    # among |beta4| up to 3e3 its series take 14 terms, alone 9: the extra terms are below
    # the last digit, so its receptance is the same to rounding (weak pivots near the top
    # of the range are flagged: they do not touch the first point)
    beta4, pad = _stack(compiled._B, lo=0.5, hi=3000.0)
    x = np.array([0.3, -0.8])
    together, _, bad = compiled.compiled_receptance(beta4, pad, x, x, kernel=compiled._points)
    alone, _, bad_alone = compiled.compiled_receptance(
        beta4[:1], pad[:1], x, x, kernel=compiled._points
    )
    assert not bad[0]
    assert not bad_alone[0]
    # reason: a different number of series terms, each change below the last digit
    np.testing.assert_allclose(together[0], alone[0], rtol=1e-13, atol=0)


def test_flagged_points_leave_their_batch_mates_exact():
    # a lossless rail on a lossless pad: band edges, where the NumPy kernel solves densely
    n = 3 * compiled._B
    beta4 = np.linspace(5.0, 120.0, n).astype(complex) * (1 - 1e-12j)
    pad = np.full(n, 4.0 + 0j)
    x = np.array([0.3, -1.7])
    rec, _, bad = compiled.compiled_receptance(beta4, pad, x, x, kernel=compiled._points)
    ref, ref_condition = _reference(beta4, pad, x, x)
    assert bad.any()
    ok = ~bad
    assert ok.sum() > n // 2
    # reason: without loss the matching's condition number reaches ~1e4 near the band
    # edges, and two evaluations of equal quality differ by about condition x 1e-16
    err = np.abs(rec[ok] - ref[ok]) / np.abs(ref[ok]).max(axis=0, keepdims=True)
    assert float(err.max()) < 1e-10


@pytest.mark.slow  # compiles the kernel afresh (numba's cache holds no assembly): ~20 s
def test_the_compiled_batches_use_packed_vector_instructions():
    numba = pytest.importorskip("numba")
    llvm = pytest.importorskip("llvmlite.binding")
    features = llvm.get_host_cpu_features()
    if not features.get("avx2", False):
        pytest.skip("the host has no AVX2: LLVM has no packed double FMA to choose")
    kernel = numba.njit(error_model="numpy", fastmath={"contract"})(compiled._points)
    beta4, pad = _stack(2 * compiled._B)
    x = np.array([0.3, -0.8])
    compiled.compiled_receptance(beta4, pad, x, x, kernel=kernel)
    asm = "\n".join(kernel.inspect_asm().values())
    packed = asm.count("pd\t") + asm.count("pd ")
    scalar = asm.count("sd\t") + asm.count("sd ")
    # the stages' vector bodies: hundreds of packed multiplies and FMAs (scalar code,
    # the remainder loops and the closed form's libm calls, has none)
    assert asm.count("vfmadd") + asm.count("vmulpd") > 300
    assert packed > 0.3 * scalar
