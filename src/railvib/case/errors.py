"""The one conversion of pydantic validation errors into a field-named :class:`CaseError`.

Case files and sweep files are both validated by pydantic models; whichever
fails, the user reads one line ``field = value: what is allowed (unit)``.
"""

from __future__ import annotations

import re
from typing import Any

from pydantic import BaseModel, ValidationError

from railvib.errors import CaseError, did_you_mean

__all__ = ["case_error"]

_BOUNDS = {
    "greater_than": ">",
    "greater_than_equal": ">=",
    "less_than": "<",
    "less_than_equal": "<=",
}
_NUMBER_KINDS = ("float_parsing", "float_type", "int_parsing", "int_type", "int_from_float")


def case_error(exc: ValidationError, root: type[BaseModel] | None = None) -> CaseError:
    """The first error of `exc` as a one-line :class:`CaseError` with its dotted field.

    Parameters
    ----------
    exc : pydantic.ValidationError
        From validating a case, a sweep file or one of their sections.
    root : type, optional
        The model validated; its fields' ``json_schema_extra["unit"]`` gives the unit
        in the message and its fields the keys allowed next to an unknown one.

    Returns
    -------
    CaseError
        A CaseError raised inside a validator is kept (its field prefixed with the
        location where it is relative to it).
    """
    err = exc.errors()[0]
    loc = list(err["loc"])
    field = _dotted(loc)
    inner = (err.get("ctx") or {}).get("error")
    if isinstance(inner, CaseError):
        if field and not inner.field.startswith(field.split("[")[0].split(".")[0]):
            return CaseError(f"{field}.{inner.field}", inner.value, inner.allowed)
        return inner
    unit = _unit_of(root, loc)
    unit_txt = f" ({unit})" if unit else ""
    kind = err["type"]
    value = err.get("input")
    ctx = err.get("ctx") or {}
    field = field or "case"
    if kind == "missing":
        return CaseError(field, "<missing>", f"required{unit_txt}")
    if kind == "extra_forbidden":
        keys = sorted(getattr(_model_at(root, loc[:-1]), "model_fields", {}))
        allowed = f"; allowed here: {', '.join(keys)}" if keys else ""
        return CaseError(field, value, f"unknown key{allowed}{did_you_mean(loc[-1], keys)}")
    if kind in _BOUNDS:
        return CaseError(
            field, value, f"must be {_BOUNDS[kind]} {next(iter(ctx.values()))}{unit_txt}"
        )
    if kind == "too_long":
        return CaseError(
            field,
            f"<{ctx.get('actual_length', '?')} items>",
            f"at most {ctx.get('max_length')} items{unit_txt}",
        )
    if kind == "literal_error":
        expected = str(ctx.get("expected", ""))
        names = re.findall(r"'([^']*)'", expected)
        return CaseError(field, value, f"must be one of {expected}{did_you_mean(value, names)}")
    if kind in _NUMBER_KINDS:
        what = "an integer" if kind.startswith("int") else "a number"
        return CaseError(field, value, f"must be {what}{unit_txt}")
    return CaseError(field, value, err["msg"] + unit_txt)


def _dotted(loc: list[Any]) -> str:
    """``["axes", 0, "step"]`` -> ``"axes[0].step"``."""
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
    return out


def _model_at(root: Any, loc: list[Any]) -> Any:
    model = root
    for part in loc:
        if isinstance(part, int):
            continue
        fields = getattr(model, "model_fields", None)
        if not fields or part not in fields:
            return None
        model = fields[part].annotation
        args = getattr(model, "__args__", ())
        if args and not hasattr(model, "model_fields"):  # list[...] / X | None
            model = next((a for a in args if hasattr(a, "model_fields")), model)
    return model


def _unit_of(root: Any, loc: list[Any]) -> str:
    names = [p for p in loc if not isinstance(p, int)]
    if not names:
        return ""
    info = getattr(_model_at(root, names[:-1]), "model_fields", {}).get(names[-1])
    extra = getattr(info, "json_schema_extra", None) or {}
    return str(extra.get("unit", "")) if isinstance(extra, dict) else ""
