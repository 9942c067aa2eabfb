"""The repository cites only what it contains (issue 10, item 9).

Sources, docs, presets, tests and the README once cited notes that live outside the
repository (a "physics" notes file of a shared folder). Every such citation now points
to a document of ``docs/``; this test keeps it so, and checks that every ``docs/...``
file cited anywhere exists.
"""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCANNED = [ROOT / "README.md", *(ROOT / "src").rglob("*"), *(ROOT / "docs").rglob("*")]
SCANNED += list((ROOT / "tests").rglob("*"))
TEXT_SUFFIXES = {".py", ".md", ".toml", ".txt", ".csv", ".cfg"}
#: the outside notes, spelt so that this file does not match itself
OUTSIDE = re.compile("|".join(["physics" + r"\.md", "physics" + " notes", r"\bshared" + "/"]))


def _texts():
    for path in SCANNED:
        if path.is_file() and path.suffix in TEXT_SUFFIXES and "__pycache__" not in path.parts:
            yield path, path.read_text(encoding="utf-8", errors="replace")


def test_nothing_cites_notes_outside_the_repository():
    hits = [
        f"{path.relative_to(ROOT)}:{n}: {line.strip()}"
        for path, text in _texts()
        for n, line in enumerate(text.splitlines(), 1)
        if OUTSIDE.search(line)
    ]
    assert not hits, "\n".join(hits)


def test_every_cited_doc_exists():
    cited = {
        (path.relative_to(ROOT), match)
        for path, text in _texts()
        for match in re.findall(r"\bdocs/[\w./-]+\.md\b", text)
    }
    missing = sorted(f"{where}: {doc}" for where, doc in cited if not (ROOT / doc).is_file())
    assert not missing, "\n".join(missing)
