"""Benchmark: one case on one core (issue 13 goals 1, 2 and the honest finite-track ratio).

Run: ``python3 benchmarks/bench_core.py [--repeat N] [--million-repeat N] [--skip-million]
[--skip-finite] [--skip-slab]``
(single-threaded BLAS is enforced for a one-core figure). After a warm-up, each figure is
the min and median of repeated runs, printed with PASS/FAIL against its goal:

1. the default case (``wang2017_metro``) at 10^4 frequencies, ``run_system``: <= 15 ms of
   CPU time (``time.process_time``: one core's work, what a loaded machine does not
   inflate as it does the wall time, printed beside it); with the share of each part
   (track receptance between the wheels and to the seats under them, vehicle
   condensation, coupled solve, each over the run's frequency blocks);
2. 10^6 frequencies: <= 2 s CPU (median) and <= 500 MB peak resident memory (the
   largest), over ``--million-repeat`` fresh processes, each one run after a warm-up (the
   same call on 8192 frequencies: the process's one-off costs, printed beside it),
   streamed to results.nc block by block (``railvib.solve.stream_to_netcdf``, the writes
   counted: the PASS/FAIL figure) and held in memory (``run_system``: printed beside it;
   the result dataset itself is 608 bytes per frequency and the process holds ~140 MB
   before the run, ~270 MB with numba loaded: printed, with the memory beyond them);
4. the finite-track reference at **equal accuracy**: of a ladder of finite models
   (``railvib.validation.FiniteTrack``: bays beyond the wheels x Hermite elements per
   bay, absorbing ends or none), the cheapest whose receptance between the wheels is within 1e-4 of
   the symplectic one (relative to its largest entry, on 40 frequencies over the grid),
   timed with repeats; the ratio is per frequency, receptance against receptance and
   against the whole case.

Issue 14: the whole case (``run_system``) of the ballasted preset (``thompson_ballasted``:
goal <= 1.5x) and of the floating-slab preset (``floating_slab_metro``, the 8-state cell
solved by doubling: goal <= 4x) against the rigid-base default case, all at 10^4
frequencies, CPU time of interleaved runs, NumPy against NumPy and compiled against
compiled; the track receptance between the wheels alone is printed beside it.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import argparse  # noqa: E402
import importlib.util  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

import railvib  # noqa: E402
from railvib.case import build_spectrum  # noqa: E402
from railvib.coupled_kernel import fused_points  # noqa: E402
from railvib.coupling import (  # noqa: E402
    FREQUENCY_BLOCK,
    _compiled_receptance,
    _receptance_parts,
    coupled_response,
)
from railvib.outputs.supports import seat_positions  # noqa: E402
from railvib.pem import excitation_vector, wheel_delays  # noqa: E402
from railvib.track.compiled import compile_kernel  # noqa: E402
from railvib.validation import FiniteTrack  # noqa: E402

#: the finite models tried: (bays beyond the wheels on each side, Hermite elements per bay,
#: absorbing bays at each end with graded pad damping up to 40 x the pad's 5e4 N s/m)
FINITE_LADDER = [(m, e, a) for m in (30, 60, 100) for e in (4, 6, 8, 12) for a in (0, m // 3)] + [
    (300, 12, 100)
]  # the last: the reference model of the earlier benchmark
#: the accuracy the finite model must reach (relative to the largest receptance entry)
EQUAL_ACCURACY = 1e-4

MILLION = """
import json, os, resource, sys, tempfile, time
def peak_rss():  # this process's own high-water mark: ru_maxrss keeps the parent's after exec
    try:
        with open("/proc/self/status") as status:
            return next(int(l.split()[1]) * 1024 for l in status if l.startswith("VmHWM:"))
    except (OSError, StopIteration):
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
import railvib, railvib.solve
from railvib.case import build_spectrum
from railvib.track import compiled
if sys.argv[2] == "compiled":
    compiled.compile_kernel()  # loaded before the timing: a process that holds it
