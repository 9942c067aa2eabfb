"""The generators and the docstring check of the documentation site (docs/_ext/railvib_docs.py).

Fast: no Sphinx build (tests/docs/test_site.py builds the site). The expected pages are
read off the registries and the CLI, the expected verdicts off docstrings written here.
"""

import dataclasses
import importlib.util
from pathlib import Path

import pydantic
import pytest

from railvib.models import FAMILIES
from railvib.registry import parameter

ROOT = Path(__file__).resolve().parents[2]
_SPEC = importlib.util.spec_from_file_location(
    "railvib_docs", ROOT / "docs" / "_ext" / "railvib_docs.py"
)
ext = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(ext)


def _lines(func):
    return (func.__doc__ or "").splitlines()


# -- the family pages ---------------------------------------------------------------------


def test_one_page_per_family_lists_every_member_with_its_keys(tmp_path):
    ext.family_pages(tmp_path)
    pages = sorted(p.stem for p in (tmp_path / "families").iterdir())
    assert pages == sorted(FAMILIES)
    for name, registry in FAMILIES.items():
        text = (tmp_path / "families" / f"{name}.md").read_text()
        assert text.startswith("# "), f"{name}: the page needs one title"
        assert text.count("\n# ") == 0, f"{name}: a second title would split the page"
        for member in registry:
            assert f"## `{member.name}`" in text, f"{name}: {member.name} missing"
            for p in member.parameters:
                assert f"`{p.key}`" in text, f"{name}.{member.name}: key {p.key} missing"


def test_a_removed_family_page_does_not_linger(tmp_path):
    (tmp_path / "families").mkdir()
    (tmp_path / "families" / "gone.md").write_text("# a family that no longer exists\n")
    ext.family_pages(tmp_path)
    assert not (tmp_path / "families" / "gone.md").exists()


def test_the_models_index_links_every_family_page():
    text = ext.models_index()
    for name, registry in FAMILIES.items():
        assert f"families/{name}" in text
        assert all(f"`{m}`" in text for m in registry.names())


def test_the_cli_page_has_every_command(tmp_path):
    from railvib.cli.main import cli

    ext.cli_page(tmp_path)
    text = (tmp_path / "cli.md").read_text()
    for name in cli.list_commands(None):
        if not cli.commands[name].hidden:
            assert f"## `railvib {name}`" in text


# -- the docstring check (the rule of tests/unit/test_docstrings.py) ----------------------


def documented(f, speed):
    """Documented.

    Parameters
    ----------
    f : float
        Frequency, Hz.
    speed : float
        Speed, m/s.
    """


def one_missing(f, speed):
    """Documented except one.

    Parameters
    ----------
    f : float
        Frequency, Hz.
    """


def short_form(f, speed):
    """The value at `f` (Hz) and `speed` (m/s)."""


def short_form_missing(f, speed):
    """The value at `f` (Hz)."""


class Base:
    def value(self, f):
        """A value.

        Parameters
        ----------
        f : float
            Frequency, Hz.
        """


class Override(Base):
    def value(self, f):
        """The override (parameters as in the base class)."""


class OverrideWithMore(Base):
    def value(self, f, g):
        """An override with a parameter the base does not document."""


@pytest.mark.parametrize(
    ("func", "missing"),
    [
        (documented, []),
        (one_missing, ["speed"]),
        (short_form, []),
        (short_form_missing, ["speed"]),
        (Override.value, []),
        (OverrideWithMore.value, ["f", "g"]),
    ],
    ids=lambda x: getattr(x, "__qualname__", str(x)),
)
def test_functions_follow_the_project_rule(func, missing):
    what = "method" if "." in func.__qualname__ else "function"
    assert sorted(ext.undocumented(what, func, _lines(func))) == missing


@dataclasses.dataclass(frozen=True)
class Declared:
    """A member whose fields are declared (unit, bounds, doc) and documented by that."""

    stiffness_n_per_m: float = parameter("N/m", "spring stiffness", gt=0.0)


@dataclasses.dataclass(frozen=True)
class WithAttributes:
    """A record.

    Attributes
    ----------
    x : float
        Position, m.
    """

    x: float
    _cache: object = None


@dataclasses.dataclass(frozen=True)
class Undocumented:
    """A record whose fields the docstring does not mention.

    It has two lines.
    """

    x: float
    y: float


class Described(pydantic.BaseModel):
    """A section."""

    speed_kmh: float = pydantic.Field(80.0, description="vehicle speed")


class NotDescribed(pydantic.BaseModel):
    """A section with a field nobody describes, and a second line.

    See above.
    """

    speed_kmh: float = 80.0


@pytest.mark.parametrize(
    ("cls", "missing"),
    [
        (Declared, []),
        (WithAttributes, []),
        (Undocumented, ["x", "y"]),
        (Described, []),
        (NotDescribed, ["speed_kmh"]),
    ],
    ids=lambda x: getattr(x, "__name__", str(x)),
)
def test_classes_document_their_fields(cls, missing):
    assert sorted(ext.undocumented("class", cls, _lines(cls))) == missing


def test_the_check_warns_so_that_the_build_fails(caplog):
    # Sphinx's -W turns every logged warning into an error; the check must log one
    with caplog.at_level("WARNING"):
        ext.check_docstring(None, "function", "one_missing", one_missing, {}, _lines(one_missing))
    assert "one_missing: undocumented parameter(s) speed" in caplog.text
