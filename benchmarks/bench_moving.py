"""Cost of the moving vehicle (issue 17): the coupled case, and its moving-load kernel.

**The issue's goal**: the coupled moving-vehicle default case (the paper's preset with
``mode = "moving"``: its 0.1 Hz grid, 0.5-1000 Hz, 9996 frequencies, 80 km/h) at 10^4
frequencies with harmonics ``|n| <= 5`` in <= 1 s on one core. Timed:
``railvib.moving.moving_frf`` (the harmonic transfer functions: the moving-load receptances
between every pair of wheels at every ``|f + m v / d|``, the vehicle at each, and the
``(2N+1) n_wheel`` harmonic-balance solves) on the whole grid (the default) or
on every ``k``-th frequency of it (``--n`` of them, the whole band, scaled to 10^4: an
upper bound, since the receptances are interpolated in the load frequency wherever the
asked-for frequencies are dense, ``railvib.track.moving_interp``, and a subsampled grid
has fewer of them per interval), against the stationary case (``CoupledSystem.frf`` on
the whole grid), for harmonic orders 1, 2, 3, 5 (its growth), with PASS/FAIL on the
minimum at ``|n| <= 5``; each line says how many of the load frequencies took the direct
wavenumber integral.

Then ``railvib.track.moving.moving_load_receptance`` alone for the paper's rigid-base
track at ``v = 80 km/h`` on a 1 Hz - 2 kHz grid, for harmonic orders 0, 2, 5, 10 (each
computes two harmonics more, for its order check), under the load (``r = 0``) and, at
``|n| <= 5``, at the 9 distinct gaps between the default car's 4 wheels (0 to +-14.8 m:
what the coupled case asks of it at every load frequency), on the numba kernel (and
NumPy with ``--numpy``), against ``PeriodicTrack.receptance`` (wheel above mid-span),
scaled to 10^4 frequencies from ``--kernel-n``.

Times are CPU seconds of this process (``time.process_time``: the machine may be shared;
the load average is printed), the minimum and the median of ``--repeat`` runs after one
warm-up run (numba's compile or cache load, NumPy's first touches).

Usage: ``python benchmarks/bench_moving.py [--n N] [--repeat R] [--kernel-n N] [--numpy]
[--no-kernel]``.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import railvib.track.moving as moving
import railvib.track.moving_interp as moving_interp
from railvib.case import build_grid, build_system, load_preset_case
from railvib.moving import MovingSettings, moving_frf
from railvib.pads import SpringDamper
from railvib.track import PeriodicTrack, Rail
from railvib.track.moving import moving_load_receptance

GOAL_SECONDS = 1.0
N_GOAL = 10_000
ORDERS = (0, 2, 5, 10)
COUPLED_ORDERS = (1, 2, 3, 5)


def _times(fn, repeat: int) -> tuple[float, float]:
    """Minimum and median CPU seconds of `repeat` runs after one warm-up run."""
    fn()
    runs = []
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        runs.append(time.process_time() - t0)
    return min(runs), float(np.median(runs))


def _nodes(track, f, speed, order, r=(0.0,)) -> float:
    """Wavenumber nodes a frequency used (15 per panel visited)."""
    counted = []
    original = moving.panel_rules

    def counting(mid, *args, **kwargs):
        counted.append(mid.size)
        return original(mid, *args, **kwargs)

    moving.panel_rules = counting
    try:
        moving_load_receptance(track, f, speed, order=order, r=r, tolerance=0.5)
    finally:
        moving.panel_rules = original
    return 15.0 * sum(counted) / f.size


def _direct(system, f, settings) -> tuple[int, int]:
    """Load frequencies of `moving_frf` that took the direct integral, and all of them."""
    counted = []
    original = moving_interp.integrated_harmonics

    def counting(track, freqs, *args, **kwargs):
        counted.append(freqs.size)
        return original(track, freqs, *args, **kwargs)

    moving_interp.integrated_harmonics = counting
    try:
        moving_frf(system, f, settings, check=False)
    finally:
        moving_interp.integrated_harmonics = original
    n = settings.harmonic_order
    passing = system.speed / system.track.sleeper_spacing
    loads = np.unique(np.round(np.abs(f[:, None] + np.arange(-n, n + 1) * passing), 9))
    return sum(counted), loads.size


def coupled(n: int | None, repeat: int) -> None:
    """The coupled default case: moving against stationary, growth with the order."""
    case = load_preset_case()
    system = build_system(case)
    grid = build_grid(case).f
    f = grid if n is None else grid[:: max(1, grid.size // n)][:n]
    scale = N_GOAL / f.size
    stat_min, stat_med = (t * N_GOAL / grid.size for t in _times(lambda: system.frf(grid), repeat))
    print(
        f"coupled default case, stationary, {N_GOAL} frequencies: min {stat_min:.3f} s, "
        f"median {stat_med:.3f} s"
    )
    for order in COUPLED_ORDERS:
        # a loose tolerance: the cost is timed, not the order check (nor the tail warning)
        settings = MovingSettings(order, 0.5)
        low, mid = (
            t * scale
            for t in _times(lambda s=settings: moving_frf(system, f, s, check=False), repeat)
        )
        direct, loads = _direct(system, f, settings)
        print(
            f"coupled default case, moving |n| <= {order}, {N_GOAL} frequencies (from "
            f"{f.size}): min {low:7.2f} s, median {mid:7.2f} s ({low / stat_min:6.0f} x "
            f"stationary; {direct} of {loads} load frequencies integrated directly)"
        )
        if order == 5:
            verdict = "PASS" if low <= GOAL_SECONDS else "FAIL"
            print(
                f"{verdict}: coupled moving-vehicle default case, |n| <= 5, {N_GOAL} "
                f"frequencies: {low:.2f} s against the goal {GOAL_SECONDS} s"
            )


def kernel(n: int, repeat: int, numpy: bool) -> None:
    """The moving-load receptance alone, against the stationary receptance."""
    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    speed = 80 / 3.6
    x = build_system(load_preset_case()).wheel_positions
    gaps = np.unique(np.round(x[:, None] - x[None, :], 9))
    f = np.geomspace(1.0, 2000.0, n)
    scale = N_GOAL / n
    stat_min, stat_med = (
        t * scale for t in _times(lambda: track.receptance(f, [0.3], [0.3]), repeat)
    )
    print(
        f"stationary receptance, {N_GOAL} frequencies: min {stat_min:.3f} s, "
        f"median {stat_med:.3f} s"
    )
    for compiled in [True, False] if numpy else [True]:
        name = "numba" if compiled else "numpy"
        for order in ORDERS:
            # a loose order tolerance: the cost is timed, not the order check
            low, mid = (
                t * scale
                for t in _times(
                    lambda o=order, c=compiled: moving_load_receptance(
                        track, f, speed, order=o, tolerance=0.5, compiled=c
                    ),
                    repeat,
                )
            )
            nodes = _nodes(track, f, speed, order)
            print(
                f"{name} |n| <= {order:2d} ({2 * order + 5} harmonics, {nodes:5.0f} nodes a "
                f"frequency), {N_GOAL} frequencies: min {low:7.2f} s, median {mid:7.2f} s "
                f"({low / stat_min:5.0f} x stationary)"
            )
        low, mid = (
            t * scale
            for t in _times(
                lambda c=compiled: moving_load_receptance(
                    track, f, speed, order=5, r=gaps, tolerance=0.5, compiled=c
                ),
                repeat,
            )
        )
        nodes = _nodes(track, f, speed, 5, gaps)
        print(
            f"{name} |n| <=  5 at the car's {gaps.size} gaps ({nodes:5.0f} nodes a frequency), "
            f"{N_GOAL} frequencies: min {low:7.2f} s, median {mid:7.2f} s "
            f"({low / stat_min:5.0f} x stationary)"
        )


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, default=None, help="subsample the coupled case's grid")
    parser.add_argument("--repeat", type=int, default=3, help="timed runs after the warm-up")
    parser.add_argument("--kernel-n", type=int, default=1000, help="kernel frequencies timed")
    parser.add_argument("--numpy", action="store_true", help="also time the NumPy kernel")
    parser.add_argument("--no-kernel", action="store_true", help="the coupled case only")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs; CPU seconds")
    coupled(args.n, args.repeat)
    if not args.no_kernel:
        kernel(args.kernel_n, args.repeat, args.numpy)


if __name__ == "__main__":
    main()
