"""Spatial irregularity spectra (one-sided, m^2/(rad/m) vs rad/m) and temporal conversion."""

from railvib.spectra.base import SPECTRA, SpatialSpectrum, temporal_psd
from railvib.spectra.chinese import ChineseHSR
from railvib.spectra.combined import Combined
from railvib.spectra.factory import PAPER_SPECTRUM_DICT, spectrum_from_dict
from railvib.spectra.fra import FRAClass
from railvib.spectra.german import GermanVertical
from railvib.spectra.roughness import ISO3095Limit, RoughnessLevels
from railvib.spectra.sato import Sato
from railvib.spectra.shitai import ShiTai
from railvib.spectra.tabulated import Tabulated

__all__ = [
    "PAPER_SPECTRUM_DICT",
    "SPECTRA",
    "ChineseHSR",
    "Combined",
    "FRAClass",
    "GermanVertical",
    "ISO3095Limit",
    "RoughnessLevels",
    "Sato",
    "ShiTai",
    "SpatialSpectrum",
    "Tabulated",
    "spectrum_from_dict",
    "temporal_psd",
]
