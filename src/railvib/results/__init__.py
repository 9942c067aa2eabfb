"""Result datasets, their statistics and files."""

from railvib.results.dataset import (
    atomic_path,
    build_dataset,
    load_netcdf,
    save_csv,
    save_netcdf,
)
from railvib.results.stats import band_rms, dominant_frequency, peak, summary

__all__ = [
    "atomic_path",
    "band_rms",
    "build_dataset",
    "dominant_frequency",
    "load_netcdf",
    "peak",
    "save_csv",
    "save_netcdf",
    "summary",
]
