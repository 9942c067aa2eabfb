"""How the cases of a sweep are laid out: dimensions, chunks, and the case of each index.

The sweep dimensions are the axis groups (one per axis, or one per ``zip``
label). Chunks are hyper-rectangular blocks of cases of at most ``chunk_size``
cases; the same blocks are the chunks of the Zarr store. Blocks are filled first
along the "cheap" dimensions (speed and irregularity, which share one track
solution), so each chunk batches as many cases per structure as possible.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from railvib.sweep.spec import SweepSpec

__all__ = ["CHEAP_FIELDS", "SweepLayout", "is_cheap_field", "is_pad_field"]

#: fields that change only the excitation, not the coupled system
CHEAP_FIELDS = ("speed_kmh", "irregularity")


def is_pad_field(field: str) -> bool:
    """Tell whether `field` changes the railpad only (its table, a parameter, its temperature).

    Cases differing in such fields share rail, sleepers, vehicle and contact, and are
    solved as one stack (:func:`railvib.sweep.stacked.frf_pad_stack`).

    Parameters
    ----------
    field : str
        Dotted case field, e.g. ``"track.pad.k0_n_per_m"``.

    Returns
    -------
    bool
        True for ``track.pad``, ``track.pad.*`` and ``track.pad_temperature_c``.
    """
    return field in ("track.pad", "track.pad_temperature_c") or field.startswith("track.pad.")


def is_cheap_field(field: str) -> bool:
    """Tell whether `field` leaves the track, vehicle and contact unchanged."""
    return field.split(".")[0] in CHEAP_FIELDS


@dataclass(frozen=True)
class SweepLayout:
    """Dimensions and chunk blocks of a resolved sweep.

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep, see :func:`railvib.sweep.spec.sweep_from_dict`.
    """

    spec: SweepSpec

    @cached_property
    def dims(self) -> tuple[str, ...]:
        """Sweep dimension names, in file order."""
        out: list[str] = []
        for ax in self.spec.axes:
            if ax.group not in out:
                out.append(ax.group)
        return tuple(out)

    @cached_property
    def shape(self) -> tuple[int, ...]:
        """Number of cases along each sweep dimension."""
        sizes = {ax.group: ax.size for ax in self.spec.axes}
        return tuple(sizes[d] for d in self.dims)

    @property
    def n_cases(self) -> int:
        """Total number of cases."""
        return int(np.prod(self.shape))

    @cached_property
    def block(self) -> tuple[int, ...]:
        """Chunk (block) shape along the sweep dimensions, at most ``chunk_size`` cases."""
        cheap = {
            d: all(is_cheap_field(a.field) for a in self.spec.axes if a.group == d)
            for d in self.dims
        }
        order = sorted(range(len(self.dims)), key=lambda i: (not cheap[self.dims[i]], -i))
        left = self.spec.chunk_size
        block = [1] * len(self.dims)
        for i in order:
            block[i] = max(1, min(self.shape[i], left))
            left = max(1, left // block[i])
        return tuple(block)

    @cached_property
    def grid(self) -> tuple[int, ...]:
        """Number of chunks along each sweep dimension."""
        return tuple(-(-n // b) for n, b in zip(self.shape, self.block, strict=True))

    @property
    def n_chunks(self) -> int:
        """Total number of chunks."""
        return int(np.prod(self.grid))

    def chunk_slices(self, chunk_id: int) -> tuple[slice, ...]:
        """Index ranges of chunk `chunk_id` (C order over the chunk grid)."""
        pos = np.unravel_index(chunk_id, self.grid)
        return tuple(
            slice(int(p) * b, min((int(p) + 1) * b, n))
            for p, b, n in zip(pos, self.block, self.shape, strict=True)
        )

    def chunk_shape(self, chunk_id: int) -> tuple[int, ...]:
        """Count the cases along each dimension in chunk `chunk_id`."""
        return tuple(s.stop - s.start for s in self.chunk_slices(chunk_id))

    def chunk_indices(self, chunk_id: int) -> NDArray[np.int64]:
        """Sweep indices of the cases of a chunk, ``(n_case, n_dim)``, C order.

        Parameters
        ----------
        chunk_id : int
            Chunk number, ``0 <= chunk_id < n_chunks`` (C order over the chunk grid).

        Returns
        -------
        numpy.ndarray
            Integer indices along each sweep dimension, shape ``(n_case, n_dim)``.
        """
        ranges = [np.arange(s.start, s.stop) for s in self.chunk_slices(chunk_id)]
        mesh = np.meshgrid(*ranges, indexing="ij")
        return np.stack([m.ravel() for m in mesh], axis=1)

    def overrides(self, index: NDArray[np.int64]) -> list[tuple[str, Any]]:
        """``(field, value)`` of every axis for the case at sweep `index`.

        The values are plain, mutable copies (tables as dicts), ready for
        :func:`railvib.case.merge_case_dicts`.

        Parameters
        ----------
        index : numpy.ndarray
            Integer index along each sweep dimension, shape ``(n_dim,)`` (a row of
            :meth:`chunk_indices`).

        Returns
        -------
        list of (str, object)
            Dotted case field and its value, one per sweep axis.
        """
        pos = dict(zip(self.dims, (int(i) for i in index), strict=True))
        return [(ax.field, ax.value(pos[ax.group])) for ax in self.spec.axes]

    def describe(self) -> str:
        """Say how many cases over which dimensions, in how many chunks.

        Returns
        -------
        str
            E.g. ``"12 cases (3 x 4 over track.pad_temperature_c, speed_kmh) in 3 chunks"``.
        """
        shape = " x ".join(map(str, self.shape))
        dims = ", ".join(self.dims)
        return f"{self.n_cases} cases ({shape} over {dims}) in {self.n_chunks} chunks"
