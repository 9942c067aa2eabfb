"""Cost of the moving-load receptance (issue 17) against the stationary receptance.

Times ``railvib.track.moving.moving_load_receptance`` for the paper's rigid-base track at
``v = 80 km/h`` on a 1 Hz - 2 kHz grid, for harmonic orders 0, 2, 5, 10, against
``PeriodicTrack.receptance`` (wheel above mid-span, the stationary model) on the same
grid; the time at 10^4 frequencies is extrapolated linearly from ``--n`` frequencies
(the kernel is chunked over frequency, so its cost is linear in their number).

The issue's goal is the coupled moving-vehicle case at 10^4 frequencies, ``|n| <= 5``, in
<= 1 s on one core; the coupled case is not built yet (issue 17 item 3), so the goal is
checked on the track kernel alone, which it needs at the least.

Usage: ``python benchmarks/bench_moving.py [--n N]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from railvib.pads import SpringDamper
from railvib.track import PeriodicTrack, Rail
from railvib.track.moving import _starting_panels, moving_load_receptance

GOAL_SECONDS = 1.0
N_GOAL = 10_000


def _best(fn, repeat: int = 3) -> float:
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, default=200, help="frequencies timed")
    args = parser.parse_args()
    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    speed = 80 / 3.6
    f = np.geomspace(1.0, 2000.0, args.n)
    scale = N_GOAL / args.n
    stationary = _best(lambda: track.receptance(f, [0.3], [0.3])) * scale
    print(f"stationary receptance, {N_GOAL} frequencies:  {stationary:8.3f} s")
    for order in (0, 2, 5, 10):
        nodes = 15 * _starting_panels(track, float(f.max()), order + 2)[0].size
        # a loose tolerance: the cost is timed, not the order check
        cost = _best(
            lambda o=order: moving_load_receptance(track, f, speed, order=o, tolerance=0.5)
        )
        cost *= scale
        print(
            f"moving load |n| <= {order:2d} ({nodes} starting nodes), {N_GOAL} frequencies: "
            f"{cost:8.1f} s"
            f"  ({cost / stationary:6.0f} x stationary)"
        )
        if order == 5:
            verdict = "PASS" if cost <= GOAL_SECONDS else "FAIL"
            print(f"{verdict}: track kernel, |n| <= 5, {N_GOAL} frequencies <= {GOAL_SECONDS} s")


if __name__ == "__main__":
    main()
