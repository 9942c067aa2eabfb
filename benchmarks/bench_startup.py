"""Benchmark: how long a new user waits. ``import railvib``, ``railvib --help``, ``railvib run``.

Run: ``python3 benchmarks/bench_startup.py [--repeat N] [--strict] [--cost] [--stages]``.

Each figure is the wall time of a fresh Python process (what a user waits for), after one
warm-up run (so the OS file cache is warm, as on a second try), as min and median of
`--repeat` runs, with PASS/FAIL against the goal of issue 10:

* ``import railvib`` <= 0.3 s;
* ``railvib --help`` <= 0.3 s;
* ``railvib run`` of the template case (``railvib template``, 9,996 frequencies) <= 1.5 s,
  writing everything it writes (results.nc, two PSD CSVs, summary.csv/.md, four PNGs) into
  a fresh folder each time.

For information (no goal): ``import railvib`` followed by the first use of the facade
(``railvib.run``), which loads the numerical stack; and ``railvib run --no-plots``.

``--stages`` also prints where the time of ``railvib run`` goes: each stage of the run
(imports, compute, results.nc, each CSV, each PNG) timed in one process with the figures
drawn in it (``RAILVIB_BACKGROUND=0``, so that each stage is timed alone), min of
`--repeat` fresh processes, wall and CPU; then the CPU of the run's own process and of
its figure processes in the normal run (the figures drawn beside the writes).

``--cost`` also measures the cost per frequency of ``railvib run`` (peak memory and wall
time, from two grid sizes so fixed costs cancel), the figures behind
``railvib.case.plausibility.BYTES_PER_FREQUENCY`` and ``SECONDS_PER_FREQUENCY``.

The CLI is started as the ``railvib`` console script does (``from railvib.cli.main import
main``), so an editable install and ``PYTHONPATH=src`` measure the same thing. The exit
status is 0 unless ``--strict`` is given and a goal is missed.
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CLI = "import sys; from railvib.cli.main import main; sys.exit(main(sys.argv[1:]))"


#: the children run in a scratch folder: PYTHONPATH=src must still mean this checkout's src
ENV = {
    **os.environ,
    "PYTHONPATH": os.pathsep.join(
        str(Path(p).resolve()) for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p
    ),
}


def _wall(argv, cwd, before=None):
    if before is not None:
        before()
    t = time.perf_counter()
    subprocess.run(
        argv, cwd=cwd, env=ENV, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )
    return time.perf_counter() - t


def measure(argv, cwd, repeat, before=None):
    """(min, median) wall seconds of `argv` in fresh processes, after one warm-up."""
    _wall(argv, cwd, before)
    times = [_wall(argv, cwd, before) for _ in range(repeat)]
    return min(times), statistics.median(times)


#: one ``railvib run`` (through the CLI's main) with each stage timed; prints JSON rows
STAGES = r"""
import json, os, sys, time
rows = []
def now():
    return time.perf_counter(), time.process_time()
def mark(name, t):
    w, c = now()
    rows.append([name, w - t[0], c - t[1]])
t = now()
import railvib.cli.main
import railvib.cli.run
mark("import: the CLI and the run command (numpy, pandas, xarray, scipy, railvib)", t)
t = now()
import railvib.plot.criteria, railvib.plot.psd
mark("import: matplotlib and railvib.plot", t)
import railvib.solve as solve
def timed(module, name, label):
    inner = getattr(module, name)
    def call(*args, **kwargs):
        t = now()
        out = inner(*args, **kwargs)
        mark(label(args), t)
        return out
    setattr(module, name, call)
base = lambda args: os.path.basename(str(args[1]))
timed(solve, "load_case", lambda a: "load_case")
timed(solve, "run_system", lambda a: "compute: run_system")
timed(solve, "save_netcdf", lambda a: "write results.nc")
timed(solve, "save_csv", lambda a: "write " + base(a))
timed(solve, "write_text", lambda a: "write " + os.path.basename(str(a[0])))
timed(solve, "summary", lambda a: "summary statistics")
for module in (railvib.plot.psd, railvib.plot.criteria):
    timed(module, "save_figure", lambda a: "figure " + base(a))
