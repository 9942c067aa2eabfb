"""Benchmark: sweeps of 1000 and 10^4 cases at 1000 frequencies on 2 cores, vs cases one by one.

The speed sweep is pad temperature (10 values, -40 to +40 degC, a temperature-dependent
fractional-Zener pad with WLF shift) x speed (100 values, 40 to 160 km/h): 1000 cases,
1000 log-spaced frequencies, 14 responses. ``--structural`` adds the structural sweep,
where no two cases share a track: 10 temperatures x 100 pad stiffnesses (1000 cases),
and ``--large`` the same with 1000 pad stiffnesses (10^4 cases; issue 13 goal: <= 10 s
wall on 2 cores, the parent's memory bounded by the chunk). ``--rail-vehicle`` adds a
sweep of 10 rail bending stiffnesses x 100 car body masses (1000 cases, no two sharing a
track or a vehicle: every case's rail and vehicle evaluated on the stack).

Each sweep is timed as a user runs it (worker start, chunk files and the Zarr store
included): a warm-up run, then ``--repeat`` runs (default 3), min and median of the wall
time and of the CPU time of every process of the run (the parent and its workers, read
from ``/proc``), with the parent's peak resident memory during the run (sampled every
20 ms) for the sweep's size and for a tenth of it (``--large``: 10^3 against 10^4 cases),
so that its growth with the sweep shows, and the size of the output folder the run
leaves (what it wrote: the store, the chunks' records, the manifest). Loading the sweep
file (``sweep_from_dict``: the base case and every axis value validated, as ``railvib
sweep`` does before it computes) is timed too, before each run; the goal's wall figure
is the whole command's: the load plus the run.

The one-by-one reference does the same work per case as the sweep, case by case in one
process (one core): the case validated and built, solved alone
(``CoupledSystem.frf``), the same per-frequency variable, contact check, criteria and
summary; on a sample of the cases (``--sample``, default 100), scaled to the sweep. The
speed-up is stated per core: that CPU time against the sweep's core-seconds (wall x
workers) and against its CPU time. ``railvib.run`` + ``railvib.summary`` per case (the
whole dataset of a run: more work than the sweep stores) is printed beside it.

Usage::

    python benchmarks/bench_sweep.py [--workers 2] [--sample 100] [--repeat 3] [--structural]
        [--large] [--rail-vehicle] [--only-goals]
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import railvib
from railvib.case import build_grid, build_spectrum, build_system, case_from_dict
from railvib.case.load import merge_case_dicts
from railvib.results.variables import compute_variables
from railvib.sweep import SweepLayout, SweepSpec, run_sweep, sweep_from_dict
from railvib.sweep.batch import _summary, criteria_summary
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


_TICK = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


def _stat(pid: int) -> tuple[int, float] | None:
    """``(parent pid, CPU seconds)`` of process `pid` from /proc, None if it is gone."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()
    except OSError:
        return None
    return int(fields[1]), (int(fields[11]) + int(fields[12])) / _TICK


def _descendants(pid: int) -> list[int]:
    """Processes under `pid` (Linux's /proc/PID/task/TID/children; none elsewhere)."""
    out: list[int] = []
    todo = [pid]
    while todo:
        p = todo.pop()
        try:
            tasks = list(Path(f"/proc/{p}/task").iterdir())
        except OSError:
            continue
        for task in tasks:
            try:
                kids = [int(k) for k in (task / "children").read_text().split()]
            except OSError:
                continue
            out += kids
            todo += kids
    return out


def _rss_mb() -> float:
    """This process's resident memory now, MB (/proc; 0 where there is none)."""
    try:
        pages = int(Path("/proc/self/statm").read_text().split()[1])
    except OSError:
        return 0.0
    return pages * os.sysconf("SC_PAGE_SIZE") / 2**20