case = railvib.load_preset_case(); system = railvib.build_system(case)
spectrum = build_spectrum(case)
grid = railvib.FrequencyGrid.linear(0.5, 1000.0, 999.5 / (int(sys.argv[1]) - 1))
folder = tempfile.mkdtemp()
path = os.path.join(folder, "results.nc")
# the warm-up: the same call on 8192 frequencies (two blocks, above the compiled path's
# LOADED_MIN_POINTS), so that the one-off costs of a process are paid before the timing:
# numba's load of the fused kernel (compiled), xarray's first to_netcdf (which imports
# dask.distributed where it is installed: 0.3-0.9 s); printed as "first" beside it
warm = railvib.FrequencyGrid.linear(0.5, 1000.0, 999.5 / 8191)
first = time.process_time()
if sys.argv[3] == "held":
    railvib.run_system(system, warm, spectrum)
else:
    railvib.solve.stream_to_netcdf(system, warm, spectrum, path)
    os.remove(path)
first = time.process_time() - first
before = peak_rss()
t, cpu = time.perf_counter(), time.process_time()
if sys.argv[3] == "held":
    ds = railvib.run_system(system, grid, spectrum)
else:  # streamed to a file: the writes counted
    ds = railvib.solve.stream_to_netcdf(system, grid, spectrum, path)
t, cpu = time.perf_counter() - t, time.process_time() - cpu
rss = peak_rss()
size = os.path.getsize(path) if os.path.exists(path) else 0
if size:
    os.remove(path)
os.rmdir(folder)
fast = bool(compiled._KERNEL) and compiled._KERNEL[0] is not None
print(json.dumps({"n": len(grid), "t": t, "cpu": cpu, "rss": rss, "before": before,
                  "result": ds.nbytes, "file": size, "compiled": fast, "first": first}))
