"""Shared by the file-fault and kill tests: a quick case, the CLI, folder snapshots, caps."""

from __future__ import annotations

import ctypes
import os
import resource
import subprocess
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

#: a quick case (12 frequencies, about 0.3 s without plots); TITLE and SPEED vary it
CASE = """preset = "wang2017_metro"
title = "{title}"
speed_kmh = {speed}
[frequency]
spacing = "log"
f_min = 1.0
f_max = 100.0
n = 12
"""


def write_case(path: Path, title: str = "A", speed: float = 80.0) -> Path:
    """A quick case file at `path` (run A or run B of a test), returned."""
    path.write_text(CASE.format(title=title, speed=speed), encoding="utf-8")
    return path


def run_cli(
    *args: str | Path,
    cwd: Path | None = None,
    preexec_fn: Callable[[], None] | None = None,
    timeout: float = 120,
    stdout: int | None = subprocess.PIPE,
) -> subprocess.CompletedProcess[str]:
    """Run the command line in a new Python process (faults that need one: limits, caps)."""
    return subprocess.run(
        [sys.executable, "-m", "railvib.cli.main", *map(str, args)],
        cwd=cwd,
        preexec_fn=preexec_fn,
        stdout=stdout,
        stderr=subprocess.PIPE,
        text=True,
        timeout=timeout,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )


def one_error_line(stderr: str, *names: str) -> str:
    """The single ``error: ...`` line of `stderr` (blank and ``warning:`` lines aside), naming
    all of `names`."""
    assert "Traceback" not in stderr, stderr
    lines = [s for s in stderr.splitlines() if s.strip() and not s.startswith("warning: ")]
    assert len(lines) == 1, stderr
    assert lines[0].startswith("error: "), lines[0]
    for name in names:
        assert name in lines[0], f"{lines[0]!r} does not name {name!r}"
    return lines[0]


def snapshot(folder: Path) -> dict[str, bytes] | None:
    """Every file below `folder` (hidden ones too) -> its bytes; None when it does not exist."""
    if not folder.exists():
        return None
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def hidden(folder: Path) -> list[str]:
    """Names starting with a dot in `folder` (and, for a run's folder, beside it)."""
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


@contextmanager
def file_size_limit(n_bytes: int) -> Iterator[None]:
    """``ulimit -f`` in this process: a write past `n_bytes` fails with EFBIG (CPython ignores
    SIGXFSZ, so no signal kills the process)."""
    soft, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
    resource.setrlimit(resource.RLIMIT_FSIZE, (n_bytes, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, (soft, hard))


_CAP_DAC_OVERRIDE, _CAP_DAC_READ_SEARCH, _PR_CAPBSET_DROP = 1, 2, 24


def _drop_dac_capabilities() -> None:
    """In a child about to exec: root without the capabilities that bypass file modes."""
    libc = ctypes.CDLL(None, use_errno=True)
    for cap in (_CAP_DAC_OVERRIDE, _CAP_DAC_READ_SEARCH):
        if libc.prctl(_PR_CAPBSET_DROP, cap, 0, 0, 0) != 0:
            raise OSError(ctypes.get_errno(), "prctl(PR_CAPBSET_DROP)")


def mode_blocking_preexec(probe: Path) -> Callable[[], None] | None:
    """A preexec_fn under which a folder's mode bits are obeyed, or None where none is needed.

    Tests run as root in CI, where ``chmod 0o555`` blocks nothing; a root child that has
    dropped CAP_DAC_OVERRIDE (and CAP_DAC_READ_SEARCH) from its bounding set obeys modes
    like any user. `probe` (a folder the caller made read-only) checks that it works.

    Raises
    ------
    pytest.skip.Exception
        When the modes cannot be made to hold (no CAP_SETPCAP, not Linux).
    """
    if os.geteuid() != 0:
        return None
    try:
        check = subprocess.run(
            [sys.executable, "-c", f"open({str(probe / 'x')!r}, 'w')"],
            preexec_fn=_drop_dac_capabilities,
            capture_output=True,
        )
    except subprocess.SubprocessError:  # prctl refused (no CAP_SETPCAP)
        pytest.skip("running as root and cannot drop CAP_DAC_OVERRIDE: file modes block nothing")
    if check.returncode == 0:
        (probe / "x").unlink()
        pytest.skip("running as root and cannot drop CAP_DAC_OVERRIDE: file modes block nothing")
    return _drop_dac_capabilities
