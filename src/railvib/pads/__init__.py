"""Railpad models: complex dynamic stiffness K*(f, T) of one rail seat, in N/m.

Models (all :class:`PadModel`): :class:`SpringDamper`, :class:`Hysteretic`,
:class:`LogLinear`, :class:`ConstantPhase`, :class:`FractionalZener`,
:class:`GeneralizedMaxwell`, and :class:`TemperatureShifted` (any of them plus
time-temperature superposition with a :class:`WLF` law). Build them from case-file
tables with :func:`pad_from_dict`; fit them to measurements with :func:`fit_pad`;
predict one from a single-frequency temperature sweep with :func:`predict_pad` (the
paper's section 3.2).
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
from railvib.pads.predict import (
    PadPrediction,
    hysteresis_loop,
    loss_factor_peak,
    predict_pad,
    single_frequency_sweep,
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
    "PadPrediction",
    "SpringDamper",
    "TabulatedPad",
    "TemperatureShifted",
    "build_master_curve",
    "fit_free_shifts",
    "fit_log_linear",
    "fit_model",
    "fit_pad",
    "fittable_models",
    "hysteresis_loop",
    "load_pad_toml",
    "loss_factor_peak",
    "pad_from_dict",
    "pad_to_dict",
    "pad_toml",
    "predict_pad",
    "read_measurements_csv",
    "single_frequency_sweep",
    "vertical_shift_factor",
    "wj7_example_csv",
]
