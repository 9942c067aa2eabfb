"""Sweeps over train length: one dataset whose cases are trains of different lengths.

A train's responses are labelled per car (``car2.bogie1.bounce``, ``rail@car3.wheel2``),
so trains of different lengths have response and wheel axes of different lengths. A
sweep over ``train.cars`` (or over whole ``train`` tables) keeps one dataset: its
``response`` axis is the longest train's labels and its ``wheel`` axis numbers the
longest train's wheels; a shorter train's values for the cars it does not have are NaN
(a ragged layout padded with NaN). A single car (``cars = 1``) reads as the train's
leading car (``car1.carbody.bounce``, ``rail@car1.wheel2``). Each train length is solved
on its own (its wheels are another coupled system), as a sweep of that length alone.
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from railvib.case import build_vehicle, case_from_dict
from railvib.case.load import merge_case_dicts
from railvib.labels import leading_car_label, response_labels
from railvib.results.variables import VARIABLES
from railvib.sweep.layout import SweepLayout
from railvib.sweep.spec import SweepAxis, SweepSpec, is_train_length_field, nested_override

__all__ = [
    "TRAIN_CARS",
    "compute_train_chunk",
    "label_car",
    "length_groups",
    "sweep_labels",
    "train_labels",
]

#: the per-case variable of a sweep over train length: the number of cars of each case
TRAIN_CARS = "train_cars"

#: a chunk's results: variable name -> ``(n_case, ...)``
ChunkArrays = dict[str, NDArray[Any]]


def length_groups(spec: SweepSpec) -> tuple[str, ...]:
    """The sweep dimensions along which the train length varies (none: one layout).

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep.

    Returns
    -------
    tuple of str
        The groups (dimension names) holding an axis over ``train.cars`` or ``train``.
    """
    groups = [ax.group for ax in spec.axes if is_train_length_field(ax.field)]
    return tuple(dict.fromkeys(groups))


def train_labels(case_dict: Mapping[str, Any]) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Response labels and wheel names of a case as a train sweep names them.

    Parameters
    ----------
    case_dict : mapping
        A resolved case (validated).

    Returns
    -------
    tuple of (tuple of str, tuple of str)
        The response labels (vehicle DOFs, then the rail under each wheel) and the wheel
        names; a single car's read as car 1 of a train (:func:`railvib.labels.
        leading_car_label`).
    """
    vehicle = build_vehicle(case_from_dict(dict(case_dict), warn=False))
    labels = response_labels(vehicle.dofs, len(vehicle.wheels), vehicle.wheel_names)
    if _cars(case_dict) > 1:  # already named per car (railvib.vehicle.make_train)
        return labels, vehicle.wheel_names
    return tuple(map(leading_car_label, labels)), tuple(f"car1.{w}" for w in vehicle.wheel_names)


def label_car(label: str) -> int:
    """The car a response label or wheel name of a train belongs to (1 = the leading car).

    Parameters
    ----------
    label : str
        ``car3.bogie1.bounce``, ``rail@car3.wheel2`` or ``car3.wheel2``.

    Returns
    -------
    int
        The car's number (3 in these examples).
    """
    return int(label.removeprefix("rail@").split(".")[0].removeprefix("car"))


def _cars(case_dict: Mapping[str, Any]) -> int:
    """Number of cars of a resolved case (1 without a ``[train]``)."""
    return int(case_dict.get("train", {}).get("cars", 1))


def _length_cases(spec: SweepSpec) -> list[tuple[dict[int, int], dict[str, Any]]]:
    """Every combination of positions along the length groups, with its case dict.

    Each entry is ``({group index: position}, case)``: the base case with the values of
    every axis of those groups at those positions.
    """
    layout = SweepLayout(spec)
    groups = length_groups(spec)
    dims = [layout.dims.index(g) for g in groups]
    out = []
    for positions in itertools.product(*(range(layout.shape[d]) for d in dims)):
        where = dict(zip(dims, positions, strict=True))
        out.append((where, _case_at(spec, layout, where)))
    return out


def _case_at(spec: SweepSpec, layout: SweepLayout, where: Mapping[int, int]) -> dict[str, Any]:
    """The base case with every axis of the dimensions `where` at its position there."""
    case = spec.base_case_dict()
    for ax in spec.axes:
        d = layout.dims.index(ax.group)
        if d in where:
            case = merge_case_dicts(case, nested_override(ax.field, ax.value(where[d])))
    dumped: dict[str, Any] = case_from_dict(case, warn=False).model_dump(
        mode="json", exclude_none=True
    )
    return dumped


