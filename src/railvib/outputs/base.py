"""The derived-output family: quantities computed from the variables of a result dataset.

A derived output is a frozen dataclass (its settings declared with
:func:`railvib.registry.parameter`) registered in :data:`OUTPUTS`. It reads the
dataset's variables (PSDs per Hz, one-sided, with their units) and returns new
variables, each with ``units`` and ``long_name``.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping, Sequence
from typing import Any, ClassVar

import xarray as xr

from railvib.registry import Registry, check_parameters

__all__ = ["DEFAULT_OUTPUTS", "OUTPUTS", "DerivedOutput", "derive"]


class DerivedOutput(ABC):
    """A check or criterion computed from a result dataset."""

    #: name in case files and the registry, set on registration
    model_name: ClassVar[str] = ""

    def __post_init__(self) -> None:
        check_parameters(self, "must")

    @abstractmethod
    def compute(self, ds: xr.Dataset) -> dict[str, xr.DataArray]:
        """New variables (with ``units`` and ``long_name``) from the variables of `ds`.

        Parameters
        ----------
        ds : xarray.Dataset
            A result dataset (see :func:`railvib.results.build_dataset`).
        """


#: every derived output railvib can add to a result
OUTPUTS: Registry[DerivedOutput] = Registry(
    "derived output", DerivedOutput, "type", where="computed for every run", tagged=False
)

#: the outputs every run computes
DEFAULT_OUTPUTS = ("contact_check",)


def derive(
    ds: xr.Dataset,
    names: Sequence[str] = DEFAULT_OUTPUTS,
    settings: Mapping[str, Mapping[str, Any]] | None = None,
) -> xr.Dataset:
    """`ds` with the variables of the derived outputs `names` added.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset.
    names : sequence of str
        Registered outputs.
    settings : mapping, optional
        Output name -> its settings (constructor arguments, in the units of their
        declarations, e.g. ``{"contact_check": {"loss_of_contact_threshold": 0.05}}``);
        an output not named takes its defaults.

    Returns
    -------
    xarray.Dataset
        A new dataset.
    """
    out = ds.copy()
    for name in names:
        kwargs = dict((settings or {}).get(name, {}))
        out = out.assign(OUTPUTS.get(name).build(**kwargs).compute(out))
    return out
