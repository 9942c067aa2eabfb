"""Named presets shipped as TOML data (with provenance notes next to each value).

``presets/cases/<name>.toml`` are case files; a user case (or another preset)
names one with ``preset = "<name>"`` and overrides any field.
``presets/vehicles/<name>.toml`` are vehicle files (``docs/vehicles.md``); a case's
``[vehicle]`` table names one with ``preset = "<name>"``.
"""

from __future__ import annotations

import functools
import tomllib
from importlib import resources
from typing import Any

from railvib.errors import CaseError, did_you_mean
from railvib.registry import merge_tables

__all__ = [
    "DEFAULT_PRESET",
    "list_presets",
    "list_vehicle_presets",
    "load_preset",
    "load_vehicle_preset",
    "preset_text",
    "vehicle_preset_text",
]

#: the paper's analysis: type-B metro, 80 km/h, embedded-sleeper slab track, WJ-7 pads
DEFAULT_PRESET = "wang2017_metro"


def _case_dir() -> Any:
    return resources.files("railvib.presets").joinpath("cases")


def _vehicle_dir() -> Any:
    return resources.files("railvib.presets").joinpath("vehicles")


def list_vehicle_presets() -> list[str]:
    """Names of the shipped vehicle presets (vehicle files)."""
    return sorted(p.name[:-5] for p in _vehicle_dir().iterdir() if p.name.endswith(".toml"))


@functools.cache
def vehicle_preset_text(name: str) -> str:
    """The TOML text of vehicle preset `name`, comments (sources, bases) included."""
    names = list_vehicle_presets()
    if name not in names:
        raise CaseError("vehicle.preset", name, f"one of {names}{did_you_mean(name, names)}")
    return _vehicle_dir().joinpath(f"{name}.toml").read_text(encoding="utf-8")


def load_vehicle_preset(name: str) -> dict[str, Any]:
    """The parsed table of vehicle preset `name` (a ``[vehicle]`` table).

    Parameters
    ----------
    name : str
        One of :func:`list_vehicle_presets`.

    Returns
    -------
    dict
        The vehicle table, ``model`` included.
    """
    return tomllib.loads(vehicle_preset_text(name))


def list_presets() -> list[str]:
    """Names of the shipped case presets."""
    return sorted(p.name[:-5] for p in _case_dir().iterdir() if p.name.endswith(".toml"))


@functools.cache
def preset_text(name: str) -> str:
    """The TOML text of preset `name`, comments included."""
    names = list_presets()
    if name not in names:
        raise CaseError("preset", name, f"one of {names}{did_you_mean(name, names)}")
    return _case_dir().joinpath(f"{name}.toml").read_text(encoding="utf-8")


def load_preset(name: str, _chain: tuple[str, ...] = ()) -> dict[str, Any]:
    """The parsed tables of preset `name`, with any preset it names merged underneath.

    A preset may itself start from another with ``preset = "<name>"`` and override
    fields, exactly like a user's case file.

    Parameters
    ----------
    name : str
        Preset name (one of :func:`list_presets`).
    _chain : tuple of str
        Presets already being loaded (internal: detects a cycle of presets).

    Returns
    -------
    dict
        The parsed TOML tables, the ``preset`` key resolved.

    Raises
    ------
    CaseError
        Unknown preset, or a cycle of presets.
    """
    if name in _chain:
        raise CaseError("preset", name, f"no cycle of presets ({' -> '.join((*_chain, name))})")
    data = tomllib.loads(preset_text(name))
    parent = data.pop("preset", None)
    if parent is None:
        return data
    return merge_tables(load_preset(parent, (*_chain, name)), data)
