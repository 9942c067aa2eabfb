"""One moving-load receptance table for the whole grid (railvib.moving.harmonic).

On a uniform grid whose spacing divides ``v / d`` the shifted load frequencies
``|f + m v / d|`` coincide: the table holds each once, and the blocks built from it are
those built block by block.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.coupling import CoupledSystem
from railvib.moving import MovingSettings
from railvib.moving.harmonic import harmonic_blocks, load_receptances
from railvib.pads import SpringDamper
from railvib.track import PeriodicTrack, Rail
from railvib.vehicle.library import PitchPlaneParameters

D = 0.6
TRACK = PeriodicTrack(Rail(6.4e6, 60.0, loss_factor=0.01), SpringDamper(2.0e8, 3.0e4), D)
#: Wang et al. (2017) Table 1 metro car, half of it on one rail
VEHICLE = (
    PitchPlaneParameters(
        21920.0, 617310.0, 2550.0, 1750.0, 1420.0, 1.7e6, 5.0e3, 2.75e5, 3.0e4, 6.3, 1.1
    )
    .vehicle()
    .scaled(0.5)
)
#: v / d = 37.0 Hz exactly: 370 grid steps of 0.1 Hz
SYSTEM = CoupledSystem(VEHICLE, TRACK, 1.0e9, 0.1, 37.0 * D)


def test_coinciding_shifted_frequencies_are_computed_once():
    # base frequencies 1 + 9.25 k Hz: v / d = 37 Hz is 4 grid steps, so f + m v / d falls
    # on the grid; counted in integer quarters of a Hertz, without floating point
    quarters = 4 + 37 * np.arange(8)
    table = load_receptances(SYSTEM, quarters / 4.0, MovingSettings(1, 0.5))
    expected = {abs(int(k) + 148 * m) for k in quarters for m in (-1, 0, 1)}
    assert len(expected) < 3 * quarters.size  # 24 shifted frequencies, 16 distinct
    assert table.f.size == len(expected)
    np.testing.assert_allclose(table.f * 4.0, sorted(expected), rtol=0, atol=1e-6)


@pytest.mark.slow  # ~2 s: the moving-load receptance twice at 100 frequencies
def test_blocks_from_one_table_are_those_built_block_by_block():
    settings = MovingSettings(2, 0.5)
    f = 20.0 + 0.1 * np.arange(20)
    table = load_receptances(SYSTEM, f, settings)
    for part in (f[:10], f[10:]):
        got = harmonic_blocks(SYSTEM, part, settings, table).receptance
        ref = harmonic_blocks(SYSTEM, part, settings).receptance
        # the kernel batches the frequencies differently in the two calls; each keeps its
        # quadrature error below 1e-6 of the largest harmonic (docs/moving-load.md)
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-5 * np.abs(ref).max())
