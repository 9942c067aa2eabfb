"""`railvib sweep` under faults: damaged stores, leftovers, bad schedulers, Ctrl-C, kills.

Issue 11, part D. Each fault asserts the documented exit code, one line naming the
field or file, no traceback, and no output left that was not there before (or, for
a damaged store, that exactly the damaged part is computed again). The kill and
interrupt tests run the real command line in a new process group, as a terminal
does, and are marked slow.
"""

import json
import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import tomli_w
import xarray as xr

from railvib.cli.main import main
from railvib.errors import DamagedOutputWarning
from railvib.sweep import ChunkStore, SweepMismatchError, load_sweep, run_sweep, sweep_from_dict
from railvib.sweep import runner as runner_mod
from tests.unit.sweep.sweep_cases import BASE_CASE, assert_recomputed, small_sweep


def _tiny(**over):
    """Three cases of one chunk each, on a 20-frequency grid (a fraction of a second)."""
    d = small_sweep(
        **{
            "chunk_size": 1,
            "variables": ["psd_acceleration"],
            "axes": [{"field": "speed_kmh", "values": [40.0, 80.0, 120.0]}],
            **over,
        }
    )
    d["case"]["frequency"]["n"] = 20
    return d


def _files(folder):
    return sorted(str(p.relative_to(folder)) for p in Path(folder).rglob("*"))


def _one_line(capsys, *needles):
    """The single stderr line of a failed command, which names each of `needles`."""
    captured = capsys.readouterr()
    lines = [line for line in captured.err.splitlines() if line.strip()]
    assert "Traceback" not in captured.err
    assert len(lines) == 1, captured.err
    for needle in needles:
        assert needle in lines[0], lines[0]
    return lines[0]