"""


def timed(fn, repeat):
    """(min, median) CPU seconds of `fn` over `repeat` runs after one warm-up, and its result.

    CPU time (``time.process_time``) of this single-threaded process is one core's work;
    the wall times (min, median) are in the result's fourth and fifth places.
    """
    out = fn()
    cpu, wall = [], []
    for _ in range(repeat):
        t, w = time.process_time(), time.perf_counter()
        out = fn()
        cpu.append(time.process_time() - t)
        wall.append(time.perf_counter() - w)
    return min(cpu), statistics.median(cpu), out, min(wall), statistics.median(wall)


def verdict(ok):
    return "PASS" if ok else "FAIL"


def goal_one(system, spectrum, repeat):
    grid = railvib.FrequencyGrid.linear(0.5, 1000.0, 0.1)
    f = grid.f
    # the NumPy kernels, then the compiled one where numba is installed (loaded first: a
    # process that has solved a large stack holds it; a cold `railvib run` of 10^4
    # frequencies stays on NumPy, where importing numba would cost more than it saves)
    paths = [("NumPy", "0")] + ([("compiled (numba)", "1")] if compile_kernel() else [])
    best = None
    for label, flag in paths:
        os.environ["RAILVIB_COMPILED"] = flag
        lo, med, _, wall_lo, wall_med = timed(
            lambda: railvib.run_system(system, grid, spectrum), repeat
        )
        best = med if best is None else min(best, med)
        print(f"1. default case, {len(grid)} frequencies (run_system, one core), {label}")
        print(
            f"   CPU min {lo * 1e3:7.1f} ms, median {med * 1e3:7.1f} ms "
            f"(wall min {wall_lo * 1e3:.1f} ms, median {wall_med * 1e3:.1f} ms)"
        )
        breakdown(system, f, flag == "1", repeat, lo)
    os.environ.pop("RAILVIB_COMPILED")
    print(f"   best CPU median {best * 1e3:.1f} ms   goal <= 15 ms: {verdict(best <= 0.015)}")


def breakdown(system, f, fast, repeat, total_time):
    """Print the share of each part of a run (CPU, min of each), block by block as a run."""
    x = system.wheel_positions
    vehicle = system.vehicle
    seats = seat_positions(x, system.track.sleeper_spacing)
    x_obs = np.concatenate([x, seats])
    blocks = [f[i : i + FREQUENCY_BLOCK] for i in range(0, f.size, FREQUENCY_BLOCK)]
    parts = {}
    parts["track receptance (wheels and seats, waves included)"] = timed(
        lambda: [
            _compiled_receptance(system.track, fb, x, x_obs)
            if fast
            else system.track.receptance(fb, x, x_obs)
            for fb in blocks
        ],
        repeat,
    )[0]
    delays = wheel_delays(vehicle.wheel_offsets, system.speed)
    if fast:  # as frf_blocks solves a block with the kernels loaded: one fused kernel
        fused = [
            (fb, vehicle.element_stiffness(fb), _receptance_parts(system.track, fb, x, x_obs))
            for fb in blocks
        ]
        program, k_h = vehicle.elimination_program, system.contact_stiffness
        parts["vehicle condensation, coupled solve and recovery (fused kernel)"] = timed(
            lambda: [fused_points(program, fb, ke, r, s, k_h, delays) for fb, ke, (r, s) in fused],
            repeat,
        )[0]
        report(parts, total_time)
        return
    parts["vehicle condensation"] = timed(
        lambda: [vehicle.condensed_to_wheels(fb) for fb in blocks], repeat
    )[0]
    inputs = [
        (
            vehicle.condensed_to_wheels(fb),
            system.track.receptance(fb, x, x),
            excitation_vector(fb, delays)[..., None],
        )
        for fb in blocks
    ]
    k_h = system.contact_stiffness
    parts["coupled solve"] = timed(
        lambda: [coupled_response(c, r, k_h, v) for c, r, v in inputs], repeat
    )[0]
    report(parts, total_time)


def report(parts, total_time):
    """Print the parts of a run and the rest of its time (CPU ms, share of the run)."""
    rest = max(total_time - sum(parts.values()), 0)
    print(
        "   breakdown (CPU, min of each): "
        + ", ".join(
            f"{k} {t * 1e3:.1f} ms ({100 * t / total_time:.0f} %)" for k, t in parts.items()
        )
        + f"; the rest (excitation, PSDs, dataset, support forces, contact check) "
        f"{rest * 1e3:.1f} ms"
    )


def _million(n, kind, mode, repeat):
    """`repeat` fresh processes of the MILLION script: their JSON lines."""
    runs = []
    for _ in range(repeat):
        out = subprocess.run(
            [sys.executable, "-c", MILLION, str(n), kind, mode],
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        runs.append(json.loads(out.strip().splitlines()[-1]))
    return runs


def _figures(runs):
    cpu = [r["cpu"] for r in runs]
    wall = [r["t"] for r in runs]
    rss = max(r["rss"] for r in runs)
    return (
        cpu,
        wall,
        rss,
        (
            f"CPU min {min(cpu):.2f} s, median {statistics.median(cpu):.2f} s (wall min "
            f"{min(wall):.2f} s, median {statistics.median(wall):.2f} s), peak RSS "
            f"{rss / 1e6:.0f} MB (largest)"
        ),
    )


def goal_two(repeat, n=1_000_000):
    """Goal 2: `repeat` fresh processes per path and mode, each one run after a warm-up.

    Streamed to results.nc block by block (``railvib.solve.stream_to_netcdf``, what
    ``railvib run`` does above ``STREAM_FREQUENCIES``; the writes counted): PASS/FAIL.
    Held in memory (``run_system``, a 608 MB dataset at 10^6): printed beside it.
    """
    # as a user's single run gets it (NumPy: a run never loads numba itself), then in a
    # process that has loaded the compiled kernel, where numba is installed; a fresh process
    # each time, so that its peak memory is this run's
    kinds = ["numpy"] + (["compiled"] if importlib.util.find_spec("numba") else [])
    for kind in kinds:
        streamed = _million(n, kind, "streamed", repeat)
        held = _million(n, kind, "held", repeat)
        cpu, _, rss, text = _figures(streamed)
        ok = statistics.median(cpu) <= 2.0 and rss <= 500e6
        r = streamed[0]
        path = "compiled kernel (loaded first)" if r["compiled"] else "NumPy kernels"
        print(
            f"2. {r['n']:,} frequencies, {repeat} fresh processes per mode (each one run "
            f"after a warm-up), {path}"
        )
        print(
            f"   streamed to results.nc ({r['file'] / 1e6:.0f} MB): {text}   goal <= 2 s "
            f"and <= 500 MB: {verdict(ok)}"
        )
        print(f"   held in memory: {_figures(held)[3]}")
        print(
            "   the warm-up (8192 frequencies, the same call: the process's one-off costs, "
            f"numba's load of the fused kernel, the netCDF writer's imports) CPU median: "
            f"streamed {statistics.median(q['first'] for q in streamed):.2f} s, held "
            f"{statistics.median(q['first'] for q in held):.2f} s"
        )
        beyond = max(q["rss"] - q["before"] - q["result"] for q in held)
        print(
            f"   of the peak: the process before the run {r['before'] / 1e6:.0f} MB; held: the "
            f"result dataset {held[0]['result'] / 1e6:.0f} MB and the run's working memory "
            f"beyond both {beyond / 1e6:.0f} MB; streamed: "
            f"{max(q['rss'] - q['before'] for q in streamed) / 1e6:.0f} MB beyond the process"
        )


def honest_finite(system, repeat):
    track = system.track
    x = system.wheel_positions
    grid = railvib.FrequencyGrid.linear(0.5, 1000.0, 0.1)
    subset = grid.f[:: len(grid) // 40][:40]
    rec = track.receptance(subset, x, x)
    ref_scale = np.abs(rec).max(axis=(1, 2), keepdims=True)
    per_freq_sym = timed(lambda: track.receptance(grid.f, x, x), repeat)[0] / len(grid)
    per_freq_case = timed(lambda: system.frf(grid.f), repeat)[0] / len(grid)
    best = None
    print(f"4. finite track at equal accuracy ({EQUAL_ACCURACY:g} of the largest receptance)")
    for n, e, a in FINITE_LADDER:
        model = FiniteTrack.around(
            x,
            track.rail,
            track.pad,
            track.sleeper_spacing,
            margin_spans=n,
            elements_per_span=e,
            absorber_spans=a,
            absorber_damping=40.0 * 5.0e4 if a else 0.0,
        )
        t0 = time.perf_counter()
        fin = model.receptance(subset, x, x)
        first = (time.perf_counter() - t0) / subset.size
        err = float(np.max(np.abs(fin - rec) / ref_scale))
        if err <= EQUAL_ACCURACY and (best is None or first < 3 * best[2]):
            lo = timed(lambda m=model: m.receptance(subset, x, x), max(1, repeat // 5))[0]
            per = lo / subset.size
            if best is None or per < best[2]:
                best = (n, e, a, per, err)
        print(
            f"   {n:3d} bays beyond the wheels x {e:2d} elements, {a:3d} absorbing: "
            f"error {err:.1e}, {first * 1e3:6.2f} ms/frequency"
        )
    if best is None:
        print("   no finite model of the ladder reaches it")
        return
    n, e, a, per, err = best
    print(
        f"   cheapest at equal accuracy: {n} bays beyond the wheels x {e} elements "
        f"({a} absorbing), error {err:.1e}, "
        f"{per * 1e3:.2f} ms/frequency (min of repeats)"
    )
    print(
        f"   symplectic receptance {per_freq_sym * 1e6:.1f} us/frequency, whole case "
        f"{per_freq_case * 1e6:.1f} us/frequency"
    )
    print(
        f"   ratio finite / symplectic at equal accuracy: {per / per_freq_sym:,.0f}x "
        f"(receptance against receptance), {per / per_freq_case:,.0f}x (against the whole case)"
    )


def slab_ratio(repeat):
    """Ballasted and floating-slab cases against the rigid-base case, each path on both sides.

    The issue's goal is on the **case**: ``run_system`` of each preset on the default case's
    grid (0.5-1000 Hz, 0.1 Hz, 9996 frequencies; every case's own spectrum), CPU time of
    interleaved runs, the ratio of the minima printed with PASS/FAIL. NumPy (what a single
    ``railvib run`` uses: it never loads numba) is compared with NumPy, and the compiled
    kernels (loaded first, as in a sweep worker) with the compiled kernels. For information,
    the track receptance between the wheels alone (``track.receptance``): there the
    rigid base runs on its NumPy entry kernel on both paths (its compiled kernel serves the
    coupled run only), so that compiled ratio is against NumPy's rigid base.
    """
    grid = railvib.FrequencyGrid.linear(0.5, 1000.0, 0.1)
    f = grid.f
    cases = {
        "rigid_base": railvib.load_preset_case(),
        "ballasted": railvib.load_preset_case("thompson_ballasted"),
        "floating_slab": railvib.load_preset_case("floating_slab_metro"),
    }
    systems = {name: railvib.build_system(case) for name, case in cases.items()}
    spectra = {name: build_spectrum(case) for name, case in cases.items()}
    saved = os.environ.get("RAILVIB_COMPILED")
    for label, setting in (("NumPy (a single run)", "0"), ("compiled (loaded)", "1")):
        os.environ["RAILVIB_COMPILED"] = setting
        jobs = {
            "case": lambda name: railvib.run_system(systems[name], grid, spectra[name]),
            "receptance": lambda name: systems[name].track.receptance(
                f, systems[name].wheel_positions, systems[name].wheel_positions
            ),
        }
        print(f"  {label}, load {os.getloadavg()[0]:.1f}:")
        for what, job in jobs.items():
            times = {name: [] for name in systems}
            for name in systems:
                job(name)  # warm-up
            for _ in range(repeat):  # interleaved: the same load for each track
                for name in systems:
                    t0 = time.process_time()
                    job(name)
                    times[name].append(time.process_time() - t0)
            for name, values in times.items():
                print(
                    f"    {name:14s} {what} at {f.size} frequencies: CPU min "
                    f"{min(values) * 1e3:.0f} ms, median {statistics.median(values) * 1e3:.0f} ms"
                )
            base = min(times["rigid_base"])
            for name, goal in (("ballasted", 1.5), ("floating_slab", 4.0)):
                ratio = min(times[name]) / base
                if what == "case":
                    text = f"(goal <= {goal:g}x) {verdict(ratio <= goal)}"
                else:
                    text = "(information: the rigid base on NumPy's entry kernel)"
                print(f"    {name} / rigid base, {what} (min): {ratio:.1f}x {text}")
    if saved is None:
        os.environ.pop("RAILVIB_COMPILED")
    else:
        os.environ["RAILVIB_COMPILED"] = saved


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=15)
    parser.add_argument("--skip-million", action="store_true")
    parser.add_argument(
        "--million-repeat", type=int, default=3, help="fresh processes per path for goal 2"
    )
    parser.add_argument("--skip-finite", action="store_true")
    parser.add_argument("--skip-slab", action="store_true")
    args = parser.parse_args()
    case = railvib.load_preset_case()
    system = railvib.build_system(case)
    spectrum = build_spectrum(case)
    print(f"railvib from {os.path.dirname(railvib.__file__)}, load {os.getloadavg()[0]:.1f}")
    goal_one(system, spectrum, args.repeat)
    if not args.skip_million:
        goal_two(args.million_repeat)
    if not args.skip_finite:
        honest_finite(system, args.repeat)
    if not args.skip_slab:
        slab_ratio(max(3, args.repeat // 3))


if __name__ == "__main__":
    main()
