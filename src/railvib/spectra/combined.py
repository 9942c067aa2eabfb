"""A long-wave spectrum joined to a short-wave one at a split wavelength."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.registry import MAX_MEMBER_DEPTH, parameter
from railvib.spectra._checks import as_wavenumber
from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = ["Combined"]


@SPECTRA.register("combined")
@dataclass(frozen=True)
class Combined(SpatialSpectrum):
    """Long-wave spectrum above the split wavelength, short-wave spectrum below it.

    With ``blend_decades == 0`` (default) the switch is hard, as in the paper: wavelengths
    strictly longer than `split_wavelength_m` (Omega < 2 pi / split) use `long_wave`, and
    wavelengths shorter than **or equal to** the split (Omega >= 2 pi / split) use
    `short_wave`. The joined spectrum is discontinuous at the split (the paper's class 5 +
    Shi-tai recipe jumps up by a factor of about 2.55 at 1 m).

    With ``blend_decades > 0`` the two are blended smoothly in log space over that many
    decades of Omega centred on the split: ``S = S_long^(1 - w) S_short^w`` with ``w`` a
    C1 smoothstep of ``log10(Omega / Omega_split)`` going from 0 to 1 over
    ``[-blend_decades / 2, +blend_decades / 2]``. Where either spectrum is zero inside the
    blend zone the arithmetic blend ``(1 - w) S_long + w S_short`` is used instead.

    Parameters
    ----------
    long_wave : SpatialSpectrum
        Spectrum used at wavelengths above the split (m^2/(rad/m)).
    short_wave : SpatialSpectrum
        Spectrum used at wavelengths below the split (m^2/(rad/m)).
    split_wavelength_m : float
        Split wavelength in m (> 0). Default 1.0 (the paper).
    blend_decades : float
        Width of the smooth blend in decades of wavenumber (>= 0). Default 0.0: hard switch.
    """

    long_wave: SpatialSpectrum = parameter(
        "m^2/(rad/m)", "spectrum above the split wavelength", kind="member", family=SPECTRA
    )
    short_wave: SpatialSpectrum = parameter(
        "m^2/(rad/m)", "spectrum below the split wavelength", kind="member", family=SPECTRA
    )
    split_wavelength_m: float = parameter(
        "m", "split wavelength", default=1.0, gt=0.0, le=1e3, typical=(0.5, 2.0)
    )
    blend_decades: float = parameter(
        "decades",
        "width of a smooth log-space blend (0: hard switch)",
        default=0.0,
        ge=0.0,
        le=10.0,
    )

    def validate(self) -> None:
        """At most :data:`railvib.registry.MAX_MEMBER_DEPTH` spectra nested in each other."""
        long, short = _depth(self.long_wave), _depth(self.short_wave)
        depth = 1 + max(long, short)
        if depth > MAX_MEMBER_DEPTH:
            raise CaseError(
                "long_wave" if long >= short else "short_wave",
                f"<combined spectra {depth} deep>",
                f"combined spectra nested at most {MAX_MEMBER_DEPTH} deep",
            )
        object.__setattr__(self, "_depth", depth)  # not a field: kept out of eq, repr, dicts

    @property
    def depth(self) -> int:
        """Combined spectra nested in this one, counting itself: 1 for two plain spectra."""
        return int(self.__dict__["_depth"])

    @property
    def split_wavenumber_rad_per_m(self) -> float:
        """Wavenumber of the split, ``2 pi / split_wavelength_m``, in rad/m."""
        return 2.0 * np.pi / self.split_wavelength_m

    def steps_rad_per_m(self) -> tuple[float, ...]:
        """Wavenumbers (rad/m) of the jumps: the hard split, and those of the two members.

        Returns
        -------
        tuple of float
            Ascending, in rad/m: the split wavenumber when ``blend_decades == 0`` (the
            joined spectrum is discontinuous there), and each member's own steps on the
            side of the split where that member is used.
        """
        om_s = self.split_wavenumber_rad_per_m
        steps = [om for om in self.long_wave.steps_rad_per_m() if om < om_s]
        steps += [om for om in self.short_wave.steps_rad_per_m() if om > om_s]
        if self.blend_decades == 0.0:
            steps.append(om_s)
        return tuple(sorted(steps))

    def short_wave_weight(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """Weight w in [0, 1] of the short-wave spectrum at `wavenumber` (rad/m, > 0)."""
        om = as_wavenumber(wavenumber)
        om_s = self.split_wavenumber_rad_per_m
        if self.blend_decades == 0.0:
            return np.where(om >= om_s, 1.0, 0.0)
        t = np.clip(np.log10(om / om_s) / self.blend_decades + 0.5, 0.0, 1.0)
        return t * t * (3.0 - 2.0 * t)

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at spatial circular frequency `wavenumber` (rad/m, > 0)."""
        om = as_wavenumber(wavenumber)
        w = self.short_wave_weight(om)
        s_long = np.asarray(self.long_wave.psd(om), dtype=float)
        s_short = np.asarray(self.short_wave.psd(om), dtype=float)
        if self.blend_decades == 0.0:
            return np.where(w == 1.0, s_short, s_long)
        both = (s_long > 0.0) & (s_short > 0.0)
        with np.errstate(divide="ignore"):
            geometric = np.exp(
                (1.0 - w) * np.log(np.where(both, s_long, 1.0))
                + w * np.log(np.where(both, s_short, 1.0))
            )
        arithmetic = (1.0 - w) * s_long + w * s_short
        return np.where(both, geometric, arithmetic)


def _depth(spectrum: SpatialSpectrum) -> int:
    """:attr:`Combined.depth` of `spectrum`, 0 for a spectrum that holds no other."""
    return spectrum.depth if isinstance(spectrum, Combined) else 0
