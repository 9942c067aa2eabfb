"""The paper's study: its cases, its figures and every number it states, read from data.

Wang, Yang, Wei, Zhou, "Stationary random vibration analysis of vehicle-track coupled
system with nonlinear stiffness of railpads", J. Vibroengineering 19(6), 2017
(DOI 10.21595/jve.2017.17947), sections 3.3 and 3.4, Figs. 9-16.

The study is data, in ``railvib/reproduce/paper_wang2017.toml`` (:data:`DATA_FILE`): *which*
presets form each comparison, *what* each figure shows and *how* each of the paper's numbers
is read from our curves (the metric named in :mod:`railvib.reproduce.metrics`, the response
and the band searched). This module defines the records, reads and checks that file once on
import (:func:`load_study`) and exposes its tables as :data:`CASES`, :data:`COMPARISONS`,
:data:`FIGURES` and :data:`PAPER_NUMBERS`. Nothing is computed except a derived paper value
(``paper_expr``: a ratio or a difference of two numbers the paper prints).
The interpretation of every ambiguous paper value lives in the preset files
(``railvib/presets/cases/wang2017_*.toml``) and in ``docs/paper-interpretation.md``.

Components (the file's ``[components]``): the paper's "bogie" is read as the front bogie
(``bogie1.bounce``, the one carrying the 2nd wheelset), "wheelset" as the 2nd wheelset
(``wheelset2.bounce``, named in the caption of Fig. 11) and "rail" as the rail under the 2nd
wheel (``rail@wheel2``).
"""

from __future__ import annotations

import inspect
import math
import operator
import tomllib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from types import MappingProxyType
from typing import Any

from railvib.errors import CaseError
from railvib.reproduce.metrics import METRICS

__all__ = [
    "CASES",
    "CAUSES",
    "COMPARISONS",
    "DATA_FILE",
    "FIGURES",
    "PAPER_NUMBERS",
    "Comparison",
    "FigureSpec",
    "Mark",
    "PaperNumber",
    "PaperPoint",
    "Study",
    "StudyCase",
    "load_study",
]

#: name of the study's data file, shipped in this package
DATA_FILE = "paper_wang2017.toml"


@dataclass(frozen=True)
class StudyCase:
    """One computed case of the study.

    Parameters
    ----------
    key : str
        Short name used throughout the study tables.
    preset : str
        Shipped preset that defines the case completely.
    label : str
        Legend label (the paper's wording).
    color : str
        Matplotlib colour of its curves.
    """

    key: str
    preset: str
    label: str
    color: str


@dataclass(frozen=True)
class Comparison:
    """A set of cases the paper overlays (section 3.3 or 3.4).

    Parameters
    ----------
    key : str
        Name of the comparison.
    title : str
        What is compared.
    section : str
        The paper's section.
    cases : tuple of str
        Case keys, in legend order.
    """

    key: str
    title: str
    section: str
    cases: tuple[str, ...]


@dataclass(frozen=True)
class PaperPoint:
    """A (frequency, PSD) point the paper states, drawn as a marker on our figure.

    Parameters
    ----------
    case : str
        Case key whose colour the marker takes.
    frequency_hz : float
        Frequency stated by the paper, Hz.
    psd : float
        PSD stated by the paper, m^2/s^4/Hz.
    """

    case: str
    frequency_hz: float
    psd: float


@dataclass(frozen=True)
class Mark:
    """A peak we read from our curve, drawn as a labelled circle.

    Parameters
    ----------
    label : str
        Text next to the marker (the paper's point name, e.g. ``"A"``).
    band : (float, float)
        Band searched for the maximum, Hz.
    """

    label: str
    band: tuple[float, float]


