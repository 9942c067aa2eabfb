"""Benchmark: the default case at 10,000 frequencies vs a finite-track model of equal accuracy.

Run: ``python3 benchmarks/bench_core.py`` (single-threaded BLAS is enforced for a one-core
figure). The finite-track model (railvib.validation.FiniteTrack: Hermite elements, 12 per
bay, 600 bays, one sparse LU per frequency) is timed on a subset of frequencies and its
cost scaled linearly to 10,000 (its cost per frequency does not depend on the frequency).
Its agreement with the symplectic solution on the subset is printed too, so "equal accuracy"
is measured, not assumed.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import statistics  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

import railvib  # noqa: E402
from railvib.case import build_spectrum  # noqa: E402
from railvib.pads import SpringDamper  # noqa: E402
from railvib.track import Rail  # noqa: E402
from railvib.validation import FiniteTrack  # noqa: E402


def timed(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), min(times), out


def main():
    case = railvib.load_preset_case()
    system = railvib.build_system(case)
    spectrum = build_spectrum(case)
    grid = railvib.FrequencyGrid.linear(0.5, 1000.0, 0.1)
    railvib.run_system(system, grid, spectrum)  # warm-up
    t_pem, t_min, _ = timed(lambda: railvib.run_system(system, grid, spectrum), 15)

    x = system.wheel_positions
    finite = FiniteTrack(  # sleepers -300..300, 12 Hermite elements per bay, absorbing ends
        Rail(6.62e6, 60.64),
        SpringDamper(5.0e7, 5.0e4),
        0.6,
        -300,
        300,
        elements_per_span=12,
        absorber_spans=100,
        absorber_damping=40.0 * 5.0e4,
    )
    subset = grid.f[:: len(grid) // 100][:100]
    t0 = time.perf_counter()
    rec_finite = finite.receptance(subset, x, x)
    t_sub = time.perf_counter() - t0
    t_finite = t_sub / subset.size * len(grid)
    rec = system.track.receptance(subset, x, x)
    err = np.max(np.abs(rec - rec_finite) / np.abs(rec_finite).max(axis=(1, 2), keepdims=True))

    print(f"frequencies                      : {len(grid)} (0.5-1000 Hz, 0.1 Hz steps)")
    print(
        f"symplectic + PEM, whole case     : {t_pem * 1e3:8.1f} ms "
        f"(median of 15, fastest {t_min * 1e3:.1f} ms, one core)"
    )
    print(
        f"finite track receptance only     : {t_finite:8.1f} s  "
        f"(measured {t_sub:.2f} s for {subset.size} frequencies, scaled)"
    )
    print(f"finite vs symplectic receptance  : max relative difference {err:.1e}")
    print(f"ratio finite / symplectic        : {t_finite / t_pem:8.0f}x")
    print("goal: <= 0.1 s and >= 100x")


if __name__ == "__main__":
    main()
