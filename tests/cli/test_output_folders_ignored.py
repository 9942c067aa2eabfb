"""Every default output folder of the commands is ignored by git (issue 10, item 8)."""

import shutil
import subprocess
from pathlib import Path

import pytest

from railvib.cli.main import cli
from railvib.sweep import default_output_folder
from tests.cli.test_run_cli import _commands

ROOT = Path(__file__).resolve().parents[2]


def _default_folders():
    for name, command in _commands(cli):
        for param in command.params:
            if param.name in ("outdir", "output") and isinstance(param.default, Path):
                if param.default != Path("."):  # pad example: a file the user asked for, here
                    yield name, param.default
    yield "sweep run", default_output_folder(Path("my_sweep.toml"))  # <stem>.sweep


@pytest.mark.skipif(
    shutil.which("git") is None or not (ROOT / ".git").exists(), reason="needs a git checkout"
)
def test_default_output_folders_are_git_ignored():
    folders = dict(_default_folders())
    assert {"run", "reproduce", "pad fit", "validate", "sweep run"} <= set(folders)
    paths = [str(folder / "some_output_file") for folder in folders.values()]
    done = subprocess.run(
        ["git", "check-ignore", "--no-index", *paths], cwd=ROOT, capture_output=True, text=True
    )
    ignored = set(done.stdout.split())
    assert ignored == set(paths), f"not ignored: {sorted(set(paths) - ignored)}"
