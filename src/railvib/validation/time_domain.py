"""Newmark average-acceleration integration of the vehicle on the finite track.

The effective matrix ``K + (2/dt) C + (4/dt^2) M`` is factorised once with
``scipy.sparse.linalg.splu``; every step is one sparse mat-vec, one triangular
solve and a few array updates, done for all realisations at once (the right-hand
sides are the columns of one array), so there is no Python work per DOF.

The scheme is unconditionally stable and undamped; for a linear system it is the
bilinear (Tustin) map, so a harmonic at ``f`` is answered as the continuous system
answers at ``tan(pi f dt) / (pi dt)``: with ``dt = 1e-4`` s that is +0.8 % at 500 Hz
and +3.3 % at 1 kHz.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.sparse import hstack
from scipy.sparse.linalg import splu

from railvib.errors import CaseError
from railvib.labels import response_labels
from railvib.validation.coupled import FiniteCoupledSystem

__all__ = ["TimeHistory", "newmark_frequency_warp", "simulate_time_domain"]


def newmark_frequency_warp(f: ArrayLike, dt: float) -> NDArray[np.float64]:
    """Frequency (Hz) at which the continuous system answers what Newmark shows at `f` (Hz).

    The average-acceleration (trapezoidal) Newmark scheme warps frequencies as
    ``f_c = tan(pi f dt) / (pi dt)``.

    Parameters
    ----------
    f : array_like
        Frequencies seen in the Newmark response, Hz, any shape (``f dt < 1/2``).
    dt : float
        Time step in s.

    Returns
    -------
    numpy.ndarray
        Frequencies of the continuous system in Hz, shape of `f`.
    """
    f = np.asarray(f, dtype=float)
    return np.tan(np.pi * f * dt) / (np.pi * dt)


@dataclass(frozen=True, eq=False)
class TimeHistory:
    """Accelerations recorded by :func:`simulate_time_domain`.

    Attributes
    ----------
    t : numpy.ndarray
        Sample times in s, ``(n_samples,)``.
    acceleration : numpy.ndarray
        ``(n_samples, n_output, n_realisations)``: m/s^2 (rad/s^2 for pitch DOFs).
    labels : tuple of str
        Name of each output.
    """

    t: NDArray[np.float64]
    acceleration: NDArray[np.float64]
    labels: tuple[str, ...]

    @property
    def sample_rate(self) -> float:
        """Samples per second, Hz."""
        return 1.0 / (self.t[1] - self.t[0])


def output_dofs(system: FiniteCoupledSystem) -> tuple[NDArray[np.intp], tuple[str, ...]]:
    """Global DOF indices and labels of the outputs: vehicle DOFs, then rail under the wheels."""
    nv = system.n_vehicle
    labels = response_labels(system.vehicle.dofs, system.rail_dofs.size, system.vehicle.wheel_names)
    return np.concatenate([np.arange(nv), system.rail_dofs]), labels


def simulate_time_domain(
    system: FiniteCoupledSystem,
    irregularity: ArrayLike,
    dt: float,
    *,
    decimation: int = 1,
    dofs: ArrayLike | None = None,
    labels: tuple[str, ...] | None = None,
    progress: Callable[[int], None] | None = None,
    chunk: int = 2000,
) -> TimeHistory:
    """Integrate the coupled system from rest under the irregularity at each wheel.

    Parameters
    ----------
    system : FiniteCoupledSystem
        Vehicle, finite track and Hertz springs (the track pads must be viscous).
    irregularity : array_like
        ``(n_steps + 1, n_wheel)`` or ``(n_steps + 1, n_wheel, n_realisations)``,
        irregularity in m (positive a dip) under each wheel at ``t = k dt``, delays
        already applied. It should start at 0 (the system starts at rest).
    dt : float
        Time step in s (> 0).
    decimation : int
        Record every `decimation`-th step (the input must have no content above the
        resulting Nyquist frequency ``1 / (2 dt decimation)``).
    dofs : array_like of int, optional
        Global DOFs to record; default all vehicle DOFs and the rail under the wheels.
    labels : tuple of str, optional
        Names of `dofs`.
    progress : callable, optional
        Called with the number of steps just done (for a progress bar).
    chunk : int
        Steps between progress calls.

    Returns
    -------
    TimeHistory
        Accelerations at the recorded steps.
    """
    if not (np.isfinite(dt) and dt > 0):
        raise CaseError("dt", dt, "must be > 0 (s)")
    r = np.asarray(irregularity, dtype=float)
    if r.ndim == 2:
        r = r[:, :, None]
    n_wheel = system.rail_dofs.size
    if r.ndim != 3 or r.shape[1] != n_wheel or r.shape[0] < 2:
        raise CaseError("irregularity", r.shape, f"(n_steps + 1, {n_wheel}[, n_realisations])")
    if dofs is None:
        dofs, labels = output_dofs(system)
    dofs = np.asarray(dofs, dtype=int)
    labels = labels if labels is not None else tuple(str(i) for i in dofs)
    q = int(decimation)
    if q < 1:
        raise CaseError("decimation", decimation, ">= 1")

    m, c, k = system.time_domain_matrices()
    lu = splu((k + (2.0 / dt) * c + (4.0 / dt**2) * m).tocsc())
    history = hstack([(4.0 / dt) * m + 2.0 * c, 2.0 * m], format="csr")
    force = system.force_matrix().toarray()
    f_rows = np.flatnonzero(np.any(force != 0.0, axis=1))
    f_sub = force[f_rows]  # (n_rows, n_wheel)

    n = m.shape[0]  # the system's DOFs and the internal ones of Maxwell layers
    n_steps = r.shape[0] - 1
    n_real = r.shape[2]
    state = np.zeros((2 * n, n_real))  # [v; a]
    vel, acc = state[:n], state[n:]
    n_rec = n_steps // q + 1
    out = np.zeros((n_rec, dofs.size, n_real))
    c_a, c_v = 4.0 / dt**2, 4.0 / dt
    two_dt = 2.0 / dt
    for start in range(0, n_steps, chunk):
        stop = min(start + chunk, n_steps)
        d_force = np.einsum("ij,sjr->sir", f_sub, np.diff(r[start : stop + 1], axis=0))
        for step in range(start, stop):
            rhs = history @ state
            rhs[f_rows] += d_force[step - start]
            du = lu.solve(rhs)
            acc *= -1.0
            acc += c_a * du - c_v * vel
            vel *= -1.0
            vel += two_dt * du
            if (step + 1) % q == 0:
                out[(step + 1) // q] = acc[dofs]
        if progress is not None:
            progress(stop - start)
    t = np.arange(n_rec) * dt * q
    return TimeHistory(t=t, acceleration=out, labels=labels)
