"""Sphinx configuration of the railvib documentation site (docs/design/0008-documentation-site.md).

The site is built from this folder: the existing Markdown pages through myst-parser,
the model-family pages and the API reference generated from the code when the build
starts (``docs/families/``, ``docs/api/``), the gallery executed by sphinx-gallery
(``docs/gallery/`` into ``docs/auto_gallery/``). Those three folders are build
products (git-ignored). Build with warnings as errors, as CI does
(``tests/docs/test_site.py``)::

    python -m sphinx -W --keep-going -b html docs docs/_build/html
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

from railvib.io import railvib_version  # noqa: E402

project = "railvib"
author = "railvib developers"
copyright = "railvib developers, BSD-3-Clause"  # noqa: A001 (Sphinx's name)
release = railvib_version()
version = release

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "railvib_docs",  # docs/_ext/railvib_docs.py: the generated pages
]

root_doc = "index"
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "_ext", "gallery/README.rst", "**/.ipynb_checkpoints"]
# every warning is an error in CI, so a broken link or cross-reference fails the build
nitpicky = False
suppress_warnings: list[str] = []

# MyST: the existing docs/*.md pages, with $...$ maths and heading anchors for their
# in-page links ([...](#one-run-one-set-of-files))
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 4

# numpydoc: the project's docstring convention (CONVENTIONS.md)
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
# numpydoc's own validation (PR01) knows neither the one-line form nor inherited
# parameter docs of the project's rule; docs/_ext/railvib_docs.py checks that rule
# instead, and a parameter documented but not in the signature still fails:
numpydoc_validation_checks = {"PR02"}
# numpydoc drops a first parameter named ``cls`` as if the function were a classmethod
numpydoc_validation_exclude = {r"railvib\.registry\.parameters\.declared_parameters$"}

autodoc_typehints = "none"  # the numpydoc sections give the types, with units
autodoc_member_order = "bysource"

sphinx_gallery_conf = {
    "examples_dirs": "gallery",
    "gallery_dirs": "auto_gallery",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "within_subsection_order": "FileNameSortKey",
}

html_theme = "pydata_sphinx_theme"
html_title = f"railvib {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
}
html_static_path: list[str] = []
html_show_sourcelink = False
