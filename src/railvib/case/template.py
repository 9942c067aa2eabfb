"""Render the fully commented default case from the schema and the default preset."""

from __future__ import annotations

from typing import Any

import tomli_w
from pydantic import BaseModel

from railvib.case.schema import Case
from railvib.presets import DEFAULT_PRESET, load_preset

__all__ = ["render_template"]


def _comment(info: Any) -> str:
    extra = info.json_schema_extra if isinstance(info.json_schema_extra, dict) else {}
    unit = extra.get("unit")
    doc = info.description or ""
    req = "" if info.is_required() else " (optional)"
    return f"# {doc}{f' [{unit}]' if unit else ''}{req}"


def _section(model: type[BaseModel], values: dict[str, Any], prefix: str) -> list[str]:
    lines: list[str] = []
    tables: list[tuple[str, Any, Any]] = []
    for name, info in model.model_fields.items():
        value = values.get(name)
        annotation = info.annotation
        if isinstance(annotation, type) and issubclass(annotation, BaseModel):
            tables.append((name, annotation, value or {}))
            continue
        if isinstance(value, dict):
            tables.append((name, None, value))
            lines.append(_comment(info))
            continue
        lines.append(_comment(info))
        if value is None:
            lines.append(f"# {name} = ...")
        else:
            lines.append(tomli_w.dumps({name: value}).strip())
    for name, sub_model, value in tables:
        header = f"{prefix}{name}"
        lines.append("")
        lines.append(f"[{header}]")
        if sub_model is not None:
            if sub_model.__doc__:
                lines.insert(len(lines) - 1, f"# {sub_model.__doc__.strip().splitlines()[0]}")
            lines.extend(_section(sub_model, value, f"{header}."))
        else:
            lines.extend(_free_table(value, header))
    return lines


def _free_table(value: dict[str, Any], header: str) -> list[str]:
    flat = {k: v for k, v in value.items() if not isinstance(v, dict)}
    lines = tomli_w.dumps(flat).strip().splitlines() if flat else []
    for k, v in value.items():
        if isinstance(v, dict):
            lines.append("")
            lines.append(f"[{header}.{k}]")
            lines.extend(_free_table(v, f"{header}.{k}"))
    return lines


def render_template(preset: str = DEFAULT_PRESET) -> str:
    """A complete, commented case file whose values are those of `preset`.

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
        "# [track.pad] models: spring_damper, hysteretic, log_linear, constant_phase,",
        "#   fractional_zener, generalized_maxwell, tabulated (see `railvib pad --help`).",
        "# [irregularity] types: fra, shitai, sato, german, chinese_hsr, combined, tabulated.",
        "",
    ]
    return "\n".join(head + _section(Case, load_preset(preset), "")) + "\n"