@dataclass(frozen=True)
class FigureSpec:
    """One of the paper's figures, redrawn from our results.

    Parameters
    ----------
    number : int
        The paper's figure number.
    comparison : str
        Key of the :class:`Comparison` overlaid.
    component : str
        The component, in words.
    response : str
        Response label of our dataset.
    panels : tuple of (float, float)
        Frequency range of each panel, Hz (the paper's zoomed panels (a), (b)).
    paper_points : tuple of PaperPoint
        The (frequency, PSD) pairs the paper states for this figure.
    marks : tuple of Mark
        Peaks read from our curves (every case of the comparison), drawn on the panels.
    paper_lines : tuple of (float, str)
        Frequencies (Hz) the paper states for this figure, drawn as dotted lines with
        their label.
    zoom : (float, float) or None
        A band (Hz) inside one panel drawn again as an extra panel, to tell the teeth of
        a comb apart; the comb spacing measured over that panel is annotated there.
    """

    number: int
    comparison: str
    component: str
    response: str
    panels: tuple[tuple[float, float], ...]
    paper_points: tuple[PaperPoint, ...] = ()
    marks: tuple[Mark, ...] = ()
    paper_lines: tuple[tuple[float, str], ...] = ()
    zoom: tuple[float, float] | None = None

    @property
    def stem(self) -> str:
        """File stem of the figure, e.g. ``fig11_wheelset2_freqdep``."""
        return f"fig{self.number:02d}_{self.response.split('.')[0].replace('@', '_')}_" + (
            self.comparison
        )


@dataclass(frozen=True)
class PaperNumber:
    """A number the paper states, with how we read the same quantity from our results.

    Parameters
    ----------
    id : str
        Stable identifier, e.g. ``"fig11.peak.constant"``.
    source : str
        Where the paper states it (figure and section).
    quantity : str
        What the number is, in words.
    unit : str
        Unit of `paper` and of our value.
    paper : float or None
        The paper's value; None for a qualitative statement.
    paper_text : str
        The paper's statement as printed (short).
    metric : str
        Name of the reading function in :data:`railvib.reproduce.metrics.METRICS`.
    args : mapping
        Keyword arguments of the metric (cases, response, band in Hz, ...).
    reading : str
        How the number is read from our curves, in words.
    note : str
        Why ours differs (interpretation, printing error, modelling choice), or "": the
        `remark` and the text of each of the `causes`, joined.
    claim : (str, float) or None
        A comparison our value must satisfy for the paper's statement to hold, e.g.
        ``(">", 1.0)``; None for a plain number.
    derived : bool
        True when `paper` is computed from numbers the paper states (a ratio or a
        difference), not printed by it.
    causes : tuple of str
        The shared causes of the difference (names of the study's ``[notes]``), in order.
    remark : str
        What `note` says about this number alone (its parts that are not a cause).
    """

    id: str
    source: str
    quantity: str
    unit: str
    paper: float | None
    paper_text: str
    metric: str
    args: MappingProxyType[str, Any]
    reading: str
    note: str = ""
    claim: tuple[str, float] | None = None
    derived: bool = False
    causes: tuple[str, ...] = ()
    remark: str = ""


@dataclass(frozen=True)
class Study:
    """The whole study as read from its data file by :func:`load_study`.

    Parameters
    ----------
    cases : tuple of StudyCase
        The computed cases, in file order.
    comparisons : tuple of Comparison
        The sets of cases the paper overlays.
    figures : tuple of FigureSpec
        The paper's figures, in file order (a number repeats for another comparison).
    numbers : tuple of PaperNumber
        Every number the paper states, in file order.
    components : mapping of str to str
        The paper's components (``body``, ``bogie``, ``wheelset``, ``rail``) and the
        response label each is read as.
    psd_unit : str
        Unit of the PSDs, ``"m^2/s^4/Hz"``.
    notes : mapping of str to str
        The shared notes, by name (a number's ``note = "@name"``): the causes of the
        differences, each written once and referenced from every number it explains.
    """

    cases: tuple[StudyCase, ...]
    comparisons: tuple[Comparison, ...]
    figures: tuple[FigureSpec, ...]
    numbers: tuple[PaperNumber, ...]
    components: MappingProxyType[str, str]
    psd_unit: str
    notes: MappingProxyType[str, str]


# --- reading and checking the data file ---------------------------------------------------

