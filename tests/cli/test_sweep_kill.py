"""A sweep killed with SIGKILL midway resumes with the same command and loses nothing."""

import os
import signal
import subprocess
import sys
import time

import pytest
import tomli_w
import xarray as xr

from railvib.sweep import ChunkStore, load_sweep, load_sweep_dataset, run_sweep
from tests.unit.sweep.sweep_cases import BASE_CASE

SWEEP = {
    "title": "kill test",
    "chunk_size": 1,
    "case": {**BASE_CASE, "frequency": {"spacing": "log", "f_min": 0.5, "f_max": 1000.0, "n": 200}},
    "axes": [
        {"field": "track.pad_temperature_c", "start": -40.0, "stop": 40.0, "num": 16},
        {"field": "speed_kmh", "values": [60.0, 120.0]},
    ],
}


def _cli(sweep_file, out):
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


@pytest.mark.slow  # kills a real sweep process: ~12 s
def test_sigkill_midway_then_resume_equals_uninterrupted(tmp_path):
    sweep_file = tmp_path / "kill.toml"
    sweep_file.write_text(tomli_w.dumps(SWEEP))
    out = tmp_path / "out"
    spec = load_sweep(sweep_file)
    store = ChunkStore(out, spec)
    n_chunks = store.layout.n_chunks
    proc = subprocess.Popen(
        _cli(sweep_file, out),
        start_new_session=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            if store.chunk_dir.exists() and len(list(store.chunk_dir.glob("chunk-*"))) >= 3:
                break
            assert proc.poll() is None, proc.stderr.read().decode()
            time.sleep(0.002)
        os.killpg(proc.pid, signal.SIGKILL)  # the client, the forkserver and its workers
    finally:
        proc.wait(timeout=30)
    proc.stderr.close()
    done = store.done()
    assert 3 <= len(done) < n_chunks, "the sweep must be killed midway"
    assert not (out / "sweep.zarr").exists()
    before = {cid: store.chunk_path(cid).stat().st_mtime_ns for cid in done}

    rerun = subprocess.run(_cli(sweep_file, out), capture_output=True, text=True, timeout=120)
    assert rerun.returncode == 0, rerun.stderr
    assert store.missing() == []
    for cid, mtime in before.items():  # finished chunks were kept, not recomputed
        assert store.chunk_path(cid).stat().st_mtime_ns == mtime
    resumed = load_sweep_dataset(out)
    reference = run_sweep(spec, tmp_path / "ref", workers=1, progress=False)
    xr.testing.assert_identical(resumed, load_sweep_dataset(tmp_path / "ref"))
    xr.testing.assert_identical(resumed.drop_attrs(), reference.drop_attrs())
