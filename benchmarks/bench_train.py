"""Benchmark: trains on one core (issue 15): an 8-car train at 10^4 frequencies, and the cost
against the number of wheels.

Run: ``python3 benchmarks/bench_train.py [--repeat N]`` (single-threaded BLAS is enforced
for a one-core figure). The train is the paper's type-B car repeated (``[train] cars = n``,
4 m between the trailing wheel of a car and the leading wheel of the next, no couplers) on
the default case's track, 10^4 frequencies from 0.5 to 1000 Hz. After a warm-up each figure
is the min and median of repeated ``CoupledSystem.frf`` calls, with the share of its three
kernels: the track's receptance between all wheels (an ``n x n`` matrix at every
frequency: the part that grows as the square of the wheels), the car-by-car vehicle
condensation, and the coupled solve (batched LAPACK above 8 wheels).

Growth: the table runs 1 to 8 cars (4 to 32 wheels) by default; the closing lines fit each
kernel's CPU time to ``t = a n^p`` (least squares in log-log over the sizes run) and give the
exponent ``p`` of the whole call and of each kernel, with the fraction of the 8-car time that
the part growing with ``n^2`` (the receptance matrix) takes. CPU times (``process_time``) so
that a loaded machine's other processes do not count.

Goal: 8 cars (32 wheels) in <= 1 s.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import argparse  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from railvib.case import case_from_dict  # noqa: E402
from railvib.case.build import build_system  # noqa: E402
from railvib.coupling import coupled_response  # noqa: E402
from railvib.pem import excitation_vector, wheel_delays  # noqa: E402

GOAL_S = 1.0
N_FREQ = 10_000


def _system(cars: int):
    data = {"preset": "wang2017_metro", "train": {"cars": cars, "gap_m": 4.0}}
    return build_system(case_from_dict(data, warn=False))


def _time(fn, repeat: int) -> tuple[float, float]:
    fn()  # warm-up
    times = []
    for _ in range(repeat):
        t = time.process_time()
        fn()
        times.append(time.process_time() - t)
    return min(times), statistics.median(times)


def _exponent(wheels: list[int], seconds: list[float]) -> float:
    """``p`` of the least-squares fit ``log t = log a + p log n`` (nan for < 2 sizes)."""
    if len(wheels) < 2:
        return float("nan")
    return float(np.polyfit(np.log(wheels), np.log(np.maximum(seconds, 1e-9)), 1)[0])


def _kernels(system, f: np.ndarray) -> tuple[float, float, float]:
    """Seconds of the receptance, the condensation and the solve (one pass, whole grid)."""
    x = system.wheel_positions
    t0 = time.process_time()
    rec = system.track.receptance(f, x, x)
    t1 = time.process_time()
    cond = system.vehicle.condensed_to_wheels(f)
    t2 = time.process_time()
    v = excitation_vector(f, wheel_delays(system.vehicle.wheel_offsets, system.speed))
    coupled_response(cond, rec, system.contact_stiffness, v[..., None])
    t3 = time.process_time()
    return t1 - t0, t2 - t1, t3 - t2


def main() -> int:
    """Print the figures; exit status 1 if the goal is missed."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--cars", type=int, nargs="*", default=list(range(1, 9)))
    args = parser.parse_args()
    f = np.linspace(0.5, 1000.0, N_FREQ)
    print(
        f"{'cars':>4} {'wheels':>6} {'min s':>8} {'median s':>8} {'per wheel^2 us':>14}  "
        "receptance / condensation / solve (s)"
    )
    ok = True
    rows: list[tuple[int, float, float, float, float]] = []
    for cars in args.cars:
        system = _system(cars)
        t_min, t_med = _time(lambda s=system: s.frf(f), args.repeat)
        n = len(system.vehicle.wheels)
        rec, cond, solve = _kernels(system, f)
        rows.append((n, t_min, rec, cond, solve))
        print(
            f"{cars:>4} {n:>6} {t_min:8.3f} {t_med:8.3f} {1e6 * t_min / n**2:14.1f}  "
            f"{rec:.3f} / {cond:.3f} / {solve:.3f}"
        )
        if cars == 8:
            passed = t_min <= GOAL_S
            ok = ok and passed
            print(
                f"     8 cars (32 wheels), 10^4 frequencies, one core: {t_min:.3f} s "
                f"(goal <= {GOAL_S} s): {'PASS' if passed else 'FAIL'}"
            )
    wheels = [r[0] for r in rows]
    print("growth with the number of wheels n (fit t = a n^p over the sizes run):")
    for name, col in (("whole call", 1), ("receptance", 2), ("condensation", 3), ("solve", 4)):
        print(f"  {name:<12} p = {_exponent(wheels, [r[col] for r in rows]):.2f}")
    if rows:
        n, total, rec, cond, solve = rows[-1]
        print(
            f"  at {n} wheels the receptance takes {rec / (rec + cond + solve):.0%} of the "
            f"kernels' time, the condensation {cond / (rec + cond + solve):.0%}, "
            f"the solve {solve / (rec + cond + solve):.0%}"
        )
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
