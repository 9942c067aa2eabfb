"""Cost of the time-domain Monte Carlo needed for issue-5 accuracy vs the PEM run, as a ratio.

Runs the paper's default case with the default ``ValidationSettings`` (the settings
whose acceptance figures are reported in docs/validation.md) and times:

* PEM (symplectic track + pseudo excitation) on the Monte Carlo's Welch bins, 1-500 Hz;
* the finite-track frequency-domain reference on the 1 Hz - 1 kHz log grid;
* the time-domain Monte Carlo.

The finite-track ratio is stated at **equal accuracy**: the coarsest finite model (fewest
DOFs among margins of 10-60 bays x 2-8 elements per bay) whose acceleration PSDs agree
with the PEM's to 1e-4 of each response's peak over the 600 frequencies of 1 Hz-1 kHz
(the PEM agrees with the independent references to ~1e-11, so this is the finite model's
own error), against the PEM on the same frequencies; both timed with repeats (min and
median). The default validation mesh (60 bays x 8 elements, more accurate than that) is
printed beside it.

The Monte Carlo ratio is stated at equal PSD scatter as far as the two allow: the Monte
Carlo at its own scatter (``sqrt(2 / dof)`` per Welch bin), the PEM, which has none, on
the same bins (so the ratio is a lower bound), and the Monte Carlo scaled to 1 % scatter
(its cost grows as 1 / scatter^2). The Monte Carlo (minutes) runs once.

Usage: ``python benchmarks/bench_validation.py [--quick] [--x0 X0] [--plots DIR]
[--finite-only] [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

from railvib.coupling import CoupledSystem
from railvib.pads import SpringDamper
from railvib.response import FRF
from railvib.results.variables import compute_variables
from railvib.spectra import Combined, FRAClass, ShiTai
from railvib.track import PeriodicTrack, Rail
from railvib.validation import FiniteCoupledSystem, ValidationSettings, validate_case
from railvib.vehicle import PitchPlaneParameters, pitch_plane_10dof

PARAMS = PitchPlaneParameters(21920, 617310, 2550, 1750, 1420, 1.7e6, 5e3, 2.75e5, 3e4, 6.3, 1.1)

#: accuracy at which the finite track is compared: its PSDs within this fraction of each
#: response's peak PSD of the PEM's, at every frequency
EQUAL_ACCURACY = 1e-4

#: finite meshes tried, (bays beyond the outer wheels, Hermite elements per bay)
MESHES = [(m, e) for m in (10, 20, 30, 40, 60) for e in (2, 3, 4, 6, 8)]


def _timed(func: Callable[[], Any], repeat: int) -> tuple[Any, list[float]]:
    """``func()`` and the wall seconds of `repeat` calls of it."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = func()
        times.append(time.perf_counter() - t0)
    return out, times


def _psd(frf: FRF, spectrum: Combined, speed: float) -> NDArray[np.float64]:
    return np.asarray(
        compute_variables(frf, spectrum.temporal(frf.f, speed), ["psd_acceleration"])[
            "psd_acceleration"
        ]
    )


def peak_error(finite: NDArray[np.float64], pem: NDArray[np.float64]) -> float:
    """Largest ``|finite - PEM|`` over the frequencies, relative to each response's PEM peak."""
    return float((np.abs(finite - pem).max(axis=0) / pem.max(axis=0)).max())


