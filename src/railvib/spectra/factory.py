"""Build a spectrum from a plain dict (as read from a case file)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from railvib.errors import CaseError
from railvib.spectra.base import SpatialSpectrum
from railvib.spectra.chinese import ChineseHSR
from railvib.spectra.combined import Combined
from railvib.spectra.fra import FRAClass
from railvib.spectra.german import GermanVertical
from railvib.spectra.sato import Sato
from railvib.spectra.shitai import ShiTai
from railvib.spectra.tabulated import Tabulated

__all__ = ["PAPER_SPECTRUM_DICT", "spectrum_from_dict"]

#: The paper's recipe: FRA class 5 for wavelengths above 1 m, Shi-tai below (hard switch).
#: A plain dict so that it serialises; deep-copy it before modifying.
PAPER_SPECTRUM_DICT: dict[str, Any] = {
    "type": "combined",
    "long_wave": {"type": "fra", "class_number": 5},
    "short_wave": {"type": "shitai"},
    "split_wavelength_m": 1.0,
}

# type -> (required keys, optional keys)
_KEYS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "fra": (("class_number",), ()),
    "shitai": ((), ("coefficient", "exponent")),
    "sato": ((), ("coefficient",)),
    "german": (("level",), ()),
    "chinese_hsr": ((), ("extrapolate",)),
    "combined": (("long_wave", "short_wave"), ("split_wavelength_m", "blend_decades")),
    "tabulated": ((), ("path", "delimiter", "wavenumber_rad_per_m", "psd_m2_per_rad_per_m")),
}


def _build(cls: Callable[..., SpatialSpectrum], field: str, **kwargs: Any) -> SpatialSpectrum:
    """Call ``cls(**kwargs)``, prefixing the field of any CaseError with `field`."""
    try:
        return cls(**kwargs)
    except CaseError as exc:
        raise CaseError(f"{field}.{exc.field}", exc.value, exc.allowed) from None


def _tabulated(d: dict[str, Any], field: str) -> SpatialSpectrum:
    has_path = "path" in d
    has_arrays = "wavenumber_rad_per_m" in d or "psd_m2_per_rad_per_m" in d
    if has_path == has_arrays:
        raise CaseError(
            field,
            sorted(d),
            "either 'path' or both 'wavenumber_rad_per_m' and 'psd_m2_per_rad_per_m'",
        )
    if has_path:
        if "delimiter" in d:
            return _build(Tabulated.from_csv, field, path=d["path"], delimiter=d["delimiter"])
        return _build(Tabulated.from_csv, field, path=d["path"])
    if "delimiter" in d:
        raise CaseError(f"{field}.delimiter", d["delimiter"], "only together with 'path'")
    for key in ("wavenumber_rad_per_m", "psd_m2_per_rad_per_m"):
        if key not in d:
            raise CaseError(f"{field}.{key}", None, "required with the other array (list)")
    return _build(Tabulated, field, **d)


def spectrum_from_dict(d: Mapping[str, Any], field: str = "irregularity") -> SpatialSpectrum:
    """Build a spatial spectrum from a plain dict.

    Parameters
    ----------
    d : Mapping
        ``{"type": ..., **parameters}``. Types and keys (units as in the classes):

        * ``"fra"``: ``class_number`` (1-6) -> :class:`FRAClass`;
        * ``"shitai"``: optional ``coefficient`` (mm^2/(cycle/m)), ``exponent``
          -> :class:`ShiTai`;
        * ``"sato"``: optional ``coefficient`` -> :class:`Sato`;
        * ``"german"``: ``level`` ("low" | "high") -> :class:`GermanVertical`;
        * ``"chinese_hsr"``: optional ``extrapolate`` (bool) -> :class:`ChineseHSR`;
        * ``"combined"``: ``long_wave``, ``short_wave`` (nested dicts), optional
          ``split_wavelength_m`` (m), ``blend_decades`` -> :class:`Combined`;
        * ``"tabulated"``: ``path`` (CSV, relative to the current directory) with optional
          ``delimiter``, or ``wavenumber_rad_per_m`` (rad/m) and ``psd_m2_per_rad_per_m``
          (m^2/(rad/m)) lists -> :class:`Tabulated`.
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
    if not isinstance(d, Mapping):
        raise CaseError(field, d, "a table with a 'type' key")
    if "type" not in d:
        raise CaseError(f"{field}.type", None, f"required, one of {', '.join(_KEYS)}")
    kind = d["type"]
    if not isinstance(kind, str) or kind not in _KEYS:
        raise CaseError(f"{field}.type", kind, f"one of {', '.join(_KEYS)}")
    required, optional = _KEYS[kind]
    params = {k: v for k, v in d.items() if k != "type"}
    for key in params:
        if key not in required and key not in optional:
            allowed = ", ".join((*required, *optional)) or "no other keys"
            raise CaseError(f"{field}.{key}", params[key], f"unknown key for '{kind}'; {allowed}")
    for key in required:
        if key not in params:
            raise CaseError(f"{field}.{key}", None, f"required for '{kind}'")
    if kind == "combined":
        params["long_wave"] = spectrum_from_dict(params["long_wave"], f"{field}.long_wave")
        params["short_wave"] = spectrum_from_dict(params["short_wave"], f"{field}.short_wave")
        return _build(Combined, field, **params)
    if kind == "tabulated":
        return _tabulated(params, field)
    classes: dict[str, Callable[..., SpatialSpectrum]] = {
        "fra": FRAClass,
        "shitai": ShiTai,
        "sato": Sato,
        "german": GermanVertical,
        "chinese_hsr": ChineseHSR,
    }
    return _build(classes[kind], field, **params)
