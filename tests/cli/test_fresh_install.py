"""Every command of the README works after the README's install, without extras (issue 10).

A fresh virtual environment gets ``pip install <this checkout>`` (no ``[sweep]``, no
``[test]``); then each line of the README's "Quick start (CLI)" block runs there, in
an empty folder, with the README's sweep file. Slow (a wheel build and an install,
about a minute, then the commands, 20 s): marked ``slow``.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"


def _block(text: str, after: str, language: str) -> str:
    """The first fenced `language` block after the line `after`."""
    tail = text[text.index(after) :]
    match = re.search(rf"```{language}\n(.*?)```", tail, flags=re.S)
    assert match is not None, f"no {language} block after {after!r}"
    return match.group(1)


def readme_commands() -> list[str]:
    """The Quick start (CLI) commands, comments dropped."""
    block = _block(README.read_text(encoding="utf-8"), "## Quick start (CLI)", "bash")
    lines = [line.split("  #")[0].strip() for line in block.splitlines()]
    return [line for line in lines if line]


def readme_sweep_file() -> str:
    """The README's sweep file (the toml block that starts ``# my_sweep.toml``)."""
    text = README.read_text(encoding="utf-8")
    return _block(text, "```toml\n# my_sweep.toml", "toml")


def readme_braking_file() -> str:
    """The README's non-stationary case (the toml block that starts ``# braking.toml``)."""
    text = README.read_text(encoding="utf-8")
    return _block(text, "```toml\n# braking.toml", "toml")


def test_the_readme_lists_the_commands_this_test_runs():
    commands = readme_commands()
    for word in ("template", "run", "presets", "validate", "sweep", "pad example", "pad fit"):
        assert any(c.startswith(f"railvib {word}") for c in commands), word
    assert "base = " in readme_sweep_file()
    assert 'mode = "nonstationary"' in readme_braking_file()


def _run(args: str, cwd: Path, env: dict[str, str], timeout: float = 300):
    return subprocess.run(
        args, shell=True, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout
    )


@pytest.mark.slow
def test_every_readme_command_works_after_pip_install_without_extras(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=120)
    python = venv / "bin" / "python"
    # a copy of the checkout's files: a build in the checkout rewrites src/railvib.egg-info,
    # whose version (from git, setuptools-scm) the test session itself may be reading
    files = subprocess.run(
        ["git", "ls-files", "-co", "--exclude-standard", "-z"],
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
    ).stdout.split("\0")
    source = tmp_path / "checkout"
    for name in filter(None, files):
        if (ROOT / name).is_file():
            (source / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, source / name)
    install = subprocess.run(
        [str(python), "-m", "pip", "install", "--quiet", str(source)],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert install.returncode == 0, install.stderr[-3000:]
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PATH"] = f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["MPLBACKEND"] = "Agg"
    # no extra crept in: a Dask cluster is the only thing that needs [sweep]
    probe = _run(f"{python} -c 'import distributed'", tmp_path, env)
    assert probe.returncode != 0, "distributed is installed: the test would prove nothing"
    work = tmp_path / "work"
    work.mkdir()
    (work / "my_sweep.toml").write_text(readme_sweep_file(), encoding="utf-8")
    (work / "braking.toml").write_text(readme_braking_file(), encoding="utf-8")
    for command in readme_commands():
        if command.startswith("railvib validate") and "--realisations" not in command:
            command += " --realisations 1"  # the same command, one Monte Carlo record
        done = _run(command, work, env)
        assert done.returncode == 0, f"{command}\n{done.stderr[-3000:]}"
        assert "Traceback" not in done.stderr, command
    assert (work / "out" / "results.nc").is_file()
    assert (work / "my_sweep.sweep" / "sweep.zarr").is_dir()
    assert (work / "pad-fit" / "pad.toml").is_file()
    assert (work / "track-out" / "track.nc").is_file()
    assert (work / "braking-out" / "results.nc").is_file()
    # a Dask cluster without the extra: one line saying what to install, before any work
    done = _run("railvib sweep my_sweep.toml -o dask-out --scheduler tcp://127.0.0.1:1", work, env)
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        "error: scheduler = 'tcp://127.0.0.1:1': a Dask cluster needs the \"distributed\" "
        'package: pip install "railvib[sweep]"'
    ]
    assert not (work / "dask-out").exists()
