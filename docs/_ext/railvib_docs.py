"""The pages of the documentation site that are generated from the code when the build starts.

* ``families/<family>.md``: one page per model family (pads, spectra, tracks,
  vehicles, derived outputs and criteria), written by the family's own
  ``Registry.markdown`` from the members' declarations (keys, units, defaults,
  bounds), so a new model appears on the site without anyone editing a page;
* ``api/<unit>.rst``: the API reference, one page per unit of the library
  (``docs/design/0004-architecture.md``), each public name (a module's ``__all__``)
  documented once, in the module that defines it;
* ``cli.md``: every command's ``--help``;
* a check of every docstring the API reference shows (:func:`check_docstring`):
  an undocumented parameter or field is a warning, so the build (``-W``) fails;
* the page ``models`` (``docs/models.md``, the ``railvib models`` output kept for
  readers of the repository) becomes the index of the family pages on the site.

The generated folders are build products: they are rewritten at every build.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil
import re
import shutil
import sys
import types
from pathlib import Path
from typing import Any

import click
from numpydoc.docscrape import NumpyDocString
from sphinx.application import Sphinx
from sphinx.pycode import ModuleAnalyzer
from sphinx.util import logging

import railvib
from railvib.models import FAMILIES

LOGGER = logging.getLogger(__name__)

#: units of the library left out of the API reference, with the reason
API_EXCLUDED = {
    "railvib.cli": "the command line; its commands are on the page cli",
    "railvib.testing": "hypothesis strategies for railvib's own tests",
    "railvib.data": "generator scripts of the shipped example data",
}

FAMILY_TITLES = {
    "pad": "Pads (and frequency-dependent suspension elements)",
    "spectrum": "Irregularity spectra",
    "track": "Tracks",
    "vehicle": "Vehicles",
    "output": "Derived outputs and criteria",
}


def _write(path: Path, text: str) -> None:
    """Write `path` only when its text changed (Sphinx then rereads only what changed)."""
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _fresh_folder(path: Path, names: set[str]) -> None:
    """Create `path` and remove its files that are not in `names` (a member or unit removed)."""
    path.mkdir(exist_ok=True)
    for old in path.iterdir():
        if old.name not in names:
            shutil.rmtree(old) if old.is_dir() else old.unlink()


# -- model families -----------------------------------------------------------------------


def family_pages(srcdir: Path) -> None:
    """``families/<name>.md`` for every family of :data:`railvib.models.FAMILIES`."""
    folder = srcdir / "families"
    _fresh_folder(folder, {f"{name}.md" for name in FAMILIES})
    for name, registry in FAMILIES.items():
        body = registry.markdown().split("\n", 1)[1]  # its "## ..." heading becomes the title
        intro = (
            f"# {FAMILY_TITLES.get(name, registry.plural.capitalize())}\n\n"
            f"Generated from the declarations of the `{name}` family "
            f"(`railvib models {name}` prints the same tables). Every key with its unit, "
            "default and allowed values; a case file outside these bounds is refused "
            "with the field named.\n"
        )
        _write(folder / f"{name}.md", intro + body.replace("\n### ", "\n## "))


def models_index() -> str:
    """The page ``models`` on the site: the family pages."""
    items = "\n".join(f"families/{name}" for name in FAMILIES)
    links = "\n".join(
        f"* [{FAMILY_TITLES.get(name, name)}](families/{name}.md): "
        + ", ".join(f"`{m}`" for m in registry.names())
        for name, registry in FAMILIES.items()
    )
    return (
        "# Models\n\n"
        "Every model railvib can build from a case file, one page per family, generated "
        "from the models' own declarations when this site is built (`railvib models` "
        "prints the same tables). How to add a model: [extending railvib](extending.md).\n\n"
        f"{links}\n\n"
        f"```{{toctree}}\n:hidden:\n\n{items}\n```\n"
    )


def _replace_models_page(app: Sphinx, docname: str, source: list[str]) -> None:
    if docname == "models":
        source[0] = models_index()


# -- API reference ------------------------------------------------------------------------


def _modules() -> list[Any]:
    names = ["railvib"] + [
        info.name
        for info in pkgutil.walk_packages(railvib.__path__, "railvib.")
        if not any(info.name == ex or info.name.startswith(ex + ".") for ex in API_EXCLUDED)
    ]
    return [importlib.import_module(name) for name in sorted(names)]


def _canonical(modules: list[Any]) -> dict[str, list[tuple[str, str]]]:
    """The (directive, name) of each public object, by the module that documents it.

    A function or class is documented in the module that defines it, other
    objects (registries, constants) in the deepest module listing them in
    ``__all__``, so every object has one place and every reference one target.
    """
    home: dict[int, tuple[str, str, str]] = {}
    for module in modules:
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name)
            if (inspect.isclass(obj) and not isinstance(obj, types.GenericAlias)) or (
                inspect.isfunction(obj)
            ):
                where = obj.__module__
                if not where.startswith("railvib") or where == "railvib":
                    continue
                if getattr(sys.modules[where], obj.__name__, None) is not obj:
                    where = module.__name__  # made by a factory (a pydantic section model)
                kind = "autoclass" if inspect.isclass(obj) else "autofunction"
                home[id(obj)] = (where, kind, obj.__name__)
            elif inspect.ismodule(obj):
                continue
            elif id(obj) not in home or module.__name__.count(".") > home[id(obj)][0].count("."):
                home[id(obj)] = (module.__name__, "autodata", name)
    out: dict[str, list[tuple[str, str]]] = {}
    for where, kind, name in home.values():
        out.setdefault(where, []).append((kind, name))
    return out


def _unit(name: str) -> str:
    return ".".join(name.split(".")[:2])


def api_pages(srcdir: Path) -> None:
    """``api/index.rst`` and ``api/<unit>.rst``: every module's public names."""
    modules = _modules()
    members = _canonical(modules)
    units: dict[str, list[Any]] = {}
    for module in modules:
        if module.__name__ != "railvib":
            units.setdefault(_unit(module.__name__), []).append(module)
    folder = srcdir / "api"
    _fresh_folder(folder, {"index.rst"} | {f"{u}.rst" for u in units})
    for unit, mods in units.items():
        lines = [unit, "=" * len(unit), ""]
        for module in mods:
            if module.__name__ != unit:
                lines += [module.__name__, "-" * len(module.__name__), ""]
            lines += [f".. automodule:: {module.__name__}", "   :no-members:", ""]
            for kind, name in sorted(members.get(module.__name__, []), key=lambda m: m[1]):
                if isinstance(getattr(module, name), types.GenericAlias):
                    lines += _type_alias(module.__name__, name)
                    continue
                lines += [f".. {kind}:: {module.__name__}.{name}"]
                lines += ["   :members:"] if kind == "autoclass" else []
                lines += ["   :no-value:"] if kind == "autodata" else []
                lines += [""]
        _write(folder / f"{unit}.rst", "\n".join(lines))
    facade = [
        f"* :py:obj:`railvib.{name} <{_home_of(getattr(railvib, name), members, name)}>`"
        for name in railvib.__all__
    ]
    index = [
        "API reference",
        "=============",
        "",
        ".. automodule:: railvib",
        "   :no-members:",
        "",
        "The names of the facade ``railvib`` (each loaded from its module on first use):",
        "",
        *facade,
        "",
        "Every unit of the library, in the order of its layers is in "
        ":doc:`../design/0004-architecture`; excluded here: "
        + "; ".join(f"``{m}`` ({why})" for m, why in API_EXCLUDED.items())
        + ".",
        "",
        ".. toctree::",
        "   :maxdepth: 1",
        "",
        *[f"   {unit}" for unit in units],
        "",
    ]
    _write(folder / "index.rst", "\n".join(index))


