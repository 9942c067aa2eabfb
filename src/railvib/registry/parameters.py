"""Declared parameters: what a family member's table holds, and the checks derived from it."""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, TypeVar

import numpy as np

from railvib.errors import CaseError, did_you_mean

if TYPE_CHECKING:
    from railvib.registry.family import Registry

__all__ = [
    "REQUIRED",
    "Kind",
    "Parameter",
    "check_parameters",
    "check_value",
    "declared_parameters",
    "parameter",
    "take_table",
]

T = TypeVar("T")

Kind = Literal[
    "number", "integer", "boolean", "text", "numbers", "path", "member", "table", "tables"
]


class _Required:
    """Marker of a parameter without a default."""

    def __repr__(self) -> str:
        return "REQUIRED"


#: the default of a parameter that must be given
REQUIRED: Any = _Required()

_ANNOTATION_KINDS: dict[str, Kind] = {
    "float": "number",
    "int": "integer",
    "bool": "boolean",
    "str": "text",
    "tuple[float,...]": "numbers",
}
_OPS = (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<="))


@dataclass(frozen=True)
class Parameter:
    """The declaration of one parameter of a family member.

    Parameters
    ----------
    key : str
        Name in case-file tables, carrying its unit where not obvious (``stiffness_n_per_m``).
    unit : str
        Unit of the value (``"-"`` for dimensionless, ``""`` where none applies).
    doc : str
        One line of documentation.
    kind : str
        ``number`` (finite float), ``integer``, ``boolean``, ``text``, ``numbers``
        (tuple of finite floats), ``path`` (file, resolved relative to the case
        file), ``member`` (a nested table of family `family`), ``table`` (a nested
        table of the fixed dataclass `table`) or ``tables`` (a list of tables the
        member checks itself, e.g. a vehicle's ``[[bodies]]``).
    default : object
        Value when the key is omitted; :data:`REQUIRED` when it must be given.
    gt, ge, lt, le : float, optional
        Bounds of a number (of each element of ``numbers``).
    choices : tuple, optional
        The values allowed (``integer`` and ``text``).
    allowed : str, optional
        Text used in errors instead of the one built from bounds and choices.
    typical : (float, float), optional
        A plausible range (hypothesis strategies, docs); sampled log-uniformly when
        `log` is true.
    log : bool
        The plausible range spans decades.
    attr : str, optional
        Attribute and constructor argument, when it differs from `key`.
    family : Registry, optional
        Family of a ``member`` parameter.
    table : type, optional
        Dataclass of a ``table`` parameter (its fields declared with :func:`parameter`).
    """

    key: str
    unit: str
    doc: str
    kind: Kind = "number"
    default: Any = REQUIRED
    gt: float | None = None
    ge: float | None = None
    lt: float | None = None
    le: float | None = None
    choices: tuple[Any, ...] | None = None
    allowed: str | None = None
    typical: tuple[float, float] | None = None
    log: bool = False
    attr: str | None = None
    family: Registry[Any] | None = field(default=None, repr=False, compare=False)
    table: type | None = field(default=None, repr=False, compare=False)

    @property
    def name(self) -> str:
        """Attribute and constructor argument name."""
        return self.attr or self.key

    @property
    def required(self) -> bool:
        """Whether the key must be given."""
        return self.default is REQUIRED

    @property
    def bounds(self) -> list[tuple[str, float]]:
        """``(operator, bound)`` pairs, e.g. ``[(">", 0.0)]``."""
        return [(op, float(getattr(self, a))) for a, op in _OPS if getattr(self, a) is not None]

    def describe_allowed(self, with_unit: bool = True) -> str:
        """What the parameter accepts, in words (bounds, choices and, if asked, the unit).

        Parameters
        ----------
        with_unit : bool
            Append the unit in parentheses (not for dimensionless ``"-"`` or unitless
            parameters).

        Returns
        -------
        str
            `allowed` if given, else e.g. ``"> 0.0 (N/m)"`` or ``"one of 'a', 'b'"``.
        """
        if self.allowed is not None:
            return self.allowed
        unit = f" ({self.unit})" if with_unit and self.unit and self.unit != "-" else ""
        if self.choices is not None:
            return "one of " + ", ".join(repr(c) for c in self.choices) + unit
        if self.kind == "boolean":
            return "true or false"
        if self.kind in ("text", "path", "tables"):
            return {"text": "text", "path": "a file path", "tables": "a list of tables"}[self.kind]
        parts = [f"{op} {_number(bound)}" for op, bound in self.bounds]
        return (" and ".join(parts) or "any finite value") + unit


def parameter(
    unit: str,
    doc: str,
    *,
    default: Any = REQUIRED,
    kind: Kind | None = None,
    key: str | None = None,
    gt: float | None = None,
    ge: float | None = None,
    lt: float | None = None,
    le: float | None = None,
    choices: tuple[Any, ...] | None = None,
    allowed: str | None = None,
    typical: tuple[float, float] | None = None,
    log: bool = False,
    family: Registry[Any] | None = None,
    table: type | None = None,
) -> Any:
    """Declare a dataclass field as a member parameter (see :class:`Parameter`).

    Use it as the field's default: ``stiffness_n_per_m: float = parameter("N/m", "k", gt=0)``.
    The kind follows from the annotation (``float``, ``int``, ``bool``, ``str``,
    ``tuple[float, ...]``) unless given; the key is the field name unless given.

    Parameters
    ----------
    unit : str
        Unit of the value (``"-"`` for dimensionless, ``""`` where none applies).
    doc : str
        One line of documentation.
    default : object
        Value when the key is omitted; :data:`REQUIRED` (the default) when it must be given.
    kind : str, optional
        The kind of value (see :class:`Parameter`); None derives it from the annotation.
    key : str, optional
        Name in case-file tables; None uses the field name.
    gt, ge, lt, le : float, optional
        Bounds of a number (of each element of ``numbers``), in the parameter's `unit`.
    choices : tuple, optional
        The values allowed (``integer`` and ``text``).
    allowed : str, optional
        Text used in errors instead of the one built from bounds and choices.
    typical : (float, float), optional
        A plausible range in the parameter's `unit` (hypothesis strategies, docs);
        sampled log-uniformly when `log` is true.
    log : bool
        The plausible range spans decades.
    family : Registry, optional
        Family of a ``member`` parameter.
    table : type, optional
        Dataclass of a ``table`` parameter (its fields declared with :func:`parameter`).

    Returns
    -------
    dataclasses.Field
        The field, with the declaration in its metadata.
    """
    spec = {
        "unit": unit,
        "doc": doc,
        "kind": kind,
        "key": key,
        "gt": gt,
        "ge": ge,
        "lt": lt,
        "le": le,
        "choices": choices,
        "allowed": allowed,
        "typical": typical,
        "log": log,
        "family": family,
        "table": table,
    }
    metadata = {"railvib": spec}
    if default is REQUIRED:
        return dataclasses.field(metadata=metadata)
    return dataclasses.field(default=default, metadata=metadata)


def declared_parameters(cls: type) -> tuple[Parameter, ...]:
    """The parameters declared on the dataclass fields of `cls`, in field order (cached).

    Parameters
    ----------
    cls : type
        A dataclass whose fields are declared with :func:`parameter`.

    Returns
    -------
    tuple of Parameter
        One per declared field.
    """
    return _declared_parameters(cls)


@functools.cache
def _declared_parameters(cls: Any) -> tuple[Parameter, ...]:
    """See :func:`declared_parameters` (the cache)."""
    out = []
    for f in dataclasses.fields(cls):
        spec = f.metadata.get("railvib")
        if spec is None:
            continue
        annotation = f.type.__name__ if isinstance(f.type, type) else str(f.type)
        annotation = annotation.replace(" ", "").removesuffix("|None")
        kind = spec["kind"] or _ANNOTATION_KINDS.get(annotation)
        if kind is None:
            raise TypeError(f"{cls.__name__}.{f.name}: give kind= (annotation {f.type!r})")
        default = REQUIRED if f.default is dataclasses.MISSING else f.default
        key = spec["key"] or f.name
        values = {k: v for k, v in spec.items() if k not in ("kind", "key")}
        out.append(Parameter(key=key, kind=kind, default=default, attr=f.name, **values))
    return tuple(out)


# --------------------------------------------------------------------- value checks


def _number(x: float) -> str:
    """A bound as written in messages: ``0.0``, ``3.0``, ``1e+15`` (not ``1000000000000000.0``)."""
    text = repr(x)
    return text if len(text) <= 10 else f"{x:.6g}"


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(
        value, bool | np.bool_
    )


def _in_bounds(p: Parameter, x: float) -> bool:
    ok = math.isfinite(x)
    for attr, _ in _OPS:
        bound = getattr(p, attr)
        if bound is None:
            continue
        ok = ok and {"gt": x > bound, "ge": x >= bound, "lt": x < bound, "le": x <= bound}[attr]
    return ok


def _bad(p: Parameter, where: str, value: Any, style: str, type_error: bool) -> CaseError:
    """The error for `value` of `p`: ``must be > 0.0 (N/m)`` or ``a finite number > 0.0 (N/m)``."""
    if p.allowed is not None:
        return CaseError(where, value, p.allowed)
    if p.kind not in ("number", "numbers"):
        text = p.describe_allowed()
        return CaseError(where, value, f"must be {text}" if style == "must" else text)
    unit = f"({p.unit})" if p.unit not in ("", "-") else ""
    limits = " ".join(
        x for x in (" and ".join(f"{o} {_number(b)}" for o, b in p.bounds), unit) if x
    )
    if style == "finite" or type_error:
        text = f"a finite number {limits}".strip()
    else:
        text = limits
    return CaseError(where, value, f"must be {text}" if style == "must" else text)


def check_value(p: Parameter, value: Any, where: str, style: str = "must") -> Any:
    """Check one value against its declaration and return it normalised.

    Numbers become ``float``, ``numbers`` a tuple of floats, integers ``int``,
    booleans ``bool``.

    Parameters
    ----------
    p : Parameter
        The declaration.
    value : object
        The value.
    where : str
        Field name used in the error.
    style : {"must", "finite"}
        Wording of the error: ``must be > 0 (N/m)`` or ``a finite number > 0 (N/m)``.

    Raises
    ------
    CaseError
        The value does not fit the declaration.
    """
    if p.kind == "number":
        if not _is_number(value):
            raise _bad(p, where, value, style, type_error=True)
        if not _in_bounds(p, float(value)):
            raise _bad(p, where, value, style, type_error=not math.isfinite(float(value)))
        return float(value)
    if p.kind == "numbers":
        if isinstance(value, str | bytes | Mapping) or not isinstance(value, Sequence | np.ndarray):
            raise CaseError(where, value, "must be a list of finite numbers")
        items = np.asarray(value, dtype=object).ravel().tolist()
        return tuple(
            check_value(_element(p), v, f"{where}[{i}]", style) for i, v in enumerate(items)
        )
    if p.kind == "integer":
        ok = isinstance(value, int | np.integer) and not isinstance(value, bool | np.bool_)
        if not ok or (p.choices is not None and value not in p.choices):
            raise _bad(p, where, value, style, type_error=not ok)
        if not _in_bounds(p, float(value)):
            raise _bad(p, where, value, style, type_error=False)
        return int(value)
    if p.kind == "boolean":
        if not isinstance(value, bool | np.bool_):
            raise _bad(p, where, value, style, type_error=True)
        return bool(value)
    if p.kind in ("text", "path"):
        if not isinstance(value, str) or (p.choices is not None and value not in p.choices):
            raise _bad(p, where, value, style, type_error=True)
        return value
    if p.kind == "tables":
        if isinstance(value, str | bytes | Mapping) or not isinstance(value, Sequence):
            raise CaseError(where, value, "must be a list of tables")
        for i, item in enumerate(value):
            if not isinstance(item, Mapping):
                raise CaseError(f"{where}[{i}]", item, "must be a table")
        return tuple(dict(item) for item in value)
    return value  # members are checked by their own family


def _element(p: Parameter) -> Parameter:
    return dataclasses.replace(p, kind="number")


def check_parameters(obj: Any, style: str = "must", prefix: str = "") -> None:
    """Check and normalise every declared parameter of the dataclass instance `obj`.

    Called by the ``__post_init__`` of a family's base class, so a member built
    in Python is checked exactly like one read from a case file.

    Parameters
    ----------
    obj : dataclass instance
        A family member.
    style : {"must", "finite"}
        Error wording (see :func:`check_value`).
    prefix : str
        Prepended to the key in errors (``"track.rail."`` for a part with a fixed place).
    """
    for p in declared_parameters(type(obj)):
        value = getattr(obj, p.name)
        if value is None and p.default is None:
            continue  # an optional parameter left out
        if p.kind == "member":
            if p.family is not None and not isinstance(value, p.family.base):
                raise CaseError(prefix + p.key, value, f"a {p.family.base.__name__} ({p.unit})")
            continue
        if p.kind == "table":
            continue  # a part checked by its own class
        object.__setattr__(obj, p.name, check_value(p, value, prefix + p.key, style))


def take_table(
    d: Any, params: Sequence[Parameter], field: str, style: str = "must"
) -> dict[str, Any]:
    """Check a plain table against declarations; return every value (defaults filled in).

    Parameters
    ----------
    d : mapping
        The table.
    params : sequence of Parameter
        Its declared keys (no ``member`` parameters).
    field : str
        Dotted name of the table, used in errors.
    style : {"must", "finite"}
        Error wording (see :func:`check_value`).

    Returns
    -------
    dict
        Values by key (None where an optional key without default is omitted).
    """
    if not isinstance(d, Mapping):
        raise CaseError(field, d, "a table")
    keys = [p.key for p in params]
    for key, value in d.items():
        if key not in keys:
            raise CaseError(
                f"{field}.{key}",
                value,
                f"unknown key; allowed here: {', '.join(keys)}{did_you_mean(key, keys)}",
            )
    out: dict[str, Any] = {}
    for p in params:
        if p.key in d:
            out[p.key] = check_value(p, d[p.key], f"{field}.{p.key}", style)
        elif p.required:
            unit = f" ({p.unit})" if p.unit not in ("", "-") else ""
            raise CaseError(f"{field}.{p.key}", None, f"required (missing){unit}")
        else:
            out[p.key] = p.default
    return out


# --------------------------------------------------------------------- families