@pytest.fixture
def sweep_file(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(tomli_w.dumps(_tiny()))
    return path


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """A finished tiny sweep: its spec, folder and the mtimes of its chunk files."""
    spec = sweep_from_dict(_tiny())
    out = tmp_path_factory.mktemp("done") / "out"
    ds = run_sweep(spec, out, workers=1, progress=False)
    return spec, out, ds


def _copy(src, dst):
    subprocess.run(["cp", "-a", str(src), str(dst)], check=True)
    return dst


# ------------------------------------------------------------------- damaged chunks

DAMAGE = [
    pytest.param("truncated", lambda p: p.write_bytes(p.read_bytes()[: p.stat().st_size // 2])),
    pytest.param("empty", lambda p: p.write_bytes(b"")),
    pytest.param("garbage", lambda p: p.write_bytes(b"not a chunk at all")),
    pytest.param("a folder", lambda p: (p.unlink(), p.mkdir())),
    pytest.param("deleted", lambda p: p.unlink()),
    pytest.param(
        "bit flip",
        # one byte flipped in the middle: the file reads, its values (or CRCs) are not as written
        lambda p: p.write_bytes(
            (lambda b: b[: len(b) // 2] + bytes([b[len(b) // 2] ^ 0x01]) + b[len(b) // 2 + 1 :])(
                p.read_bytes()
            )
        ),
    ),
]


def _region_files(out):
    """The Zarr chunk files of the finished store, with their mtimes."""
    zarr_dir = out / "sweep.zarr"
    return {
        str(p.relative_to(zarr_dir)): p.stat().st_mtime_ns
        for p in zarr_dir.rglob("*")
        if p.is_file() and not p.name.startswith(".")
    }


@pytest.mark.parametrize(("how", "damage"), DAMAGE, ids=[d.values[0] for d in DAMAGE])
@pytest.mark.parametrize("part", ["record", "region"])
def test_damaged_chunk_is_named_and_computed_again(
    finished, part, how, damage, tmp_path, monkeypatch
):
    spec, done, reference = finished
    out = _copy(done, tmp_path / "out")
    store = ChunkStore(out, spec)
    kept = {p.name: p.stat().st_mtime_ns for p in store.chunk_dir.iterdir()}
    regions = _region_files(out)
    if part == "record":
        target = store.chunk_path(1)
        # a flipped bit may leave the record readable, with a CRC its region fails
        message = r"chunk record .*chunk-000001\.done is damaged|chunk 1 of .* is damaged"
        if how == "deleted":  # a missing record is a chunk not done: no warning
            message = None
    else:
        # chunk 1 of the speed axis (chunk_size 1): its block of the per-frequency variable
        target = out / "sweep.zarr" / "psd_acceleration" / "0.0.1"
        message = r"chunk 1 of .*sweep\.zarr is damaged \((unreadable|psd_acceleration)"
    damage(target)
    computed = []
    real = runner_mod._compute
    monkeypatch.setattr(runner_mod, "_compute", lambda s, cid: computed.append(cid) or real(s, cid))
    if message is None:
        ds = run_sweep(spec, out, workers=1, progress=False)
    else:
        with pytest.warns(DamagedOutputWarning, match=message) as record:
            ds = run_sweep(spec, out, workers=1, progress=False)
        assert len(record) == 1
    assert computed == [1]  # only the damaged chunk
    for name in ("chunk-000000.done", "chunk-000002.done"):
        assert store.chunk_path(int(name[6:12])).stat().st_mtime_ns == kept[name]
    now = _region_files(out)
    rewritten = {k for k, t in now.items() if regions.get(k) != t}
    assert rewritten, "chunk 1 is written again"
    assert all(k.endswith("1") for k in rewritten), rewritten  # chunk 1's files only
    assert_recomputed(ds, reference)  # the same function on the same chunk


@pytest.mark.filterwarnings("default::railvib.errors.DamagedOutputWarning")
def test_damaged_chunk_is_one_warning_line_on_the_command_line(finished, tmp_path, capsys):
    spec, done, _ = finished
    out = _copy(done, tmp_path / "out")
    ChunkStore(out, spec).chunk_path(2).write_bytes(b"")  # was: "aborted", exit 130
    path = tmp_path / "s.toml"
    path.write_text(tomli_w.dumps(_tiny()))
    assert main(["sweep", str(path), "-o", str(out), "--no-progress", "-j", "1"]) == 0
    err = capsys.readouterr().err
    assert "Traceback" not in err
    warned = [line for line in err.splitlines() if line.startswith("warning:")]
    assert warned == [
        f"warning: chunk record {out}/chunks/chunk-000002.done is damaged (cut short or not a "
        "chunk record); it is computed again"
    ]


# ------------------------------------------------------------------- damaged manifest


@pytest.mark.parametrize(
    ("text", "why"),
    [
        ("", "not valid JSON"),  # emptied by a full disk
        ('{"fingerprint": 12}', "no fingerprint"),
        (b"\xff\xfe\x00garbage", "not UTF-8 text"),
    ],
)
def test_damaged_manifest_is_rewritten_from_the_chunk_stamps(finished, text, why, tmp_path):
    spec, done, reference = finished
    out = _copy(done, tmp_path / "out")
    manifest = out / "manifest.json"
    good = json.loads(manifest.read_text())
    (manifest.write_bytes if isinstance(text, bytes) else manifest.write_text)(text)
    chunks = {p.name: p.stat().st_mtime_ns for p in (out / "chunks").iterdir()}
    with pytest.warns(DamagedOutputWarning, match=rf"manifest\.json is damaged \({why}") as rec:
        ds = run_sweep(spec, out, workers=1, progress=False)
    assert "3 finished chunks of this sweep kept" in str(rec[0].message)
    assert json.loads(manifest.read_text()) == good
    assert {p.name: p.stat().st_mtime_ns for p in (out / "chunks").iterdir()} == chunks
    xr.testing.assert_identical(ds, reference)


def test_damaged_manifest_with_another_sweeps_chunks_says_damaged_not_changed(finished, tmp_path):
    _, done, _ = finished
    out = _copy(done, tmp_path / "out")
    (out / "manifest.json").write_text("garbage{")
    other = sweep_from_dict(_tiny(chunk_size=2))  # same cases, other chunks
    before = _files(out)
    with pytest.raises(SweepMismatchError) as info:
        run_sweep(other, out, workers=1, progress=False)
    message = str(info.value)
    assert message.startswith(f"{out}/manifest.json is damaged (not valid JSON")
    assert "3 of the 3 chunk records" in message
    assert "--overwrite" in message
    assert "changed" not in message  # was: every field "changed"
    assert _files(out) == before
    with pytest.warns(DamagedOutputWarning, match="other sweep are discarded"):
        ds = run_sweep(other, out, workers=1, progress=False, overwrite=True)
    assert ds.sizes["speed_kmh"] == 3


# ------------------------------------------------------------------- leftovers


def test_leftover_temporaries_of_a_killed_run_are_removed_and_nothing_else(finished, tmp_path):
    spec, done, reference = finished
    out = _copy(done, tmp_path / "out")
    zarr_part = out / ".sweep.zarr.k3j_x9q2.part"  # what a killed run leaves
    (zarr_part / "store" / "peak").mkdir(parents=True)
    (zarr_part / "store" / "peak" / "0.0").write_bytes(bytes(100_000))
    ours = [
        zarr_part,
        out / ".manifest.json.abcdefgh.part",  # railvib.io.atomic_path's names
        out / ".sweep.nc.abcdefgh.part",
        out / ".summary.csv.abcdefgh.part",
        out / "chunks" / ".chunk-000001.done.abcdefgh.part",
        out / "chunks" / ".sweep.zarr.abcdefgh.part",  # a store's layout being written
        out / "plots" / ".sweep_peak_carbody_bounce.png.abcdefgh.part",
    ]
    theirs = [out / ".notes.part", out / "keep.part", out / "plots" / ".mine.part"]
    for p in [*ours[1:], *theirs]:
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_bytes(b"half written")
    ds = run_sweep(spec, out, workers=1, progress=False)
    assert not [p for p in ours if p.exists()]
    assert all(p.exists() for p in theirs)
    xr.testing.assert_identical(ds, reference)


# ------------------------------------------------------------------- edits and messages


def test_title_only_edit_of_a_partial_sweep_resumes_with_the_new_title(tmp_path, monkeypatch):
    out = tmp_path / "out"
    run_sweep(sweep_from_dict(_tiny()), out, workers=1, progress=False, assemble=False)
    (out / "chunks" / "chunk-000002.done").unlink()  # cut short: chunk 2 missing
    computed = []
    real = runner_mod._compute
    monkeypatch.setattr(runner_mod, "_compute", lambda s, cid: computed.append(cid) or real(s, cid))
    retitled = sweep_from_dict(_tiny(title="pad study, second try"))
    ds = run_sweep(retitled, out, workers=1, progress=False)  # was: "changed: data files"
    assert computed == [2]
    assert ds.attrs["title"] == "pad study, second try"
    assert json.loads((out / "manifest.json").read_text())["spec"]["title"] == ds.attrs["title"]


def test_a_changed_base_case_names_the_field(finished, tmp_path):
    _, done, _ = finished
    out = _copy(done, tmp_path / "out")
    d = _tiny()
    d["case"]["track"]["pad"]["k0_n_per_m"] = 5.0e7
    with pytest.raises(SweepMismatchError, match=r"changed: base_case \(track\.pad\.k0_n_per_m\)"):
        run_sweep(sweep_from_dict(d), out, workers=1, progress=False)


@pytest.mark.parametrize("base", ["s.toml", "./s.toml", "sub/../s.toml"])
def test_base_pointing_at_the_sweep_file_itself_is_one_line(base, tmp_path, capsys):
    (tmp_path / "sub").mkdir()
    path = tmp_path / "s.toml"
    path.write_text(
        tomli_w.dumps({"base": base, "axes": [{"field": "speed_kmh", "values": [1.0]}]})
    )
    out = tmp_path / "out"
    assert main(["sweep", str(path), "-o", str(out)]) == 2
    line = _one_line(capsys, f"base = {base!r}", "this sweep file itself")
    assert "rail_model" not in line  # was: rail_model = '<missing>': required
    assert not out.exists()


def test_base_pointing_at_another_sweep_file_is_one_line(sweep_file, tmp_path, capsys):
    path = tmp_path / "outer.toml"
    path.write_text(
        tomli_w.dumps({"base": "s.toml", "axes": [{"field": "speed_kmh", "values": [1.0]}]})
    )
    assert main(["sweep", str(path), "-o", str(tmp_path / "out")]) == 2
    _one_line(capsys, "base = 's.toml'", "sweep file")
    assert not (tmp_path / "out").exists()


# ------------------------------------------------------------------- sweep plot


@pytest.mark.parametrize(
    ("options", "needle"),
    [(["--x", "speed_kmh", "--y", "speed_kmh"], "y = 'speed_kmh'"), (["--y", "speed_kmh"], "y = ")],
)
def test_plot_with_the_same_dimension_twice_is_one_line(
    finished, options, needle, tmp_path, capsys
):
    _, done, _ = finished
    out = tmp_path / "plots"
    assert main(["sweep", "plot", str(done), *options, "-o", str(out)]) == 2
    _one_line(capsys, needle)
    assert not out.exists()


@pytest.mark.parametrize("kind", ["empty folder", "chunks only", "manifest file"])
def test_plot_of_a_folder_without_a_sweep_is_one_line(finished, kind, tmp_path, capsys):
    _, done, _ = finished
    target = {
        "empty folder": tmp_path / "nothing",
        "chunks only": done / "chunks",
        "manifest file": done / "manifest.json",
    }[kind]
    target.mkdir(exist_ok=True) if kind == "empty folder" else None
    assert main(["sweep", "plot", str(target), "-o", str(tmp_path / "plots")]) == 2
    _one_line(capsys, f"sweep = '{target}'")
    assert not (tmp_path / "plots").exists()


@pytest.mark.slow  # ~1.1 s: whole commands with their files, kept out of the fast suite
@pytest.mark.filterwarnings("default::railvib.errors.DamagedOutputWarning")
def test_plot_of_a_store_with_missing_zarr_chunks_is_one_line_and_a_rerun_repairs_it(
    finished, sweep_file, tmp_path, capsys
):
    _, done, _ = finished
    out = _copy(done, tmp_path / "out")
    for p in list((out / "sweep.zarr" / "peak").glob("[0-9]*"))[:1]:
        p.unlink()  # Zarr reads the values of a deleted chunk as NaN (was: plotted silently)
    plots = tmp_path / "plots"
    assert main(["sweep", "plot", str(out), "-v", "peak", "-o", str(plots)]) == 2
    line = _one_line(capsys, f"sweep = '{out / 'sweep.zarr'}'")
    assert "peak has 14 of 42 values missing" in line  # one of 3 cases, 14 responses each
    assert "rerun the same" in line
    assert not plots.exists()
    # the advice holds: the same sweep command finds the damaged chunk and computes it again
    assert main(["sweep", str(sweep_file), "-o", str(out)]) == 0
    warned = [line for line in capsys.readouterr().err.splitlines() if "warning:" in line]
    assert len(warned) == 1
    assert "is damaged (peak); it is computed again" in warned[0]
    assert main(["sweep", "plot", str(out), "-v", "peak", "-o", str(plots)]) == 0


# ------------------------------------------------------------------- --scheduler

MALFORMED = [
    "foo",
    "tcp:/host:8786",
    "http://host:8786",
    "tcp://host",
    "tcp://host:99999",
    "tcp://host:8786/path",
    "",
    "tcp://:8786",
]


@pytest.mark.parametrize("address", MALFORMED)
def test_malformed_scheduler_is_one_line_before_any_work(address, sweep_file, tmp_path, capsys):
    out = tmp_path / "out"
    before = _files(tmp_path)
    assert main(["sweep", str(sweep_file), "-o", str(out), "--scheduler", address]) == 2
    line = _one_line(capsys, f"scheduler = {address!r}", "--scheduler", "tcp://")
    assert line.startswith("error: ")
    assert _files(tmp_path) == before


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]  # closed again: nothing listens there


class _FakeServer:
    """A TCP server on 127.0.0.1 that is not a Dask scheduler: answers garbage, or nothing."""

    def __init__(self, reply):
        self.sock = socket.create_server(("127.0.0.1", 0))
        self.port = self.sock.getsockname()[1]
        self.reply = reply
        self.conns = []
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self):
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            self.conns.append(conn)
            if self.reply:
                conn.sendall(self.reply)

    def close(self):
        for c in self.conns:
            c.close()
        self.sock.close()


@pytest.mark.parametrize("scheme", ["tcp://", ""])
def test_refused_scheduler_is_one_line_at_once(scheme, sweep_file, tmp_path, capsys):
    pytest.importorskip("distributed")
    address = f"{scheme}127.0.0.1:{_free_port()}"
    out = tmp_path / "out"
    t0 = time.monotonic()
    assert main(["sweep", str(sweep_file), "-o", str(out), "--scheduler", address]) == 2
    assert time.monotonic() - t0 < 10  # was: OSError after 30 s; a refusal needs no timeout
    line = _one_line(capsys, f"cannot reach the Dask scheduler at {address}", "refused")
    assert "--scheduler-timeout" in line
    assert not out.exists()


def test_a_server_that_is_not_dask_is_one_line(sweep_file, tmp_path, capsys):
    pytest.importorskip("distributed")
    server = _FakeServer(b"HTTP/1.1 400 Bad Request\r\n\r\n" * 8)
    try:
        address = f"tcp://127.0.0.1:{server.port}"
        assert (
            main(["sweep", str(sweep_file), "-o", str(tmp_path / "out"), "--scheduler", address])
            == 2
        )
    finally:
        server.close()
    _one_line(capsys, f"cannot reach the Dask scheduler at {address}", "not a Dask scheduler")
    assert not (tmp_path / "out").exists()


@pytest.mark.slow  # waits for the timeout: ~2 s
def test_a_silent_server_times_out_after_scheduler_timeout(sweep_file, tmp_path, capsys):
    pytest.importorskip("distributed")
    server = _FakeServer(b"")  # accepts, never answers: Dask's own client would hang
    try:
        address = f"127.0.0.1:{server.port}"
        args = ["sweep", str(sweep_file), "-o", str(tmp_path / "out"), "--scheduler", address]
        t0 = time.monotonic()
        assert main([*args, "--scheduler-timeout", "1"]) == 2
        elapsed = time.monotonic() - t0
    finally:
        server.close()
    assert elapsed < 8  # 1 s to wait, the rest is start-up (imports) on a loaded machine
    _one_line(capsys, f"cannot reach the Dask scheduler at {address} within 1 s", "does not answer")
    assert not (tmp_path / "out").exists()


# ------------------------------------------------------------------- start-up and exit


def _python(code, *args):
    return subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, timeout=60
    )


def test_ctrl_c_while_the_command_line_imports_is_aborted_exit_130():
    # the signal lands before main() runs (in a terminal: the first ~0.1 s)
    done = _python(
        "import os, signal, time\n"
        "import railvib.cli.main\n"
        "os.kill(os.getpid(), signal.SIGINT)\n"
        "time.sleep(5)\n"
    )
    assert done.returncode == 130
    assert done.stderr.split() == ["aborted"], done.stderr


def test_ctrl_c_after_the_command_has_ended_keeps_its_exit_code():
    # the interpreter only shuts down then; a signal must not turn 0 into 130 or -2
    done = _python(
        "import os, signal, sys, time\n"
        "from railvib.cli.main import main\n"
        "code = main()\n"
        "os.kill(os.getpid(), signal.SIGINT)\n"
        "time.sleep(0.2)\n"
        "sys.exit(code)\n",
        "presets",
    )
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr


# ------------------------------------------------------------------- processes, slow

#: a sweep long enough to be mid-run at every signal time below (120 chunks, 2 workers)
LONG = {
    "title": "long",
    "chunk_size": 1,
    "variables": ["psd_acceleration"],
    "case": {**BASE_CASE, "frequency": {"spacing": "log", "f_min": 0.5, "f_max": 1000.0, "n": 400}},
    "axes": [{"field": "speed_kmh", "start": 40.0, "stop": 200.0, "num": 120}],
}
#: LONG with 4 times the cases: it runs far beyond the latest Ctrl-C below (3 s) on any
#: machine (LONG takes about 6 s on 2 cores since sweeps are stacked, too close)
LONGER = {**LONG, "axes": [{"field": "speed_kmh", "start": 40.0, "stop": 200.0, "num": 480}]}


def _command(sweep_file, out):
    return [
        sys.executable,
        "-m",
        "railvib.cli.main",
        "sweep",
        str(sweep_file),
        "-o",
        str(out),
        "-j",
        "2",
        "--no-progress",
    ]


def _start(sweep_file, out):
    """The command in a new session (its own process group, as a terminal starts it)."""
    return subprocess.Popen(
        _command(sweep_file, out),
        start_new_session=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )


def _group_alive(pgid):
    """Processes of group `pgid` still running (zombies, already dead, are not counted)."""
    alive = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        fields = stat.rpartition(")")[2].split()  # state, ppid, pgrp, ...
        if int(fields[2]) == pgid and fields[0] != "Z":
            alive.append(int(entry.name))
    return alive


def _wait_gone(pgid, seconds):
    deadline = time.monotonic() + seconds
    while (left := _group_alive(pgid)) and time.monotonic() < deadline:
        time.sleep(0.05)
    return left


linux_only = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc")


@linux_only
@pytest.mark.slow  # six real sweeps interrupted: ~15 s
@pytest.mark.parametrize("after_s", [0.1, 0.5, 1.0, 1.5, 2.0, 3.0])
def test_ctrl_c_at_any_moment_is_one_line_exit_130(after_s, tmp_path):
    sweep_file = tmp_path / "long.toml"
    sweep_file.write_text(tomli_w.dumps(LONGER))
    out = tmp_path / "out"
    proc = _start(sweep_file, out)
    time.sleep(after_s)
    os.killpg(proc.pid, signal.SIGINT)  # the whole group, as Ctrl-C in a terminal
    _, err = proc.communicate(timeout=120)  # also waits for the workers: they share stderr
    assert proc.returncode == 130, err
    assert "Traceback" not in err, err
    assert "Error" not in err, err
    lines = [line for line in err.splitlines() if line.strip()]
    assert lines[-1] == "aborted" or re.fullmatch(
        rf"aborted: finished chunks are kept in {re.escape(str(out))}/chunks - rerun the same "
        "command to resume",
        lines[-1],
    ), err
    assert len(lines) <= 2, err  # at most the "N cases ... -> OUT/" line before it
    assert _wait_gone(proc.pid, 5) == []


@linux_only
@pytest.mark.slow  # one sweep started, its main process killed: ~5 s
def test_sigkill_of_the_main_process_leaves_no_process(tmp_path):
    sweep_file = tmp_path / "long.toml"
    sweep_file.write_text(tomli_w.dumps(LONG))
    out = tmp_path / "out"
    proc = _start(sweep_file, out)
    try:
        deadline = time.monotonic() + 60
        while not list((out / "chunks").glob("chunk-*.done")):  # workers are computing
            assert proc.poll() is None, proc.stderr.read()
            assert time.monotonic() < deadline
            time.sleep(0.01)
        others = [pid for pid in _group_alive(proc.pid) if pid != proc.pid]
        assert len(others) >= 3  # fork server, resource tracker, workers: the test is real
        os.kill(proc.pid, signal.SIGKILL)  # the main process only; was: 4 alive after 70 s
        proc.wait(timeout=10)
        assert _wait_gone(proc.pid, 5) == []
    finally:
        for pid in _group_alive(proc.pid):
            os.kill(pid, signal.SIGKILL)
        proc.stderr.close()


@linux_only
@pytest.mark.slow  # a sweep killed while writing sweep.zarr, then resumed: ~15 s
def test_kill_during_the_zarr_write_leaves_nothing_after_the_next_run(tmp_path):
    sweep_file = tmp_path / "long.toml"
    sweep_file.write_text(tomli_w.dumps(LONG))
    out = tmp_path / "out"
    work = out / "chunks" / "sweep.zarr"  # the store being filled, region by region
    proc = _start(sweep_file, out)
    try:
        deadline = time.monotonic() + 120
        while not work.is_dir():
            assert proc.poll() is None, proc.stderr.read()
            assert time.monotonic() < deadline
            time.sleep(0.0005)
        os.killpg(proc.pid, signal.SIGKILL)
    finally:
        proc.wait(timeout=30)
        proc.stderr.close()
    assert work.is_dir(), "the kill must come during the Zarr writes"
    assert not (out / "sweep.zarr").exists()  # never there half-written
    rerun = subprocess.run(_command(sweep_file, out), capture_output=True, text=True, timeout=120)
    assert rerun.returncode == 0, rerun.stderr
    assert "Traceback" not in rerun.stderr
    assert not list(out.rglob(".*.part"))
    assert not work.exists()  # moved into place
    ds = xr.open_zarr(out / "sweep.zarr")
    assert ds.sizes["speed_kmh"] == 120
    assert np.isfinite(ds.peak.values).all()
    store = ChunkStore(out, load_sweep(sweep_file))
    assert store.missing() == []
