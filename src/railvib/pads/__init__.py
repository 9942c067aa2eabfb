"""Railpad models: complex dynamic stiffness K*(f, T) of one rail seat, in N/m.

Models (all :class:`PadModel`): :class:`SpringDamper`, :class:`Hysteretic`,
:class:`LogLinear`, :class:`ConstantPhase`, :class:`FractionalZener`,
:class:`GeneralizedMaxwell`, and :class:`TemperatureShifted` (any of them plus
time-temperature superposition with a :class:`WLF` law). Build them from case-file
tables with :func:`pad_from_dict`; fit them to measurements with :func:`fit_pad`.
"""

from railvib.pads.base import PADS, PASSIVITY_TOLERANCE, FitStart, PadModel
from railvib.pads.fit import (
    FITTABLE_MODELS,
    LogLinearFit,
    MasterCurve,
    ModelFit,
    build_master_curve,
    fit_free_shifts,
    fit_log_linear,
    fit_model,
    fit_pad,
    fittable_models,
)
from railvib.pads.io import (
    MODEL_ALIASES,
    PAD_MODELS,
    Measurements,
    load_pad_toml,
    pad_from_dict,
    pad_to_dict,
    pad_toml,
    read_measurements_csv,
    wj7_example_csv,
)
from railvib.pads.simple import ConstantPhase, Hysteretic, LogLinear, SpringDamper
from railvib.pads.tabulated import TabulatedPad
from railvib.pads.tts import (
    DEFAULT_EXPANSION_COEFFICIENT_PER_K,
    UNIVERSAL_C1,
    UNIVERSAL_C2_K,
    WLF,
    TemperatureShifted,
    vertical_shift_factor,
)
from railvib.pads.viscoelastic import FractionalZener, GeneralizedMaxwell

__all__ = [
    "DEFAULT_EXPANSION_COEFFICIENT_PER_K",
    "FITTABLE_MODELS",
    "FitStart",
    "MODEL_ALIASES",
    "PADS",
    "PAD_MODELS",
    "PASSIVITY_TOLERANCE",
    "UNIVERSAL_C1",
    "UNIVERSAL_C2_K",
    "WLF",
    "ConstantPhase",
    "FractionalZener",
    "GeneralizedMaxwell",
    "Hysteretic",
    "LogLinear",
    "LogLinearFit",
    "MasterCurve",
    "Measurements",
    "ModelFit",
    "PadModel",
    "SpringDamper",
    "TabulatedPad",
    "TemperatureShifted",
    "build_master_curve",
    "fit_free_shifts",
    "fit_log_linear",
    "fit_model",
    "fit_pad",
    "fittable_models",
    "load_pad_toml",
    "pad_from_dict",
    "pad_to_dict",
    "pad_toml",
    "read_measurements_csv",
    "vertical_shift_factor",
    "wj7_example_csv",
]
