"""Case-file sections generated from a family member's declared parameters.

A section such as ``[vehicle]`` or ``[track]`` is a pydantic model whose fields,
units, bounds and descriptions come from the member's declarations
(:class:`railvib.registry.Parameter`), so a parameter is declared once, next to
the physics that uses it. A nested fixed table (``[track.rail]``) is a nested
section; a family table (``[track.pad]``) is a free table validated by its
family when the case is loaded.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, create_model, model_validator

from railvib.registry import Parameter, declared_parameters

__all__ = ["Section", "section_model", "table_section"]


class Section(BaseModel):
    """Base of every case section: unknown keys are refused, values are frozen."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=False)


_PYTHON_TYPES: dict[str, Any] = {
    "number": float,
    "integer": int,
    "boolean": bool,
    "text": str,
    "path": str,
    "numbers": list[float],
    "tables": list[dict[str, Any]],
}


def _annotation(p: Parameter) -> Any:
    if p.kind == "member":
        return dict[str, Any]
    if p.kind == "table":
        assert p.table is not None, "a table parameter names its dataclass"
        return table_section(p.table)
    if p.choices is not None:
        return Literal[p.choices]
    base = _PYTHON_TYPES[p.kind]
    return base | None if p.default is None else base


def _field(p: Parameter) -> Any:
    description = p.doc
    if p.kind == "member":
        assert p.family is not None, "a member parameter names its family"
        description += f" ({p.family.tag} = <name>: `railvib models`)"
    extra: dict[str, Any] = (
        {"unit": p.unit} if p.unit not in ("", "-") or p.kind == "number" else {}
    )
    bounds = {"gt": p.gt, "ge": p.ge, "lt": p.lt, "le": p.le}
    kw: dict[str, Any] = {k: v for k, v in bounds.items() if v is not None and p.kind == "number"}
    default = ... if p.required else p.default
    return Field(default, description=description, json_schema_extra=extra or None, **kw)


def section_model(
    name: str,
    parameters: Sequence[Parameter],
    doc: str | None,
    build: Callable[..., Any] | None = None,
) -> type[Section]:
    """A pydantic section with one field per declared parameter.

    Parameters
    ----------
    name : str
        Class name of the section.
    parameters : sequence of Parameter
        Its keys.
    doc : str, optional
        Docstring (its first line heads the section in the case template).
    build : callable, optional
        Called with the validated values after validation, so the member's own
        checks between parameters (raising :class:`~railvib.errors.CaseError`) run
        when the case is loaded.

    Returns
    -------
    type
        A subclass of :class:`Section`.
    """
    fields = {p.key: (_annotation(p), _field(p)) for p in parameters}
    validators: dict[str, Any] = {}
    if build is not None:

        def _check(self: Section) -> Section:
            values = {
                p.name: getattr(self, p.key)
                for p in parameters
                if p.kind not in ("member", "table") and getattr(self, p.key) is not None
            }
            values.update(
                {
                    p.name: _table_value(p, getattr(self, p.key))
                    for p in parameters
                    if p.kind == "table"
                }
            )
            build(**values)
            return self

        validators["_check_member"] = model_validator(mode="after")(_check)
    model = create_model(name, __base__=Section, __validators__=validators, **fields)  # type: ignore[call-overload]
    model.__doc__ = (doc or "").strip() or name
    return model


@functools.cache
def table_section(cls: type) -> type[Section]:
    """The section of a fixed nested table: one field per declared field of dataclass `cls`."""
    return section_model(f"{cls.__name__}Section", declared_parameters(cls), cls.__doc__, cls)


def _table_value(p: Parameter, section: Section) -> Any:
    """The dataclass of a nested table section (already checked by its own validator)."""
    assert p.table is not None, "a table parameter names its dataclass"
    return p.table(**section.model_dump())
