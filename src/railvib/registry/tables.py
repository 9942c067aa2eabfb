"""Case tables across families: merging presets and overrides, resolving file paths."""

from __future__ import annotations

import copy
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from railvib.registry.family import TAG_KEYS, Registry

__all__ = ["merge_tables", "resolve_paths"]


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
