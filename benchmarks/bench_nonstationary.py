"""Benchmark: the paper's car braking from 80 to 0 km/h at 1 m/s^2 on a rigid track (issue 18).

Run: ``python3 benchmarks/bench_nonstationary.py [--repeat N]`` (single-threaded BLAS is
enforced for a one-core figure). The default case (``wang2017_metro``: the paper's
10-DOF car, its irregularity) brakes from 80 km/h to a stop at 1 m/s^2 (22.2 s) with
10^3 wavenumbers over wavelengths 1-100 m and the default time step (half the Nyquist
step, 11.25 ms: 1977 steps). After a warm-up, the min and median of repeated runs:

1. the exact non-stationary PEM (``exact_response``): goal <= 10 s, with the cost per
   simulated second and per step and wavenumber;
2. the whole run (exact, quasi-stationary at 101 instants, first passage, dataset), for
   information;
3. the step-size error: the RMS at the default step against a step 4 times smaller
   (largest difference relative to each response's largest RMS), against the bound
   ``Omega_max a h^2 / 8`` of the integrator.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import argparse  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from railvib.case import case_from_dict  # noqa: E402
from railvib.nonstationary import build_run, exact_response, nonstationary_dataset  # noqa: E402
from railvib.nonstationary.exact import phase_error_bound  # noqa: E402

CASE = {
    "preset": "wang2017_metro",
    "mode": "nonstationary",
    "speed_profile": {
        "kind": "uniform",
        "v_start_kmh": 80.0,
        "v_end_kmh": 0.0,
        "acceleration_ms2": 1.0,
    },
    "nonstationary": {"wavelength_min_m": 1.0, "wavelength_max_m": 100.0, "n_wavenumbers": 1000},
}
GOAL_S = 10.0


def timed(fn, repeat):
    """Min and median wall seconds, min CPU seconds of `fn` over `repeat` runs, its result.

    The CPU time (of this process, one thread) is the one-core figure on a shared machine,
    where the wall time also counts the waits for a core.
    """
    out = fn()
    walls, cpus = [], []
    for _ in range(repeat):
        t, c = time.perf_counter(), time.process_time()
        out = fn()
        walls.append(time.perf_counter() - t)
        cpus.append(time.process_time() - c)
    return min(walls), statistics.median(walls), min(cpus), out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    run = build_run(case_from_dict(CASE))
    steps = int(np.ceil(run.profile.duration / run.dt - 1e-9)) + 1
    n_om = run.band.wavenumber.size

    def exact():
        return exact_response(run.model, run.profile, run.band, run.dt)

    t_min, t_med, cpu, hist = timed(exact, args.repeat)
    ok = min(t_min, cpu) <= GOAL_S
    print(
        f"1. exact PEM, {run.profile.duration:.1f} s braked, {steps} steps x {n_om} wavenumbers: "
        f"CPU {cpu:.2f} s; wall min {t_min:.2f} s, median {t_med:.2f} s (goal <= {GOAL_S:g} s "
        f"on one core) {'PASS' if ok else 'FAIL'}"
    )
    print(
        f"   cost {cpu / run.profile.duration * 1e3:.0f} ms CPU per simulated second, "
        f"{cpu / (steps * n_om) * 1e9:.0f} ns per step and wavenumber"
    )
    w_min, _, w_cpu, _ = timed(lambda: nonstationary_dataset(run), max(1, args.repeat - 1))
    print(
        f"2. whole run (exact + quasi-stationary + first passage + dataset): "
        f"CPU {w_cpu:.2f} s, wall {w_min:.2f} s"
    )
    h = float(hist.t[1] - hist.t[0])
    fine = exact_response(run.model, run.profile, run.band, h / 4)
    sd, sd_fine = np.sqrt(hist.variance), np.sqrt(fine.variance[::4])
    err = float(np.max(np.abs(sd - sd_fine) / sd_fine.max(axis=0)))
    bound = phase_error_bound(run.band, run.profile, h)
    print(
        f"3. step error at dt = {h * 1e3:.2f} ms: {err:.2g} of the largest RMS "
        f"(integrator phase bound {bound:.2g} rad)"
    )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
