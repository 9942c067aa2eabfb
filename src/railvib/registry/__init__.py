"""Open model families: members declared once, everything else derived from the declarations.

A *family* (pad models, irregularity spectra, track models, vehicle models,
derived outputs) is a :class:`Registry`. A *member* is one class in one module:
a frozen dataclass whose fields are declared with :func:`parameter` (key in
case files, unit, bounds, one line of documentation, a plausible range), and
which registers itself with ``@REGISTRY.register("name")``. From those
declarations, and nowhere else, railvib derives:

* the validation of a member's table in a case file (unknown, missing and
  mistyped keys, bounds) with errors that name the dotted field
  (:meth:`Registry.from_dict`), and of the object built in Python
  (:func:`check_parameters`, called by the family's base class);
* the table written back from an object (:meth:`Registry.to_dict`);
* the commented case template (:meth:`Registry.template_lines`);
* the docs' model tables (:meth:`Registry.markdown`, ``railvib models``);
* the hypothesis strategies (:mod:`railvib.testing.strategies`).

``docs/extending.md`` shows a new pad model and a new spectrum added in one file each.
"""

from railvib.registry.docs import toml_line
from railvib.registry.family import MAX_MEMBER_DEPTH, TAG_KEYS, ExtraTable, Member, Registry
from railvib.registry.parameters import (
    REQUIRED,
    Kind,
    Parameter,
    check_parameters,
    check_value,
    declared_parameters,
    parameter,
    take_table,
)
from railvib.registry.tables import merge_tables, resolve_paths

__all__ = [
    "MAX_MEMBER_DEPTH",
    "REQUIRED",
    "TAG_KEYS",
    "ExtraTable",
    "Kind",
    "Member",
    "Parameter",
    "Registry",
    "check_parameters",
    "check_value",
    "declared_parameters",
    "merge_tables",
    "parameter",
    "resolve_paths",
    "take_table",
    "toml_line",
]
