"""A speed profile: knots joined by segments of constant acceleration."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError

__all__ = ["SpeedProfile"]


@dataclass(frozen=True, eq=False)
class SpeedProfile:
    """Position and speed of the leading wheel against time, piecewise uniformly accelerated.

    Parameters
    ----------
    t : numpy.ndarray
        Times of the knots, s, increasing from 0, ``(n_knot,)``.
    x : numpy.ndarray
        Position of the leading wheel at the knots, m, from 0, ``(n_knot,)``.
    v : numpy.ndarray
        Speed at the knots, m/s, >= 0, ``(n_knot,)``; between knots the speed is
        linear in time (``x`` must be consistent: ``diff(x) = (v_a + v_b) diff(t) / 2``).
    """

    t: NDArray[np.float64]
    x: NDArray[np.float64]
    v: NDArray[np.float64]

    def __post_init__(self) -> None:
        t, x, v = (np.asarray(a, dtype=float) for a in (self.t, self.x, self.v))
        if t.ndim != 1 or t.size < 2 or x.shape != t.shape or v.shape != t.shape:
            raise CaseError("speed_profile", t.shape, "at least 2 knots of (t, x, v)")
        if not (np.all(np.isfinite(t)) and np.all(np.diff(t) > 0)):
            raise CaseError("speed_profile.time_s", t.tolist(), "finite and increasing (s)")
        if not (np.all(np.isfinite(v)) and np.all(v >= 0)):
            raise CaseError("speed_profile.speeds_kmh", v.tolist(), "finite and >= 0")
        dx = 0.5 * (v[1:] + v[:-1]) * np.diff(t)
        if not np.allclose(
            np.diff(x), dx, rtol=1e-9, atol=1e-12 * max(1.0, float(np.abs(x).max()))
        ):
            raise CaseError("speed_profile.position_m", x.tolist(), "diff(x) = (v_a + v_b) dt / 2")
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "v", v)

    @classmethod
    def uniform(cls, v_start: float, v_end: float, acceleration: float) -> SpeedProfile:
        """From `v_start` to `v_end` (m/s) at the constant ``|acceleration|`` (m/s^2, > 0)."""
        duration = abs(v_end - v_start) / acceleration
        return cls(
            np.array([0.0, duration]),
            np.array([0.0, 0.5 * (v_start + v_end) * duration]),
            np.array([v_start, v_end], dtype=float),
        )

    @classmethod
    def constant(cls, speed: float, duration: float) -> SpeedProfile:
        """`speed` (m/s) for `duration` (s)."""
        return cls(
            np.array([0.0, duration]), np.array([0.0, speed * duration]), np.array([speed, speed])
        )

    @property
    def duration(self) -> float:
        """Length of the run, s."""
        return float(self.t[-1] - self.t[0])

    @property
    def v_max(self) -> float:
        """Highest speed, m/s."""
        return float(self.v.max())

    @property
    def acceleration_max(self) -> float:
        """Largest ``|acceleration|``, m/s^2."""
        return float(np.max(np.abs(np.diff(self.v) / np.diff(self.t))))

    def _segment(self, time: ArrayLike) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
        tt = np.clip(np.asarray(time, dtype=float), self.t[0], self.t[-1])
        i = np.clip(np.searchsorted(self.t, tt, side="right") - 1, 0, self.t.size - 2)
        return i, tt - self.t[i]

    def acceleration(self, time: ArrayLike) -> NDArray[np.float64]:
        """Acceleration at `time` (s), m/s^2 (that of the segment starting at or before it)."""
        i, _ = self._segment(time)
        return (np.diff(self.v) / np.diff(self.t))[i]

    def speed(self, time: ArrayLike) -> NDArray[np.float64]:
        """Speed at `time` (s), m/s."""
        i, tau = self._segment(time)
        return self.v[i] + self.acceleration(time) * tau

    def position(self, time: ArrayLike) -> NDArray[np.float64]:
        """Position of the leading wheel at `time` (s), m (exact for the piecewise profile)."""
        i, tau = self._segment(time)
        return self.x[i] + self.v[i] * tau + 0.5 * self.acceleration(time) * tau**2