def _type_alias(module: str, name: str) -> list[str]:
    """A type alias (``tuple[...]``) with its ``#:`` comment: autodoc fails on its signature."""
    doc = ModuleAnalyzer.for_module(module).find_attr_docs().get(("", name), [])
    return [f".. py:data:: {module}.{name}", "", *[f"   {line}" for line in doc], ""]


def _home_of(obj: Any, members: dict[str, list[tuple[str, str]]], name: str) -> str:
    for where, entries in members.items():
        if any(n == getattr(obj, "__name__", name) for _, n in entries) and (
            getattr(importlib.import_module(where), getattr(obj, "__name__", name), None) is obj
        ):
            return f"{where}.{getattr(obj, '__name__', name)}"
    raise LookupError(f"railvib.{name} is documented nowhere")


def _signature_names(obj: Any) -> list[str]:
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    return [
        p.name
        for p in sig.parameters.values()
        if p.name not in ("self", "cls") and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
    ]


def _fields(cls: type) -> list[str]:
    """Fields of a dataclass or pydantic model that no declaration documents."""
    if dataclasses.is_dataclass(cls):
        return [
            f.name
            for f in dataclasses.fields(cls)
            if f.init and not f.name.startswith("_") and "railvib" not in f.metadata
        ]
    model_fields = getattr(cls, "model_fields", None)
    if isinstance(model_fields, dict):  # pydantic: a field's description documents it
        return [name for name, info in model_fields.items() if not info.description]
    return []