def sweep_labels(spec: SweepSpec) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The response labels and wheel names of a sweep's dataset.

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep.

    Returns
    -------
    tuple of (tuple of str, tuple of str)
        Those of the base case; with a train-length axis, those of the longest train (the
        cars of every shorter train are among them, :func:`train_labels`).
    """
    if not length_groups(spec):
        vehicle = build_vehicle(case_from_dict(spec.base_case_dict(), warn=False))
        labels = response_labels(vehicle.dofs, len(vehicle.wheels), vehicle.wheel_names)
        return labels, vehicle.wheel_names
    layouts = [train_labels(case) for _, case in _length_cases(spec)]
    return max(layouts, key=lambda lw: len(lw[1]))


def compute_train_chunk(
    spec: SweepSpec,
    chunk_id: int,
    compute: Callable[[SweepSpec, int], ChunkArrays],
    trailing: Mapping[str, Sequence[str]],
) -> ChunkArrays:
    """One chunk of a sweep over train length: each length solved alone, padded with NaN.

    The chunk's cases at one position along the length groups form a block of their own;
    each block is the one chunk of a sweep of that train length alone (`compute`), and
    its responses and wheels are placed at their labels in the longest train's axes.

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep with a train-length axis (:func:`length_groups`).
    chunk_id : int
        Chunk number (C order over the chunk grid).
    compute : callable
        ``compute(spec, chunk_id)``: the results of a chunk of one layout
        (:func:`railvib.sweep.batch.compute_chunk`).
    trailing : mapping
        The dimensions after the case of each ``summary/<name>`` variable that is not a
        per-response statistic (``contact_force_rms``: ``("wheel",)``, ...).

    Returns
    -------
    dict of numpy.ndarray
        As `compute` returns them, cases in C order over the chunk block; the response
        and wheel axes those of :func:`sweep_labels`, NaN where a train has no such
        response or wheel; and ``summary/train_cars``, ``(n_case,)``, each case's number
        of cars.
    """
    layout = SweepLayout(spec)
    labels, wheels = sweep_labels(spec)
    slices = layout.chunk_slices(chunk_id)
    rows = {tuple(map(int, index)): i for i, index in enumerate(layout.chunk_indices(chunk_id))}
    dims = [layout.dims.index(g) for g in length_groups(spec)]
    out: ChunkArrays = {f"summary/{TRAIN_CARS}": np.zeros(len(rows), dtype=np.int64)}
    for positions in itertools.product(*(range(slices[d].start, slices[d].stop) for d in dims)):
        where = dict(zip(dims, positions, strict=True))
        sub = _block_spec(spec, layout, slices, where)
        part = compute(sub, 0)
        part_labels, part_wheels = train_labels(sub.base_case_dict())
        at = {
            "response": np.array([labels.index(r) for r in part_labels]),
            "wheel": np.array([wheels.index(w) for w in part_wheels]),
        }
        sub_layout = SweepLayout(sub)
        offsets = np.array([s.start for s in slices])
        for d, p in where.items():
            offsets[d] = p
        targets = [rows[tuple(map(int, i + offsets))] for i in sub_layout.chunk_indices(0)]
        out[f"summary/{TRAIN_CARS}"][targets] = _cars(sub.base_case_dict())
        for name, value in part.items():
            dim = _last_dim(name, trailing)
            if name not in out:
                shape = (len(rows), *value.shape[1:])
                if dim:
                    shape = (*shape[:-1], len(labels) if dim == "response" else len(wheels))
                out[name] = _empty(shape, value.dtype)
            for r, t in enumerate(targets):
                if dim:
                    out[name][t][..., at[dim]] = value[r]
                else:
                    out[name][t] = value[r]
    return out


def _empty(shape: tuple[int, ...], dtype: np.dtype[Any]) -> NDArray[Any]:
    """An array of `shape` of NaN (or, for a type without NaN, zeros)."""
    if np.issubdtype(dtype, np.inexact):
        return np.full(shape, np.nan, dtype=dtype)
    return np.zeros(shape, dtype=dtype)


def _last_dim(name: str, trailing: Mapping[str, Sequence[str]]) -> str | None:
    """``"response"`` or ``"wheel"`` where chunk variable `name` ends with that axis, else None."""
    if name.startswith("summary/"):
        key = name.removeprefix("summary/")
        dims = tuple(trailing[key]) if key in trailing else ("response",)
    else:
        dims = tuple(VARIABLES[name].dims)
    last = dims[-1] if dims else None
    return last if last in ("response", "wheel") else None


def _block_spec(
    spec: SweepSpec, layout: SweepLayout, slices: Sequence[slice], where: Mapping[int, int]
) -> SweepSpec:
    """The sweep of one train length whose one chunk is the chunk's cases at `where`.

    Its base case holds the values of the length groups' axes at `where` (so its criteria
    are those of that train); its axes the chunk's values along the other dimensions.
    """
    axes = []
    for ax in spec.axes:
        d = layout.dims.index(ax.group)
        keep = slice(where[d], where[d] + 1) if d in where else slices[d]
        axes.append(
            SweepAxis(
                field=ax.field,
                dim=ax.dim,
                group=ax.group,
                values=tuple(ax.values[keep]),
                coords=tuple(ax.coords[keep]),
            )
        )
    # the block holds at most chunk_size cases, so it is the sub-sweep's one chunk
    return dataclasses.replace(spec, base_case=_case_at(spec, layout, where), axes=tuple(axes))
