"""A sweep chunk's criteria on NumPy arrays are those of the outputs' own classes, bit for bit."""

import numpy as np
import pytest
import xarray as xr

from railvib.outputs import ContactCheck, RideComfort, WheelRailForces
from railvib.results.variables import compute_variables, response_psds
from railvib.sweep import batch as sweep_batch
from railvib.sweep import sweep_from_dict
from railvib.sweep.batch import CONTACT_SUMMARY, CRITERIA_SUMMARY, criteria_summary
from tests.unit.sweep.sweep_cases import small_sweep


@pytest.fixture(scope="module")
def chunk():
    """The inputs of one chunk's criteria: responses, irregularity PSDs, forces, loads."""
    spec = sweep_from_dict(small_sweep())
    context = sweep_batch._context(spec)
    cases, groups = sweep_batch._chunk_groups(spec, context.layout, 1, context.base)
    frf, s_r, loads = sweep_batch._solve_groups(context, cases, groups, False)
    psd_force = np.abs(frf.contact_force) ** 2 * s_r[..., None]
    return spec, context, frf, s_r, psd_force, loads


def test_the_contact_check_and_criteria_equal_the_output_classes_exactly(chunk):
    spec, context, frf, s_r, psd_force, loads = chunk
    f = context.f
    got = criteria_summary(spec, f, frf, s_r, psd_force, loads)
    forces = xr.Dataset(
        {
            "psd_force": (("case", "frequency", "wheel"), psd_force),
            "static_contact_load": (("case", "wheel"), loads),
        },
        coords={"frequency": f},
    )
    want = ContactCheck(loss_of_contact_threshold=spec.loss_of_contact_threshold).compute(forces)
    want.update(WheelRailForces().compute(forces))
    assert "ride_comfort" in context.criteria, "the base case's grid reaches the comfort band"
    responses = xr.Dataset(
        {
            "frf_displacement": (("case", "frequency", "response"), frf.vehicle),
            "irregularity_psd": (("case", "frequency"), s_r),
        },
        coords={"frequency": f, "response": list(frf.dofs)},
    )
    want.update(RideComfort(**context.criteria["ride_comfort"]).compute(responses))
    names = [*CONTACT_SUMMARY, *CRITERIA_SUMMARY]
    assert sorted(got) == sorted(f"summary/{n}" for n in names)
    for name in names:
        expected = want[name].transpose("case", ...).values
        # the same operations on the same numbers: equal exactly, not to a tolerance
        np.testing.assert_array_equal(got[f"summary/{name}"], expected, err_msg=name)
        assert got[f"summary/{name}"].dtype == expected.dtype, name


@pytest.mark.parametrize("name", ["psd_acceleration", "psd_displacement"])
def test_the_response_psds_written_in_place_equal_the_variables_exactly(chunk, name):
    _, _, frf, s_r, _, _ = chunk
    want = compute_variables(frf, s_r, [name])[name]
    got = response_psds(frf, s_r, name == "psd_acceleration")
    # the same operations on the same numbers, only written elsewhere: equal exactly
    np.testing.assert_array_equal(got, want)
    assert got.shape == (*frf.vehicle.shape[:-1], frf.vehicle.shape[-1] + frf.rail.shape[-1])


def test_a_chunk_stores_what_the_variables_give_for_its_cases(chunk):
    spec, context, frf, s_r, psd_force, loads = chunk
    names = ["psd_acceleration", "psd_force", "irregularity_psd", "psd_displacement"]
    got = sweep_batch._chunk_variables(frf, s_r, dict.fromkeys(names))
    want = compute_variables(frf, s_r, names)
    assert list(got) == names
    for name in names:
        np.testing.assert_array_equal(got[name], want[name], err_msg=name)
