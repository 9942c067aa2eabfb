"""The documentation site builds with warnings as errors (docs/design/0008-documentation-site.md).

One Sphinx build of a copy of ``docs/`` (the build writes its generated pages next to
the sources, so the checkout is left as it was): a broken link or reference, a
docstring that is not valid reStructuredText, an undocumented parameter or a gallery
example that raises fails it. Then the pages the issue asks for are looked for in the
output, with what each must hold, read off the registries and the files themselves.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from railvib.models import FAMILIES

ROOT = Path(__file__).resolve().parents[2]
#: build products of a local build, not sources (.gitignore)
GENERATED = ("_build", "api", "families", "auto_gallery", "cli.md", "sg_execution_times.rst")


def _build(tmp):
    """Build a copy of docs/ under `tmp`: (the finished process, the HTML folder)."""
    shutil.copytree(
        ROOT / "docs", tmp / "docs", ignore=shutil.ignore_patterns(*GENERATED, "__pycache__")
    )
    shutil.copy(ROOT / "CHANGELOG.md", tmp / "CHANGELOG.md")  # the changelog page includes it
    out = tmp / "html"
    path = os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path, "MPLBACKEND": "Agg"}
    command = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html"]
    proc = subprocess.run(
        [*command, str(tmp / "docs"), str(out)],
        capture_output=True,
        text=True,
        env=env,
        timeout=900,
    )
    return proc, out


# one test, so that pytest-xdist does not build the site once per worker
@pytest.mark.slow  # one Sphinx build: about 35 s of CPU (autodoc imports, the gallery runs)
def test_the_site_builds_with_warnings_as_errors_and_has_its_pages(tmp_path):
    for module in ("sphinx", "numpydoc", "myst_parser", "sphinx_gallery", "pydata_sphinx_theme"):
        pytest.importorskip(module, reason="the docs extra: pip install -e '.[docs]'")
    proc, out = _build(tmp_path)
    assert proc.returncode == 0, proc.stderr[-6000:]
    assert not re.search(r"WARNING|ERROR", proc.stderr), proc.stderr[-6000:]
    _one_page_per_model_family_with_every_member_and_key(out)
    _the_api_reference_documents_the_public_names(out)
    _the_gallery_ran_and_the_other_pages_are_there(out)


def _one_page_per_model_family_with_every_member_and_key(out):
    index = (out / "models.html").read_text(encoding="utf-8")
    for name, registry in FAMILIES.items():
        assert f"families/{name}.html" in index
        page = (out / "families" / f"{name}.html").read_text(encoding="utf-8")
        for member in registry:
            assert member.name in page
            for p in member.parameters:
                assert p.key in page, f"{name}.{member.name}: {p.key}"


def _the_api_reference_documents_the_public_names(out):
    pads = (out / "api" / "railvib.pads.html").read_text(encoding="utf-8")
    # defined in railvib.pads.base, listed in railvib.pads.__all__: documented once, there
    assert 'id="railvib.pads.base.PadModel"' in pads
    assert 'id="railvib.pads.PadModel"' not in pads
    solve = (out / "api" / "railvib.solve.html").read_text(encoding="utf-8")
    assert 'id="railvib.solve.run"' in solve
    assert "Parameters" in solve  # numpydoc rendered the sections


def _the_gallery_ran_and_the_other_pages_are_there(out):
    for script in sorted((ROOT / "docs" / "gallery").glob("plot_*.py")):
        assert (out / "auto_gallery" / f"{script.stem}.html").is_file()
        figures = list((out / "_images").glob(f"sphx_glr_{script.stem}_*.png"))
        assert figures, f"{script.name} drew no figure: it did not run"
    for page in ("getting-started", "user-guide", "theory", "validation", "cli", "changelog"):
        assert (out / f"{page}.html").is_file(), page
    changelog = (out / "changelog.html").read_text(encoding="utf-8")
    first = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8").splitlines()[2]  # "## ..."
    assert first.lstrip("# ").strip() in changelog
    validation = (ROOT / "docs" / "validation.md").read_text(encoding="utf-8")
    for png in re.findall(r"figures/validation/(\w+\.png)", validation):
        assert (out / "_images" / png).is_file(), png