class ProcessWatch:
    """CPU seconds of this process's descendants (the workers) and this process's peak RSS.

    Polls /proc every 20 ms while running (about 0.1 ms a poll on a quiet machine, more
    under load, in this process's CPU: its own thread's CPU is kept in `own_cpu`, to be
    taken off this process's): a worker's CPU is its last reading (it runs until the
    pool shuts down, so at most 20 ms of it is lost).
    """

    def __init__(self) -> None:
        self.cpu: dict[int, float] = {}
        self.peak_rss_mb = 0.0
        self.own_cpu = 0.0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._poll, daemon=True)

    def __enter__(self) -> ProcessWatch:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()

    def _poll(self) -> None:
        me = os.getpid()
        while not self._stop.wait(0.02):
            self.peak_rss_mb = max(self.peak_rss_mb, _rss_mb())
            for pid in _descendants(me):
                if (st := _stat(pid)) is not None:
                    self.cpu[pid] = max(self.cpu.get(pid, 0.0), st[1])
        self.own_cpu = time.thread_time()

    @property
    def children_cpu(self) -> float:
        """CPU seconds of the descendants seen (fork server and workers)."""
        return sum(self.cpu.values())


@dataclass
class SweepRun:
    """One timed sweep: wall s, CPU s of every process, parent's peak RSS and bytes written, MB."""

    wall: float
    cpu: float
    parent_cpu: float
    rss_mb: float
    written_mb: float


def time_load(d: dict[str, Any]) -> tuple[SweepSpec, float, float]:
    """The sweep file `d` validated and resolved (``sweep_from_dict``), wall and CPU seconds."""
    c0, t0 = time.process_time(), time.perf_counter()
    spec = sweep_from_dict(d)
    return spec, time.perf_counter() - t0, time.process_time() - c0


def time_sweep(spec: SweepSpec, workers: int) -> SweepRun:
    """One ``run_sweep`` into a fresh folder, timed (wall, CPU of all processes, parent RSS)."""
    out = Path(tempfile.mkdtemp(prefix="railvib-bench-"))
    try:
        with ProcessWatch() as watch:
            c0, t0 = time.process_time(), time.perf_counter()
            run_sweep(spec, out / "sweep", workers=workers, progress=False)
            wall, parent = time.perf_counter() - t0, time.process_time() - c0
        parent -= watch.own_cpu  # the polling is the benchmark's, not the sweep's
        written = sum(p.stat().st_size for p in out.rglob("*") if p.is_file()) / 1e6
        return SweepRun(wall, parent + watch.children_cpu, parent, watch.peak_rss_mb, written)
    finally:
        shutil.rmtree(out, ignore_errors=True)


def _sample_cases(spec: SweepSpec, sample: int) -> list[dict[str, Any]]:
    lay = SweepLayout(spec)
    all_idx = np.stack(np.unravel_index(np.arange(lay.n_cases), lay.shape), axis=1)
    pick = np.linspace(0, lay.n_cases - 1, min(sample, lay.n_cases)).astype(int)
    cases = []
    for index in all_idx[pick]:
        d = spec.base_case_dict()
        for field, value in lay.overrides(index):
            d = merge_case_dicts(d, nested_override(field, value))
        cases.append(d)
    return cases


def same_work_alone(spec: SweepSpec, d: dict[str, Any]) -> None:
    """What the sweep computes and keeps for one case, for that case alone.

    Validated and built (``case_from_dict``, ``build_system``), solved alone
    (``CoupledSystem.frf``), then the sweep's per-frequency variables, contact check,
    criteria and summary of that one case.
    """
    case = case_from_dict(d, warn=False)
    system = build_system(case)
    f = build_grid(case).f
    s_r = build_spectrum(case).temporal(f, system.speed)[None]
    frf = system.frf(f)
    batch = type(frf)(
        f, frf.vehicle[None], frf.rail[None], frf.contact_force[None], frf.dofs,
        wheels=frf.wheels,
    )  # fmt: skip
    names = dict.fromkeys([*spec.variables, "psd_force", spec.summary_variable])
    values = compute_variables(batch, s_r, names)
    loads = np.asarray(system.vehicle.static_wheel_loads(), dtype=float)[None]
    psd_force = values["psd_force"]
    criteria_summary(spec, f, batch, s_r, psd_force, loads)
    _summary(f, np.asarray(values[spec.summary_variable]), spec.rms_bands)


