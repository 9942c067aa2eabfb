"""The examples in the README and in docstrings run and say what they claim."""

import doctest
import re
from pathlib import Path

import pytest

import railvib
import railvib.contact
import railvib.grid
import railvib.moving.parametric
import railvib.solve
import railvib.track.moving
import railvib.track.periodic
import railvib.track.slab

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"


@pytest.mark.parametrize(
    "doc",
    [
        "README.md",
        "docs/user-guide.md",
        "docs/extending.md",
        "docs/moving-load.md",
        "docs/moving-vehicle.md",
        "docs/slab-track.md",
    ],
)
def test_python_examples_in_docs_run(doc, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / doc).read_text(), flags=re.S)
    assert blocks, f"{doc} has no python example"
    for block in blocks:
        exec(compile(block, doc, "exec"), {})  # noqa: S102


def test_readme_opens_with_the_two_commands():
    text = README.read_text()
    bash = re.findall(r"```bash\n(.*?)```", text, flags=re.S)
    assert "railvib reproduce" in bash[0]
    assert "pytest" in bash[1]
    ci = (README.parent / ".ci" / "run").read_text()
    assert bash[1].split("&&")[-1].strip() in ci


@pytest.mark.parametrize(
    "module",
    [
        railvib,
        railvib.grid,
        railvib.contact,
        railvib.track.periodic,
        railvib.track.moving,
        railvib.moving.parametric,
        railvib.track.slab,
        railvib.solve,
    ],
)
def test_docstring_examples(module):
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0
    assert result.failed == 0


def test_models_page_is_generated_from_the_declarations():
    from railvib.models import models_markdown

    page = (ROOT / "docs" / "models.md").read_text()
    assert page == models_markdown(), "docs/models.md is stale: railvib models > docs/models.md"
