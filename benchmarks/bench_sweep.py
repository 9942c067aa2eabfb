"""Benchmark: a 1000-case sweep at 1000 frequencies on 2 cores, vs running cases one by one.

The sweep is pad temperature (10 values, -40 to +40 degC, a temperature-dependent
fractional-Zener pad with WLF shift) x speed (100 values, 40 to 160 km/h): 1000
cases, 1000 log-spaced frequencies, 14 responses. The goal (issue 6) is at most
10 s on 2 cores, including process start, chunk files and the Zarr store.

The one-by-one reference calls ``railvib.run(case)`` for a sample of the cases
(``--sample``, default 100) in one process and scales to 1000; ``--sample 1000``
runs them all.

Usage::

    python benchmarks/bench_sweep.py [--workers 2] [--sample 100] [--structural]

``--structural`` also times the worst case for batching: 1000 different pads
(10 temperatures x 100 pad stiffnesses), where no two cases share a track.
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

import railvib
from railvib.case.load import merge_case_dicts
from railvib.sweep import SweepLayout, SweepSpec, run_sweep, sweep_from_dict
from railvib.sweep.spec import nested_override

PAD = {
    "model": "fractional_zener",
    "k0_n_per_m": 4.0e7,
    "k_inf_n_per_m": 2.0e8,
    "tau_s": 1.0e-3,
    "alpha": 0.4,
    "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -50.0},
}


def sweep_dict(structural: bool = False) -> dict[str, Any]:
    second = (
        {
            "field": "track.pad.k0_n_per_m",
            "start": 2.0e7,
            "stop": 8.0e7,
            "num": 100,
            "spacing": "log",
        }
        if structural
        else {"field": "speed_kmh", "start": 40.0, "stop": 160.0, "num": 100}
    )
    return {
        "title": "benchmark: pad temperature x speed",
        "chunk_size": 50,
        "case": {
            "preset": "wang2017_metro",
            "track": {"pad": PAD, "pad_temperature_c": 20.0},
            "frequency": {"spacing": "log", "f_min": 0.5, "f_max": 1000.0, "n": 1000},
        },
        "axes": [
            {"field": "track.pad_temperature_c", "start": -40.0, "stop": 40.0, "num": 10},
            second,
        ],
    }


def time_sweep(spec: SweepSpec, workers: int) -> float:
    out = Path(tempfile.mkdtemp(prefix="railvib-bench-"))
    try:
        t0 = time.perf_counter()
        run_sweep(spec, out / "sweep", workers=workers, progress=False)
        return time.perf_counter() - t0
    finally:
        shutil.rmtree(out, ignore_errors=True)


def time_one_by_one(spec: SweepSpec, sample: int) -> float:
    """Seconds per case of ``railvib.run`` (the case validated, built and run alone)."""
    lay = SweepLayout(spec)
    all_idx = np.stack(np.unravel_index(np.arange(lay.n_cases), lay.shape), axis=1)
    pick = np.linspace(0, lay.n_cases - 1, min(sample, lay.n_cases)).astype(int)
    cases = []
    for index in all_idx[pick]:
        d = spec.base_case_dict()
        for field, value in lay.overrides(index):
            d = merge_case_dicts(d, nested_override(field, value))
        cases.append(d)
    railvib.run(railvib.case_from_dict(cases[0]))  # warm imports and caches
    t0 = time.perf_counter()
    for d in cases:
        ds = railvib.run(railvib.case_from_dict(d))
        railvib.summary(ds, bands=[(0.5, 20.0), (20.0, 100.0), (100.0, 1000.0)])
    return (time.perf_counter() - t0) / len(cases)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--sample", type=int, default=100)
    p.add_argument("--structural", action="store_true")
    args = p.parse_args()
    print(f"cores available: {os.cpu_count()}, workers: {args.workers}")
    kinds = [False, True] if args.structural else [False]
    for structural in kinds:
        spec = sweep_from_dict(sweep_dict(structural))
        n = SweepLayout(spec).n_cases
        label = (
            "10 temperatures x 100 pad stiffnesses"
            if structural
            else ("10 temperatures x 100 speeds")
        )
        wall = time_sweep(spec, args.workers)
        per_case = time_one_by_one(spec, args.sample)
        serial = per_case * n
        print(f"\n{label}: {n} cases x 1000 frequencies")
        print(
            f"  railvib sweep, {args.workers} workers: {wall:7.2f} s "
            f"({n / wall:,.0f} cases/s; goal <= 10 s)"
        )
        print(
            f"  one by one (railvib.run, 1 process): {per_case * 1e3:6.1f} ms/case "
            f"-> {serial:7.1f} s for {n} (from {min(args.sample, n)} cases)"
        )
        print(f"  speed-up: {serial / wall:5.1f}x")


if __name__ == "__main__":
    main()
