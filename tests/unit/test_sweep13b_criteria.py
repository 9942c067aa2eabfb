"""A sweep chunk's criteria on NumPy arrays are those of the outputs' own classes, bit for bit."""

import numpy as np
import pytest
import xarray as xr

from railvib.outputs import ContactCheck, RideComfort, WheelRailForces
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
