"""Faults of the file system: full disks, size limits, unwritable folders (issue 11, part A).

Each fault must end with one line ``error: ...`` naming the file or folder and the
system's reason, exit code 2, no traceback (and no crash: before, HDF5 segfaulted
after a failed netCDF write), and the output folder as it was: absent if it was,
or holding the earlier run's complete set, with no temporary left beside or in it.
"""

import errno
import fcntl
import os
import shutil
import stat
import subprocess

import numpy as np
import pytest

from railvib import solve
from railvib.cli.main import main
from railvib.errors import NonFiniteResult, OutputError
from railvib.io import atomic_path, is_temporary_name, remove_temporaries, staged_folder
from railvib.padfit import write_example_data
from railvib.results.dataset import check_finite
from railvib.solve import RUN_FILES, run_to_folder
from tests.reliability.files_support import (
    file_size_limit,
    hidden,
    mode_blocking_preexec,
    one_error_line,
    run_cli,
    snapshot,
    write_case,
)


@pytest.fixture
def case(tmp_path):
    return write_case(tmp_path / "b.toml", "B", 120.0)


@pytest.fixture
def run_a(tmp_path):
    """A folder holding run A's complete set (no plots), and its snapshot."""
    out = tmp_path / "out"
    run_to_folder(write_case(tmp_path / "a.toml", "A", 80.0), out, plots=False)
    return out, snapshot(out)


def _run(capsys, *args):
    code = main([str(a) for a in args])
    return code, capsys.readouterr().err


# --- the output folder is not a folder, or cannot be written -------------------------


def _commands(tmp_path, out):
    data = write_example_data(tmp_path)
    return {
        "run": ["run", write_case(tmp_path / "b.toml"), "-o", out, "--no-plots"],
        "reproduce": ["reproduce", "--quiet", "-o", out],
        "pad fit": ["pad", "fit", data, "-o", out, "--tg", "-40"],
    }


@pytest.mark.parametrize("command", ["run", "reproduce", "pad fit"])
@pytest.mark.parametrize(
    ("where", "reason"),
    [
        ("/dev/full", "a folder, not a character device"),
        ("/dev/null/out", "'/dev/null' is a character device"),
        ("a_file/out", "is a file"),
        ("a_file/deeper/out", "is a file"),
    ],
)
def test_output_that_is_no_folder_is_one_line(tmp_path, capsys, command, where, reason):
    (tmp_path / "a_file").write_text("not a folder")
    out = where if where.startswith("/") else str(tmp_path / where)
    args = _commands(tmp_path, out)[command]
    before = snapshot(tmp_path)
    code, err = _run(capsys, *args)
    assert code == 2
    one_error_line(err, out, reason)
    assert snapshot(tmp_path) == before


@pytest.mark.slow  # ~1.2 s: whole commands with their files, kept out of the fast suite
def test_unwritable_output_folder_is_one_line_and_keeps_the_earlier_set(tmp_path, run_a):
    out, before = run_a
    os.chmod(out, 0o555)
    try:
        preexec = mode_blocking_preexec(out)
        result = run_cli("run", write_case(tmp_path / "b.toml"), "-o", out, preexec_fn=preexec)
        assert result.returncode == 2
        one_error_line(result.stderr, f"cannot write {out}: Permission denied")
        assert snapshot(out) == before
        assert hidden(tmp_path) == []
    finally:
        os.chmod(out, 0o755)


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_unwritable_parent_folder_is_one_line_and_makes_nothing(tmp_path):
    parent = tmp_path / "locked"
    parent.mkdir(mode=0o555)
    try:
        preexec = mode_blocking_preexec(parent)
        out = parent / "new" / "out"
        result = run_cli("run", write_case(tmp_path / "b.toml"), "-o", out, preexec_fn=preexec)
        assert result.returncode == 2
        one_error_line(result.stderr, str(out), "Permission denied")
        assert list(parent.iterdir()) == []
    finally:
        os.chmod(parent, 0o755)


