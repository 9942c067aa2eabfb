"""``railvib run`` draws its figures in forked children (issue 13, the CLI's wall time).

The work of :meth:`railvib.io.StagedFolder.background` must give what the same work gives
in the process itself: its value, its exception (raised in the parent, as the CLI's one
line), nothing left behind when the run fails, is interrupted or is killed.
"""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import pytest

import railvib.io as rio
from railvib.errors import OutputError
from railvib.io import Background, staged_folder


@pytest.fixture
def forking(monkeypatch):
    """Fork even where the test runner has threads of its own (the guard is tested below)."""
    monkeypatch.setattr(rio, "_can_fork", lambda: True)


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with open(f"/proc/{pid}/stat") as stat:  # a zombie is not alive
        return stat.read().split(") ")[1][0] != "Z"


def _in_child(parent):
    return os.getpid() != parent


pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forks on Linux")


def test_value_comes_back_from_the_child(forking):
    parent = os.getpid()
    work = Background(lambda: (os.getpid() != parent, [1.5, "x"]))
    assert work.forked
    assert work.result() == (True, [1.5, "x"])  # computed in another process


def test_exception_of_the_child_is_raised_in_the_parent(forking, tmp_path):
    def fail():
        raise OutputError(tmp_path / "a.png", "No space left on device", 28)

    work = Background(fail)
    with pytest.raises(OutputError) as caught:
        work.result()
    assert str(caught.value) == f"cannot write {tmp_path / 'a.png'}: No space left on device"
    assert caught.value.errno == 28


def test_a_child_killed_without_a_word_is_replaced_by_the_work_here(forking):
    parent = os.getpid()

    def work():
        if _in_child(parent):
            os.kill(os.getpid(), signal.SIGKILL)  # as the out-of-memory killer would
        return os.getpid()

    assert Background(work).result() == parent


def test_without_a_fork_the_work_runs_here_when_asked(monkeypatch):
    monkeypatch.setenv(rio.BACKGROUND_ENV, "0")
    calls = []
    work = Background(lambda: calls.append(os.getpid()) or "done")
    assert not work.forked
    assert calls == []  # not yet: the caller's other work comes first, as before
    assert work.result() == "done"
    assert calls == [os.getpid()]


def test_no_fork_beside_another_thread_or_when_switched_off(monkeypatch):
    monkeypatch.setenv(rio.BACKGROUND_ENV, "1")
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1})
    assert rio._can_fork() == (threading.active_count() == 1)
    stop = threading.Event()
    thread = threading.Thread(target=stop.wait)
    thread.start()
    try:
        assert not rio._can_fork()  # a lock held by that thread would stay held in a child
    finally:
        stop.set()
        thread.join()
    monkeypatch.setattr(threading, "active_count", lambda: 1)
    assert rio._can_fork()
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0})
    assert not rio._can_fork()  # one CPU: nothing to gain
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1})
    monkeypatch.setenv(rio.BACKGROUND_ENV, "0")
    assert not rio._can_fork()


@pytest.mark.parametrize(("load", "forks"), [(0.3, True), (1.5, True), (1.6, False), (9.0, False)])
def test_unless_asked_a_child_is_forked_only_while_a_cpu_is_idle(monkeypatch, load, forks):
    monkeypatch.delenv(rio.BACKGROUND_ENV, raising=False)
    monkeypatch.setattr(threading, "active_count", lambda: 1)
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1})
    monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load))
    assert rio._can_fork() is forks  # 2 CPUs: a fork at a load of 1.5 or less
    monkeypatch.setenv(rio.BACKGROUND_ENV, "1")
    assert rio._can_fork()  # asked for: whatever the load


def test_cancel_stops_the_child(forking):
    work = Background(time.sleep, 60)
    pid = work._pid
    start = time.monotonic()
    work.cancel()
    assert time.monotonic() - start < 5  # not the child's 60 s
    assert not _alive(pid)


def test_a_failing_block_stops_its_background_work_before_removing_the_stage(forking, tmp_path):
    out = tmp_path / "out"
    pids = []

    def late_file(folder):
        time.sleep(0.5)
        (folder / "late.png").write_text("x")

    def failing_run():
        with staged_folder(out) as stage:
            pids.append(stage.background(late_file, stage.path)._pid)
            raise RuntimeError("netCDF failed")

    with pytest.raises(RuntimeError, match="netCDF failed"):
        failing_run()
    time.sleep(0.8)  # past the moment the child would have written
    assert not _alive(pids[0])
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []  # nor a staging folder, nor a late file


@pytest.mark.slow  # a subprocess: ~1.5 s
def test_the_child_dies_with_its_parent(tmp_path):
    script = textwrap.dedent(
        """
        import os, signal, sys, time
        import railvib.io as rio
        rio._can_fork = lambda: True
        work = rio.Background(time.sleep, 60)
        print(work._pid, flush=True)
        os.kill(os.getpid(), signal.SIGKILL)
        """
    )
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert proc.returncode == -signal.SIGKILL
    child = int(proc.stdout)
    deadline = time.monotonic() + 10
    while _alive(child):  # reaped by init once it died with its parent
        assert time.monotonic() < deadline, "the child outlived its parent"
        time.sleep(0.05)
