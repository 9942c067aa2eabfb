"""Benchmark: the stacked kernels on a GPU (CuPy or JAX), with a NumPy fallback on any machine.

Run: ``python benchmarks/bench_gpu.py [--backend auto|numpy|cupy|jax] [--quick]``.

Two workloads, in complex128, through :func:`railvib.sweep.stacked.frf_stack` (waves,
receptance, vehicle condensation and coupled solve all on the chosen array library):

* the default case (``wang2017_metro``) at many frequencies;
* a structural sweep: every case its own Kelvin-Voigt pad (k, c drawn log-uniformly) and
  speed, on the case's 1000-frequency log grid; 10^5 cases (10^8 frequency-case points) on
  a GPU.

Each prints frequency-case points per second (after a warm-up, min and median of the
repeats) and the largest relative difference (per response, to its peak) from railvib's
NumPy result of the same cases (``CoupledSystem.frf``, case by case, on a sample). Goals
(issue 13): <= 1e-10 relative difference; >= 10^8 frequency-case points in <= 10 s on one
data-centre GPU. With ``--backend auto`` it uses CuPy when a CUDA device is there, else
JAX on a GPU, else NumPy on the CPU (smaller sizes; the GPU goal is then not judged).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from dataclasses import replace
from typing import Any

import numpy as np

import railvib
from railvib.case import build_system
from railvib.pads import SpringDamper
from railvib.stack import namespace, to_numpy
from railvib.sweep.stacked import frf_stack

#: relative difference from NumPy allowed (issue 13)
ACCURACY_GOAL = 1e-10
#: points and seconds of the GPU goal
GPU_POINTS, GPU_SECONDS = 10**8, 10.0


def pick_backend(name: str) -> str:
    """The backend to run: `name`, or for ``auto`` the first usable GPU library, else numpy."""
    if name != "auto":
        return name
    try:
        import cupy

        if cupy.cuda.runtime.getDeviceCount() > 0:
            return "cupy"
    except Exception:  # noqa: BLE001 (not installed, or no driver/device)
        pass
    try:
        import jax

        if any(d.platform == "gpu" for d in jax.devices()):
            return "jax"
    except Exception:  # noqa: BLE001
        pass
    return "numpy"


def _jax_on_gpu() -> bool:
    import jax

    return jax.default_backend() == "gpu"


def _sync(xp: Any, arrays: tuple[Any, ...]) -> None:
    """Wait for the device to finish (CuPy and JAX run asynchronously)."""
    for a in arrays:
        if hasattr(a, "block_until_ready"):
            a.block_until_ready()
    if xp.__name__ == "cupy":
        xp.cuda.Device().synchronize()


def _timed(fn: Any, repeat: int) -> tuple[float, float, Any]:
    fn()  # warm-up (compilation, device allocation)
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), statistics.median(times), out


def _max_rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=0, keepdims=True)))


def run(backend: str, n_freq: int, n_case: int, repeat: int, block: int | None) -> dict[str, Any]:
    """Time both workloads on `backend`; returns the figures (also printed)."""
    xp = namespace(backend)
    system = build_system(railvib.load_preset_case())
    k0 = system.track.pad.stiffness(np.array([1.0]))[0].real
    c0 = system.track.pad.stiffness(np.array([1.0]))[0].imag / (2 * np.pi)
    results: dict[str, Any] = {"backend": backend}

    # the default case on a fine linear grid
    f = np.linspace(0.5, 1000.0, n_freq)
    pad = xp.asarray(system.track.pad.stiffness(f)[None, :])

    def one_case() -> tuple[Any, ...]:
        out = frf_stack(system, f, pad, [system.speed], xp, block=block)
        _sync(xp, out)
        return out

    lo, med, out = _timed(one_case, repeat)
    sample = slice(None, None, max(1, n_freq // 2000))
    ref = system.frf(f[sample])
    err = max(
        _max_rel(to_numpy(o)[0][sample], r)
        for o, r in zip(out, (ref.vehicle, ref.rail, ref.contact_force), strict=True)
    )
    results["default"] = (n_freq, lo, med, err)
    print(
        f"default case, {n_freq:,} frequencies: {n_freq / lo:,.0f} points/s "
        f"(min {lo * 1e3:.1f} ms, median {med * 1e3:.1f} ms); max rel diff to NumPy {err:.1e}"
    )

    # a structural sweep: each case its own pad and speed
    f = np.geomspace(0.5, 1000.0, 1000)
    rng = np.random.default_rng(13)
    k = k0 * np.exp(rng.uniform(-1.0, 1.0, n_case))
    c = c0 * np.exp(rng.uniform(-1.0, 1.0, n_case))
    v = rng.uniform(40.0, 160.0, n_case) / 3.6
    fx = xp.asarray(f)
    stiffness = xp.asarray(k)[:, None] + 2j * np.pi * fx[None, :] * xp.asarray(c)[:, None]

    def sweep() -> tuple[Any, ...]:
        out = frf_stack(system, f, stiffness, v, xp, block=block)
        _sync(xp, out)
        return out

    lo, med, out = _timed(sweep, repeat)
    err = 0.0
    for i in np.linspace(0, n_case - 1, min(n_case, 8)).astype(int):
        track = replace(system.track, pad=SpringDamper(float(k[i]), float(c[i])))
        ref = replace(system, track=track, speed=float(v[i])).frf(f)
        for o, r in zip(out, (ref.vehicle, ref.rail, ref.contact_force), strict=True):
            err = max(err, _max_rel(to_numpy(o[i]), r))
    points = n_case * f.size
    results["sweep"] = (points, lo, med, err)
    print(
        f"structural sweep, {n_case:,} cases x {f.size} frequencies: {points / lo:,.0f} points/s "
        f"(min {lo:.2f} s, median {med:.2f} s); max rel diff to NumPy {err:.1e}"
    )
    return results


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--backend", default="auto", choices=["auto", "numpy", "cupy", "jax"])
    parser.add_argument("--quick", action="store_true", help="small sizes (a test of the path)")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    backend = pick_backend(args.backend)
    gpu = backend == "cupy" or (backend == "jax" and _jax_on_gpu())
    if args.quick:
        n_freq, n_case, block = 2_000, 20, None
    elif gpu:
        n_freq, n_case, block = 1_000_000, 100_000, 2**21
    else:
        n_freq, n_case, block = 100_000, 1_000, None
    print(f"backend {backend} ({'GPU' if gpu else 'on the CPU: no GPU used'})")
    res = run(backend, n_freq, n_case, args.repeat, block)
    errs = [res["default"][3], res["sweep"][3]]
    ok = max(errs) <= ACCURACY_GOAL
    print(f"goal: max rel diff <= {ACCURACY_GOAL:g}: {'PASS' if ok else 'FAIL'} ({max(errs):.1e})")
    points, lo = res["sweep"][0], res["sweep"][1]
    if gpu and not args.quick:
        rate_ok = points >= GPU_POINTS and lo <= GPU_SECONDS
        print(
            f"goal: >= {GPU_POINTS:.0e} points in <= {GPU_SECONDS:g} s on one GPU: "
            f"{'PASS' if rate_ok else 'FAIL'} ({points:.1e} points in {lo:.2f} s)"
        )
    else:
        print("goal: 1e8 points in <= 10 s on a GPU: not judged (no GPU run)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
