"""The glue around the kernels cut without changing a value (issue 13, goals 1 and 2).

A held run's fused kernel writes its responses straight into the result's arrays
(``CoupledSystem.frf_blocks(into=...)``), a streamed run's later blocks are written
straight into the file's write buffers (``NetCDFStream.rows``), the finite check tests a
complex array's parts as reals (``all_finite``) and the support PSDs come as arrays
(``support_force_psd``). Each is the same arithmetic on the same values as before, so the
comparisons here are exact (bit for bit), not within a tolerance.
"""

import importlib.util

import numpy as np
import pytest
import xarray as xr

import railvib
from railvib.case import build_spectrum, build_system
from railvib.coupled_kernel import fused_points
from railvib.grid import FrequencyGrid
from railvib.outputs.supports import support_force_data, support_force_psd
from railvib.pem import wheel_delays
from railvib.response import FRF
from railvib.results import load_netcdf, save_netcdf
from railvib.results.dataset import all_finite, value_arrays
from railvib.results.variables import VARIABLES, compute_variables
from railvib.solve import run_system, stream_to_netcdf
from railvib.track import compiled
from railvib.track.stacked import receptance_entries, stacked_waves

NUMBA = importlib.util.find_spec("numba") is not None


def _system(name="wang2017_metro"):
    case = railvib.load_preset_case(name)
    return build_system(case), build_spectrum(case)


@pytest.mark.parametrize(
    "bad",
    [np.nan, np.inf, -np.inf, complex(0.0, np.nan), complex(np.inf, 0.0), complex(1.0, -np.inf)],
)
def test_all_finite_finds_a_bad_real_or_imaginary_part(bad):
    values = np.ones((50, 3), dtype=np.complex128)
    values[17, 2] = bad
    assert not all_finite([values])
    assert not all_finite([values[:, 1:]])  # not contiguous: tested as complex
    assert not all_finite([values.real.copy(), values])
    assert all_finite([np.ones(3), np.ones((4, 2), dtype=np.complex128)])


def test_all_finite_does_not_test_other_types():
    assert all_finite([np.array([True, False]), np.array([1, 2]), np.array(["a"])])


def test_value_arrays_are_laid_out_as_the_variables_are_computed():
    n_dof, n_wheel = 10, 4
    frf = FRF(
        np.array([1.0, 2.0]),
        np.ones((2, n_dof), dtype=np.complex128),
        np.ones((2, n_wheel), dtype=np.complex128),
        np.ones((2, n_wheel), dtype=np.complex128),
    )
    expected = compute_variables(frf, np.ones(2), VARIABLES)
    got = value_arrays(7, n_dof, n_wheel)
    assert list(got) == list(expected)
    for name, values in expected.items():
        assert got[name].shape == (7, *values.shape[1:]), name
        assert got[name].dtype == values.dtype, name


def test_support_force_psd_is_the_pads_force_from_the_seats_displacement():
    """On a rigid base the pad carries ``K* w(x_s)``, ``w(x_s) = sum_j alpha(x_s, x_j) P_j``."""
    system, spectrum = _system()
    track = system.track
    f = np.linspace(1.0, 300.0, 40)
    frf = system.frf(f)
    s_r = spectrum.temporal(f, system.speed)
    seats, names, psd = support_force_psd(system, f, s_r, lambda: frf.contact_force)
    x = system.wheel_positions
    assert names == ["pad"]
    # wheels at 0.3, -1.9, -12.3, -14.5 m, seats every 0.6 m: the nearest (the one ahead
    # for the two at mid-span)
    np.testing.assert_allclose(x, [0.3, -1.9, -12.3, -14.5], rtol=0, atol=1e-12)
    np.testing.assert_allclose(seats, [0.6, -1.8, -12.0, -14.4], rtol=0, atol=1e-12)
    rail = np.stack([track.receptance(f, x, [s])[:, 0, :] for s in seats], axis=1)  # (f, seat, w)
    w_seat = np.sum(rail * frf.contact_force[:, None, :], axis=2)
    pad = track.pad.stiffness(f, track.pad_temperature)
    expected = np.abs(pad[:, None] * w_seat) ** 2 * s_r[:, None]
    # the same products summed in another order: rounding, ~1e-15 relative
    np.testing.assert_allclose(psd[..., 0], expected, rtol=1e-12, atol=0)
    # and support_force_data gives these arrays as its variables
    data = {
        "frequency": xr.Variable("frequency", f),
        "irregularity_psd": xr.Variable("frequency", s_r),
        "frf_force": xr.Variable(("frequency", "wheel"), frf.contact_force),
    }
    variables = support_force_data(system, data)
    np.testing.assert_array_equal(variables["psd_support_force"].values, psd)


