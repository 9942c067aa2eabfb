"""Render the fully commented case file of a preset from the schema and the declarations."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel

from railvib.case.schema import FAMILY_TABLES, Case
from railvib.presets import DEFAULT_PRESET, load_preset
from railvib.registry import toml_line

__all__ = ["render_template"]


def _comment(info: Any) -> str:
    extra = info.json_schema_extra if isinstance(info.json_schema_extra, dict) else {}
    unit = extra.get("unit")
    doc = info.description or ""
    req = "" if info.is_required() else " (optional)"
    return f"# {doc}{f' [{unit}]' if unit else ''}{req}"


def _section(model: type[BaseModel], values: dict[str, Any], path: tuple[str, ...]) -> list[str]:
    """Lines of one section: its keys with comments, then its sub-tables.

    A key's comment is the line right above it; a sub-table's description is the
    line right above its ``[header]``.
    """
    lines: list[str] = []
    tables: list[list[str]] = []
    for name, info in model.model_fields.items():
        value = values.get(name)
        here = (*path, name)
        header = ".".join(here)
        annotation = info.annotation
        if here in FAMILY_TABLES and isinstance(value, dict):
            doc = (info.description or "").split(" (")[0]
            tables.append(FAMILY_TABLES[here].template_lines(value, header, doc))
        elif (section := _section_type(annotation)) is not None:
            head = [f"# {section.__doc__.strip().splitlines()[0]}"] if section.__doc__ else []
            body = [f"[{header}]", *_section(section, value or {}, here)]
            if value is None:  # an optional section the preset leaves out: shown commented
                body = [line if line.startswith("#") else f"# {line}" for line in body]
            tables.append([*head, *body])
        else:
            lines.append(_comment(info))
            lines.append(f"# {name} = ..." if value is None else toml_line(name, value))
    for table in tables:
        lines += ["", *table]
    return lines


def _section_type(annotation: Any) -> type[BaseModel] | None:
    """The section model of a field annotated ``Section`` or ``Section | None``."""
    for candidate in (annotation, *getattr(annotation, "__args__", ())):
        if isinstance(candidate, type) and issubclass(candidate, BaseModel):
            return candidate
    return None


def _families_header() -> list[str]:
    lines = []
    for location, family in FAMILY_TABLES.items():
        names = ", ".join(family.names())
        lines.append(f"# [{'.'.join(location)}] {family.tag}s: {names}.")
    return [*lines, "#   (`railvib models` lists every model with its keys and units.)"]


def render_template(preset: str = DEFAULT_PRESET) -> str:
    """A complete, commented case file whose values are those of `preset`.

    Every key carries its description and unit as a comment; the keys of the
    pad and irregularity tables come from the chosen models' declarations.

    Parameters
    ----------
    preset : str
        Name of the preset supplying the values.

    Returns
    -------
    str
        TOML text; ``railvib run`` accepts it as it is.
    """
    head = [
        "# railvib case file. Units: SI unless the key names its unit (speed_kmh, *_c = degC).",
        f"# Values below are those of preset {preset!r}. Instead of a full file you may write",
        f'#   preset = "{preset}"',
        "# and override only the keys you change.",
        *_families_header(),
        "",
    ]
    return "\n".join(head + _section(Case, load_preset(preset), ())) + "\n"
