"""The files of a sweep folder, and where a sweep's outputs go by default.

Layout of a sweep folder::

    OUT/manifest.json             fingerprint, layout and the resolved sweep
    OUT/chunks/sweep.zarr         the store being filled, one region per chunk
    OUT/chunks/chunk-000012.done  a finished chunk's record, written after its region
    OUT/sweep.zarr                the finished store (moved there when all chunks are done)
    OUT/sweep.nc, summary.csv    optional exports; OUT/plots/ the summary plots
"""

from __future__ import annotations

from pathlib import Path

__all__ = [
    "CSV_NAME",
    "MANIFEST",
    "NETCDF_NAME",
    "PLOTS_NAME",
    "ZARR_NAME",
    "default_output_folder",
    "default_plot_folder",
]

MANIFEST = "manifest.json"
ZARR_NAME = "sweep.zarr"
#: optional exports of a sweep folder
NETCDF_NAME = "sweep.nc"
CSV_NAME = "summary.csv"
PLOTS_NAME = "plots"


def default_output_folder(sweep_file: str | Path) -> Path:
    """The output folder of a sweep file run without ``--output``.

    Parameters
    ----------
    sweep_file : str or pathlib.Path
        The sweep file.

    Returns
    -------
    pathlib.Path
        ``<sweep file stem>.sweep``, relative to the current folder (not to the
        sweep file), e.g. ``temp_speed.sweep`` for ``cases/temp_speed.toml``.
    """
    return Path(f"{Path(sweep_file).stem}.sweep")


def default_plot_folder(result: str | Path) -> Path:
    """The folder that the plots of a sweep result go to when none is given.

    Parameters
    ----------
    result : str or pathlib.Path
        A sweep folder, its ``sweep.zarr`` store or a netCDF export.

    Returns
    -------
    pathlib.Path
        ``RESULT/plots`` for a sweep folder, else ``plots`` next to the store or file.
    """
    result = Path(result)
    folder = result if result.is_dir() and result.suffix != ".zarr" else result.parent
    return folder / PLOTS_NAME