_TOP_REQUIRED = ("psd_unit", "components", "case", "comparison", "figure", "number")
_TOP_OPTIONAL = ("notes",)
_COMPONENTS = ("body", "bogie", "wheelset", "rail")
_CASE_KEYS = ("key", "preset", "label", "color")
_COMPARISON_KEYS = ("key", "title", "section", "cases")
_FIGURE_REQUIRED = ("number", "comparison", "component", "response", "panels")
_FIGURE_OPTIONAL = ("paper_points", "marks", "paper_lines", "zoom")
_POINT_KEYS = ("case", "frequency_hz", "psd")
_MARK_KEYS = ("label", "band")
_LINE_KEYS = ("frequency_hz", "label")
_NUMBER_REQUIRED = ("id", "source", "quantity", "unit", "paper_text", "metric", "args", "reading")
_NUMBER_OPTIONAL = ("paper", "paper_expr", "derived", "note", "claim")
_CLAIM_OPS = ("<", "<=", ">", ">=")
_EXPR_OPS: Mapping[str, Callable[[float, float], float]] = {
    "/": operator.truediv,
    "-": operator.sub,
}


class _Reader:
    """Type and key checks of one parsed study file; errors name ``<file>: <field>``."""

    def __init__(self, name: str) -> None:
        self.name = name

    def error(self, field: str, value: Any, allowed: str) -> CaseError:
        return CaseError(f"{self.name}: {field}", value, allowed)

    def table(
        self,
        value: Any,
        field: str,
        required: Sequence[str],
        optional: Sequence[str] = (),
    ) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise self.error(field, value, "a table")
        allowed = (*required, *optional)
        for key in value:
            if key not in allowed:
                raise self.error(
                    f"{field}.{key}", value[key], f"unknown key; allowed: {', '.join(allowed)}"
                )
        for key in required:
            if key not in value:
                raise self.error(f"{field}.{key}", None, "required")
        return value

    def tables(
        self,
        value: Any,
        field: str,
        required: Sequence[str],
        optional: Sequence[str] = (),
        *,
        nonempty: bool = True,
    ) -> list[tuple[str, dict[str, Any]]]:
        if not isinstance(value, list) or (nonempty and not value):
            raise self.error(
                field, value, "a non-empty array of tables" if nonempty else "an array of tables"
            )
        return [
            (f"{field}[{i}]", self.table(item, f"{field}[{i}]", required, optional))
            for i, item in enumerate(value)
        ]

    def string(self, value: Any, field: str) -> str:
        if not isinstance(value, str) or not value:
            raise self.error(field, value, "a non-empty string")
        return value

    def choice(self, value: Any, field: str, allowed: Sequence[str], what: str) -> str:
        if value not in allowed:
            raise self.error(field, value, f"{what}, one of {', '.join(allowed)}")
        return str(value)

    def number(self, value: Any, field: str, unit: str) -> float:
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
        ):
            raise self.error(field, value, f"a finite number ({unit})")
        return float(value)

    def band(self, value: Any, field: str) -> tuple[float, float]:
        if not isinstance(value, list) or len(value) != 2:
            raise self.error(field, value, "[low, high], 0 <= low < high (Hz)")
        low, high = (self.number(v, f"{field}[{i}]", "Hz") for i, v in enumerate(value))
        if not 0.0 <= low < high:
            raise self.error(field, value, "[low, high], 0 <= low < high (Hz)")
        return low, high

    def keys(self, value: Any, field: str, allowed: Sequence[str], what: str) -> tuple[str, ...]:
        if not isinstance(value, list) or not value:
            raise self.error(field, value, f"a non-empty array of {what}")
        return tuple(self.choice(v, f"{field}[{i}]", allowed, what) for i, v in enumerate(value))

    def unique(self, keys: Sequence[str], field: str, name: str) -> None:
        for i, key in enumerate(keys):
            if key in keys[:i]:
                raise self.error(
                    f"{field}[{i}].{name}", key, f"unique (already {field}[{keys.index(key)}])"
                )


def _cases(r: _Reader, value: Any) -> tuple[StudyCase, ...]:
    cases = tuple(
        StudyCase(**{k: r.string(t[k], f"{f}.{k}") for k in _CASE_KEYS})
        for f, t in r.tables(value, "case", _CASE_KEYS)
    )
    r.unique([c.key for c in cases], "case", "key")
    return cases


