"""The same sweep on a real dask.distributed LocalCluster equals the serial run."""

import pytest
import xarray as xr

from railvib.sweep import run_sweep, sweep_from_dict
from tests.unit.sweep.sweep_cases import small_sweep

distributed = pytest.importorskip("distributed")


@pytest.mark.slow  # starts a Dask LocalCluster: ~8 s
def test_local_cluster_equals_serial_bit_for_bit(tmp_path):
    spec = sweep_from_dict(small_sweep())
    serial = run_sweep(spec, tmp_path / "serial", workers=1, progress=False)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        on_cluster = run_sweep(
            spec, tmp_path / "dask", scheduler=cluster.scheduler_address, progress=False
        )
    # identical: the same chunks through the same function; only the executor differs
    xr.testing.assert_identical(on_cluster, serial)
