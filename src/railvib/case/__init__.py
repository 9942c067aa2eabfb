"""Case files: the validated description of one analysis."""

from railvib.case.build import (
    build_grid,
    build_pad,
    build_spectrum,
    build_system,
    build_track,
    build_vehicle,
    contact_stiffness,
)
from railvib.case.header import case_header
from railvib.case.load import case_from_dict, load_case, merge_case_dicts
from railvib.case.schema import Case

__all__ = [
    "Case",
    "build_grid",
    "build_pad",
    "build_spectrum",
    "build_system",
    "build_track",
    "build_vehicle",
    "case_from_dict",
    "case_header",
    "contact_stiffness",
    "load_case",
    "merge_case_dicts",
]
