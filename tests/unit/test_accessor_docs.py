"""The Python examples of docs/notebooks.md (the accessor) and docs/explorer.md run."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow  # each runs the default case once or twice: 1-3 s
@pytest.mark.parametrize("doc", ["docs/notebooks.md", "docs/explorer.md"])
def test_python_examples_run(doc, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / doc).read_text(), flags=re.S)
    assert blocks, f"{doc} has no python example"
    for block in blocks:
        exec(compile(block, doc, "exec"), {})  # noqa: S102


def test_the_docs_name_every_accessor_method():
    from railvib.accessor import RailvibAccessor

    text = (ROOT / "docs" / "notebooks.md").read_text()
    public = [name for name in vars(RailvibAccessor) if not name.startswith("_")]
    documented = {"summary", "rms", "octave_bands", "plot_psd"}
    assert documented <= set(public)
    for name in documented:
        assert f"ds.railvib.{name}(" in text, name


@pytest.mark.slow  # runs the default case: about 1 s
def test_the_accessor_docstring_example_holds():
    import doctest

    import railvib.accessor

    result = doctest.testmod(railvib.accessor)
    assert result.attempted >= 3
    assert result.failed == 0
