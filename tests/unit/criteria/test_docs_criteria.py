"""The examples of docs/criteria.md run, and its case-file snippets load."""

import re
import tomllib
from pathlib import Path

import pytest

import railvib

DOC = Path(__file__).resolve().parents[3] / "docs" / "criteria.md"


@pytest.mark.slow
def test_python_example_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), flags=re.S)
    assert blocks
    for block in blocks:
        exec(compile(block, str(DOC), "exec"), {})  # noqa: S102


def test_toml_snippets_are_valid_case_sections():
    blocks = re.findall(r"```toml\n(.*?)```", DOC.read_text(), flags=re.S)
    assert len(blocks) == 2
    for block in blocks:
        table = tomllib.loads(block)
        case = railvib.case_from_dict({"preset": "wang2017_metro", **table})
        assert case is not None
