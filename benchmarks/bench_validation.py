"""Cost of the time-domain Monte Carlo needed for issue-5 accuracy vs the PEM run, as a ratio.

Runs the paper's default case with the default ``ValidationSettings`` (the settings
whose acceptance figures are reported in docs/validation.md) and times:

* PEM (symplectic track + pseudo excitation) on the Monte Carlo's Welch bins, 1-500 Hz;
* the finite-track frequency-domain reference on the 1 Hz - 1 kHz log grid;
* the time-domain Monte Carlo.

The Monte Carlo ratio is stated at the Monte Carlo's own PSD scatter (``sqrt(2 / dof)``
per Welch bin) and scaled to 1 % scatter (its cost grows as 1 / scatter^2; the PEM's
PSD has none).

Usage: ``python benchmarks/bench_validation.py [--quick] [--x0 X0] [--plots DIR]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from railvib.coupling import CoupledSystem
from railvib.pads import SpringDamper
from railvib.results.variables import compute_variables
from railvib.spectra import Combined, FRAClass, ShiTai
from railvib.track import PeriodicTrack, Rail
from railvib.validation import ValidationSettings, validate_case
from railvib.vehicle import PitchPlaneParameters, pitch_plane_10dof

PARAMS = PitchPlaneParameters(21920, 617310, 2550, 1750, 1420, 1.7e6, 5e3, 2.75e5, 3e4, 6.3, 1.1)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--x0", type=float, default=0.3)
    parser.add_argument("--plots", default=None, help="folder for overlay plots")
    args = parser.parse_args()
    vehicle = pitch_plane_10dof(PARAMS)
    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    spectrum = Combined(FRAClass(5), ShiTai())
    speed = 80 / 3.6
    settings = ValidationSettings.quick() if args.quick else ValidationSettings()
    system = CoupledSystem(vehicle, track, 9.873e8, args.x0, speed)
    res = validate_case(system, spectrum, settings=settings)

    # PEM on exactly the Monte Carlo's output bins (best of 5), through the result pipeline
    f = res.mc["frequency"].values
    best = np.inf
    for _ in range(5):
        t0 = time.perf_counter()
        compute_variables(system.frf(f), spectrum.temporal(f, speed), ["psd_acceleration"])
        best = min(best, time.perf_counter() - t0)
    mc = res.timings["monte_carlo_seconds"]
    fe = res.timings["finite_track_seconds"]
    print(f"case x0 = {args.x0} m, {'quick' if args.quick else 'default'} settings")
    print(f"PEM, {f.size} bins 1-500 Hz:             {best * 1e3:8.1f} ms")
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
        f"ratio Monte Carlo / PEM at the Monte Carlo's PSD scatter ({100 * scatter:.1f} % "
        f"per bin, {dof:g} dof): {mc / best:,.0f}"
    )
    print(
        f"  at an equal scatter of 1 % the Monte Carlo would cost {(scatter / 0.01) ** 2:,.0f} "
        f"times more: ratio {mc / best * (scatter / 0.01) ** 2:,.0f}"
    )
    print(
        f"ratio finite track / PEM (per frequency): "
        f"{(fe / res.frf['frequency'].size) / (best / f.size):,.0f}"
    )
    print(res.summary_markdown())
    print(res.table_markdown())
    print("passed:", res.passed, "dof:", res.mc.attrs["dof"])
    if args.plots:
        from railvib.validation import plot_overlays

        plot_overlays(res, args.plots, prefix=f"x0_{args.x0:g}")


if __name__ == "__main__":
    main()
