"""Open model families: members declared once, everything else derived from the declarations.

A *family* (pad models, irregularity spectra, track models, vehicle models,
derived outputs) is a :class:`Registry`. A *member* is one class in one module:
a frozen dataclass whose fields are declared with :func:`parameter` (key in
case files, unit, bounds, one line of documentation, a plausible range), and
which registers itself with ``@REGISTRY.register("name")``. From those
declarations, and nowhere else, railvib derives:

* the validation of a member's table in a case file (unknown, missing and
  mistyped keys, bounds) with errors that name the dotted field
  (:meth:`Registry.from_dict`), and of the object built in Python
  (:func:`check_parameters`, called by the family's base class);
* the table written back from an object (:meth:`Registry.to_dict`);
* the commented case template (:meth:`Registry.template_lines`);
* the docs' model tables (:meth:`Registry.markdown`, ``railvib models``);
* the hypothesis strategies (:mod:`railvib.testing.strategies`).

``docs/extending.md`` shows a new pad model and a new spectrum added in one file each.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import math
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Generic, Literal, TypeVar

import numpy as np

from railvib.errors import CaseError

__all__ = [
    "REQUIRED",
    "Member",
    "Parameter",
    "Registry",
    "check_parameters",
    "check_value",
    "declared_parameters",
    "merge_tables",
    "parameter",
    "resolve_paths",
    "take_table",
]

T = TypeVar("T")

#: the keys that name a family member in a table (``Registry.tag`` of every family)
TAG_KEYS = ("model", "type")
Kind = Literal["number", "integer", "boolean", "text", "numbers", "path", "member", "table"]


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
        file), ``member`` (a nested table of family `family`) or ``table`` (a nested
        table of the fixed dataclass `table`).
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
        if self.kind in ("text", "path"):
            return {"text": "text", "path": "a file path"}[self.kind]
        parts = [f"{op} {bound!r}" for op, bound in self.bounds]
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


@functools.cache
def declared_parameters(cls: type) -> tuple[Parameter, ...]:
    """The parameters declared on the dataclass fields of `cls`, in field order (cached)."""
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
    limits = " ".join(x for x in (" and ".join(f"{o} {b!r}" for o, b in p.bounds), unit) if x)
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
                f"{field}.{key}", value, f"unknown key; allowed here: {', '.join(keys)}"
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


@dataclass(frozen=True)
class Member(Generic[T]):
    """A registered member of a family.

    Parameters
    ----------
    name : str
        Name in case files (the value of the family's tag key).
    cls : type
        The class.
    parameters : tuple of Parameter
        The keys of its table.
    aliases : tuple of str
        Other accepted names.
    build : callable
        ``build(**values)`` -> member object, from the checked values of the table.
    """

    name: str
    cls: type[T]
    parameters: tuple[Parameter, ...]
    aliases: tuple[str, ...]
    build: Callable[..., T]

    @property
    def doc(self) -> str:
        """First line of the class docstring."""
        return (self.cls.__doc__ or "").strip().splitlines()[0] if self.cls.__doc__ else ""

    def parameter(self, key: str) -> Parameter:
        """The declaration of `key`."""
        return next(p for p in self.parameters if p.key == key)


#: extra table of a family (e.g. ``tts`` of a pad): (declarations, wrap(member, table, field))
ExtraTable = tuple[tuple[Parameter, ...], Callable[[Any, Mapping[str, Any], str], Any]]


class Registry(Generic[T]):
    """A family of models chosen by name in case files.

    Parameters
    ----------
    family : str
        The family in words (``"pad model"``), used in messages and docs.
    base : type
        Base class of every member.
    tag : str
        The key that names the member in a table (``"model"``, ``"type"``).
    style : {"must", "finite"}
        Wording of value errors (see :func:`check_value`).
    plural : str, optional
        Plural of `family` (default: `family` + "s").
    where : str
        Where its tables stand in a case file, for the docs (``"[track.pad]"``).
    tagged : bool
        Whether its tables name their member with `tag` (false while a family has
        one member whose table carries no tag, e.g. ``[vehicle]``).
    """

    def __init__(
        self,
        family: str,
        base: type,
        tag: str,
        *,
        style: Literal["must", "finite"] = "must",
        plural: str | None = None,
        where: str = "",
        tagged: bool = True,
    ) -> None:
        if tag not in TAG_KEYS:
            raise ValueError(f"a family's tag is one of {TAG_KEYS} (merge_tables relies on it)")
        self.family = family
        self.plural = plural or f"{family}s"
        self.where = where
        self.tagged = tagged
        self.base = base
        self.tag = tag
        self.style = style
        #: the value shown for a missing key (the spectra's legacy wording shows None)
        self._missing: Any = None if style == "finite" else "<missing>"
        self._members: dict[str, Member[T]] = {}
        self._aliases: dict[str, str] = {}
        self.extra_tables: dict[str, ExtraTable] = {}

    # -- membership ---------------------------------------------------------------------
    def register(
        self,
        name: str,
        *,
        aliases: Sequence[str] = (),
        parameters: Sequence[Parameter] | None = None,
        build: Callable[..., T] | None = None,
    ) -> Callable[[type[T]], type[T]]:
        """Class decorator registering a member under `name`.

        Parameters
        ----------
        name : str
            Name in case files.
        aliases : sequence of str
            Other accepted names.
        parameters : sequence of Parameter, optional
            The table's keys when they are not the dataclass fields (then give `build`).
        build : callable, optional
            ``build(**values)`` -> member; default: the class itself.
        """

        def decorate(cls: type[T]) -> type[T]:
            if name in self._members or name in self._aliases:
                raise ValueError(f"{self.family} {name!r} is registered already")
            if not (isinstance(cls, type) and issubclass(cls, self.base)):
                raise TypeError(f"a {self.family} must subclass {self.base.__name__}")
            params = tuple(parameters) if parameters is not None else declared_parameters(cls)
            self._members[name] = Member(name, cls, params, tuple(aliases), build or cls)
            for alias in aliases:
                self._aliases[alias] = name
            if getattr(cls, "model_name", None) == "":
                cls.model_name = name  # type: ignore[attr-defined]
            return cls

        return decorate

    def unregister(self, name: str) -> None:
        """Remove member `name` and its aliases (for tests that register toy members)."""
        member = self._members.pop(name)
        for alias in member.aliases:
            self._aliases.pop(alias, None)

    def names(self) -> list[str]:
        """Member names, in registration order."""
        return list(self._members)

    def as_mapping(self) -> Mapping[str, Member[T]]:
        """A live, read-only view ``name -> Member`` (members registered later appear)."""
        return _LiveView(self._members)

    def aliases_mapping(self) -> Mapping[str, str]:
        """A live, read-only view ``alias -> member name``."""
        return _LiveView(self._aliases)

    def aliases(self) -> dict[str, str]:
        """Alias -> member name."""
        return dict(self._aliases)

    def __iter__(self) -> Iterator[Member[T]]:
        return iter(list(self._members.values()))

    def __contains__(self, name: object) -> bool:
        return name in self._members or name in self._aliases

    def get(self, name: str, field: str = "") -> Member[T]:
        """The member called `name` (or an alias of it).

        Parameters
        ----------
        name : str
            Member name or alias, e.g. ``"spring_damper"``.
        field : str
            Dotted name of the table, used in errors (``"track.pad"``).

        Returns
        -------
        Member
            The registered member.

        Raises
        ------
        CaseError
            No such member; the message lists the names allowed.
        """
        key = self._aliases.get(name, name) if isinstance(name, str) else name
        if key not in self._members:
            where = f"{field}.{self.tag}" if field else self.tag
            raise CaseError(where, name, f"one of {', '.join([*self._members, *self._aliases])}")
        return self._members[key]

    def member_of(self, obj: object) -> Member[T]:
        """The member whose class is exactly ``type(obj)``."""
        for member in self._members.values():
            if type(obj) is member.cls:
                return member
        raise CaseError(
            self.tag, type(obj).__name__, f"a registered {self.family}: {', '.join(self._members)}"
        )

    # -- tables -------------------------------------------------------------------------
    def from_dict(self, d: Any, field: str) -> T:
        """Build a member from its table, checking every key against the declarations.

        Parameters
        ----------
        d : mapping
            ``{tag: name, <parameters>, <extra tables>}``, e.g. a case file's ``[track.pad]``.
        field : str
            Dotted name of the table, used in errors (``"track.pad"``).

        Returns
        -------
        object
            The member.

        Raises
        ------
        CaseError
            Unknown name or key, missing key, wrong type or value; the field is dotted,
            e.g. ``irregularity.long_wave.class_number``.
        """
        if not isinstance(d, Mapping):
            raise CaseError(field, d, f"a table with a {self.tag!r} key")
        if self.tag not in d:
            raise CaseError(
                f"{field}.{self.tag}", self._missing, f"required; one of {', '.join(self._members)}"
            )
        member = self.get(d[self.tag], field)
        params = {k: v for k, v in d.items() if k != self.tag and k not in self.extra_tables}
        allowed = [p.key for p in member.parameters]
        for key, value in params.items():
            if key not in allowed:
                raise CaseError(
                    f"{field}.{key}",
                    value,
                    "unknown key; allowed here: "
                    + (", ".join([*allowed, *self.extra_tables]) or "no other keys"),
                )
        kwargs: dict[str, Any] = {}
        for p in member.parameters:
            if p.key not in params:
                if p.required:
                    unit = f" ({p.unit})" if p.unit not in ("", "-") else ""
                    raise CaseError(f"{field}.{p.key}", self._missing, f"required{unit}")
                continue
            value = params[p.key]
            if p.kind == "member":
                assert p.family is not None, "a member parameter names its family"
                value = p.family.from_dict(value, f"{field}.{p.key}")
            elif p.kind == "table":
                assert p.table is not None, "a table parameter names its dataclass"
                value = p.table(
                    **take_table(value, declared_parameters(p.table), f"{field}.{p.key}")
                )
            kwargs[p.name] = value
        try:
            obj = member.build(**kwargs)
        except CaseError as err:
            raise CaseError(
                f"{field}.{err.field}" if err.field else field, err.value, err.allowed
            ) from None
        for key, (_, wrap) in self.extra_tables.items():
            if key in d:
                obj = wrap(obj, d[key], f"{field}.{key}")
        return obj

    def to_dict(self, obj: T) -> dict[str, Any]:
        """The table of member `obj`, such that ``from_dict(to_dict(obj))`` rebuilds it.

        Parameters
        ----------
        obj : object
            An instance of a registered member class (exactly, not a subclass).

        Returns
        -------
        dict
            TOML-ready: floats, booleans, lists of floats, nested tables.
        """
        member = self.member_of(obj)
        out: dict[str, Any] = {self.tag: member.name}
        for p in member.parameters:
            value = getattr(obj, p.name)
            if p.kind == "member":
                assert p.family is not None, "a member parameter names its family"
                out[p.key] = p.family.to_dict(value)
            elif p.kind == "numbers":
                out[p.key] = [float(x) for x in value]
            elif p.kind == "number":
                out[p.key] = float(value)
            else:
                out[p.key] = value
        return out

    def paths(self, d: Any) -> Iterator[tuple[Mapping[str, Any], str]]:
        """``(table, key)`` of every ``path`` parameter in table `d`, nested tables included."""
        if not isinstance(d, Mapping) or d.get(self.tag) not in self:
            return
        member = self.get(d[self.tag])
        for p in member.parameters:
            if p.key not in d:
                continue
            if p.kind == "path":
                yield d, p.key
            elif p.kind == "member" and p.family is not None:
                yield from p.family.paths(d[p.key])

    # -- documentation ------------------------------------------------------------------
    def template_lines(self, d: Mapping[str, Any], header: str) -> list[str]:
        """Lines of a commented TOML table for `d` under ``[header]`` (nested tables follow)."""
        import tomli_w

        member = self.get(d[self.tag])
        others = [n for n in self._members if n != member.name]
        lines = [
            f"[{header}]",
            f"# {self.family}: {member.doc}",
            f"# (other {self.tag}s: {', '.join(others)}; see `railvib models`)",
            tomli_w.dumps({self.tag: member.name}).strip(),
        ]
        nested: list[str] = []
        for p in member.parameters:
            if p.key not in d:
                continue
            if p.kind == "member":
                assert p.family is not None, "a member parameter names its family"
                nested += ["", *p.family.template_lines(d[p.key], f"{header}.{p.key}")]
                continue
            lines.append(f"# {_comment(p)}")
            lines.append(tomli_w.dumps({p.key: d[p.key]}).strip())
        for key, (params, _) in self.extra_tables.items():
            if isinstance(d.get(key), Mapping):
                nested += ["", f"[{header}.{key}]"]
                for p in params:
                    if p.key in d[key]:
                        nested += [
                            f"# {_comment(p)}",
                            tomli_w.dumps({p.key: d[key][p.key]}).strip(),
                        ]
        return lines + nested

    def markdown(self) -> str:
        """A Markdown section per member: its description and a table of its keys."""
        where = [f"`{self.where}`"] if self.where else []
        where += [f"`{self.tag} = ...`"] if self.tagged else []
        out = [f"## {self.plural.capitalize()}" + (f" ({', '.join(where)})" if where else ""), ""]
        for member in self:
            alias = (
                f" (alias {', '.join(f'`{a}`' for a in member.aliases)})" if member.aliases else ""
            )
            out += [f"### `{member.name}`{alias}", "", member.doc, ""]
            out += _parameter_table(member.parameters)
            for p in member.parameters:
                if p.kind == "table" and p.table is not None:
                    out += [f"Keys of its `{p.key}` table:", ""]
                    out += _parameter_table(declared_parameters(p.table))
        for key, (params, _) in self.extra_tables.items():
            out += [f"### Optional `[...{key}]` table of any {self.family}", ""]
            out += _parameter_table(params)
        return "\n".join(out)


V = TypeVar("V")


class _LiveView(Mapping[str, V]):
    """Read-only view of a dict that keeps changing (a registry's members or aliases)."""

    def __init__(self, data: dict[str, V]) -> None:
        self._data = data

    def __getitem__(self, name: str) -> V:
        return self._data[name]

    def __iter__(self) -> Iterator[str]:
        return iter(list(self._data))

    def __len__(self) -> int:
        return len(self._data)


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


def merge_tables(base: Mapping[str, Any], override: Mapping[str, Any]) -> dict[str, Any]:
    """Deep-merge `override` onto a copy of `base`, table by table.

    A table of `override` that names a family member (it holds a tag key of
    :data:`TAG_KEYS`, ``model`` or ``type``) replaces the table of `base`
    wholesale, since another member takes other keys; other tables merge key by key.

    Parameters
    ----------
    base, override : mapping
        Parsed TOML tables (e.g. a preset and a user's case file).

    Returns
    -------
    dict
        A new dict; neither input is modified.
    """
    out = copy.deepcopy(dict(base))
    for key, value in override.items():
        old = out.get(key)
        names_member = isinstance(value, Mapping) and any(tag in value for tag in TAG_KEYS)
        if isinstance(value, Mapping) and isinstance(old, Mapping) and not names_member:
            out[key] = merge_tables(old, value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def resolve_paths(table: Any, registry: Registry[Any], base_dir: Path) -> None:
    """Make every relative ``path`` parameter in `table` relative to `base_dir` (in place).

    Parameters
    ----------
    table : mapping
        A member table of `registry`'s family (nested tables included); anything else
        is left alone.
    registry : Registry
        The family whose declarations say which keys are paths.
    base_dir : pathlib.Path
        Folder the relative paths are taken from (the case file's folder).
    """
    for d, key in registry.paths(table):
        if isinstance(d[key], str) and not Path(d[key]).is_absolute():
            d[key] = str(base_dir / d[key])  # type: ignore[index]
