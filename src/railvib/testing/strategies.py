"""Hypothesis strategies for physically plausible railvib inputs (for users' and our tests).

Every strategy is generated from the families' declarations: a member's table
is drawn from the plausible range (``typical``) of each of its parameters, so a
newly registered model is exercised without editing this module. Members with
a required parameter that has no plausible range (tabulated data, series
models) are left out.
"""

from __future__ import annotations

import math
from typing import Any

from hypothesis import strategies as st

from railvib.errors import CaseError
from railvib.pads import PADS
from railvib.registry import Member, Parameter, Registry, declared_parameters
from railvib.spectra import SPECTRA
from railvib.track import Rail
from railvib.vehicle import DEFAULT_VEHICLE_MODEL, VEHICLES

__all__ = ["case_overrides", "member_tables", "pad_tables", "spectrum_tables"]

#: the vehicle parameters :func:`case_overrides` varies (the rest keep the preset's values)
VARIED_VEHICLE_FIELDS = (
    "carbody_mass",
    "bogie_mass",
    "wheelset_mass",
    "primary_stiffness",
    "secondary_stiffness",
    "primary_damping",
    "secondary_damping",
)


def _log_uniform(lo: float, hi: float) -> st.SearchStrategy[float]:
    """Log-uniform in [lo, hi] (clipped: exp(log(lo)) may round just below lo)."""
    return st.floats(math.log(lo), math.log(hi)).map(lambda x: min(max(math.exp(x), lo), hi))


def _values(p: Parameter, depth: int = 0) -> st.SearchStrategy[Any] | None:
    """Plausible values of one parameter, or None when it declares none."""
    if p.kind == "member" and p.family is not None and depth > 0:
        return _tables(p.family, depth - 1)
    if p.choices is not None:
        return st.sampled_from(p.choices)
    if p.kind == "boolean":
        return st.booleans()
    if p.kind == "number" and p.typical is not None:
        lo, hi = p.typical
        return _log_uniform(lo, hi) if p.log else st.floats(lo, hi)
    return None


def _table(member: Member[Any], tag: str, depth: int) -> st.SearchStrategy[dict[str, Any]] | None:
    fields: dict[str, st.SearchStrategy[Any]] = {tag: st.just(member.name)}
    for p in member.parameters:
        values = _values(p, depth)
        if values is not None:
            fields[p.key] = values
        elif p.required:
            return None
    return st.fixed_dictionaries(fields)


def member_tables(registry: Registry[Any]) -> st.SearchStrategy[dict[str, Any]]:
    """Tables of the members of `registry` drawn from their declared plausible ranges.

    Only tables the family accepts are drawn (conditions between parameters, such
    as ``k_inf >= k0`` of a Zener pad, are checked by building each table).

    Parameters
    ----------
    registry : Registry
        A family, e.g. :data:`railvib.pads.PADS`.
    """
    return _tables(registry, depth=1).filter(lambda d: _builds(registry, d))


def _tables(registry: Registry[Any], depth: int) -> st.SearchStrategy[dict[str, Any]]:
    """Tables of every member drawable at nesting `depth` (members holding members need > 0)."""
    tables = [t for m in registry if (t := _table(m, registry.tag, depth)) is not None]
    if not tables:
        raise ValueError(f"no {registry.family} declares plausible ranges for its parameters")
    return st.one_of(tables)


def _builds(registry: Registry[Any], d: dict[str, Any]) -> bool:
    try:
        registry.from_dict(d, "strategy")
    except CaseError:
        return False
    return True


def pad_tables() -> st.SearchStrategy[dict[str, Any]]:
    """``[track.pad]`` tables of plausible railpads (every registered pad model with ranges)."""
    return member_tables(PADS)


def spectrum_tables() -> st.SearchStrategy[dict[str, Any]]:
    """``[irregularity]`` tables of every registered spectrum with plausible ranges."""
    return member_tables(SPECTRA)


def _declared(cls_params: tuple[Parameter, ...], keys: tuple[str, ...]) -> dict[str, Any]:
    by_key = {p.key: p for p in cls_params}
    out = {}
    for key in keys:
        values = _values(by_key[key])
        assert values is not None, f"{key} declares a plausible range"
        out[key] = values
    return out


def case_overrides() -> st.SearchStrategy[dict[str, Any]]:
    """Overrides of the default preset spanning plausible vehicles, tracks and speeds."""
    vehicle = VEHICLES.get(DEFAULT_VEHICLE_MODEL).parameters
    rail = declared_parameters(Rail)
    return st.fixed_dictionaries(
        {
            "speed_kmh": st.floats(20.0, 350.0),
            "rail_model": st.sampled_from(["single_rail", "rail_pair"]),
            "vehicle": st.fixed_dictionaries(_declared(vehicle, VARIED_VEHICLE_FIELDS)),
            "track": st.fixed_dictionaries(
                {
                    "sleeper_spacing": st.floats(0.5, 0.75),
                    "rail": st.fixed_dictionaries(
                        {
                            **_declared(rail, ("bending_stiffness", "mass_per_length")),
                            "loss_factor": st.sampled_from([0.0, 0.01]),
                        }
                    ),
                    "pad": pad_tables(),
                }
            ),
            "contact": st.fixed_dictionaries({"leading_wheel_position": st.floats(0.0, 0.499)}),
        }
    )
