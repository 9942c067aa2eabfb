"""Frequency weightings of whole-body vibration: ISO 2631-1 Wk and Wd, ISO 2631-4 Wb, Sperling.

ISO 2631-1:1997, Annex A defines each weighting as the product
of analogue filters in ``p = i 2 pi f``:

* band limiting, high pass ``H_h = p^2 / (p^2 + w1 p / Q1 + w1^2)`` and low pass
  ``H_l = w2^2 / (p^2 + w2 p / Q2 + w2^2)``, ``Q1 = Q2 = 1/sqrt(2)``;
* acceleration-velocity transition ``H_t = (1 + p/w3) / (1 + p/(Q4 w4) + p^2/w4^2)``;
* upward step ``H_s = (p^2 + w5 p/Q5 + w5^2) / (p^2 + w6 p/Q6 + w6^2)`` (gain
  ``(f5/f6)^2`` at low frequency, 1 at high frequency);
* gain ``K``: ``W = K |H_h H_l H_t H_s|``.

Parameters (Hz): Wk (vertical, seated, ISO 2631-1 Annex A) f1 0.4, f2 100,
f3 = f4 12.5, Q4 0.63, f5 2.37, Q5 0.91, f6 3.35, Q6 0.91, K 1; Wd (horizontal)
f1 0.4, f2 100, f3 = f4 2, Q4 0.63, no step, K 1; Wb (vertical, rail vehicles,
ISO 2631-4:2001 Annex A and EN 12299:2009 Annex A; BS 6841:1987) f1 0.4, f2 100,
f3 = f4 16, Q4 0.55, f5 2.5, Q5 0.9, f6 4, Q6 0.95, K 1.024. ISO 8041 (human response
to vibration, measuring instrumentation) tabulates the same parameters of all
three, with ``Q1 = Q2 = 1/sqrt(2)`` exactly (ISO 2631-4 rounds Q1 to 0.71).

The Sperling ride index uses the weighting of Sperling (1941) as given by Garg and
Dukkipati, *Dynamics of Railway Vehicle Systems* (1984), section 12.3, for vertical
vibration: ``B(f) = 0.588 sqrt((1.911 f^2 + (0.25 f^2)^2) / ((1 - 0.277 f^2)^2 +
(1.563 f - 0.0368 f^3)^2))``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["COMFORT_RANGE_HZ", "WEIGHTINGS", "Weighting", "sperling_weighting"]

#: the frequency range of ISO 2631-1:1997 for comfort (clause 1, Scope: 0.5 Hz to 80 Hz)
COMFORT_RANGE_HZ = (0.5, 80.0)

_Q_BAND = 1.0 / np.sqrt(2.0)


@dataclass(frozen=True)
class Weighting:
    """A frequency weighting of ISO 2631-1 Annex A built from its analogue filters.

    Parameters
    ----------
    name : str
        E.g. ``"Wk"``.
    f1, f2 : float
        Band-limiting corner frequencies (high pass, low pass), Hz.
    f3, f4 : float
        Acceleration-velocity transition frequencies, Hz.
    q4 : float
        Its quality factor (dimensionless).
    f5, f6 : float or None
        Upward-step frequencies, Hz (None: no step).
    q5, q6 : float
        Their quality factors (dimensionless).
    gain : float
        K (dimensionless).
    source : str
        The clause and table defining it.
    """

    name: str
    f1: float
    f2: float
    f3: float
    f4: float
    q4: float
    f5: float | None
    q5: float
    f6: float | None
    q6: float
    gain: float
    source: str

    def transfer(self, f: ArrayLike) -> NDArray[np.complex128]:
        """The complex weighting ``K H_h H_l H_t H_s`` at `f` (Hz, >= 0), dimensionless."""
        p = 2j * np.pi * np.asarray(f, dtype=float)
        w1, w2, w3, w4 = (2.0 * np.pi * x for x in (self.f1, self.f2, self.f3, self.f4))
        out = p**2 / (p**2 + w1 * p / _Q_BAND + w1**2)
        out = out * w2**2 / (p**2 + w2 * p / _Q_BAND + w2**2)
        out = out * (1.0 + p / w3) / (1.0 + p / (self.q4 * w4) + (p / w4) ** 2)
        if self.f5 is not None and self.f6 is not None:
            w5, w6 = 2.0 * np.pi * self.f5, 2.0 * np.pi * self.f6
            out = out * (p**2 + w5 * p / self.q5 + w5**2) / (p**2 + w6 * p / self.q6 + w6**2)
        return np.asarray(self.gain * out)

    def magnitude(self, f: ArrayLike) -> NDArray[np.float64]:
        """``|W(f)|`` at `f` (Hz), dimensionless."""
        return np.abs(self.transfer(f))


#: the weightings railvib applies, by name (vertical: Wk, Wb; horizontal: Wd)
WEIGHTINGS: dict[str, Weighting] = {
    w.name: w
    for w in (
        Weighting(
            "Wk", 0.4, 100.0, 12.5, 12.5, 0.63, 2.37, 0.91, 3.35, 0.91, 1.0,
            "ISO 2631-1:1997, Annex A (vertical, seated)",
        ),
        Weighting(
            "Wd", 0.4, 100.0, 2.0, 2.0, 0.63, None, 0.0, None, 0.0, 1.0,
            "ISO 2631-1:1997, Annex A (horizontal)",
        ),
        Weighting(
            "Wb", 0.4, 100.0, 16.0, 16.0, 0.55, 2.5, 0.9, 4.0, 0.95, 1.024,
            "ISO 2631-4:2001, Annex A; EN 12299:2009, Annex A (vertical, rail vehicles)",
        ),
    )
}  # fmt: skip


def sperling_weighting(f: ArrayLike) -> NDArray[np.float64]:
    """Sperling's vertical weighting ``B(f)`` (Garg and Dukkipati 1984, section 12.3).

    Parameters
    ----------
    f : array_like
        Frequencies, Hz.

    Returns
    -------
    numpy.ndarray
        ``B(f)``, dimensionless.
    """
    f = np.asarray(f, dtype=float)
    num = 1.911 * f**2 + (0.25 * f**2) ** 2
    den = (1.0 - 0.277 * f**2) ** 2 + (1.563 * f - 0.0368 * f**3) ** 2
    return np.asarray(0.588 * np.sqrt(num / den))
