"""Benchmark: how long a new user waits. ``import railvib``, ``railvib --help``, ``railvib run``.

Run: ``python3 benchmarks/bench_startup.py [--repeat N] [--strict] [--cost]``.

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
        if args.cost:
            per_byte, per_s = _cost(work)
            print(f"cost per frequency: {per_byte:,.0f} B peak memory, {per_s * 1e6:.1f} us wall")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if (missed and args.strict) else 0


if __name__ == "__main__":
    sys.exit(main())