def _in_namespace(script):
    """Run `script` (sh) as root in a private mount namespace, or skip (needs unshare(1))."""
    unshare = shutil.which("unshare")
    if unshare is None or os.geteuid() != 0:
        pytest.skip("needs root and unshare(1) to mount a private tmpfs")
    probe = subprocess.run([unshare, "-m", "--propagation", "private", "true"], capture_output=True)
    if probe.returncode != 0:
        pytest.skip(f"cannot make a mount namespace: {probe.stderr.decode().strip()}")
    return subprocess.run(
        [unshare, "-m", "--propagation", "private", "sh", "-c", script],
        capture_output=True,
        text=True,
        timeout=120,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )


@pytest.mark.slow  # three subprocesses, two with plots: ~6 s
def test_full_disk_and_read_only_file_system_are_one_line(tmp_path):
    """A 200 kB file system: the run fails midway (ENOSPC); remounted read-only: EROFS."""
    import sys

    mnt = tmp_path / "mnt"
    mnt.mkdir()
    case = write_case(tmp_path / "b.toml")
    cli = f"{sys.executable} -m railvib.cli.main run {case}"
    script = f"""
        mount -t tmpfs -o size=200k tmpfs {mnt} || exit 99
        {cli} -o {mnt}/out > /dev/null 2> {tmp_path}/full.err; echo $? > {tmp_path}/full.rc
        ls -A {mnt} > {tmp_path}/full.ls
        mkdir {mnt}/old && echo kept > {mnt}/old/notes.txt
        mount -o remount,ro {mnt}
        {cli} -o {mnt}/old > /dev/null 2> {tmp_path}/ro.err; echo $? > {tmp_path}/ro.rc
        {cli} -o {mnt}/new > /dev/null 2> {tmp_path}/ro_new.err; echo $? > {tmp_path}/ro_new.rc
        ls -A {mnt} {mnt}/old > {tmp_path}/ro.ls
    """
    result = _in_namespace(script)
    if result.returncode == 99:
        pytest.skip(f"cannot mount a tmpfs: {result.stderr.strip()}")
    read = lambda name: (tmp_path / name).read_text()  # noqa: E731
    assert read("full.rc").strip() == "2"  # not 139 (a segfault) nor 1 (a traceback)
    line = one_error_line(read("full.err"), f"cannot write {mnt}/out/", "No space left on device")
    assert line.split("/out/")[1].split(":")[0] in RUN_FILES  # names the file, as the user will
    assert read("full.ls") == ""  # nothing left: neither the folder nor a temporary
    assert read("ro.rc").strip() == read("ro_new.rc").strip() == "2"
    one_error_line(read("ro.err"), f"cannot write {mnt}/old: Read-only file system")
    one_error_line(read("ro_new.err"), f"{mnt}/new", "Read-only file system")
    assert read("ro.ls").split() == [f"{mnt}:", "old", f"{mnt}/old:", "notes.txt"]


# --- a file-size limit (ulimit -f) ---------------------------------------------------


def test_file_size_limit_is_one_line_and_keeps_the_earlier_set(tmp_path, capsys, run_a, case):
    out, before = run_a
    with file_size_limit(1000):  # smaller than results.nc, the first file written
        code, err = _run(capsys, "run", case, "-o", out, "--no-plots")
    assert code == 2
    one_error_line(err, f"cannot write {out / 'results.nc'}: File too large")
    assert snapshot(out) == before
    assert hidden(tmp_path) == hidden(out) == []


@pytest.mark.slow  # two runs with plots: ~3 s
def test_file_size_limit_after_writing_started_leaves_nothing(tmp_path, capsys, case):
    ref = tmp_path / "ref"
    run_to_folder(case, ref)
    sizes = {p.name: p.stat().st_size for p in ref.iterdir()}
    # results.nc, written first, is cut half-way through its write: a partial temporary
    # exists when the error comes (a figure larger than results.nc, which this test used
    # to cut, no longer exists since the criteria joined the dataset)
    limit = sizes["results.nc"] // 2
    out = tmp_path / "out"
    with file_size_limit(limit):
        code, err = _run(capsys, "run", case, "-o", out)
    assert code == 2
    line = one_error_line(err, f"cannot write {out}/", "File too large")
    assert sizes[line.split(f"{out}/")[1].split(":")[0]] > limit
    assert not out.exists()
    assert hidden(tmp_path) == []