def _comparisons(r: _Reader, value: Any, case_keys: Sequence[str]) -> tuple[Comparison, ...]:
    comparisons = tuple(
        Comparison(
            key=r.string(t["key"], f"{f}.key"),
            title=r.string(t["title"], f"{f}.title"),
            section=r.string(t["section"], f"{f}.section"),
            cases=r.keys(t["cases"], f"{f}.cases", case_keys, "case keys"),
        )
        for f, t in r.tables(value, "comparison", _COMPARISON_KEYS)
    )
    r.unique([c.key for c in comparisons], "comparison", "key")
    return comparisons


def _figure(
    r: _Reader,
    f: str,
    t: dict[str, Any],
    comparisons: Mapping[str, Comparison],
    responses: Sequence[str],
) -> FigureSpec:
    number = t["number"]
    if isinstance(number, bool) or not isinstance(number, int) or number < 1:
        raise r.error(f"{f}.number", number, "the paper's figure number, an integer >= 1")
    comparison = r.choice(t["comparison"], f"{f}.comparison", list(comparisons), "comparison key")
    shown = comparisons[comparison].cases
    panels = t["panels"]
    if not isinstance(panels, list) or not panels:
        raise r.error(f"{f}.panels", panels, "a non-empty array of [low, high] bands (Hz)")
    points = tuple(
        PaperPoint(
            case=r.choice(p["case"], f"{g}.case", shown, f"a case of comparison '{comparison}'"),
            frequency_hz=r.number(p["frequency_hz"], f"{g}.frequency_hz", "Hz"),
            psd=r.number(p["psd"], f"{g}.psd", "m^2/s^4/Hz"),
        )
        for g, p in r.tables(
            t.get("paper_points", []), f"{f}.paper_points", _POINT_KEYS, nonempty=False
        )
    )
    marks = tuple(
        Mark(label=r.string(m["label"], f"{g}.label"), band=r.band(m["band"], f"{g}.band"))
        for g, m in r.tables(t.get("marks", []), f"{f}.marks", _MARK_KEYS, nonempty=False)
    )
    lines = tuple(
        (
            r.number(ln["frequency_hz"], f"{g}.frequency_hz", "Hz"),
            r.string(ln["label"], f"{g}.label"),
        )
        for g, ln in r.tables(
            t.get("paper_lines", []), f"{f}.paper_lines", _LINE_KEYS, nonempty=False
        )
    )
    bands = tuple(r.band(p, f"{f}.panels[{i}]") for i, p in enumerate(panels))
    zoom = r.band(t["zoom"], f"{f}.zoom") if "zoom" in t else None
    if zoom is not None and not any(lo <= zoom[0] and zoom[1] <= hi for lo, hi in bands):
        raise r.error(f"{f}.zoom", t["zoom"], "[low, high] inside one of the panels (Hz)")
    return FigureSpec(
        number=number,
        comparison=comparison,
        component=r.string(t["component"], f"{f}.component"),
        response=r.choice(t["response"], f"{f}.response", responses, "a [components] response"),
        panels=bands,
        paper_points=points,
        marks=marks,
        paper_lines=lines,
        zoom=zoom,
    )


def _frozen(value: Any) -> Any:
    """TOML arrays as tuples, recursively (the metrics' arguments are immutable)."""
    if isinstance(value, list):
        return tuple(_frozen(v) for v in value)
    return value


def _args(
    r: _Reader,
    value: Any,
    f: str,
    metric: str,
    case_keys: Sequence[str],
    responses: Sequence[str],
) -> MappingProxyType[str, Any]:
    """A number's metric arguments, checked against the metric's signature."""
    params = list(inspect.signature(METRICS[metric]).parameters.values())[1:]  # after results
    names = [p.name for p in params]
    if not isinstance(value, dict):
        raise r.error(f, value, f"a table of the keyword arguments of metrics.{metric}")
    for key in value:
        if key not in names:
            raise r.error(
                f"{f}.{key}", value[key], f"an argument of metrics.{metric}: {', '.join(names)}"
            )
    for p in params:
        if p.default is inspect.Parameter.empty and p.name not in value:
            raise r.error(f"{f}.{p.name}", None, f"required by metrics.{metric}")
    args: dict[str, Any] = {}
    for key, v in value.items():
        field = f"{f}.{key}"
        if key == "band":
            args[key] = r.band(v, field)
        elif key == "cases":
            args[key] = r.keys(v, field, case_keys, "case keys")
        elif key in ("case", "reference"):
            args[key] = r.choice(v, field, case_keys, "case key")
        elif key == "response":
            args[key] = r.choice(v, field, responses, "a [components] response")
        else:
            args[key] = _frozen(v)
    return MappingProxyType(args)


