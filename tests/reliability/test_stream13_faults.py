"""Faults of a run streamed to results.nc block by block (issue 13, goal 2).

A streamed run writes its file as it solves; whatever stops it (an interrupt, a result
that is not finite in a later block, a full disk or a file-size limit) must leave no
half-written results.nc and no temporary, an earlier file as it was, and from the
command line one ``error:`` line and exit code 2 (no crash: HDF5 left with a failed
write segfaults when it closes the file).
"""

import dataclasses
import os
import subprocess
import sys

import numpy as np
import pytest

import railvib
from railvib.case import build_spectrum, build_system
from railvib.coupling import CoupledSystem
from railvib.errors import NonFiniteResult
from railvib.grid import FrequencyGrid
from railvib.solve import stream_to_netcdf
from tests.reliability.files_support import hidden, one_error_line, snapshot, write_case

GRID = FrequencyGrid.linear(0.5, 100.0, 0.5)  # 200 frequencies
BLOCK = 40


@pytest.fixture
def earlier(tmp_path):
    """A folder holding an earlier results.nc, and its snapshot."""
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "results.nc").write_bytes(b"an earlier run's file")
    return folder, snapshot(folder)


def _system():
    case = railvib.load_preset_case()
    return build_system(case), build_spectrum(case)


def _patched_blocks(monkeypatch, change):
    """`CoupledSystem.frf_blocks` with `change(index, frf)` applied to each block's FRF."""
    original = CoupledSystem.frf_blocks

    def blocks(self, f, block=None, observe=None):
        for i, (sl, frf) in enumerate(original(self, f, block=block, observe=observe)):
            yield sl, change(i, frf)

    monkeypatch.setattr(CoupledSystem, "frf_blocks", blocks)


def test_an_interrupted_stream_leaves_the_earlier_file(monkeypatch, earlier):
    folder, before = earlier

    def stop(i, frf):
        if i == 3:
            raise KeyboardInterrupt
        return frf

    _patched_blocks(monkeypatch, stop)
    system, spectrum = _system()
    with pytest.raises(KeyboardInterrupt):
        stream_to_netcdf(system, GRID, spectrum, folder / "results.nc", block=BLOCK)
    assert snapshot(folder) == before
    assert hidden(folder) == []


def test_a_non_finite_later_block_is_refused_and_leaves_nothing(monkeypatch, tmp_path):
    def spoil(i, frf):
        if i == 2:
            force = frf.contact_force.copy()
            force[5, 1] = np.nan
            return dataclasses.replace(frf, contact_force=force)
        return frf

    _patched_blocks(monkeypatch, spoil)
    system, spectrum = _system()
    with pytest.raises(NonFiniteResult) as info:
        stream_to_netcdf(system, GRID, spectrum, tmp_path / "results.nc", block=BLOCK)
    message = str(info.value)
    first = GRID.f[2 * BLOCK + 5]
    assert message.startswith("result psd_force is NaN or infinite at 1 of the 40 frequencies")
    assert f"(a block of the {GRID.f.size}), the first at {first:g} Hz" in message
    assert "frf_force" in message
    assert list(tmp_path.iterdir()) == []


#: the command line with every grid streamed (STREAM_FREQUENCIES lowered), in a process
#: under a file-size limit
LIMITED = """
import resource, sys
resource.setrlimit(resource.RLIMIT_FSIZE, (int(sys.argv[1]), int(sys.argv[1])))
from railvib import solve
solve.STREAM_FREQUENCIES = 10
from railvib.cli.main import main
sys.exit(main(["run", sys.argv[2], "-o", sys.argv[3], "--no-plots"]))
"""


@pytest.mark.slow  # fresh processes: ~2-4 s each
@pytest.mark.parametrize("limit", [20_000, 400_000])  # the first block; the reservation
def test_a_file_size_limit_is_one_line_and_does_not_crash(tmp_path, limit):
    case = write_case(tmp_path / "a.toml")
    out = tmp_path / "out"
    out.mkdir()
    (out / "results.nc").write_bytes(b"an earlier run's file")
    before = snapshot(out)
    result = subprocess.run(
        [sys.executable, "-c", LIMITED, str(limit), str(case), str(out)],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )
    assert result.returncode == 2, (result.returncode, result.stderr[-2000:])
    one_error_line(result.stderr, f"{out / 'results.nc'}: File too large")
    assert snapshot(out) == before
    assert hidden(tmp_path) == []
