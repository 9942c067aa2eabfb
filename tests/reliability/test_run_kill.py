"""``railvib run`` and ``reproduce`` killed with SIGKILL at any moment (issue 11, part A).

Before, a run killed in a folder holding an earlier run's results left a mix (the new
``results.nc`` beside the old summary and figures) and hidden ``.NAME.XXXX.part``
files that no later run removed. Now the folder holds either the earlier complete set
or the new one, and the next run removes what the killed one left.
"""

import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

from railvib.reproduce import reproduce_files
from railvib.solve import run_to_folder
from tests.reliability.files_support import hidden, snapshot, write_case


def _start(*args):
    return subprocess.Popen(
        [sys.executable, "-m", "railvib.cli.main", *map(str, args)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )


def _stages(out):
    return sorted(out.parent.glob(f".{out.name}.*.part"))


def _kill_when(proc, ready, timeout=60.0):
    """SIGKILL `proc` as soon as `ready()` holds (or it ended); True if it was killed."""
    deadline = time.monotonic() + timeout
    while not ready():
        if proc.poll() is not None:
            break
        assert time.monotonic() < deadline, "the moment to kill never came"
        time.sleep(0.001)
    killed = proc.poll() is None
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    err = proc.stderr.read().decode()
    proc.stderr.close()
    if not killed:
        assert proc.returncode == 0, err
    return killed


def _after(seconds):
    """A moment `seconds` after its first look (just after the process started)."""
    start = []

    def ready():
        start[:] = start or [time.monotonic()]
        return time.monotonic() - start[0] >= seconds

    return ready


def _title(out):
    try:
        return (out / "summary.md").read_bytes().split(b"\n")[0]
    except OSError:  # between the two renames where the system has no exchange
        return b""


def _staged(out, pattern, count=1):
    return lambda: any(len(list(s.glob(pattern))) >= count for s in _stages(out))


@pytest.mark.slow  # nine killed runs and three complete ones: ~30 s
def test_sigkill_of_run_leaves_the_old_or_the_new_complete_set(tmp_path):
    a, b = write_case(tmp_path / "a.toml", "A", 80.0), write_case(tmp_path / "b.toml", "B", 120.0)
    run_to_folder(a, tmp_path / "ref_a")
    run_to_folder(b, tmp_path / "ref_b")
    old, new = snapshot(tmp_path / "ref_a"), snapshot(tmp_path / "ref_b")
    assert old != new
    assert set(old) == set(new)
    out = tmp_path / "out"
    moments = {  # the last one leaves a staging folder for the complete run to remove
        **{f"{s} s after start": _after(s) for s in (0.3, 1.2, 2.2, 3.0, 3.6)},
        "swapped in": lambda: _title(out) == b"# B",  # before the earlier set is removed
        "staging folder made": lambda: bool(_stages(out)),
        "results.nc staged": _staged(out, "results.nc"),
        "four figures staged": _staged(out, "*.png", 4),
    }
    outcome = {}
    for moment, ready in moments.items():
        shutil.rmtree(out, ignore_errors=True)
        shutil.copytree(tmp_path / "ref_a", out)
        killed = _kill_when(_start("run", b, "-o", out), ready)
        state = snapshot(out)
        assert state in (old, new), f"killed at {moment}: a mix of the two runs"
        outcome[moment] = ("old" if state == old else "new") + ("" if killed else " (ended)")
    print(outcome)  # which moments fell before and after the swap, for the record
    for moment in ("staging folder made", "results.nc staged", "four figures staged"):
        assert outcome[moment] == "old", outcome  # killed before the swap
    assert outcome["swapped in"].startswith("new"), outcome

    assert len(_stages(out)) == 1  # each run removed the one killed before it
    done = subprocess.run(
        [sys.executable, "-m", "railvib.cli.main", "run", str(b), "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert snapshot(out) == new
    assert hidden(tmp_path) == []  # the killed run's staging folder is gone


@pytest.mark.slow  # three killed runs and two complete ones: ~9 s
def test_sigkill_of_run_in_a_folder_with_user_files_keeps_them_and_the_old_set(tmp_path):
    a, b = write_case(tmp_path / "a.toml", "A", 80.0), write_case(tmp_path / "b.toml", "B", 120.0)
    out = tmp_path / "out"
    run_to_folder(a, out)
    (out / "notes.txt").write_text("mine")
    (out / "a.toml").write_bytes(a.read_bytes())
    before = snapshot(out)
    for ready in (lambda: bool(_stages(out)), _staged(out, "results.nc"), _staged(out, "*.png", 6)):
        assert _kill_when(_start("run", b, "-o", out), ready)
        assert snapshot(out) == before
    assert _stages(out)
    assert _kill_when(_start("run", b, "-o", out, "--no-plots"), lambda: False) is False
    after = snapshot(out)
    assert after["notes.txt"] == b"mine"
    assert after["a.toml"] == a.read_bytes()
    assert after["summary.md"].startswith(b"# B\n")
    assert not any(name.endswith(".png") for name in after)  # A's figures: not B's set
    assert hidden(tmp_path) == []


@pytest.mark.slow  # two killed reproductions and a complete one: ~15 s
def test_sigkill_of_reproduce_leaves_nothing_and_the_next_one_cleans_up(tmp_path):
    out = tmp_path / "study"
    for ready in (_staged(out, "cases/*.toml"), _staged(out, "fig*.png", 3)):
        assert _kill_when(_start("reproduce", "--quiet", "-o", out), ready)
        assert not out.exists()
    assert len(_stages(out)) == 1  # SIGKILL leaves its staging folder; the next run removed it
    assert _kill_when(_start("reproduce", "--quiet", "-o", out), lambda: False) is False
    assert set(snapshot(out)) == set(reproduce_files())
    assert hidden(tmp_path) == []