def _note(
    r: _Reader, value: Any, f: str, notes: Mapping[str, str]
) -> tuple[str, tuple[str, ...], str]:
    """A number's note, causes and remark.

    The note is a string or a list of strings joined by spaces, "@name" standing for
    notes[name] (a cause); the remark joins the other parts.
    """
    parts = [value] if isinstance(value, str) else value
    if not isinstance(parts, list) or not parts or not all(isinstance(p, str) for p in parts):
        raise r.error(
            f, value, "a string or a non-empty array of strings ('@name': a [notes] entry)"
        )
    for part in parts:
        if part.startswith("@") and part[1:] not in notes:
            raise r.error(f, part, f"'@' and a [notes] entry, one of {', '.join(notes)}")
    note = " ".join(notes[p[1:]] if p.startswith("@") else p for p in parts)
    causes = tuple(dict.fromkeys(p[1:] for p in parts if p.startswith("@")))
    return note, causes, " ".join(p for p in parts if not p.startswith("@"))


def _paper(r: _Reader, t: dict[str, Any], f: str, unit: str) -> tuple[float | None, bool]:
    """The paper's value and whether it is derived (computed from two printed numbers)."""
    derived = t.get("derived", False)
    if not isinstance(derived, bool):
        raise r.error(f"{f}.derived", derived, "true or false")
    if "paper_expr" not in t:
        if derived:
            raise r.error(f"{f}.paper_expr", None, "required with derived = true")
        return (r.number(t["paper"], f"{f}.paper", unit) if "paper" in t else None), False
    expr = t["paper_expr"]
    allowed = "[a, op, b]: two numbers the paper prints, op one of " + ", ".join(_EXPR_OPS)
    if "paper" in t:
        raise r.error(f"{f}.paper", t["paper"], "not together with paper_expr")
    if not derived:
        raise r.error(f"{f}.derived", derived, "true with paper_expr (a computed value)")
    if not isinstance(expr, list) or len(expr) != 3 or expr[1] not in _EXPR_OPS:
        raise r.error(f"{f}.paper_expr", expr, allowed)
    a = r.number(expr[0], f"{f}.paper_expr[0]", "as printed")
    b = r.number(expr[2], f"{f}.paper_expr[2]", "as printed")
    if expr[1] == "/" and b == 0.0:
        raise r.error(f"{f}.paper_expr", expr, "a non-zero divisor")
    return _EXPR_OPS[expr[1]](a, b), True


def _number(
    r: _Reader,
    f: str,
    t: dict[str, Any],
    case_keys: Sequence[str],
    responses: Sequence[str],
    notes: Mapping[str, str],
) -> PaperNumber:
    unit = r.string(t["unit"], f"{f}.unit")
    metric = r.choice(t["metric"], f"{f}.metric", list(METRICS), "a reading function in METRICS")
    paper, derived = _paper(r, t, f, unit)
    claim: tuple[str, float] | None = None
    if "claim" in t:
        c = t["claim"]
        if not isinstance(c, list) or len(c) != 2 or c[0] not in _CLAIM_OPS:
            raise r.error(f"{f}.claim", c, f"[op, bound], op one of {', '.join(_CLAIM_OPS)}")
        claim = (c[0], r.number(c[1], f"{f}.claim[1]", unit))
    elif paper is None:
        raise r.error(f"{f}.claim", None, "required without paper or paper_expr")
    note, causes, remark = _note(r, t["note"], f"{f}.note", notes) if "note" in t else ("", (), "")
    return PaperNumber(
        id=r.string(t["id"], f"{f}.id"),
        source=r.string(t["source"], f"{f}.source"),
        quantity=r.string(t["quantity"], f"{f}.quantity"),
        unit=unit,
        paper=paper,
        paper_text=r.string(t["paper_text"], f"{f}.paper_text"),
        metric=metric,
        args=_args(r, t["args"], f"{f}.args", metric, case_keys, responses),
        reading=r.string(t["reading"], f"{f}.reading"),
        note=note,
        claim=claim,
        derived=derived,
        causes=causes,
        remark=remark,
    )


