"""``railvib run`` does not import dask (issue 13: 0.5-0.9 s of its start-up).

xarray imported dask (and distributed) to learn that a variable's data is no dask array
and that no dask scheduler is active. :func:`railvib.cli.dask_probe.defer_dask_probe`
answers these from the modules loaded; the answers must stay xarray's own once dask is
loaded.
"""

import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from railvib.cli.dask_probe import DaskArrayIfLoaded

PROBE = textwrap.dedent(
    """
    import json, sys
    import numpy as np, xarray as xr
    from railvib.cli.dask_probe import defer_dask_probe
    from xarray.namedarray.utils import is_duck_dask_array
    replaced = defer_dask_probe()
    ds = xr.Dataset({"a": ("f", np.arange(4.0))})
    ds.to_netcdf(sys.argv[1] + "/a.nc", engine="h5netcdf")
    before = sorted(m for m in sys.modules if m.split(".")[0] in ("dask", "distributed"))
    import dask.array as da
    lazy = xr.DataArray(da.arange(6.0, chunks=3), dims="f")
    chunked = xr.Dataset({"b": lazy})
    chunked.to_netcdf(sys.argv[1] + "/b.nc", engine="h5netcdf")  # dask's scheduler again
    back = xr.load_dataset(sys.argv[1] + "/b.nc", engine="h5netcdf")
    print(json.dumps({
        "replaced": replaced,
        "before": before,
        "lazy": lazy.chunks is not None and is_duck_dask_array(lazy.data),
        "numpy_is_dask": is_duck_dask_array(np.arange(3.0)),
        "values": back["b"].values.tolist(),
    }))
    """
)


@pytest.mark.slow  # a fresh process that imports dask: ~2 s
def test_no_dask_until_asked_and_dask_works_after(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-c", PROBE, str(tmp_path)], capture_output=True, text=True, check=True
    )
    out = json.loads(proc.stdout)
    assert out["replaced"]
    assert out["before"] == []  # a dataset made and written without dask or distributed
    assert out["lazy"]  # a dask array made afterwards stays a lazy dask array in xarray
    assert not out["numpy_is_dask"]
    assert out["values"] == [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]  # and is written as before


@pytest.mark.slow  # a fresh `railvib run --no-plots`: ~2 s
def test_railvib_run_loads_no_dask(tmp_path):
    case = tmp_path / "case.toml"
    case.write_text('preset = "wang2017_metro"\n[frequency]\nf_min = 1.0\nf_max = 50.0\nn = 20\n')
    script = textwrap.dedent(
        """
        import sys
        from railvib.cli.main import main
        code = main(["run", sys.argv[1], "-o", sys.argv[2], "--no-plots"])
        loaded = [m for m in sys.modules if m.split(".")[0] in ("dask", "distributed")]
        print(code, len(loaded), loaded[:3])
        """
    )
    proc = subprocess.run(
        [sys.executable, "-c", script, str(case), str(tmp_path / "out")],
        capture_output=True,
        text=True,
        check=True,
    )
    assert proc.stdout.splitlines()[-1] == "0 0 []", proc.stdout + proc.stderr


def test_the_stand_in_type_is_a_dask_array_only_when_dask_made_it():
    assert not isinstance(np.arange(3.0), DaskArrayIfLoaded)
    assert not isinstance([1, 2], DaskArrayIfLoaded)
    da = pytest.importorskip("dask.array")
    assert isinstance(da.zeros(3, chunks=1), DaskArrayIfLoaded)
