"""Every public function documents each of its parameters, and numeric ones with their unit.

Public means listed in a module's ``__all__``. Parsed with numpydoc's own parser
(python-control's ``docstrings_test.py`` is the model). A numeric parameter
(annotated float, int, ArrayLike or an array) must name its unit in its type or
description, say it is dimensionless, or be a count, an index, a seed, a switch
or a tolerance, recognised by its name.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

import pytest
from numpydoc.docscrape import FunctionDoc

import railvib

#: words that name a unit (or say there is none) in a parameter's description
UNIT = re.compile(
    r"\b(Hz|rad|m|s|kg|N|K|degC|km/h|m/s|N/m|N s/m|m/N|[Dd]imensionless|decades?|Celsius)\b"
    r"|\(-\)|m\^2|1/K|kg m|N m\^2|kN/mm|unit"
)
#: parameter names that are counts, indices, seeds, switches or tolerances (no unit)
UNITLESS_NAME = re.compile(
    r"^(n|n_.*|.*_count|index|chunk_id|seed|realisations|workers|decimation|chunk|repeat|"
    r"dpi|width|depth|max_examples|.*_spans|elements_per_span|n_terms|n_points|batch|"
    r"confidence|loss_weight|factor|tol|rtol|atol|percent|style)$"
)
NUMERIC = ("float", "ArrayLike", "NDArray", "ndarray", "FloatOrArray")


def _public_functions():
    seen = set()
    for info in pkgutil.walk_packages(railvib.__path__, "railvib."):
        if ".data." in info.name:
            continue
        module = importlib.import_module(info.name)
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name, None)
            obj = inspect.unwrap(obj) if callable(obj) and hasattr(obj, "__wrapped__") else obj
            targets = []
            if inspect.isfunction(obj):
                targets.append((f"{obj.__module__}.{obj.__qualname__}", obj))
            elif inspect.isclass(obj) and obj.__module__.startswith("railvib"):
                for meth_name, meth in vars(obj).items():
                    func = meth.__func__ if isinstance(meth, classmethod | staticmethod) else meth
                    if inspect.isfunction(func) and not meth_name.startswith("_"):
                        targets.append((f"{obj.__module__}.{obj.__qualname__}.{meth_name}", func))
            for qualname, func in targets:
                if func.__module__.startswith("railvib") and qualname not in seen:
                    seen.add(qualname)
                    yield qualname, func


FUNCTIONS = sorted(_public_functions())


def _parameters(func):
    sig = inspect.signature(func)
    return [
        p
        for p in sig.parameters.values()
        if p.name not in ("self", "cls") and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
    ]


def _needs_docs(func) -> bool:
    """Functions with parameters beyond self (a one-line docstring suffices otherwise)."""
    return bool(_parameters(func))


@pytest.mark.parametrize(("qualname", "func"), FUNCTIONS, ids=[q for q, _ in FUNCTIONS])
def test_public_function_documents_its_parameters_with_units(qualname, func):
    assert func.__doc__, f"{qualname} has no docstring"
    func = _documented(func)
    if not _needs_docs(func) or _is_short_form(func):
        return
    doc = FunctionDoc(func)
    documented = {}
    for item in doc["Parameters"]:
        for name in item.name.split(","):
            documented[name.strip().lstrip("*")] = f"{item.type} {' '.join(item.desc)}"
    for p in _parameters(func):
        assert p.name in documented, f"{qualname}: parameter {p.name!r} is not documented"
        annotation = str(p.annotation)
        integers = "of int" in documented[p.name] or "int" == annotation.split(" ")[0]
        if (
            any(t in annotation for t in NUMERIC)
            and not UNITLESS_NAME.match(p.name)
            and not integers
        ):
            assert UNIT.search(documented[p.name]) or "bool" in annotation, (
                f"{qualname}: numeric parameter {p.name!r} gives no unit ({documented[p.name]!r})"
            )


def _documented(func):
    """The method whose docstring documents `func`: itself, or the base-class method it overrides.

    An override that adds no parameter keeps the base class's parameter docs (the
    numpydoc convention), e.g. every pad's ``stiffness(f, temperature)``.
    """
    owner = _owner(func)
    if owner is None or "Parameters" in (inspect.getdoc(func) or ""):
        return func
    for base in owner.__mro__[1:]:
        parent = vars(base).get(func.__name__)
        parent = parent.__func__ if isinstance(parent, classmethod | staticmethod) else parent
        if inspect.isfunction(parent) and "Parameters" in (inspect.getdoc(parent) or ""):
            same = [p.name for p in _parameters(parent)] == [p.name for p in _parameters(func)]
            return parent if same else func
    return func


def _owner(func):
    module = importlib.import_module(func.__module__)
    owner_name = func.__qualname__.rpartition(".")[0]
    return getattr(module, owner_name, None) if owner_name and "." not in owner_name else None


def _is_short_form(func) -> bool:
    """A one-line docstring naming every parameter with its unit in the sentence itself.

    Allowed for small helpers, e.g. ``kmh_to_ms``: "Convert km/h to m/s."; their
    parameters must still appear in the line (checked here).
    """
    text = inspect.getdoc(func) or ""
    if "Parameters" in text:
        return False
    one_line = len(text.strip().splitlines()) == 1
    names = [p.name for p in _parameters(func)]
    return one_line and all(re.search(rf"`{re.escape(n)}`|\b{re.escape(n)}\b", text) for n in names)


def test_the_parser_sees_something():
    assert len(FUNCTIONS) > 100