def undocumented(what: str, obj: Any, lines: list[str]) -> list[str]:
    """Parameters of `obj` its docstring `lines` does not describe.

    The project's rule (``tests/unit/test_docstrings.py``): a function documents each
    parameter in its Parameters section, unless its docstring is one line naming every
    parameter or it overrides a documented method with the same parameters; a
    dataclass or pydantic model documents each field in Parameters or Attributes, by
    its declaration (``railvib.registry.parameter``, a pydantic description) or in a
    one-line docstring naming it.

    Parameters
    ----------
    what : str
        The kind of object autodoc documents (``"function"``, ``"class"``, ...).
    obj : Any
        The object.
    lines : list of str
        Its docstring, as autodoc gives it.

    Returns
    -------
    list of str
        The names left undocumented.
    """
    text = "\n".join(lines)
    doc = NumpyDocString(text)
    named = {
        n.strip().lstrip("*")
        for section in ("Parameters", "Other Parameters", "Attributes")
        for item in doc[section]
        for n in item.name.split(",")
    }
    if what == "class":
        names = _fields(obj) if "Parameters" not in text else _signature_names(obj)
    elif what in ("function", "method"):
        names = [] if "Parameters" not in text and _inherits_docs(obj) else _signature_names(obj)
    else:
        names = []
    if len(text.strip().splitlines()) <= 1:  # the one-line form names each parameter
        names = [n for n in names if not re.search(rf"`{n}`|\b{n}\b", text)]
    return [n for n in names if n not in named]


def _inherits_docs(func: Any) -> bool:
    """Whether `func` overrides a method of a base class that documents the same parameters."""
    owner_name, _, name = func.__qualname__.rpartition(".")
    owner = getattr(importlib.import_module(func.__module__), owner_name, None)
    for base in getattr(owner, "__mro__", ())[1:]:
        parent = inspect.getattr_static(base, name, None)
        parent = getattr(parent, "__func__", parent)
        if callable(parent) and "Parameters" in (inspect.getdoc(parent) or ""):
            return _signature_names(parent) == _signature_names(func)
    return False


def check_docstring(
    app: Sphinx, what: str, name: str, obj: Any, options: Any, lines: list[str]
) -> None:
    """Warn (so ``-W`` fails the build) about a parameter the docstring of `name` leaves out."""
    missing = undocumented(what, obj, lines)
    if missing:
        LOGGER.warning("%s: undocumented parameter(s) %s", name, ", ".join(missing), type="railvib")


# -- command line -------------------------------------------------------------------------


def _commands(group: click.Command, path: list[str]) -> list[tuple[list[str], click.Command]]:
    out = [(path, group)]
    if isinstance(group, click.Group):
        for name in sorted(group.list_commands(click.Context(group))):
            sub = group.get_command(click.Context(group), name)
            if sub is not None and not sub.hidden:
                out += _commands(sub, [*path, name])
    return out


def cli_page(srcdir: Path) -> None:
    """``cli.md``: the ``--help`` of every command."""
    from railvib.cli.main import cli  # here: importing it installs the CLI's Ctrl-C hook

    parts = [
        "# Command line\n\n"
        "Every command's `--help` (generated when this site is built). Bad input is one "
        "`error:` line naming the field, exit code 2, nothing written; exit codes are listed "
        "in `CONVENTIONS.md`.\n"
    ]
    for path, command in _commands(cli, ["railvib"]):
        with click.Context(command, info_name=" ".join(path)) as ctx:
            text = command.get_help(ctx)
        parts.append(f"## `{' '.join(path)}`\n\n```text\n{text}\n```\n")
    _write(srcdir / "cli.md", "\n".join(parts))


def _generate(app: Sphinx) -> None:
    srcdir = Path(app.srcdir)
    family_pages(srcdir)
    api_pages(srcdir)
    cli_page(srcdir)


def setup(app: Sphinx) -> dict[str, Any]:
    """Register the generators with Sphinx."""
    app.connect("builder-inited", _generate)
    app.connect("source-read", _replace_models_page)
    app.connect("autodoc-process-docstring", check_docstring, priority=400)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