@pytest.mark.slow  # a subprocess: ~1.5 s
def test_file_size_limit_in_a_fresh_process_does_not_crash(tmp_path, run_a, case):
    """The issue's ``ulimit -f``: HDF5 left with a failed write used to segfault (exit 139)."""
    import resource

    out, before = run_a
    limit = lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))  # noqa: E731
    result = run_cli("run", case, "-o", out, preexec_fn=limit)
    assert result.returncode == 2, result.stderr
    one_error_line(result.stderr, f"{out / 'results.nc'}: File too large")
    assert snapshot(out) == before
    assert hidden(tmp_path) == []


def test_atomic_path_names_the_file_and_removes_the_temporary(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("earlier\n")
    with file_size_limit(100), pytest.raises(OutputError) as info, atomic_path(target) as tmp:
        tmp.write_text("x" * 1000)
    assert str(info.value) == f"cannot write {target}: File too large"
    assert info.value.errno == errno.EFBIG
    assert isinstance(info.value, OSError)  # code catching OSError keeps working
    assert target.read_text() == "earlier\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]


# --- standard output ---------------------------------------------------------------


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_standard_output_on_a_full_disk_is_one_line():
    with open("/dev/full", "w") as full:
        result = run_cli("template", stdout=full.fileno())
    assert result.returncode == 2
    one_error_line(result.stderr, "cannot write standard output: No space left on device")


# --- results that are not numbers, failures after writing started ------------------


def test_non_finite_result_is_refused_before_anything_is_written(tmp_path, capsys):
    case = tmp_path / "stiff.toml"
    case.write_text(
        write_case(tmp_path / "x.toml").read_text()
        + '[track.pad]\nmodel = "spring_damper"\nstiffness_n_per_m = 1e300\n'
    )
    out = tmp_path / "out"
    code, err = _run(capsys, "run", case, "-o", out)
    assert code == 2
    one_error_line(err)  # by now a NonFiniteResult, or refused on input by a later check
    assert not out.exists()
    assert hidden(tmp_path) == []


def test_check_finite_names_the_variable_and_the_first_bad_frequency(tmp_path):
    ds = solve.run(write_case(tmp_path / "a.toml"))
    f = ds["frequency"].values
    bad = ds.copy(deep=True)
    bad["psd_force"][4:7, 1] = np.nan
    bad["psd_acceleration"][9, 0] = np.inf
    with pytest.raises(NonFiniteResult) as info:
        check_finite(bad)
    message = str(info.value)
    assert message.startswith("result psd_acceleration is NaN or infinite at 1 of 12 ")
    assert f"the first at {f[9]:g} Hz (also psd_force)" in message
    check_finite(ds)  # the unchanged result passes


@pytest.mark.parametrize("error", [RuntimeError("a bug"), KeyboardInterrupt()])
def test_a_run_failing_after_writing_started_leaves_the_earlier_set(
    tmp_path, monkeypatch, run_a, case, error
):
    out, before = run_a
    (out / "notes.txt").write_text("the user's")
    before = snapshot(out)
    write_text = solve.write_text

    def fail_on_summary_md(path, text):  # results.nc and the PSD tables are written by now
        if path.name == "summary.md":
            assert (path.parent / "results.nc").exists()
            raise error
        return write_text(path, text)

    monkeypatch.setattr(solve, "write_text", fail_on_summary_md)
    with pytest.raises(type(error)):
        run_to_folder(case, out, plots=False)
    assert snapshot(out) == before
    assert hidden(tmp_path) == hidden(out) == []


# --- one consistent set; the user's files are kept ---------------------------------


@pytest.mark.slow  # two runs with plots: ~3 s
@pytest.mark.parametrize("user_files", [False, True])
def test_a_run_replaces_the_earlier_set_and_keeps_other_files(tmp_path, case, user_files):
    out = tmp_path / "out"
    run_to_folder(write_case(tmp_path / "a.toml", "A"), out)  # with figures
    user = {"notes.txt": b"mine", "data/input.csv": b"1,2\n", ".hidden": b"x"} if user_files else {}
    for name, data in user.items():
        (out / name).parent.mkdir(exist_ok=True)
        (out / name).write_bytes(data)
    result = run_to_folder(case, out, plots=False)
    after = snapshot(out)
    written = {p.name for p in result.files}
    assert set(after) == written | set(user)  # A's figures are gone: B drew none
    assert {name: after[name] for name in user} == user
    assert after["summary.md"].startswith(b"# B\n")
    assert hidden(tmp_path) == []


def test_a_run_into_the_current_folder_keeps_it(tmp_path, monkeypatch, run_a, case):
    out, _ = run_a
    monkeypatch.chdir(out)
    code = main(["run", str(case), "-o", ".", "--no-plots"])
    assert code == 0
    assert os.path.samefile(os.getcwd(), out)  # the same folder, not a removed one
    assert set(snapshot(out)) == {n for n in RUN_FILES if not n.endswith(".png")}


# --- temporaries left by killed runs -----------------------------------------------


def test_leftover_temporaries_are_removed_by_the_next_run(tmp_path, run_a, case, capsys):
    out, _ = run_a
    leftovers = [
        tmp_path / ".out.k2x9qaz1.part",  # a staging folder of a killed run
        tmp_path / ".out.0a1b2c3d.old",  # an earlier set being swapped out
        out / ".results.nc.ab_cd123.part",  # atomic_path's file (railvib before issue 11)
        out / ".railvib.zz11yy22.part",  # a staging folder inside (unwritable parent)
    ]
    for path in leftovers:
        if path.suffix == ".part" and path.name.startswith(".results"):
            path.write_bytes(b"half a file")
        else:
            path.mkdir()
            (path / "results.nc").write_bytes(b"half a file")
    kept = [
        out / ".results.nc.backup",  # the user's, not railvib's form
        out / ".notes.txt",
        tmp_path / ".other.k2x9qaz1.part",  # a temporary of another folder
    ]
    for path in kept:
        path.write_text("keep")
    running = tmp_path / ".out.runs1234.part"  # the staging folder of a run still going
    running.mkdir()
    fd = os.open(running, os.O_RDONLY)
    fcntl.flock(fd, fcntl.LOCK_EX)
    try:
        code = main(["run", str(case), "-o", str(out), "--no-plots"])
        assert code == 0, capsys.readouterr().err
        for path in leftovers:
            assert not path.exists(), path
        for path in kept:
            assert path.read_text() == "keep"
        assert running.is_dir()
    finally:
        os.close(fd)


@pytest.mark.parametrize(
    ("name", "ours"),
    [
        (".results.nc.k2x9qaz1.part", True),
        (".railvib-out.a_b_c_d1.part", True),
        (".out.0a1b2c3d.old", True),
        (".sweep.zarr.ab12cd34.part", True),
        ("results.nc.k2x9qaz1.part", False),  # not hidden
        (".results.nc.k2x9qaz.part", False),  # 7 characters
        (".results.nc.K2X9QAZ1.part", False),  # mkstemp uses lower case
        (".results.nc.k2x9qaz1.tmp", False),
        (".k2x9qaz1.part", False),  # no name
    ],
)
def test_only_railvibs_temporary_names_are_recognised(name, ours):
    assert is_temporary_name(name) is ours


def test_remove_temporaries_with_a_prefix_spares_other_folders_temporaries(tmp_path):
    (tmp_path / ".a.k2x9qaz1.part").mkdir()
    (tmp_path / ".b.k2x9qaz1.part").write_text("")
    assert remove_temporaries(tmp_path, "a") == [tmp_path / ".a.k2x9qaz1.part"]
    assert [p.name for p in tmp_path.iterdir()] == [".b.k2x9qaz1.part"]
    assert remove_temporaries(tmp_path / "missing") == []


def test_staged_folder_mode_is_the_usual_folder_mode(tmp_path):
    umask = os.umask(0o022)
    try:
        with staged_folder(tmp_path / "out") as stage:
            (stage.path / "f.txt").write_text("x")
    finally:
        os.umask(umask)
    assert stat.S_IMODE((tmp_path / "out").stat().st_mode) == 0o755
