"""The layering of docs/design/0004-architecture.md, checked on the source's imports.

Each top-level unit of the package (a subpackage or a module) has a layer; a unit
imports only units of lower layers, so there is no import cycle between units,
and no module-level cycle inside them. Imports inside functions are allowed only
in the CLI (which loads its commands lazily), for the plotting modules (which
import matplotlib) and for the heavy optional libraries of :data:`LAZY_LIBRARIES`
(so that ``import railvib`` and ``railvib run`` do not pay for what they do not
use), so that no dependency hides in a function body. The facade
``railvib/__init__.py`` loads its names on first use (:data:`railvib._FACADE`).
"""

from __future__ import annotations

import ast
import importlib
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src" / "railvib"

#: the layer of every unit (docs/design/0004-architecture.md, "Layers")
LAYERS = {
    "errors": 0,
    "docstrings": 0,
    "labels": 0,
    "units": 0,
    "jit": 0,
    "io": 1,
    "registry": 1,
    "response": 1,
    "grid": 1,
    "pem": 1,
    "stack": 1,
    "contact": 1,
    "pads": 2,
    "spectra": 2,
    "track": 3,
    "vehicle": 3,
    "coupling": 4,
    "coupled_kernel": 1,
    "presets": 5,
    "results": 5,
    "outputs": 5,
    "moving": 5,
    "case": 6,
    "plot": 7,
    "solve": 8,
    "trackrun": 8,
    "movingrun": 8,
    "padfit": 9,
    "models": 9,
    "testing": 9,
    "validation": 9,
    "sweep": 9,
    "reproduce": 9,
    "nonstationary": 9,
    "accessor": 8,
    "explore": 9,
    "cli": 10,
    "__init__": 10,
    "__main__": 11,
}


#: third-party modules that may be imported inside a function (outside cli/), and why:
#: each costs 0.1-0.3 s at start-up and is needed only by a few functions
LAZY_LIBRARIES = {
    "matplotlib": "figures: only code that draws",
    "scipy.optimize": "pad and WLF fitting only (railvib.pads.fit)",
    "scipy.sparse.linalg": "the finite-track reference model only (railvib.validation)",
    "distributed": "a sweep on a Dask cluster only (railvib.sweep.runner)",
    "dask.array": "lazy placeholders of a sweep's Zarr layout, only when assembling one",
    "zarr": "a sweep's Zarr store, written chunk by chunk, only when assembling one",
    "cupy": "stacked kernels on a GPU, only when backend='cupy' is asked for (railvib.stack)",
    "jax": "stacked kernels on JAX, only when backend='jax' is asked for (railvib.stack)",
    "numba": "the compiled kernels, only on a large stack or when asked for (railvib.jit for"
    " railvib.track.compiled, compiled_cells, moving_kernel and railvib.coupled_kernel)",
    "plotly": "the plotly.js text inlined in the reproduce report only (railvib.reproduce.report)",
    "bokeh": "the live explorer only (railvib.explore, the optional extra 'explore')",
}


def _unit(path: Path) -> str:
    rel = path.relative_to(SRC)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def _module(path: Path) -> str:
    rel = path.relative_to(SRC).with_suffix("")
    parts = ["railvib", *rel.parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _all_imports(path: Path) -> list[tuple[str, bool]]:
    """``(imported module, inside a function)`` of every absolute import in `path`."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out = []

    def visit(node: ast.AST, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and getattr(child.test, "id", "") == "TYPE_CHECKING":
                continue  # imports for type hints only: never run
            inner = in_function or isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef)
            if isinstance(child, ast.ImportFrom) and child.module and child.level == 0:
                if child.module == "railvib":
                    out.extend((f"railvib.{a.name}", inner) for a in child.names)
                else:
                    out.append((child.module, inner))
            elif isinstance(child, ast.Import):
                out.extend((a.name, inner) for a in child.names)
            visit(child, inner)

    visit(tree, False)
    return out


def _imports(path: Path) -> list[tuple[str, bool]]:
    """``(imported railvib module, inside a function)`` of every import in `path`."""
    return [(m, inner) for m, inner in _all_imports(path) if m.split(".")[0] == "railvib"]


SOURCES = [p for p in sorted(SRC.rglob("*.py")) if "data" not in p.relative_to(SRC).parts]


def test_every_unit_has_a_layer():
    assert {_unit(p) for p in SOURCES} == set(LAYERS)


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: str(p.relative_to(SRC)))
def test_units_import_only_lower_layers(path):
    here = _unit(path)
    for module, _ in _imports(path):
        target = module.split(".")[1] if "." in module else "__init__"
        if target == here:
            continue
        assert LAYERS[target] < LAYERS[here], f"{here} (layer {LAYERS[here]}) imports {module}"


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: str(p.relative_to(SRC)))
def test_no_hidden_imports_in_function_bodies(path):
    if _unit(path) == "cli":
        return  # the CLI loads its commands lazily, by design
    for module, inner in _imports(path):
        assert not inner or module.startswith("railvib.plot"), (
            f"{path.relative_to(SRC)} imports {module} inside a function; import it at the "
            "top (only plotting modules, which load matplotlib, may be imported lazily)"
        )


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: str(p.relative_to(SRC)))
def test_only_heavy_optional_libraries_are_imported_in_function_bodies(path):
    if _unit(path) == "cli":
        return  # the CLI loads its commands lazily, by design
    standard = set(sys.stdlib_module_names)
    for module, inner in _all_imports(path):
        top = module.split(".")[0]
        if not inner or top in ("railvib", *standard):
            continue
        assert any(module == lib or module.startswith(lib + ".") for lib in LAZY_LIBRARIES), (
            f"{path.relative_to(SRC)} imports {module} inside a function; import it at the "
            f"top, or add it to LAZY_LIBRARIES with the reason (a heavy optional library)"
        )


def test_the_facade_names_modules_of_lower_layers_that_define_them():
    import railvib

    facade = railvib._FACADE
    assert set(railvib.__all__) <= set(facade)
    for name, module in facade.items():
        target = module.split(".")[1]
        assert LAYERS[target] < LAYERS["__init__"], f"{name}: {module}"
        assert name in vars(importlib.import_module(module)), f"{module} defines no {name}"


def test_no_import_cycle_between_modules():
    """Module-level imports form no cycle (a package importing its own modules is fine)."""
    graph = {_module(p): {m for m, inner in _imports(p) if not inner} for p in SOURCES}
    done: set[str] = set()

    def walk(node: str, stack: list[str]) -> None:
        for target in sorted(graph.get(node, ())):
            if target not in graph or node.startswith(target + "."):
                continue  # not a module of ours, or a module's own package (run first)
            if target in stack:
                cycle = [*stack[stack.index(target) :], target]
                raise AssertionError(f"import cycle: {' -> '.join(cycle)}")
            if target not in done:
                walk(target, [*stack, target])
        done.add(node)

    for module in sorted(graph):
        if module not in done:
            walk(module, [module])
