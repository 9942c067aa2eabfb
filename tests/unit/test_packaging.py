"""The wheel: version from the git tag, metadata for conda-forge, installs and runs alone.

Each test builds a wheel from a copy of the checkout's files (tracked and new, not the
ignored ones), so the checkout itself is left as it was. Building needs setuptools and
setuptools-scm from the package index (pip's isolated build).
"""

import os
import shutil
import subprocess
import sys
import tomllib
import venv
import zipfile
from email.parser import Parser
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def _git(*args, cwd):
    return subprocess.run(
        ["git", *args], cwd=cwd, check=True, capture_output=True, text=True
    ).stdout


def _copy_checkout(dest: Path) -> Path:
    if shutil.which("git") is None:
        pytest.skip("git is needed to list the checkout's files")
    names = _git("ls-files", "-co", "--exclude-standard", "-z", cwd=ROOT).split("\0")
    for name in filter(None, names):
        if (ROOT / name).is_file():
            (dest / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, dest / name)
    return dest


def _tag(src: Path, tag: str) -> None:
    identity = ["-c", "user.name=railvib tests", "-c", "user.email=tests@railvib.invalid"]
    _git("init", "-q", cwd=src)
    _git("add", "-A", cwd=src)
    _git(*identity, "commit", "-q", "-m", "release", cwd=src)
    _git("tag", tag, cwd=src)


def _build_wheel(src: Path, dist: Path) -> Path:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    proc = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(dist), str(src)],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr[-4000:]
    (wheel,) = dist.glob("railvib-*.whl")
    return wheel


def _metadata(wheel: Path):
    with zipfile.ZipFile(wheel) as zf:
        name = next(n for n in zf.namelist() if n.endswith(".dist-info/METADATA"))
        return Parser().parsestr(zf.read(name).decode()), zf.namelist()


# one test per wheel built, so that pytest-xdist does not build it once per worker
@pytest.mark.slow  # builds a wheel (about 15 s) and a venv
def test_the_tagged_wheel_has_its_version_metadata_and_runs_in_a_fresh_venv(tmp_path):
    src = _copy_checkout(tmp_path / "src")
    _tag(src, "v1.2.3")  # the version is read from this tag, not from a file
    wheel = _build_wheel(src, tmp_path / "dist")
    _the_version_comes_from_the_git_tag(wheel)
    _conda_forge_metadata_license_classifiers_and_bounds(wheel)
    _the_wheel_installs_in_a_fresh_venv_and_runs(wheel, tmp_path)


def _the_version_comes_from_the_git_tag(tagged_wheel):
    meta, _ = _metadata(tagged_wheel)
    assert meta["Version"] == "1.2.3"
    assert tagged_wheel.name.startswith("railvib-1.2.3-")


def _conda_forge_metadata_license_classifiers_and_bounds(tagged_wheel):
    meta, names = _metadata(tagged_wheel)
    assert meta["License-Expression"] == "BSD-3-Clause"
    assert meta["License-File"] == "LICENSE"
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    classifiers = meta.get_all("Classifier")
    assert "Programming Language :: Python :: 3.11" in classifiers
    assert any(c.startswith("Topic :: Scientific/Engineering") for c in classifiers)
    runtime = [r for r in meta.get_all("Requires-Dist") if "extra ==" not in r]
    assert sorted(runtime) == sorted(
        d.split("#")[0].strip() for d in PYPROJECT["project"]["dependencies"]
    )
    assert all(">=" in r for r in runtime), "every dependency has a lower bound"
    assert "railvib/__main__.py" in names
    assert "railvib/py.typed" in names
    assert "railvib/presets/cases/wang2017_metro.toml" in names  # package data


def _the_wheel_installs_in_a_fresh_venv_and_runs(tagged_wheel, tmp_path):
    env_dir = tmp_path / "venv"
    venv.EnvBuilder(with_pip=True).create(env_dir)
    py = env_dir / "bin" / "python"
    # the dependencies come from this environment (the versions the suite tests); railvib
    # only from the wheel: a .pth line adds a folder without running its .pth files, so
    # this environment's (editable) railvib is not importable there
    site = subprocess.run(
        [str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout.strip()
    deps = {p for p in sys.path if p.endswith("site-packages")}
    Path(site, "test-dependencies.pth").write_text("\n".join(sorted(deps)) + "\n")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    subprocess.run(
        [str(py), "-m", "pip", "install", "-q", "--no-deps", "--no-index", str(tagged_wheel)],
        check=True,
        capture_output=True,
        text=True,
        env=env,
    )

    def run(*args):
        return subprocess.run(
            args, capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120
        )

    where = run(str(py), "-c", "import railvib; print(railvib.__file__)")
    assert where.stdout.startswith(str(env_dir)), where.stdout + where.stderr
    for command in ([str(env_dir / "bin" / "railvib")], [str(py), "-m", "railvib"]):
        proc = run(*command, "--version")
        assert (proc.returncode, proc.stdout, proc.stderr) == (0, "railvib, version 1.2.3\n", "")
    presets = run(str(env_dir / "bin" / "railvib"), "presets")
    assert presets.returncode == 0, presets.stderr
    assert "wang2017_metro:" in presets.stdout  # the presets are package data


@pytest.mark.slow  # builds a wheel (about 15 s)
def test_a_checkout_without_git_metadata_still_builds(tmp_path):
    src = _copy_checkout(tmp_path / "src")  # no .git: a source archive
    wheel = _build_wheel(src, tmp_path / "dist")
    meta, _ = _metadata(wheel)
    assert meta["Version"] == PYPROJECT["tool"]["setuptools_scm"]["fallback_version"]
