"""Build a spectrum from a plain dict (as read from a case file)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = ["PAPER_SPECTRUM_DICT", "spectrum_from_dict"]

#: The paper's recipe: FRA class 5 for wavelengths above 1 m, Shi-tai below (hard switch).
#: A plain dict so that it serialises; deep-copy it before modifying.
PAPER_SPECTRUM_DICT: dict[str, Any] = {
    "type": "combined",
    "long_wave": {"type": "fra", "class_number": 5},
    "short_wave": {"type": "shitai"},
    "split_wavelength_m": 1.0,
}


def spectrum_from_dict(d: Mapping[str, Any], field: str = "irregularity") -> SpatialSpectrum:
    """Build a spatial spectrum from a plain dict.

    Parameters
    ----------
    d : Mapping
        ``{"type": <name>, **parameters}``; the names and their keys (with units) are
        those of the registered spectra, :data:`~railvib.spectra.base.SPECTRA`
        (``railvib models spectrum`` lists them). Nested spectra (``combined``) are
        tables themselves; a ``tabulated`` ``path`` is relative to the current folder
        here (case files resolve it relative to themselves).
    field : str
        Dotted name of `d` in the case, used in error messages (e.g. ``"irregularity"``).

    Returns
    -------
    SpatialSpectrum
        The spectrum (m^2/(rad/m) vs rad/m).

    Raises
    ------
    CaseError
        Unknown type, unknown or missing key, or a bad value; the field is dotted, e.g.
        ``irregularity.long_wave.class_number``.
    """
    return SPECTRA.from_dict(d, field)
