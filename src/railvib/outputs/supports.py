"""Forces through the rail seats under the wheels: pad, ballast and subgrade (issue 16).

The rail displacement at a seat follows from the contact forces through the track's
transfer receptance, ``w(x_s) = sum_j alpha(x_s, x_j) P_j`` (``P`` compressive positive,
displacements positive downward: :mod:`railvib.coupling`), and the seat's layers from
that displacement (:meth:`railvib.track.PeriodicTrack.seat_response`). Both are linear,
so the force of each layer per metre of irregularity is an FRF like the contact force's,
and its PSD is ``|H|^2 S_r``.

The seat of each wheel is the rail seat nearest it (at exactly mid-span, the one ahead).
Forces are per rail seat of one rail: a ``rail_pair`` track, whose seats stand for both
rails, is divided by its factor 2. A slab track gives its supports under all the contact
forces together (:meth:`railvib.track.slab.SlabTrack.seat_forces`: the slab couples the
seats): on bearings the pad and the bearing nearest each wheel, on a continuous foundation
the foundation under the slab bay (fastener spacing) holding each wheel, ``k_f* int w_s dx``
over the bay, per bay of one rail.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.coupling import FREQUENCY_BLOCK, CoupledSystem
from railvib.grid import trapezoid
from railvib.pads.scaled import ScaledPad
from railvib.track.slab import SlabTrack

__all__ = [
    "gives_seat_forces",
    "seat_positions",
    "support_force_data",
    "support_force_psd",
    "support_variables",
    "support_force_variables",
]


def seat_positions(wheel_positions: NDArray[np.float64], spacing: float) -> NDArray[np.float64]:
    """The rail seat nearest each wheel (the one ahead at exactly mid-span), m.

    Parameters
    ----------
    wheel_positions : numpy.ndarray
        Wheel positions along the rail, m.
    spacing : float
        Sleeper (fastener) spacing, m; seats lie at ``n * spacing``.

    Returns
    -------
    numpy.ndarray
        Seat positions, m, one per wheel.
    """
    # 1e-9 of a bay: a wheel at mid-span up to rounding (-12.3 / 0.6 = -20.500000000000004)
    # still takes the seat ahead
    return np.floor(np.asarray(wheel_positions, dtype=float) / spacing + 0.5 + 1e-9) * spacing


def gives_seat_forces(system: CoupledSystem, f: NDArray[np.float64]) -> bool:
    """Whether the track of `system` gives the forces through its rail seats (not a slab's).

    Parameters
    ----------
    system : CoupledSystem
        The system (its track).
    f : numpy.ndarray
        The run's frequencies, Hz (the first is tried: a tabulated layer's range holds it).

    Returns
    -------
    bool
        False where the track's ``seat_response`` raises NotImplementedError.
    """
    track = system.track
    seat = seat_positions(system.wheel_positions[:1], track.sleeper_spacing)
    try:
        track.seat_response(f[:1], seat, np.zeros((1, 1), dtype=np.complex128))
    except NotImplementedError:
        return False
    return True


def support_force_variables(
    system: CoupledSystem, ds: xr.Dataset, rail: NDArray[np.complex128] | None = None
) -> dict[str, xr.DataArray]:
    """PSD and RMS of the force in each layer of the seat under each wheel.

    Parameters
    ----------
    system : CoupledSystem
        The system of the result (its track and wheel positions).
    ds : xarray.Dataset
        The result as built in memory: ``frf_force`` (complex contact force per metre of
        irregularity, N/m) and ``irregularity_psd`` (m^2/Hz) over ``frequency``.
    rail : numpy.ndarray, optional
        The rail displacement at the seats (:func:`seat_positions`) per metre of
        irregularity, ``(frequency, wheel)``, m/m, where the solve gave it
        (``CoupledSystem.frf_blocks(observe=seats)``: ``FRF.rail_observed``); default:
        from the contact forces through the track's receptance.

    Returns
    -------
    dict of str to xarray.DataArray
        ``psd_support_force`` (``frequency``, ``wheel``, ``layer``), N^2/Hz, and
        ``support_force_rms`` (``wheel``, ``layer``), N, with the ``layer`` coordinate
        (``pad``, then ``ballast``, ``subgrade`` or ``bearing`` where the track has them;
        ``foundation`` alone for a slab bay on a continuous foundation) and
        ``support_position`` (``wheel``, m); empty for a track without seat forces.
    """
    out = support_force_data(system, ds, rail)
    coords = {k: out.pop(k) for k in SUPPORT_COORDS if k in out}
    return {
        name: xr.DataArray(var, coords={k: c for k, c in coords.items() if c.dims[0] in var.dims})
        for name, var in out.items()
    }


def support_force_data(
    system: CoupledSystem,
    ds: xr.Dataset | Mapping[str, xr.Variable],
    rail: NDArray[np.complex128] | None = None,
) -> dict[str, xr.Variable]:
    """:func:`support_force_variables` as variables, not yet a dataset's.

    Parameters
    ----------
    system : CoupledSystem
        The system of the result.
    ds : xarray.Dataset or mapping
        ``frequency`` (Hz), ``frf_force`` (N/m) and ``irregularity_psd`` (m^2/Hz), as
        in :func:`support_force_variables` or as variables by name.
    rail : numpy.ndarray, optional
        The rail displacement at the seats per metre of irregularity, m/m, as in
        :func:`support_force_variables`.

    Returns
    -------
    dict of xarray.Variable
        ``psd_support_force`` and ``support_force_rms``, and their coordinates
        (:data:`SUPPORT_COORDS`: ``layer`` and ``support_position``); empty for a track
        without seat forces.
    """
    f = ds["frequency"].values
    parts = support_force_psd(
        system, f, ds["irregularity_psd"].values, lambda: ds["frf_force"].values, rail
    )
    return support_variables(f, parts)


def support_variables(
    f: NDArray[np.float64],
    parts: tuple[NDArray[np.float64], list[str], NDArray[np.float64]] | None,
) -> dict[str, xr.Variable]:
    """The variables of :func:`support_force_data` from :func:`support_force_psd`'s arrays.

    Parameters
    ----------
    f : numpy.ndarray
        Frequencies, Hz, ``(n_freq,)``.
    parts : tuple or None
        The seat positions (m), layer names and PSDs (N^2/Hz) of
        :func:`support_force_psd`, or None (no seat forces).

    Returns
    -------
    dict of xarray.Variable
        As :func:`support_force_data`; empty for None.
    """
    return {} if parts is None else _variables(f, *parts)


def support_force_psd(
    system: CoupledSystem,
    f: NDArray[np.float64],
    irregularity_psd: NDArray[np.float64],
    contact_force: NDArray[np.complex128] | Callable[[], NDArray[np.complex128]],
    rail: NDArray[np.complex128] | None = None,
) -> tuple[NDArray[np.float64], list[str], NDArray[np.float64]] | None:
    """The PSDs of :func:`support_force_data` as arrays (a streamed run's later blocks).

    Parameters
    ----------
    system : CoupledSystem
        The system of the result.
    f : numpy.ndarray
        Frequencies, Hz, ``(n_freq,)``.
    irregularity_psd : numpy.ndarray
        One-sided temporal irregularity PSD, m^2/Hz, ``(n_freq,)``.
    contact_force : numpy.ndarray or callable
        The contact forces per metre of irregularity, N/m, ``(n_freq, n_wheel)``, or a
        callable giving them (called only where they are needed: a slab, or `rail` not
        given; a lazily opened file's variable is then not read).
    rail : numpy.ndarray, optional
        The rail displacement at the seats per metre of irregularity, m/m, as in
        :func:`support_force_variables`.

    Returns
    -------
    tuple or None
        The seat (or bay) positions, m, the layer names, and the PSDs, N^2/Hz,
        ``(frequency, wheel, layer)``; None for a track without seat forces.
    """
    track = system.track
    s_r = irregularity_psd
    forces = contact_force if callable(contact_force) else lambda: contact_force
    per_rail = track.pad.factor if isinstance(track.pad, ScaledPad) else 1.0
    if isinstance(track, SlabTrack):  # the slab couples the seats: all wheels at once
        contact = np.asarray(forces(), dtype=np.complex128)  # (frequency, wheel)
        support = track.seat_forces(f, system.wheel_positions, contact)
        slab_layers = list(support.force)
        psd = np.stack(
            [np.abs(support.force[name] / per_rail) ** 2 * s_r[:, None] for name in slab_layers],
            axis=-1,
        )  # (frequency, wheel, layer)
        return support.x, slab_layers, psd
    seats = seat_positions(system.wheel_positions, track.sleeper_spacing)
    if not gives_seat_forces(system, f):  # a track without seats modelled one by one
        return None
    names: list[str] = []
    psd = np.empty((f.size, seats.size, 0))
    # block by block, so the temporaries are a block's whatever the grid
    for start in range(0, f.size, FREQUENCY_BLOCK):
        sl = slice(start, start + FREQUENCY_BLOCK)
        if rail is None:
            contact = np.asarray(forces()[sl], dtype=np.complex128)
            receptance = track.receptance(f[sl], system.wheel_positions, seats)  # (f, seat, w)
            rail_block = np.einsum("fsw,fw->fs", receptance, contact)
        else:
            rail_block = rail[sl]
        layers = track.seat_response(f[sl], seats, rail_block).force
        if not names:
            names = list(layers)
            psd = np.empty((f.size, seats.size, len(names)))  # (frequency, wheel, layer)
        for i, name in enumerate(names):  # |F / per_rail|^2 S_r, in place
            size = np.abs(layers[name] if per_rail == 1.0 else layers[name] / per_rail)
            np.multiply(np.multiply(size, size, out=size), s_r[sl, None], out=psd[sl, :, i])
    return seats, names, psd


#: the coordinates among :func:`support_force_data`'s variables
SUPPORT_COORDS = ("layer", "support_position")

#: the long name of the ``layer`` coordinate
LAYER_LONG_NAME = "layer of the rail seat, top down"


def _variables(
    f: NDArray[np.float64], seats: NDArray[np.float64], names: list[str], psd: NDArray[np.float64]
) -> dict[str, xr.Variable]:
    """The support-force variables of `psd` (N^2/Hz, ``(frequency, wheel, layer)``)."""
    coords = {
        "layer": xr.IndexVariable(
            "layer", names, {"long_name": "layer of the rail seat, top down"}
        ),
        "support_position": xr.Variable(
            "wheel",
            seats,
            {"units": "m", "long_name": "rail seat under each wheel (the nearest one)"},
        ),
    }
    where = "through the rail seat nearest each wheel, per seat of one rail"
    data = {
        "psd_support_force": xr.Variable(
            ("frequency", "wheel", "layer"),
            psd,
            {"units": "N^2/Hz", "long_name": f"PSD of the force in each layer {where}"},
        ),
        "support_force_rms": xr.Variable(
            ("wheel", "layer"),
            np.sqrt(trapezoid(psd, f, axis=0)),
            {"units": "N", "long_name": f"RMS of the force in each layer {where}"},
        ),
    }
    return data | coords
