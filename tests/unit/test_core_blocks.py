"""One case solved block by block (issue 13, goals 1 and 2): the contact and the seats under
the wheels from one track solve per block, the stacked layout's fill, the tree condensation,
and memory bounded by a block."""

import tracemalloc

import numpy as np
import pytest

import railvib
from railvib.case import build_spectrum, build_system
from railvib.coupling import FREQUENCY_BLOCK
from railvib.outputs.supports import gives_seat_forces, seat_positions, support_force_variables
from railvib.stack import stacked
from railvib.vehicle.assembly import _dynamic_stiffness


def _max_rel(a, b):
    """Largest difference relative to the largest value of each column (PSD notches)."""
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=0, keepdims=True)))


@pytest.fixture(scope="module")
def ballasted():
    case = railvib.load_preset_case("thompson_ballasted")
    return build_system(case), build_spectrum(case)


def test_rail_observed_at_the_wheels_is_the_rail_under_them():
    system = build_system(railvib.load_preset_case())
    f = np.linspace(0.5, 1000.0, 600)
    x = system.wheel_positions
    for _, frf in system.frf_blocks(f, block=256, observe=x):
        assert frf.rail_observed is not None
        # reason: the same products R P summed by another routine (einsum against the
        # coupled solve's entry sums): a few ulp of the largest term
        assert _max_rel(frf.rail_observed, frf.rail) < 1e-13


@pytest.mark.parametrize(
    "n_freq",
    [300, pytest.param(FREQUENCY_BLOCK + 700, marks=pytest.mark.slow)],
    ids=["one block", "two blocks"],
)
def test_support_forces_of_a_run_equal_those_of_a_separate_track_solve(ballasted, n_freq):
    """The seats' receptance taken with the contact's (one solve a block) against the seats'
    own solve from the contact forces, on a ballasted track."""
    system, spectrum = ballasted
    grid = railvib.FrequencyGrid.linear(1.0, 1000.0, 999.0 / (n_freq - 1))
    ds = railvib.run_system(system, grid, spectrum)
    assert ds.sizes["frequency"] == n_freq
    separate = support_force_variables(system, ds)  # rail=None: its own track solve
    assert list(ds["layer"].values) == ["pad", "ballast"]
    for name in ("pad", "ballast"):
        got = ds["psd_support_force"].sel(layer=name).values
        want = separate["psd_support_force"].sel(layer=name).values
        # reason: the same waves up to the Krylov series' number of terms (set by each
        # block's largest beta^4) and the summation order: rounding, 1e-12 of the peak
        assert _max_rel(got, want) < 1e-12


def test_a_slab_track_gives_its_bearing_forces_not_seat_by_seat():
    case = railvib.load_preset_case("floating_slab_metro")
    system = build_system(case)
    # its seats share the slab: no seat-by-seat forces from the block solve ...
    assert not gives_seat_forces(system, np.array([1.0]))
    ds = railvib.run_system(
        system, railvib.FrequencyGrid.linear(1.0, 200.0, 5.0), build_spectrum(case)
    )
    # ... but the slab's own pad and bearing forces from the contact forces
    assert list(ds["layer"].values) == ["pad", "bearing"]
    assert ds["psd_support_force"].sizes["frequency"] == 40


def test_seats_are_the_nearest_sleepers():
    seats = seat_positions(np.array([0.31, -1.49, -12.3]), 0.6)
    # -12.3 m is mid-span up to rounding: the seat ahead (module docstring)
    np.testing.assert_allclose(seats, [0.6, -1.2, -12.0])


@pytest.mark.parametrize("shape", [(5,), (3, 4), (2, 3, 2)], ids=["vector", "matrix", "three-deep"])
def test_stacked_fills_like_numpy_stack(shape):
    rng = np.random.default_rng(1)

    def nest(dims, tail):
        if not dims:
            leaf = rng.normal(size=(7, *tail))
            return leaf + 1j * rng.normal(size=leaf.shape) if rng.random() < 0.5 else leaf
        return [nest(dims[1:], tail) for _ in range(dims[0])]

    def reference(e):
        return np.stack([reference(x) for x in e], axis=1) if isinstance(e, list) else e

    for tail in ((), (2,)):
        e = nest(shape, tail)
        got, want = stacked(e), reference(e)
        assert got.shape == want.shape
        assert got.dtype == want.dtype
        np.testing.assert_array_equal(got, want)


def test_tree_condensation_recovery_equals_the_dense_solve():
    """Bodies recovered by back-substitution over the tree (structural zeros and ones not
    multiplied) against ``-D_bb^-1 D_bw`` by LAPACK; the wheels' rows exactly the identity."""
    vehicle = build_system(railvib.load_preset_case()).vehicle
    f = np.linspace(0.5, 1000.0, 300)
    cond = vehicle.condensed_to_wheels(f)
    recovery = np.asarray(stacked(cond.recovery_entries))  # (f, dof, wheel)
    w = vehicle.wheel_dofs
    b = np.setdiff1d(np.arange(len(vehicle.dofs)), w)
    d = _dynamic_stiffness(f, vehicle.mass_matrix, vehicle.damping_matrix, vehicle.stiffness_matrix)
    x = np.linalg.solve(d[:, b][:, :, b], d[:, b][:, :, w])
    got, want = recovery[:, b].reshape(f.size, -1), -x.reshape(f.size, -1)
    coupled = np.abs(want).max(axis=0) > 0
    # reason: the elimination order differs from LAPACK's pivoting; the car's D_bb has a
    # condition number of order 1e4 at the bogie resonances: 1e-11 of each entry's peak
    assert _max_rel(got[:, coupled], want[:, coupled]) < 1e-11
    np.testing.assert_array_equal(got[:, ~coupled], 0.0)  # a body not above that wheel
    np.testing.assert_array_equal(recovery[:, w], np.broadcast_to(np.eye(w.size), (f.size, 4, 4)))


@pytest.mark.slow
def test_memory_of_a_run_is_the_result_and_one_block():
    """A 5e4-frequency run holds its result and one block's temporaries, not the grid's."""
    case = railvib.load_preset_case()
    system, spectrum = build_system(case), build_spectrum(case)
    grid = railvib.FrequencyGrid.linear(0.5, 1000.0, 999.5 / 49_999)
    railvib.run_system(system, railvib.FrequencyGrid.linear(0.5, 1000.0, 10.0), spectrum)
    tracemalloc.start()
    try:
        ds = railvib.run_system(system, grid, spectrum)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    result = ds.nbytes  # 608 bytes a frequency, 30 MB
    # reason: besides the result, a block of 4096 frequencies holds a few hundred entry
    # arrays of 64 kB (~15 MB) and the grid's seat displacements 64 B a frequency (3 MB);
    # a solve of the whole grid at once held ~10x the result (the seats' solve before)
    assert peak - result < 0.8 * result
