"""Parameter sweeps: many cases, batched, resumable, on local cores or a Dask cluster.

Examples
--------
>>> from railvib.sweep import sweep_from_dict, SweepLayout
>>> spec = sweep_from_dict({
...     "case": {"preset": "wang2017_metro"},
...     "axes": [{"field": "speed_kmh", "values": [40.0, 80.0]}],
... })
>>> spec.axes[0].values
(40.0, 80.0)
>>> SweepLayout(spec).shape
(2,)
"""

from railvib.sweep.batch import compute_chunk, frf_many_speeds
from railvib.sweep.dataset import (
    linear_model_line,
    load_sweep_dataset,
    save_sweep_csv,
    save_sweep_extras,
    save_sweep_netcdf,
    sweep_dataset,
)
from railvib.sweep.layout import SweepLayout
from railvib.sweep.runner import (
    SchedulerUnreachable,
    SweepInterrupted,
    check_scheduler,
    connect_scheduler,
    describe_run,
    run_sweep,
)
from railvib.sweep.spec import SweepAxis, SweepSpec, load_sweep, sweep_from_dict
from railvib.sweep.store import (
    ChunkStore,
    SweepMismatchError,
    default_output_folder,
    default_plot_folder,
    fingerprint,
)

__all__ = [
    "ChunkStore",
    "SchedulerUnreachable",
    "SweepInterrupted",
    "SweepLayout",
    "SweepAxis",
    "SweepMismatchError",
    "SweepSpec",
    "check_scheduler",
    "connect_scheduler",
    "compute_chunk",
    "default_output_folder",
    "default_plot_folder",
    "describe_run",
    "fingerprint",
    "frf_many_speeds",
    "linear_model_line",
    "load_sweep",
    "load_sweep_dataset",
    "run_sweep",
    "save_sweep_csv",
    "save_sweep_extras",
    "save_sweep_netcdf",
    "sweep_dataset",
    "sweep_from_dict",
]
