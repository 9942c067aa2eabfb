"""The few lines that say which case a result belongs to, at the head of every summary.

A summary that states the case title, the speed (km/h and m/s), the railpad
model and its temperature, the irregularity and the frequency band makes a unit
slip or a wrong case visible at a glance.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from railvib.case.build import build_pad
from railvib.case.schema import Case
from railvib.registry import TAG_KEYS
from railvib.units import kmh_to_ms

__all__ = ["case_header", "describe_table"]


#: longest list written in full; a longer one (a tabulated pad) shows its ends and length
_LIST_IN_FULL = 6


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return str(v).lower()
    if isinstance(v, int | float):
        return f"{v:g}"
    if isinstance(v, list | tuple):
        if len(v) > _LIST_IN_FULL:
            return f"[{_value(v[0])}, {_value(v[1])}, ..., {_value(v[-1])}] ({len(v)} values)"
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return str(v)


def describe_table(table: Mapping[str, Any]) -> str:
    """A family table in one line: the member's name, then its keys (units in the key names).

    Parameters
    ----------
    table : mapping
        A pad or irregularity table of a case (``model`` / ``type`` names the member;
        nested tables are described in parentheses).

    Returns
    -------
    str
        E.g. ``"spring_damper (stiffness_n_per_m = 5e+07; damping_ns_per_m = 50000)"``.
    """
    name = next((str(table[k]) for k in TAG_KEYS if k in table), "")
    parts = []
    for key, value in table.items():
        if key in TAG_KEYS:
            continue
        if isinstance(value, Mapping):
            parts.append(f"{key}: {describe_table(value)}")
        else:
            parts.append(f"{key} = {_value(value)}")
    inner = "; ".join(parts)
    if not inner:
        return name
    return f"{name} ({inner})" if name else f"({inner})"


def case_header(case: Case) -> list[str]:
    """The header lines of a case's summary: title, speed, pad, irregularity, frequency band.

    Parameters
    ----------
    case : Case
        A validated case.

    Returns
    -------
    list of str
        ``"<what>: <value>"`` lines, without a comment marker (each writer adds its
        own: ``"# "`` in CSV, ``"- "`` in Markdown). Speeds in km/h and m/s, the pad
        temperature in degC, frequencies in Hz and the wavelengths they stand for at
        this speed in m.
    """
    v = kmh_to_ms(case.speed_kmh)
    freq = case.frequency
    t = case.track.pad_temperature_c
    # a [track] naming a model replaces the preset's, and may leave the temperature out
    temperature = "pad temperature not given" if t is None else f"pad temperature {t:g} degC"
    if not build_pad(case).temperature_dependent:
        temperature += " (this pad model does not depend on it)"
    if freq.spacing == "linear":
        grid = f"linear grid, step {freq.step:g} Hz"
    else:
        grid = f"log grid, {freq.n} points"
    return [
        f"case: {case.title}",
        f"speed: {case.speed_kmh:g} km/h ({v:.4g} m/s)",
        f"rail model: {case.rail_model}",
        f"pad: {describe_table(case.track.pad)}; {temperature}",
        f"irregularity: {describe_table(case.irregularity)}",
        f"frequency band: {freq.f_min:g}-{freq.f_max:g} Hz ({grid}; wavelengths "
        f"{v / freq.f_min:.4g} m to {v / freq.f_max:.4g} m at this speed)",
    ]
