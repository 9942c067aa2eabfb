"""Benchmark: sweeps of 1000 and 10^4 cases at 1000 frequencies on 2 cores, vs cases one by one.

The speed sweep is pad temperature (10 values, -40 to +40 degC, a temperature-dependent
fractional-Zener pad with WLF shift) x speed (100 values, 40 to 160 km/h): 1000 cases,
1000 log-spaced frequencies, 14 responses. ``--structural`` adds the structural sweep,
where no two cases share a track: 10 temperatures x 100 pad stiffnesses (1000 cases),
and ``--large`` the same with 1000 pad stiffnesses (10^4 cases; issue 13 goal: <= 10 s
wall on 2 cores, the parent's memory bounded by the chunk). ``--rail-vehicle`` adds a
sweep of 10 rail bending stiffnesses x 100 car body masses (1000 cases, no two sharing a
track or a vehicle: every case's rail and vehicle evaluated on the stack).

Each sweep is timed as a user runs it (process start, chunk files and the Zarr store
included), with the parent's peak resident memory. The one-by-one reference calls
``railvib.run(case)`` and the summary for a sample of the cases (``--sample``, default
100) in one process (one core) and scales to the sweep: the speed-up is stated per core
(the sweep's core-seconds, wall x workers, against the same work case by case).

Usage::

    python benchmarks/bench_sweep.py [--workers 2] [--sample 100] [--structural] [--large]
        [--rail-vehicle] [--only-goals]
"""

from __future__ import annotations

import argparse
import os
import resource
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


#: the rail x vehicle sweep (--rail-vehicle): no two cases share a track or a vehicle
RAIL_VEHICLE_AXES = [
    {"field": "track.rail.bending_stiffness", "start": 5.0e6, "stop": 8.0e6, "num": 10},
    {"field": "vehicle.carbody_mass", "start": 15000.0, "stop": 30000.0, "num": 100},
]


def sweep_dict(
    structural: bool = False, n_pads: int = 100, rail_vehicle: bool = False
) -> dict[str, Any]:
    if rail_vehicle:
        d = sweep_dict()
        d["title"] = "benchmark: rail EI x car body mass"
        d["axes"] = RAIL_VEHICLE_AXES
        return d
    second = (
        {
            "field": "track.pad.k0_n_per_m",
            "start": 2.0e7,
            "stop": 8.0e7,
            "num": n_pads,
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


def time_sweep(spec: SweepSpec, workers: int) -> tuple[float, float]:
    """Wall seconds of ``run_sweep`` and the parent's peak RSS growth in MB."""
    out = Path(tempfile.mkdtemp(prefix="railvib-bench-"))
    try:
        before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        t0 = time.perf_counter()
        run_sweep(spec, out / "sweep", workers=workers, progress=False)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        return wall, (after - before) / 1024
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
    p.add_argument("--large", action="store_true", help="the 10^4-case structural sweep")
    p.add_argument("--rail-vehicle", action="store_true", help="rail EI x car body mass")
    p.add_argument(
        "--only-goals", action="store_true", help="skip the speed sweep unless it is asked for"
    )
    args = p.parse_args()
    print(
        f"cores available: {os.cpu_count()}, workers: {args.workers}, load {os.getloadavg()[0]:.1f}"
    )
    runs = [] if args.only_goals else [("10 temperatures x 100 speeds", False, 100, 10.0)]
    if args.structural:
        runs.append(("10 temperatures x 100 pad stiffnesses", True, 100, None))
    if args.rail_vehicle:
        runs.append(("10 rail EI x 100 car body masses", "rail_vehicle", 0, None))
    if args.large:
        runs.append(("10 temperatures x 1000 pad stiffnesses", True, 1000, 10.0))
    for label, structural, n_pads, goal in runs:
        if structural == "rail_vehicle":
            spec = sweep_from_dict(sweep_dict(rail_vehicle=True))
        else:
            spec = sweep_from_dict(sweep_dict(bool(structural), n_pads))
        n = SweepLayout(spec).n_cases
        wall, rss = time_sweep(spec, args.workers)
        per_case = time_one_by_one(spec, args.sample)
        serial = per_case * n
        print(f"\n{label}: {n} cases x 1000 frequencies")
        verdict = (
            "" if goal is None else f"; goal <= {goal:g} s: {'PASS' if wall <= goal else 'FAIL'}"
        )
        print(
            f"  railvib sweep, {args.workers} workers: {wall:7.2f} s wall "
            f"({n / wall:,.0f} cases/s{verdict}); parent peak memory +{rss:.0f} MB"
        )
        print(
            f"  one by one (railvib.run + summary, 1 core): {per_case * 1e3:6.1f} ms/case "
            f"-> {serial:7.1f} s for {n} (from {min(args.sample, n)} cases)"
        )
        print(
            f"  speed-up per core: {serial / (wall * args.workers):5.1f}x "
            f"(wall: {serial / wall:5.1f}x on {args.workers} workers)"
        )


if __name__ == "__main__":
    main()
