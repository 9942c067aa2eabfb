"""Run every benchmark script in this folder: ``python3 benchmarks/run_all.py``.

Each script prints its goals as PASS/FAIL; the sweep benchmark runs all its sweeps
(the speed sweep, the structural 1000-case sweeps of pads and of rail x vehicle, the
10^4-case sweep).
"""

import subprocess
import sys
from pathlib import Path

#: arguments each script runs with here (all its goals)
ARGS = {"bench_sweep.py": ["--structural", "--rail-vehicle", "--large"]}

here = Path(__file__).resolve().parent
failed = []
for script in sorted(here.glob("bench_*.py")):
    print(f"== {script.name}", flush=True)
    if subprocess.run([sys.executable, str(script), *ARGS.get(script.name, [])]).returncode:
        failed.append(script.name)
if failed:
    print(f"== scripts that failed: {', '.join(failed)}")
sys.exit(1 if failed else 0)