def test_fused_points_refuses_out_arrays_of_the_wrong_shape():
    system, _ = _system()
    vehicle = system.vehicle
    f = np.array([5.0, 6.0])
    n_w, n_dof = len(vehicle.wheels), len(vehicle.dofs)
    rec = np.ones((2, n_w, n_w), dtype=np.complex128)
    out = tuple(np.empty(s, dtype=np.complex128) for s in ((2, n_dof), (2, n_w), (2, n_w), (3, 0)))
    delays = wheel_delays(vehicle.wheel_offsets, system.speed)
    with pytest.raises(ValueError, match="out"):
        fused_points(
            vehicle.elimination_program,
            f,
            vehicle.element_stiffness(f),
            rec,
            1.0,
            system.contact_stiffness,
            delays,
            run=lambda *args: None,  # never reached
            out=out,
        )


@pytest.mark.slow  # loads numba and the kernels: 1-3 s
@pytest.mark.skipif(not NUMBA, reason="the fused kernel needs numba (the fast extra)")
def test_frf_blocks_write_the_fused_responses_into_the_given_arrays():
    compiled.compile_kernel()
    system, _ = _system()
    f = np.linspace(1.0, 500.0, 5000)  # two blocks, above the compiled path's minimum
    n_dof, n_w = len(system.vehicle.dofs), len(system.vehicle.wheels)
    displacement = np.full((f.size, n_dof + n_w), np.nan, dtype=np.complex128)
    force = np.full((f.size, n_w), np.nan, dtype=np.complex128)
    into = (displacement[:, :n_dof], force, displacement[:, n_dof:], np.empty((f.size, 0), complex))
    blocks = list(system.frf_blocks(f, into=into))
    assert len(blocks) == 2
    for sl, frf in blocks:  # the block's responses are the given arrays' rows
        assert np.shares_memory(frf.vehicle, displacement[sl, :n_dof])
        assert np.shares_memory(frf.contact_force, force[sl])
    reference = [frf for _, frf in system.frf_blocks(f)]  # into new arrays
    np.testing.assert_array_equal(
        displacement[:, :n_dof], np.concatenate([b.vehicle for b in reference])
    )
    np.testing.assert_array_equal(
        displacement[:, n_dof:], np.concatenate([b.rail for b in reference])
    )
    np.testing.assert_array_equal(force, np.concatenate([b.contact_force for b in reference]))


@pytest.mark.slow  # two runs of 5000 frequencies and their files: 1-3 s
@pytest.mark.skipif(not NUMBA, reason="the fused kernel needs numba (the fast extra)")
def test_a_streamed_run_on_the_fused_kernel_writes_the_held_runs_values(tmp_path):
    """The held run fills its arrays in place, the streamed one the file's write buffers."""
    compiled.compile_kernel()
    system, spectrum = _system()
    grid = FrequencyGrid.linear(0.5, 1000.0, 999.5 / 4999)  # 5000: a full and a short block
    held = load_netcdf(save_netcdf(run_system(system, grid, spectrum), tmp_path / "held.nc"))
    stream_to_netcdf(system, grid, spectrum, tmp_path / "results.nc")
    streamed = load_netcdf(tmp_path / "results.nc")
    for name, var in held.data_vars.items():
        if "frequency" in var.dims:
            np.testing.assert_array_equal(streamed[name].values, var.values, err_msg=name)


def test_the_wave_kernel_forms_a_repeated_entry_once():
    """Two loads a whole number of bays apart, each seen at its own place: one entry."""
    tables = compiled._geometry((0.25, -4.75), (0.25, -4.75, 0.5))
    entry = tables[-1]
    # (1, 1) repeats (0, 0): the same local coordinate, side and bay count (0 bays)
    assert entry[1, 1] == 0
    assert entry[0, 0] == 0
    # the others are their own: the bay counts 5 and 0, or another observation coordinate
    assert entry[0, 1] == 1
    assert entry[1, 0] == 2
    assert entry[2, 0] == 4
    assert entry[2, 1] == 5


@pytest.mark.slow  # loads numba and the kernel: 1-3 s
@pytest.mark.skipif(not NUMBA, reason="the wave kernel needs numba (the fast extra)")
def test_a_repeated_entry_is_the_numpy_kernels_value():
    """The copied entries against the NumPy kernel, which forms every entry itself."""
    compiled.compile_kernel()
    beta4 = np.array([0.01 + 0.001j, 0.5 + 0.02j, 3.0 + 0.1j])
    pad = np.array([2.0 + 0.2j, 1.0 + 0.1j, 0.7 + 0.05j])
    x = np.array([0.25, -4.75])
    obs = np.array([0.25, -4.75, 0.5])
    got, _, bad = compiled.compiled_receptance(beta4, pad, x, obs)
    assert not bad.any()
    expected = np.stack(
        [np.stack(row, axis=-1) for row in receptance_entries(stacked_waves(beta4, pad), x, obs)],
        axis=-2,
    )
    # two kernels, the same expressions in another order: rounding, ~1e-15 of the largest
    scale = np.abs(expected).max()
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-13 * scale)
    np.testing.assert_array_equal(got[:, 1, 1], got[:, 0, 0])