def finite_at_equal_accuracy(
    system: CoupledSystem, spectrum: Combined, speed: float, repeat: int
) -> None:
    """Print the coarsest finite mesh reaching :data:`EQUAL_ACCURACY` and its cost ratio."""
    f = np.geomspace(1.0, 1000.0, 600)
    pem, pem_times = _timed(lambda: _psd(system.frf(f), spectrum, speed), repeat + 1)
    pem_times = pem_times[1:]  # the first call warms the caches
    models = [
        FiniteCoupledSystem.from_system(system, margin_spans=m, elements_per_span=e)
        for m, e in MESHES
    ]
    order = sorted(range(len(MESHES)), key=lambda i: models[i].n_dof)
    chosen = None
    for i in order:
        err = peak_error(_psd(models[i].frf(f), spectrum, speed), pem)
        print(f"  finite mesh {MESHES[i][0]:2d} bays x {MESHES[i][1]} elements, "
              f"{models[i].n_dof:5d} DOFs: error {err:.1e} of each response's peak")  # fmt: skip
        if err <= EQUAL_ACCURACY:
            chosen = i
            break
    print(
        f"goal: the finite track timed at equal accuracy ({EQUAL_ACCURACY:g} of each "
        f"response's peak), with repeats: {'PASS' if chosen is not None else 'FAIL'}"
        + ("" if chosen is not None else " (no mesh tried reaches it)")
    )
    default = MESHES.index((60, 8))
    rows = [("coarsest at equal accuracy", chosen), ("default validation mesh", default)]
    pem_per_f = float(np.median(pem_times)) / f.size
    print(f"PEM, {f.size} freqs 1 Hz-1 kHz: min {min(pem_times) * 1e3:.1f} ms, median "
          f"{np.median(pem_times) * 1e3:.1f} ms ({pem_per_f * 1e6:.1f} us/frequency)")  # fmt: skip
    for label, i in rows:
        if i is None:
            print(f"{label}: no mesh tried reaches {EQUAL_ACCURACY:g}")
            continue
        fin, times = _timed(lambda i=i: _psd(models[i].frf(f), spectrum, speed), repeat)
        per_f = float(np.median(times)) / f.size
        print(
            f"{label}: {MESHES[i][0]} bays x {MESHES[i][1]} elements ({models[i].n_dof} DOFs), "
            f"error {peak_error(fin, pem):.1e}: min {min(times):.2f} s, median "
            f"{np.median(times):.2f} s ({per_f * 1e3:.2f} ms/frequency); "
            f"ratio finite / PEM per frequency {per_f / pem_per_f:,.0f} (medians)"
        )


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--x0", type=float, default=0.3)
    parser.add_argument("--plots", default=None, help="folder for overlay plots")
    parser.add_argument("--repeat", type=int, default=3, help="timed runs of each route")
    parser.add_argument(
        "--finite-only", action="store_true", help="the finite-track ratio only (no Monte Carlo)"
    )
    args = parser.parse_args()
    vehicle = pitch_plane_10dof(PARAMS)
    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    spectrum = Combined(FRAClass(5), ShiTai())
    speed = 80 / 3.6
    settings = ValidationSettings.quick() if args.quick else ValidationSettings()
    system = CoupledSystem(vehicle, track, 9.873e8, args.x0, speed)
    print(f"finite track at equal accuracy ({EQUAL_ACCURACY:g} of each response's peak), "
          f"x0 = {args.x0} m:")  # fmt: skip
    finite_at_equal_accuracy(system, spectrum, speed, args.repeat)
    if args.finite_only:
        return
    res = validate_case(system, spectrum, settings=settings)

    # PEM on exactly the Monte Carlo's output bins (best of 5), through the result pipeline
    f = res.mc["frequency"].values
    _, pem_times = _timed(lambda: _psd(system.frf(f), spectrum, speed), 1 + max(args.repeat, 5))
    best = float(np.median(pem_times[1:]))  # after a warm-up call
    mc = res.timings["monte_carlo_seconds"]
    fe = res.timings["finite_track_seconds"]
    print(f"case x0 = {args.x0} m, {'quick' if args.quick else 'default'} settings")
    print(
        f"PEM, {f.size} bins 1-500 Hz:             {best * 1e3:8.1f} ms (median; min "
        f"{min(pem_times[1:]) * 1e3:.1f} ms)"
    )
    print(f"finite track, {res.frf['frequency'].size} freqs 1 Hz-1 kHz:  {fe:8.2f} s")
    print(
        f"Monte Carlo ({settings.monte_carlo.realisations} x "
        f"{settings.monte_carlo.record_seconds:g} s records): {mc:8.1f} s"
    )
    # a Welch estimate with `dof` degrees of freedom scatters by sqrt(2 / dof) of the PSD
    # (chi-square); its cost grows as 1 / scatter^2, while the PEM's PSD has no scatter
    dof = float(res.mc.attrs["dof"])
    scatter = (2.0 / dof) ** 0.5
    print(
        f"ratio Monte Carlo / PEM on the same bins, the Monte Carlo at {100 * scatter:.1f} % "
        f"PSD scatter per bin ({dof:g} dof), the PEM at none: {mc / best:,.0f} (at equal "
        "scatter the Monte Carlo would cost more still)"
    )
    print(
        f"  at an equal scatter of 1 % the Monte Carlo would cost {(scatter / 0.01) ** 2:,.0f} "
        f"times more: ratio {mc / best * (scatter / 0.01) ** 2:,.0f}"
    )
    print(
        f"(the validation's finite track, {res.frf['frequency'].size} freqs, ran once in "
        f"{fe:.2f} s; its ratio at equal accuracy is printed above)"
    )
    print(res.summary_markdown())
    print(res.table_markdown())
    print("passed:", res.passed, "dof:", res.mc.attrs["dof"])
    if args.plots:
        from railvib.validation import plot_overlays

        plot_overlays(res, args.plots, prefix=f"x0_{args.x0:g}")


if __name__ == "__main__":
    main()
