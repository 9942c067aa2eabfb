"""Cost of the moving-load receptance (issue 17) against the stationary receptance.

Times ``railvib.track.moving.moving_load_receptance`` for the paper's rigid-base track at
``v = 80 km/h`` on a 1 Hz - 2 kHz grid, for harmonic orders 0, 2, 5, 10 (each computes
two harmonics more, for its order check), on the numba kernel and on NumPy, against
``PeriodicTrack.receptance`` (wheel above mid-span, the stationary model) on the same
grid. Times are CPU seconds of this process (``time.process_time``: the machine may be
shared; the load average is printed), the minimum and the median of ``--repeat`` runs
after one warm-up run (numba's compile or cache load, NumPy's first touches), scaled
to 10^4 frequencies from ``--n`` (the cost is linear in their number: each frequency
refines its own panels).

The issue's goal is the coupled moving-vehicle case at 10^4 frequencies, ``|n| <= 5``,
in <= 1 s on one core; the coupled case builds on this kernel, so the goal is checked on
the kernel alone, which it needs at the least (PASS/FAIL on the minimum).

Usage: ``python benchmarks/bench_moving.py [--n N] [--repeat R] [--numpy]``.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import railvib.track.moving as moving
from railvib.pads import SpringDamper
from railvib.track import PeriodicTrack, Rail
from railvib.track.moving import moving_load_receptance

GOAL_SECONDS = 1.0
N_GOAL = 10_000
ORDERS = (0, 2, 5, 10)


def _times(fn, repeat: int) -> tuple[float, float]:
    """Minimum and median CPU seconds of `repeat` runs after one warm-up run."""
    fn()
    runs = []
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        runs.append(time.process_time() - t0)
    return min(runs), float(np.median(runs))


def _nodes(track, f, speed, order) -> float:
    """Wavenumber nodes a frequency used (15 per panel visited)."""
    counted = []
    original = moving.panel_rules

    def counting(mid, *args, **kwargs):
        counted.append(mid.size)
        return original(mid, *args, **kwargs)

    moving.panel_rules = counting
    try:
        moving_load_receptance(track, f, speed, order=order, tolerance=0.5)
    finally:
        moving.panel_rules = original
    return 15.0 * sum(counted) / f.size


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, default=1000, help="frequencies timed")
    parser.add_argument("--repeat", type=int, default=3, help="timed runs after the warm-up")
    parser.add_argument("--numpy", action="store_true", help="also time the NumPy kernel")
    args = parser.parse_args()
    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    speed = 80 / 3.6
    f = np.geomspace(1.0, 2000.0, args.n)
    scale = N_GOAL / args.n
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs; CPU seconds")
    stat_min, stat_med = (
        t * scale for t in _times(lambda: track.receptance(f, [0.3], [0.3]), args.repeat)
    )
    print(
        f"stationary receptance, {N_GOAL} frequencies: min {stat_min:.3f} s, "
        f"median {stat_med:.3f} s"
    )
    kernels = [True, False] if args.numpy else [True]
    for compiled in kernels:
        name = "numba" if compiled else "numpy"
        for order in ORDERS:
            # a loose order tolerance: the cost is timed, not the order check
            low, mid = (
                t * scale
                for t in _times(
                    lambda o=order, c=compiled: moving_load_receptance(
                        track, f, speed, order=o, tolerance=0.5, compiled=c
                    ),
                    args.repeat,
                )
            )
            nodes = _nodes(track, f, speed, order)
            print(
                f"{name} |n| <= {order:2d} ({2 * order + 5} harmonics, {nodes:5.0f} nodes a "
                f"frequency), {N_GOAL} frequencies: min {low:7.2f} s, median {mid:7.2f} s "
                f"({low / stat_min:5.0f} x stationary)"
            )
            if order == 5 and compiled:
                verdict = "PASS" if low <= GOAL_SECONDS else "FAIL"
                print(
                    f"{verdict}: moving-load kernel, |n| <= 5, {N_GOAL} frequencies: "
                    f"{low:.2f} s against the goal {GOAL_SECONDS} s"
                )


if __name__ == "__main__":
    main()