def time_one_by_one(spec: SweepSpec, sample: int) -> tuple[float, float]:
    """CPU seconds per case: the sweep's work case by case, and ``railvib.run`` + summary."""
    cases = _sample_cases(spec, sample)
    same_work_alone(spec, cases[0])  # warm imports and caches
    railvib.run(railvib.case_from_dict(cases[0]))
    t0 = time.process_time()
    for d in cases:
        same_work_alone(spec, d)
    same = (time.process_time() - t0) / len(cases)
    t0 = time.process_time()
    for d in cases:
        ds = railvib.run(railvib.case_from_dict(d))
        railvib.summary(ds, bands=[(0.5, 20.0), (20.0, 100.0), (100.0, 1000.0)])
    return same, (time.process_time() - t0) / len(cases)


def _stats(values: list[float]) -> str:
    return f"min {min(values):6.2f} median {float(np.median(values)):6.2f}"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--sample", type=int, default=100)
    p.add_argument("--repeat", type=int, default=3, help="timed runs after the warm-up")
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
            d = sweep_dict(rail_vehicle=True)
        else:
            d = sweep_dict(bool(structural), n_pads)
        spec = time_load(d)[0]  # warm-up of the load too (imports, caches)
        n = SweepLayout(spec).n_cases
        time_sweep(spec, args.workers)  # warm-up: the fork server, numba's cache, the files
        loads, timed = [], []
        for _ in range(args.repeat):
            spec, load_wall, load_cpu = time_load(d)
            loads.append((load_wall, load_cpu))
            timed.append(time_sweep(spec, args.workers))
        # the command's wall: loading the sweep file, then running it
        walls = [lw + r.wall for (lw, _), r in zip(loads, timed, strict=True)]
        cpus = [lc + r.cpu for (_, lc), r in zip(loads, timed, strict=True)]
        same, whole = time_one_by_one(spec, args.sample)
        print(f"\n{label}: {n} cases x 1000 frequencies, load {os.getloadavg()[0]:.1f}")
        verdict = (
            ""
            if goal is None
            else f"; goal <= {goal:g} s: {'PASS' if min(walls) <= goal else 'FAIL'}"
        )
        print(
            f"  railvib sweep, {args.workers} workers, {args.repeat} runs: wall {_stats(walls)} s, "
            f"the file's load included ({n / float(np.median(walls)):,.0f} cases/s{verdict})"
        )
        print(
            f"    of which loading the sweep file: wall {_stats([w for w, _ in loads])} s, CPU "
            f"{_stats([c for _, c in loads])} s; the run alone: wall "
            f"{_stats([r.wall for r in timed])} s"
        )
        print(
            f"    CPU of all its processes, load included {_stats(cpus)} s (parent's run "
            f"{_stats([r.parent_cpu for r in timed])} s); parent peak RSS "
            f"{max(r.rss_mb for r in timed):.0f} MB; output folder {timed[0].written_mb:.0f} MB"
        )
        if n_pads == 1000:  # the parent's memory against the sweep's size
            small = time_sweep(sweep_from_dict(sweep_dict(True, 100)), args.workers)
            print(
                f"    parent peak RSS with 10^3 cases: {small.rss_mb:.0f} MB (output folder "
                f"{small.written_mb:.0f} MB)"
            )
        print(
            f"  one by one, the same work per case (1 core): {same * 1e3:6.1f} ms CPU/case -> "
            f"{same * n:7.1f} s for {n} (from {min(args.sample, n)} cases); railvib.run + "
            f"summary: {whole * 1e3:6.1f} ms/case"
        )
        med_wall, med_cpu = float(np.median(walls)), float(np.median(cpus))
        print(
            f"  speed-up per core, same work: {same * n / (med_wall * args.workers):5.1f}x "
            f"against the sweep's core-seconds (wall x {args.workers}), "
            f"{same * n / med_cpu:5.1f}x against its CPU time (medians)"
        )


if __name__ == "__main__":
    main()
