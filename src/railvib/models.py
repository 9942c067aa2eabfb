"""Every model family railvib knows, and their documentation generated from the declarations.

``railvib models`` prints :func:`models_markdown`; ``docs/models.md`` is its
output (a test keeps the file current).
"""

from __future__ import annotations

from typing import Any

from railvib.errors import CaseError, did_you_mean
from railvib.outputs import OUTPUTS
from railvib.pads import PADS
from railvib.registry import Registry
from railvib.spectra import SPECTRA
from railvib.track import TRACKS
from railvib.vehicle import VEHICLES

__all__ = ["FAMILIES", "models_markdown"]

#: the model families by their short name (``railvib models <name>``)
FAMILIES: dict[str, Registry[Any]] = {
    "pad": PADS,
    "spectrum": SPECTRA,
    "track": TRACKS,
    "vehicle": VEHICLES,
    "output": OUTPUTS,
}

_HEADER = """# Models

Every model railvib can build from a case file, with its keys, units, defaults
and allowed values. This page is generated from the models' own declarations
(`railvib models > docs/models.md`); a test fails when it is stale.
How to add a model: `docs/extending.md`.
"""


def models_markdown(family: str | None = None) -> str:
    """Markdown tables of the members of one family (or of all) with their parameters.

    Parameters
    ----------
    family : str, optional
        A key of :data:`FAMILIES`; all families when omitted.

    Returns
    -------
    str
        Markdown text.
    """
    if family is not None and family not in FAMILIES:
        raise CaseError(
            "family", family, f"one of {', '.join(FAMILIES)}{did_you_mean(family, FAMILIES)}"
        )
    names = [family] if family is not None else list(FAMILIES)
    parts = [] if family is not None else [_HEADER]
    parts += [FAMILIES[name].markdown() for name in names]
    return "\n".join(parts).rstrip() + "\n"
