"""Derived outputs: checks and engineering criteria computed from a result dataset.

Each output is a registered member of :data:`OUTPUTS` in a module of its own;
:func:`derive` adds the outputs a run asks for to its dataset, with units.
"""

from railvib.outputs.base import DEFAULT_OUTPUTS, OUTPUTS, DerivedOutput, derive
from railvib.outputs.comfort import RideComfort, floor_geometry
from railvib.outputs.contact import (
    LOSS_OF_CONTACT_NOTE,
    ContactCheck,
    contact_line,
    contact_table,
    is_linear_model_valid,
    linearity_note,
    loss_of_contact_threshold,
)
from railvib.outputs.forces import WheelRailForces
from railvib.outputs.octave import OctaveBands, ThirdOctave, band_mean_square, third_octave_bands
from railvib.outputs.report import criteria_lines, criteria_table, octave_table

__all__ = [
    "DEFAULT_OUTPUTS",
    "LOSS_OF_CONTACT_NOTE",
    "OUTPUTS",
    "RideComfort",
    "OctaveBands",
    "ThirdOctave",
    "WheelRailForces",
    "band_mean_square",
    "ContactCheck",
    "DerivedOutput",
    "contact_line",
    "criteria_lines",
    "criteria_table",
    "contact_table",
    "derive",
    "floor_geometry",
    "is_linear_model_valid",
    "linearity_note",
    "octave_table",
    "loss_of_contact_threshold",
    "third_octave_bands",
]