t = now()
code = railvib.cli.main.main(["run", sys.argv[1], "-o", sys.argv[2]])
mark("the run command in all", t)
print(json.dumps(rows))
"""

#: the normal run: CPU of the process and of its children (the figure processes)
FORKED = r"""
import json, resource, sys, time
from railvib.cli.main import main
main(["run", sys.argv[1], "-o", sys.argv[2]])
own = resource.getrusage(resource.RUSAGE_SELF)
kids = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps([own.ru_utime + own.ru_stime, kids.ru_utime + kids.ru_stime]))
"""


def _stages(cwd, repeat):
    """Print the stages of ``railvib run`` (min over `repeat` fresh processes)."""
    out = Path(cwd) / "stages"
    best = {}
    for k in range(repeat + 1):
        shutil.rmtree(out, ignore_errors=True)
        text = subprocess.run(
            [sys.executable, "-c", STAGES, "case.toml", str(out)],
            cwd=cwd,
            env={**ENV, "RAILVIB_BACKGROUND": "0"},
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        for name, wall, cpu in json.loads(text.strip().splitlines()[-1]):
            if k:  # after a warm-up
                old = best.get(name, (float("inf"), float("inf")))
                best[name] = (min(old[0], wall), min(old[1], cpu))
    print(f"stages of railvib run, figures drawn in its process (min of {repeat}):")
    print(f"  {'stage':72s} {'wall':>8s} {'CPU':>8s}")
    for name, (wall, cpu) in best.items():
        print(f"  {name:72s} {wall * 1e3:6.0f}ms {cpu * 1e3:6.0f}ms")
    rows = []
    for _ in range(repeat):
        shutil.rmtree(out, ignore_errors=True)
        text = subprocess.run(
            [sys.executable, "-c", FORKED, "case.toml", str(out)],
            cwd=cwd,
            env=ENV,
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        rows.append(json.loads(text.strip().splitlines()[-1]))
    own, kids = (statistics.median(r[i] for r in rows) for i in (0, 1))
    print(f"normal run (median of {repeat}): CPU {own:.2f} s in the run's process,")
    print(f"  {kids:.2f} s in its figure processes (0 where it draws them itself)")


def _cost(cwd):
    """Peak memory (B) and wall time (s) per frequency of ``railvib run`` (two grid sizes)."""
    probe = (
        "import json, resource, sys, time\n"
        "from railvib.solve import run_to_folder\n"
        "from railvib.case import case_from_dict\n"
        "n = int(sys.argv[1]); step = 999.5 / (n - 1)\n"
        "case = case_from_dict({'preset': 'wang2017_metro', 'frequency': {'step': step}})\n"
        "t = time.perf_counter(); run_to_folder(case, sys.argv[2]); t = time.perf_counter() - t\n"
        "rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024\n"
        "print(json.dumps({'n': n, 't': t, 'rss': rss}))\n"
    )
    rows = []
    for n in (100_000, 300_000):
        out = subprocess.run(
            [sys.executable, "-c", probe, str(n), str(Path(cwd) / f"cost{n}")],
            cwd=cwd,
            env=ENV,
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        rows.append(json.loads(out.strip().splitlines()[-1]))
    a, b = rows
    dn = b["n"] - a["n"]
    return (b["rss"] - a["rss"]) / dn, (b["t"] - a["t"]) / dn


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="timed runs per figure")
    parser.add_argument("--strict", action="store_true", help="exit 1 if a goal is missed")
    parser.add_argument("--cost", action="store_true", help="also the cost per frequency")
    parser.add_argument("--stages", action="store_true", help="also the stages of railvib run")
    args = parser.parse_args()
    py = sys.executable
    work = Path(tempfile.mkdtemp(prefix="railvib-bench-"))
    try:
        template = subprocess.run(
            [py, "-c", CLI, "template"], env=ENV, check=True, capture_output=True, text=True
        ).stdout
        (work / "case.toml").write_text(template)
        out = work / "out"

        def fresh_output():
            shutil.rmtree(out, ignore_errors=True)

        rows = [
            ("import railvib", [py, "-c", "import railvib"], 0.3, None),
            ("railvib --help", [py, "-c", CLI, "--help"], 0.3, None),
            (
                "railvib run template",
                [py, "-c", CLI, "run", "case.toml", "-o", "out"],
                1.5,
                fresh_output,
            ),
            (
                "import railvib; railvib.run (full load)",
                [py, "-c", "import railvib; railvib.run"],
                None,
                None,
            ),
            (
                "railvib run template --no-plots",
                [py, "-c", CLI, "run", "case.toml", "-o", "out", "--no-plots"],
                None,
                fresh_output,
            ),
        ]
        import railvib  # which checkout is measured

        print(f"railvib from {Path(railvib.__file__).parent}")
        load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
        print(
            f"python {sys.version.split()[0]}, {os.cpu_count()} CPUs, load {load:.1f}, "
            f"{args.repeat} repeats"
        )
        print(f"{'':42s} {'min':>7s} {'median':>7s} {'goal':>6s}")
        missed = False
        for name, argv, goal, before in rows:
            lo, med = measure(argv, work, args.repeat, before)
            if goal is None:
                verdict, goal_text = "", ""
            else:
                ok = med <= goal
                missed |= not ok
                verdict, goal_text = ("PASS" if ok else "FAIL"), f"{goal:.1f} s"
            print(f"{name:42s} {lo:6.3f}s {med:6.3f}s {goal_text:>6s} {verdict}", flush=True)
            if name == "railvib run template":
                written = sorted(p.name for p in out.iterdir())
        print(f"(railvib run template wrote {len(written)} files: {', '.join(written)})")
        if args.stages:
            _stages(work, args.repeat)
        if args.cost:
            per_byte, per_s = _cost(work)
            print(f"cost per frequency: {per_byte:,.0f} B peak memory, {per_s * 1e6:.1f} us wall")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if (missed and args.strict) else 0


if __name__ == "__main__":
    sys.exit(main())
