"""A family of models: members registered by name, built from and written to case tables."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Generic, Literal, TypeVar

from railvib.errors import CaseError, did_you_mean
from railvib.registry import docs
from railvib.registry.parameters import Parameter, declared_parameters, take_table

__all__ = ["MAX_MEMBER_DEPTH", "TAG_KEYS", "ExtraTable", "Member", "Registry"]

T = TypeVar("T")

#: the keys that name a family member in a table (``Registry.tag`` of every family)
TAG_KEYS = ("model", "type")

#: most members nested in each other (a combined spectrum in a combined spectrum ...): the
#: paper's recipe nests 2; deeper tables are refused before building recurses further
MAX_MEMBER_DEPTH = 16


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
            names = [*self._members, *self._aliases]
            raise CaseError(where, name, f"one of {', '.join(names)}{did_you_mean(name, names)}")
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
            Unknown name or key, missing key, wrong type or value, or members nested
            more than :data:`MAX_MEMBER_DEPTH` deep; the field is dotted, e.g.
            ``irregularity.long_wave.class_number``.
        """
        return self._from_dict(d, field, 1)

    def _from_dict(self, d: Any, field: str, depth: int) -> T:
        """:meth:`from_dict` of a table `depth` members deep (1: not inside another)."""
        if depth > MAX_MEMBER_DEPTH:
            raise CaseError(
                field,
                f"<{self.plural} nested {depth} deep>",
                f"{self.plural} nested at most {MAX_MEMBER_DEPTH} deep",
            )
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
                keys = [*allowed, *self.extra_tables]
                raise CaseError(
                    f"{field}.{key}",
                    value,
                    "unknown key; allowed here: "
                    + (", ".join(keys) or "no other keys")
                    + did_you_mean(key, keys),
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
                value = p.family._from_dict(value, f"{field}.{p.key}", depth + 1)
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
            elif p.kind == "tables":
                out[p.key] = [dict(t) for t in value]
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

    def template_lines(self, d: Mapping[str, Any], header: str, doc: str = "") -> list[str]:
        """Lines of a commented TOML table for `d` under ``[header]`` (nested tables follow).

        Parameters
        ----------
        d : mapping
            The table.
        header : str
            Dotted name of the table, e.g. ``"track.pad"``.
        doc : str
            What the table is for, first in the comment above the header.

        Returns
        -------
        list of str
            TOML lines with ``#`` comments, each right above what it documents.
        """
        return docs.template_lines(self, d, header, doc)

    def markdown(self) -> str:
        """A Markdown section per member: its description and a table of its keys."""
        return docs.markdown(self)


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