def _study(r: _Reader, data: dict[str, Any]) -> Study:
    r.table(data, "(top level)", _TOP_REQUIRED, _TOP_OPTIONAL)
    components = {
        k: r.string(v, f"components.{k}")
        for k, v in r.table(data["components"], "components", _COMPONENTS).items()
    }
    responses = list(components.values())
    raw_notes = data.get("notes", {})
    if not isinstance(raw_notes, dict):
        raise r.error("notes", raw_notes, "a table of named strings")
    notes = {k: r.string(v, f"notes.{k}") for k, v in raw_notes.items()}
    cases = _cases(r, data["case"])
    case_keys = [c.key for c in cases]
    comparisons = _comparisons(r, data["comparison"], case_keys)
    by_key = {c.key: c for c in comparisons}
    figures = tuple(
        _figure(r, f, t, by_key, responses)
        for f, t in r.tables(data["figure"], "figure", _FIGURE_REQUIRED, _FIGURE_OPTIONAL)
    )
    # a figure may be redrawn for another comparison (Figs. 13-16 on the predicted pads)
    r.unique([f"{g.number} ({g.comparison})" for g in figures], "figure", "number")
    numbers = tuple(
        _number(r, f, t, case_keys, responses, notes)
        for f, t in r.tables(data["number"], "number", _NUMBER_REQUIRED, _NUMBER_OPTIONAL)
    )
    r.unique([n.id for n in numbers], "number", "id")
    return Study(
        cases=cases,
        comparisons=comparisons,
        figures=figures,
        numbers=numbers,
        components=MappingProxyType(components),
        psd_unit=r.string(data["psd_unit"], "psd_unit"),
        notes=MappingProxyType(notes),
    )


def load_study(path: str | Path | None = None) -> Study:
    """Read and check a study file (TOML).

    Parameters
    ----------
    path : str or pathlib.Path, optional
        The study file; by default the shipped :data:`DATA_FILE`. Its keys are described
        in its header comment and by the records of this module (frequencies in Hz,
        PSDs in m^2/s^4/Hz).

    Returns
    -------
    Study
        Its cases, comparisons, figures and numbers, in file order; arrays as tuples,
        every ``args`` a read-only mapping, every ``note`` with its ``@name`` references
        resolved and every derived paper value computed from its ``paper_expr``.

    Raises
    ------
    CaseError
        On an unreadable file, invalid TOML, an unknown or missing key, a wrong type, or an
        unknown metric, metric argument, case, comparison, response or note. The field is
        named with the file and a 0-based index, e.g. ``paper_wang2017.toml: number[12].metric``.
    """
    if path is None:
        name = DATA_FILE
        text = resources.files("railvib.reproduce").joinpath(DATA_FILE).read_text(encoding="utf-8")
    else:
        path = Path(path)
        name = path.name
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as exc:
            raise CaseError(name, str(path), f"a readable TOML file ({exc.strerror})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(name, str(path or name), f"valid TOML ({exc})") from None
    return _study(_Reader(name), data)


_STUDY = load_study()

#: the computed cases of the study
CASES: tuple[StudyCase, ...] = _STUDY.cases
#: the sets of cases the paper overlays (sections 3.3 and 3.4)
COMPARISONS: tuple[Comparison, ...] = _STUDY.comparisons
#: the paper's Figs. 9-16, then Figs. 13-16 on the predicted pads
FIGURES: tuple[FigureSpec, ...] = _STUDY.figures
#: every number the paper states, with how we read it
PAPER_NUMBERS: tuple[PaperNumber, ...] = _STUDY.numbers

#: response read as the paper's car body
BODY: str = _STUDY.components["body"]
#: response read as the paper's bogie (the front bogie)
BOGIE: str = _STUDY.components["bogie"]
#: response read as the paper's wheelset (the 2nd wheelset)
WHEELSET: str = _STUDY.components["wheelset"]
#: response read as the paper's rail (under the 2nd wheel)
RAIL: str = _STUDY.components["rail"]
#: unit of the PSDs
PSD_UNIT: str = _STUDY.psd_unit
#: the causes of the differences (the study's ``[notes]``), by name
CAUSES: MappingProxyType[str, str] = _STUDY.notes
