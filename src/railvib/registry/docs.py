"""The documentation of a family from its declarations: case-template lines and Markdown tables."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import tomli_w

from railvib.registry.parameters import Parameter, declared_parameters

if TYPE_CHECKING:
    from railvib.registry.family import Registry

__all__ = ["markdown", "template_lines", "toml_line"]


def toml_line(key: str, value: Any) -> str:
    """``key = value`` on one line, arrays inline (``rms_bands = [[0.5, 20.0], [20.0, 100.0]]``).

    Parameters
    ----------
    key : str
        The TOML key.
    value : Any
        A TOML value (numbers, text, booleans, arrays of them; no tables).

    Returns
    -------
    str
        One TOML line.
    """
    return f"{key} = {_inline(value)}"


def _inline(value: Any) -> str:
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_inline(v) for v in value) + "]"
    return tomli_w.dumps({"x": value}).strip().removeprefix("x = ")


def template_lines(
    registry: Registry[Any], d: Mapping[str, Any], header: str, doc: str = ""
) -> list[str]:
    """Lines of a commented TOML table for `d` under ``[header]`` (nested tables follow).

    Every comment stands right above what it documents: the table's description above
    ``[header]``, each key's description and unit above the key. Optional keys that
    `d` leaves out are shown commented out with their default, so every key of the
    chosen member is documented.

    Parameters
    ----------
    registry : Registry
        The family of the table.
    d : mapping
        The table (its keys are written with their declared documentation and unit).
    header : str
        Dotted name of the table, e.g. ``"track.pad"``.
    doc : str
        What the table is for (the declaring field's description), put first above
        the header; empty: the family's name.

    Returns
    -------
    list of str
        TOML lines with ``#`` comments.
    """
    member = registry.get(d[registry.tag])
    others = [n for n in registry.names() if n != member.name]
    absent = [
        f"# (an optional [{header}.{key}] table: {', '.join(p.key for p in params)})"
        for key, (params, _) in registry.extra_tables.items()
        if not isinstance(d.get(key), Mapping)
    ]
    lines = [
        f"# {doc or registry.family}: {member.doc}",
        *absent,
        f"[{header}]",
        f"# the {registry.family}; others: {', '.join(others)} (`railvib models`)",
        toml_line(registry.tag, member.name),
    ]
    nested: list[str] = []
    for p in member.parameters:
        if p.kind == "member":
            assert p.family is not None, "a member parameter names its family"
            if p.key in d:
                unit = f" [{p.unit}]" if p.unit not in ("", "-") else ""
                sub = f"{header}.{p.key}"
                nested += ["", *template_lines(p.family, d[p.key], sub, f"{p.doc}{unit}")]
            continue
        lines.append(f"# {_comment(p)}")
        if p.key in d:
            lines.append(toml_line(p.key, d[p.key]))
        else:
            shown = "..." if p.default is None else _inline(p.default)
            lines.append(f"# {p.key} = {shown}")
    for key, (params, _) in registry.extra_tables.items():
        if isinstance(d.get(key), Mapping):
            nested += ["", f"# optional table of any {registry.family}", f"[{header}.{key}]"]
            for p in params:
                if p.key in d[key]:
                    nested += [f"# {_comment(p)}", toml_line(p.key, d[key][p.key])]
    return lines + nested


def markdown(registry: Registry[Any]) -> str:
    """A Markdown section per member of `registry`: its description and a table of its keys.

    Parameters
    ----------
    registry : Registry
        The family.

    Returns
    -------
    str
        Markdown text.
    """
    where = [f"`{registry.where}`"] if registry.where else []
    where += [f"`{registry.tag} = ...`"] if registry.tagged else []
    out = [f"## {registry.plural.capitalize()}" + (f" ({', '.join(where)})" if where else ""), ""]
    for member in registry:
        alias = f" (alias {', '.join(f'`{a}`' for a in member.aliases)})" if member.aliases else ""
        out += [f"### `{member.name}`{alias}", "", member.doc, ""]
        out += _parameter_table(member.parameters)
        for p in member.parameters:
            if p.kind == "table" and p.table is not None:
                out += [f"Keys of its `{p.key}` table:", ""]
                out += _parameter_table(declared_parameters(p.table))
    for key, (params, _) in registry.extra_tables.items():
        out += [f"### Optional `[...{key}]` table of any {registry.family}", ""]
        out += _parameter_table(params)
    return "\n".join(out)


def _toml_value(value: Any) -> str:
    """`value` as written in a TOML file (``true``, ``"low"``, ``5.0``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    return repr(value)


def _comment(p: Parameter) -> str:
    unit = f" [{p.unit}]" if p.unit not in ("", "-") else ""
    default = "" if p.required else f" (optional, default {_toml_value(p.default)})"
    return f"{p.doc}{unit}{default}"


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def _parameter_table(params: Sequence[Parameter]) -> list[str]:
    if not params:
        return ["No parameters.", ""]
    rows = ["| key | unit | default | allowed | meaning |", "|---|---|---|---|---|"]
    for p in params:
        if p.required:
            default = "required"
        elif p.default is None:
            default = "omitted"
        else:
            default = f"`{_toml_value(p.default)}`"
        tables = {
            "member": f"table: any {p.family.family if p.family else 'model'}",
            "table": "table (keys below)",
        }
        allowed = tables.get(p.kind) or p.describe_allowed(with_unit=False)
        cells = (f"`{p.key}`", p.unit or "-", default, allowed, p.doc)
        rows.append("| " + " | ".join(_cell(c) for c in cells) + " |")
    return [*rows, ""]
