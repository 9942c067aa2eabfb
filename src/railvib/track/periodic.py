"""The rail as an infinite periodic structure, solved by the symplectic (wave) method.

The cell is one sleeper bay: the rail span from just right of sleeper ``n`` to
just right of sleeper ``n+1`` (the pad at sleeper ``n+1`` belongs to the cell).
Its transfer matrix is symplectic, so its eigenvalues come in pairs
``(mu, 1/mu)``; the two waves with ``|mu| < 1`` decay to the right (where
``|mu| ~ 1`` the choice is made by the direction of energy flow) and their
mirror images decay to the left. An undamped rail is solved in the limit of
vanishing loss (``VANISHING_LOSS_FACTOR``), so that a finite, passive answer
exists at its pinned-pinned frequencies too. A point load is matched by the
decaying waves on each side of it, given at its nearest sleeper, and the
response anywhere follows by propagating each wave with ``mu^k`` (never
``mu^-k``) and the exact beam field over at most half a span. See
``docs/design/0002-track-solver.md``.

Positions ``x`` are measured along the rail in m, with sleepers at ``x = n d``.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.docstrings import fill_doc
from railvib.errors import CaseError, SolverWarning
from railvib.pads.base import PADS, PadModel
from railvib.registry import Parameter, check_parameters, check_value, parameter
from railvib.stack import stacked
from railvib.track.base import TRACKS, SupportResponse, TrackModel
from railvib.track.beam import (
    dynamic_stiffness,
    field_transfer,
    krylov_series,
    timoshenko_transfer,
)
from railvib.track.stacked import receptance_entries, stacked_waves
from railvib.track.timoshenko import Span, bay_waves, span_terms

__all__ = ["MAX_BAY_WAVENUMBER", "PeriodicTrack", "Rail", "TrackWaves"]

#: parameter documentation shared by the track methods (:func:`railvib.docstrings.fill_doc`)
_SHARED = {
    "f": """f : array_like
    Frequencies in Hz (> 0), shape ``(n_freq,)``.""",
}


#: wave-matching condition number (rows equilibrated) above which results are flagged with
#: a SolverWarning: ~1e-10 from a pinned-pinned frequency, where the vanishing loss matters
CONDITION_WARNING = 1e5

#: where ``| |mu| - 1 |`` is below this, waves are sorted by energy flow, not modulus
ENERGY_FLOW_TOLERANCE = 1e-6

#: largest bending wavenumber times sleeper spacing, ``|beta4|^(1/4) = (m omega^2 d^4 /
#: |EI*|)^(1/4)`` (dimensionless; CHN60 at d = 0.6 m: 5.9 at 5 kHz): the bay's power series
#: then needs terms up to 1/170!, the last factorial within float64, and the bay's
#: transfer matrix holds cosh(40) ~ 1e17, still finite
MAX_BAY_WAVENUMBER = 40.0

#: below this volume of the three unit rows, a Bloch vector is taken from an SVD
WEAK_CROSS_PRODUCT = 1e-3

#: the smallest rail loss factor the solver uses: an undamped rail is solved in the limit
#: ``eta_r -> 0+`` (``exp(+i omega t)``), evaluated at this value (docs/design/0002-track-solver.md)
VANISHING_LOSS_FACTOR = 1e-12

#: below this ``|a^2 + b^2|`` (the Timoshenko span's two wavenumbers, squared and times
#: d^2) the bay's waves come from its entries and its half-span pencil, which are then
#: no larger than ``cosh 2``, instead of the closed form (:mod:`railvib.track.timoshenko`)
SMALL_WAVENUMBERS = 4.0

#: mirror image ``x -> -x`` of a state ``(w, d psi, d^2 psi', d^3 v)``
_MIRROR = np.array([1.0, -1.0, 1.0, -1.0])


@dataclass(frozen=True)
class Rail:
    """The rail beam: Euler-Bernoulli, or Timoshenko when a shear stiffness is given.

    Parameters
    ----------
    bending_stiffness : float
        EI in N m^2 (> 0). CHN60, one rail: 6.62e6.
    mass_per_length : float
        m in kg/m (> 0). CHN60, one rail: 60.64.
    loss_factor : float
        Rail material loss factor eta_r (>= 0); EI (and kappa G A) become
        EI (1 + i eta_r).
    shear_stiffness : float, optional
        kappa G A in N (> 0). Given: a Timoshenko beam (shear deformation and
        rotary inertia); None: Euler-Bernoulli. CHN60: 0.4 x 7.9e10 x 7.745e-3 = 2.45e8.
    rotary_inertia : float
        rho I, rotary inertia per unit length in kg m (>= 0), used by the
        Timoshenko beam. CHN60: 7850 x 3.217e-5 = 0.2525.
    """

    # upper bounds: some 100 times any rail's value (CHN60: 6.62e6 N m^2, 60.64 kg/m,
    # eta_r ~ 0.01), so that no real rail is refused and products of them stay finite
    bending_stiffness: float = parameter(
        "N m^2",
        "bending stiffness EI of the rail beam",
        gt=0.0,
        le=1e10,
        typical=(3e6, 1.2e7),
        log=True,
    )
    mass_per_length: float = parameter(
        "kg/m", "mass per unit length of the rail beam", gt=0.0, le=1e4, typical=(40.0, 80.0)
    )
    loss_factor: float = parameter(
        "-", "rail loss factor eta_r (EI -> EI (1 + i eta_r))", default=0.0, ge=0.0, le=1.0
    )
    shear_stiffness: float | None = parameter(
        "N",
        "kappa G A; given, the rail is a Timoshenko beam (CHN60: 2.45e8), omitted, an "
        "Euler-Bernoulli beam as in the paper",
        default=None,
        kind="number",
        gt=0.0,
        le=1e20,  # far above any rail (2.45e8), so a near-rigid shear (Euler limit) is allowed
    )
    rotary_inertia: float = parameter(
        "kg m",
        "rho I, rotary inertia per length of a Timoshenko rail (CHN60: 0.2525)",
        default=0.0,
        ge=0.0,
        le=1e3,
    )

    def __post_init__(self) -> None:
        check_parameters(self, "must", prefix="track.rail.")
        if self.rotary_inertia > 0 and self.shear_stiffness is None:
            raise CaseError(
                "track.rail.rotary_inertia",
                self.rotary_inertia,
                "needs shear_stiffness too (a Timoshenko rail); leave it 0 for an Euler rail",
            )

    @property
    def is_timoshenko(self) -> bool:
        """True when the rail is a Timoshenko beam."""
        return self.shear_stiffness is not None

    @property
    def complex_bending_stiffness(self) -> complex:
        """``EI (1 + i eta_r)`` in N m^2."""
        return self.bending_stiffness * (1.0 + 1j * self.loss_factor)

    @property
    def cut_off_frequency_hz(self) -> float | None:
        """Cut-off of a Timoshenko rail's second wave pair, ``sqrt(kGA / rho I) / 2 pi``, Hz.

        None for an Euler rail or a Timoshenko rail without rotary inertia (no cut-off).
        """
        if self.shear_stiffness is None or self.rotary_inertia <= 0:
            return None
        return float(np.sqrt(self.shear_stiffness / self.rotary_inertia) / (2.0 * np.pi))


@dataclass(frozen=True, eq=False)
class TrackWaves:
    """The decaying waves of the periodic rail at each frequency (dimensionless).

    Attributes
    ----------
    f : numpy.ndarray
        Frequencies, Hz, ``(n_freq,)``.
    beta4 : numpy.ndarray
        ``m omega^2 d^4 / EI*``, ``(n_freq,)``.
    mu : numpy.ndarray
        Propagation constants of the right-going waves, ``|mu| <= 1``, ``(n_freq, 2)``.
    right, left : numpy.ndarray
        Wave states ``(w, d w', d^2 w'', d^3 w''')`` just right of a sleeper,
        ``(n_freq, 4, 2)``; ``right[..., j]`` decays to the right by ``mu_j`` per bay,
        ``left[..., j]`` decays to the left by ``mu_j`` per bay.
    scale : numpy.ndarray
        ``d^3 / EI*`` in m/N: converts a dimensionless displacement per unit
        dimensionless force to a receptance.
    pad : numpy.ndarray
        Dimensionless pad stiffness ``K* d^3 / EI*``, ``(n_freq,)``.
    """

    f: NDArray[np.float64]
    beta4: NDArray[np.complex128]
    mu: NDArray[np.complex128]
    right: NDArray[np.complex128]
    left: NDArray[np.complex128]
    scale: complex
    pad: NDArray[np.complex128]
    _matching_inv: NDArray[np.complex128] = field(repr=False)


@dataclass(frozen=True)
class PeriodicTrack(TrackModel):
    """Rail on discrete railpads at every sleeper, rigid below (embedded sleepers).

    Parameters
    ----------
    rail : Rail
        The rail beam.
    pad : PadModel
        Railpad model, complex stiffness per rail seat in N/m.
    sleeper_spacing : float
        Sleeper spacing d in m (> 0).
    pad_temperature : float, optional
        Pad temperature in degrees Celsius, passed to the pad model.

    Examples
    --------
    >>> from railvib.pads import SpringDamper
    >>> track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
    >>> alpha = track.receptance([10.0, 100.0], x_load=[0.3], x_obs=[0.3])
    >>> alpha.shape
    (2, 1, 1)
    """

    rail: Rail
    pad: PadModel
    sleeper_spacing: float
    pad_temperature: float | None = None

    def __post_init__(self) -> None:
        spacing, temperature = RIGID_BASE_PARAMETERS[0], RIGID_BASE_PARAMETERS[3]
        check_value(spacing, self.sleeper_spacing, "track.sleeper_spacing")
        if self.pad_temperature is not None:
            check_value(temperature, self.pad_temperature, "track.pad_temperature_c")

    @property
    def max_frequency_hz(self) -> float:
        """Highest frequency the track is solved at, Hz (see :data:`MAX_BAY_WAVENUMBER`)."""
        d, rail = self.sleeper_spacing, self.rail
        stiffness = abs(rail.complex_bending_stiffness)
        # in this order, so a tiny spacing gives inf rather than a division by d**4 = 0
        omega = MAX_BAY_WAVENUMBER**2 * float(np.sqrt(stiffness / rail.mass_per_length)) / d / d
        return omega / (2.0 * np.pi)

    def check_frequencies(self, f: ArrayLike) -> None:
        """Refuse frequencies above :attr:`max_frequency_hz` (named as ``frequency.f_max``).

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Raises
        ------
        CaseError
            Naming the highest frequency and the limit for this rail and sleeper spacing.
        """
        f_top = float(np.max(f, initial=0.0))
        limit = self.max_frequency_hz
        if f_top > limit:
            raise CaseError(
                "frequency.f_max",
                f_top,
                f"at most {limit:.4g} Hz for this rail and sleeper spacing (the rail's bending "
                f"wavenumber times the spacing reaches {MAX_BAY_WAVENUMBER:g} there, beyond "
                "what the bay's series can hold); lower f_max or check track.sleeper_spacing "
                "and track.rail (Hz)",
            )

    def pinned_pinned_frequencies_hz(self, f_max: float) -> NDArray[np.float64]:
        """Pinned-pinned frequencies of one bay up to `f_max`, Hz.

        The n-th bending mode of a span simply supported at both sleepers, ``k = n pi / d``:
        ``omega^2 = EI k^4 / m`` for an Euler rail; for a Timoshenko rail the lower root of
        ``rho I (m / kGA) omega^4 - ((EI m / kGA + rho I) k^2 + m) omega^2 + EI k^4 = 0``.

        Parameters
        ----------
        f_max : float
            Highest frequency, Hz.

        Returns
        -------
        numpy.ndarray
            Ascending frequencies in Hz.
        """
        rail, d = self.rail, self.sleeper_spacing
        ei, m = rail.bending_stiffness, rail.mass_per_length
        out: list[float] = []
        n = 1
        while True:
            k = n * np.pi / d
            if rail.shear_stiffness is None:
                w2 = ei * k**4 / m
            else:  # the lower root, in the form without cancellation
                kga, rho_i = rail.shear_stiffness, rail.rotary_inertia
                a, b = rho_i * m / kga, -((ei * m / kga + rho_i) * k**2 + m)
                w2 = 2.0 * ei * k**4 / (-b + np.sqrt(b * b - 4.0 * a * ei * k**4))
            f_n = float(np.sqrt(w2) / (2.0 * np.pi))
            if f_n > f_max:
                return np.asarray(out, dtype=np.float64)
            out.append(f_n)
            n += 1

    # -- dimensionless kernels ------------------------------------------------------------
    @property
    def _loss(self) -> complex:
        """``1 + i eta``, with the rail loss factor at least :data:`VANISHING_LOSS_FACTOR`."""
        return 1.0 + 1j * max(self.rail.loss_factor, VANISHING_LOSS_FACTOR)

    @property
    def _ei(self) -> complex:
        """The complex bending stiffness the solver uses, N m^2."""
        return self.rail.bending_stiffness * self._loss

    def _beta4(self, f: NDArray[np.float64]) -> NDArray[np.complex128]:
        self.check_frequencies(f)
        omega = 2.0 * np.pi * f
        d = self.sleeper_spacing
        beta4 = self.rail.mass_per_length * omega**2 * d**4 / self._ei
        return np.asarray(beta4, dtype=np.complex128)

    def support_stiffness(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Complex stiffness of one rail seat's support seen by the rail, N/m, ``(n_freq,)``.

        Here the railpad on a rigid base; a track with layers below the pad
        (:class:`~railvib.track.ballasted.BallastedTrack`) condenses them into it.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Returns
        -------
        numpy.ndarray
            ``K*(f)`` in N/m.
        """
        f = np.asarray(f, dtype=float)
        return np.asarray(self.pad.stiffness(f, self.pad_temperature), dtype=np.complex128)

    def _pad_hat(self, f: NDArray[np.float64]) -> NDArray[np.complex128]:
        z = self.support_stiffness(f)
        return np.asarray(z * self.sleeper_spacing**3 / self._ei, dtype=np.complex128)

    @fill_doc(_SHARED)
    def span_transfer(self, f: ArrayLike, length: float) -> NDArray[np.complex128]:
        """Dimensionless transfer matrix of the rail over `length` bays, ``(n_freq, 4, 4)``.

        State ``(w, d psi, d^2 psi', d^3 v)``: for an Euler rail ``psi = w'`` and
        ``v = w'''``; for a Timoshenko rail see
        :func:`~railvib.track.beam.timoshenko_transfer`.

        Parameters
        ----------
        {f}
        length : float
            Span length in bays, i.e. in units of the sleeper spacing d (dimensionless).

        Returns
        -------
        numpy.ndarray
            Complex transfer matrices (dimensionless), shape ``(n_freq, 4, 4)``.
        """
        f = _as_freq(f)
        if self.rail.shear_stiffness is None:
            return field_transfer(self._beta4(f), length)
        beta4, eps, rho, rho_eps = self._timoshenko_terms(f)
        return timoshenko_transfer(beta4, eps, rho, length, rho_eps)

    def _timoshenko_terms(
        self, f: NDArray[np.float64]
    ) -> tuple[NDArray[np.complex128], complex, NDArray[np.complex128], NDArray[np.complex128]]:
        """``beta4``, ``eps = EI* / (kGA* d^2)``, ``rho = rho_I omega^2 d^2 / EI*`` and ``rho eps``.

        ``rho eps = rho_I omega^2 / kGA*`` is formed directly (1 at the cut-off frequency).
        """
        shear = self.rail.shear_stiffness
        assert shear is not None  # only called for a Timoshenko rail
        d, ei = self.sleeper_spacing, self._ei
        kga = shear * self._loss
        omega2 = (2.0 * np.pi * f) ** 2
        rotary = np.asarray(self.rail.rotary_inertia * omega2 * d**2 / ei, dtype=np.complex128)
        rho_eps = np.asarray(self.rail.rotary_inertia * omega2 / kga, dtype=np.complex128)
        return self._beta4(f), ei / (kga * d**2), rotary, rho_eps

    @fill_doc(_SHARED)
    def cell_transfer(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Dimensionless field transfer matrix of one bay, ``(n_freq, 4, 4)``.

        Maps the state just right of sleeper n to the same just right of sleeper
        n+1: the rail over one span (:meth:`span_transfer`), then the pad's shear jump.

        Parameters
        ----------
        {f}

        Returns
        -------
        numpy.ndarray
            Complex transfer matrices (dimensionless), shape ``(n_freq, 4, 4)``.
        """
        f = _as_freq(f)
        return _cell(self.span_transfer(f, 0.5), self._pad_hat(f))

    def waves(self, f: ArrayLike) -> TrackWaves:
        """Eigen-analysis of the bay: propagation constants and decaying waves.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz (> 0).

        Returns
        -------
        TrackWaves
        """
        f = _as_freq(f)
        pad = self._pad_hat(f)
        if self.rail.is_timoshenko:
            mu_small, vec = self._timoshenko_waves(f, pad)
            mu_big = 1.0 / mu_small
        else:
            mu_small, mu_big = _propagation_constants(*_euler_characteristic(self._beta4(f), pad))
            vec = _bloch_vector(self.span_transfer(f, 0.5), pad, mu_small)
        partner = _mirror(vec, pad)  # the eigenvector of mu_big
        # the wave that decays to the right in the limit of vanishing loss: the one with
        # |mu| < 1, or, where |mu| cannot tell, the one carrying power to the right
        swap = (np.abs(np.abs(mu_small) - 1.0) < ENERGY_FLOW_TOLERANCE) & (_energy_flux(vec) < 0)
        mu = np.where(swap, mu_big, mu_small)
        right = np.where(swap[:, None, :], partner, vec)
        left = _mirror(right, pad)
        # rows equilibrated: at a stiff pad the displacement row of the waves is small
        matching = np.concatenate([right, -left], axis=2)
        rows = 1.0 / np.abs(matching).max(axis=2)
        matching = matching * rows[:, :, None]
        matching_inv = np.linalg.inv(matching)
        condition = np.abs(matching).max(axis=(1, 2)) * np.abs(matching_inv).max(axis=(1, 2)) * 4.0
        _warn_if_ill_conditioned(f, condition)
        matching_inv *= rows[:, None, :]
        return TrackWaves(
            f=f,
            beta4=self._beta4(f),
            mu=mu,
            right=right,
            left=left,
            scale=self.sleeper_spacing**3 / self._ei,
            pad=pad,
            _matching_inv=matching_inv,
        )

    def _timoshenko_waves(
        self, f: NDArray[np.float64], pad: NDArray[np.complex128]
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
        """Propagation constants ``|mu| <= 1`` and Bloch vectors of the Timoshenko bay.

        In closed form (:func:`railvib.track.timoshenko.bay_waves`), except where
        ``|a^2 + b^2| <`` :data:`SMALL_WAVENUMBERS`: there the divided differences of the
        closed form would cancel, and the entries of the bay (no larger than ``cosh 2``)
        and its half-span pencil are used, as for the Euler bay; the half-span matrices
        (closed form, :func:`~railvib.track.beam.timoshenko_transfer`) are formed only there.
        """
        span = span_terms(*self._timoshenko_terms(f))
        mu = np.empty((f.size, 2), dtype=np.complex128)
        vec = np.zeros((f.size, 4, 2), dtype=np.complex128)
        large = np.abs(span.r) >= SMALL_WAVENUMBERS
        if np.any(large):
            mu[large], vec[large] = bay_waves(Span(*(t[large] for t in span)), pad[large])
        # the entries (low frequency), and the pencil where the closed form's vector vanishes
        pencil = ~large | np.any(np.linalg.norm(vec, axis=1) == 0, axis=1)
        if np.any(pencil):
            half = self.span_transfer(f[pencil], 0.5)
            small = ~large[pencil]
            if np.any(small):
                cell = _cell(half[small], pad[pencil][small])
                mu[~large] = _propagation_constants(*_characteristic(cell))[0]
            vec[pencil] = _bloch_vector(half, pad[pencil], mu[pencil])
        return mu, vec

    # -- public physics -------------------------------------------------------------------
    def receptance(
        self, f: ArrayLike, x_load: ArrayLike, x_obs: ArrayLike, *, waves: TrackWaves | None = None
    ) -> NDArray[np.complex128]:
        """Rail receptance (vertical displacement per unit vertical force) between points.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, ``(n_freq,)``.
        x_load : array_like
            Positions of the unit loads along the rail, m (sleepers at ``n d``).
        x_obs : array_like
            Positions of the observation points, m.
        waves : TrackWaves, optional
            Reuse a precomputed :meth:`waves` for the same `f`.

        Returns
        -------
        numpy.ndarray
            Complex receptance in m/N, shape ``(n_freq, n_obs, n_load)``;
            ``[k, i, j]`` is the displacement at ``x_obs[i]`` per unit force at ``x_load[j]``.
        """
        d = self.sleeper_spacing
        x_load = np.atleast_1d(np.asarray(x_load, dtype=float)) / d
        x_obs = np.atleast_1d(np.asarray(x_obs, dtype=float)) / d
        for name, x in (("x_load", x_load), ("x_obs", x_obs)):
            if not np.all(np.isfinite(x)):
                raise CaseError(name, list(x * d), "finite positions (m)")
        if waves is None and not self.rail.is_timoshenko:
            # the same waves in the stacked layout (railvib.track.stacked): a few elementwise
            # passes per step instead of (n_freq, 2, 4, 4) temporaries and a 4x4 inverse
            f = _as_freq(f)
            stack = stacked_waves(self._beta4(f), self._pad_hat(f))
            _warn_if_ill_conditioned(f, stack.condition)
            rec = stacked(receptance_entries(stack, x_load, x_obs))
            return np.asarray(rec * (self.sleeper_spacing**3 / self._ei), dtype=np.complex128)
        w = self.waves(f) if waves is None else waves
        # every point is referred to its nearest sleeper (local coordinate in [-1/2, 1/2]):
        # the beam field is never carried over more than half a bay, where the growing
        # evanescent component would swamp the decaying one
        ref_load, xi = _nearest_sleeper(x_load)
        ref_obs, eta = _nearest_sleeper(x_obs)
        # wave amplitudes (a1, a2, b1, b2) for each load, in the states just right of its
        # sleeper: [R, -L] c = P B(-xi) e4 (the jump of the shear at the load carried to
        # there; P, the pad's shear jump, only for a load left of its sleeper)
        amps = np.empty((w.f.size, 4, x_load.size), dtype=complex)
        for xi_u in np.unique(xi):
            rhs = self._last_column(w, -xi_u)
            if xi_u < 0:
                rhs[:, 3] -= w.pad * rhs[:, 0]
            sol = np.einsum("fij,fj->fi", w._matching_inv, rhs)
            amps[:, :, xi == xi_u] = sol[:, :, None]
        # displacement of each wave at each observation point's local coordinate (from the
        # state just right of its sleeper: B(eta) P^-1 for a point left of the sleeper)
        out = np.empty((w.f.size, x_obs.size, x_load.size), dtype=complex)
        for eta_u in np.unique(eta):
            row = self._first_row(w, eta_u)
            if eta_u < 0:
                row[:, 0] += w.pad * row[:, 3]
            disp_r = np.einsum("fk,fkj->fj", row, w.right)
            disp_l = np.einsum("fk,fkj->fj", row, w.left)
            for i in np.flatnonzero(eta == eta_u):
                for j in range(x_load.size):
                    if x_obs[i] >= x_load[j]:
                        m = ref_obs[i] - ref_load[j]
                        out[:, i, j] = np.sum(amps[:, :2, j] * w.mu**m * disp_r, axis=1)
                    else:
                        m = ref_load[j] - ref_obs[i]
                        out[:, i, j] = np.sum(amps[:, 2:, j] * w.mu**m * disp_l, axis=1)
        return out * w.scale

    def _first_row(self, w: TrackWaves, length: float) -> NDArray[np.complex128]:
        """Displacement row of the span transfer matrix over `length`, ``(n_freq, 4)``."""
        if self.rail.is_timoshenko:
            return self.span_transfer(w.f, length)[:, 0, :]
        return np.stack(krylov_series(w.beta4, length), axis=-1)

    def _last_column(self, w: TrackWaves, length: float) -> NDArray[np.complex128]:
        """Shear-force column of the span transfer matrix over `length`, ``(n_freq, 4)``."""
        if self.rail.is_timoshenko:
            return self.span_transfer(w.f, length)[:, :, 3]
        return np.stack(krylov_series(w.beta4, length)[::-1], axis=-1)

    @fill_doc(_SHARED)
    def transfer_matrix(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Transfer matrix S of one bay in the paper's state ``(u, p)``, SI units.

        ``u = (w [m], theta [rad])`` and ``p = (shear [N], moment [N m])``, the
        force exerted across the interface on the bay to its right (paper Eq. 4).
        ``S^T J S = J`` with ``J = [[0, I], [-I, 0]]``.

        Parameters
        ----------
        {f}

        Returns
        -------
        numpy.ndarray
            Complex ``S`` mapping ``(w, theta, shear, moment)`` in (m, rad, N, N m) just
            right of sleeper n to the same just right of sleeper n+1, shape ``(n_freq, 4, 4)``.
        """
        c, c_inv = self._state_maps()
        return c @ self.cell_transfer(f) @ c_inv

    @fill_doc(_SHARED)
    def cell_dynamic_stiffness(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Dynamic stiffness of one bay, ``(n_freq, 4, 4)``, DOFs ``(w_a, theta_a, w_b, theta_b)``.

        Exact beam span plus the pad at the right end; SI units (N/m, N, N m).
        It has poles at the clamped-clamped frequencies of the span (3268 Hz for
        0.6 m of CHN60); the solver uses the pole-free :meth:`cell_transfer`. For
        an Euler rail it is the closed-form span stiffness; for a Timoshenko rail it
        is obtained from the transfer matrix (inverting paper Eq. 4).

        Parameters
        ----------
        {f}

        Returns
        -------
        numpy.ndarray
            Complex dynamic stiffness mapping ``(w_a, theta_a, w_b, theta_b)`` in (m, rad) to
            the end forces and moments in (N, N m), shape ``(n_freq, 4, 4)``.
        """
        f = _as_freq(f)
        if self.rail.is_timoshenko:
            s = self.transfer_matrix(f)
            k_ab = np.linalg.inv(s[:, :2, 2:])
            k_aa = -k_ab @ s[:, :2, :2]
            k_bb = -s[:, 2:, 2:] @ k_ab
            k_ba = -s[:, 2:, :2] - k_bb @ s[:, :2, :2]
            return np.concatenate(
                [np.concatenate([k_aa, k_ab], 2), np.concatenate([k_ba, k_bb], 2)], 1
            )
        d = self.sleeper_spacing
        ei = self._ei
        k = dynamic_stiffness(self._beta4(f), 1.0)
        scale = np.array([1.0, d, 1.0, d])
        k = k * scale[:, None] * scale[None, :] * ei / d**3
        k[:, 2, 2] += self.support_stiffness(f)
        return k

    @fill_doc(_SHARED)
    def semi_infinite_stiffness(
        self, f: ArrayLike
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
        """Dynamic stiffnesses of the semi-infinite rail seen from a sleeper (paper Eq. 6).

        Parameters
        ----------
        {f}

        Returns
        -------
        P_b, P_a : numpy.ndarray
            ``(n_freq, 2, 2)`` in SI units. ``P_b = N_a X_a^-1``: the right chain
            (starting just right of a sleeper, excluding that sleeper's pad) resists
            with ``p = P_b u``; ``P_a = -N_b X_b^-1`` for the left chain.
        """
        w = self.waves(f)
        c, _ = self._state_maps()
        right = c @ w.right
        left = c @ w.left
        p_b = right[:, 2:, :] @ np.linalg.inv(right[:, :2, :])
        p_a = -left[:, 2:, :] @ np.linalg.inv(left[:, :2, :])
        return p_b, p_a

    def _state_maps(self) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
        d = self.sleeper_spacing
        ei = self._ei
        c = np.zeros((4, 4), dtype=complex)
        c[0, 0] = 1.0
        c[1, 1] = 1.0 / d
        c[2, 3] = ei / d**3
        c[3, 2] = -ei / d**2
        return c, np.asarray(np.linalg.inv(c), dtype=np.complex128)

    # -- the track alone (railvib.track.outputs) ------------------------------------------
    @property
    def period(self) -> float:
        """Length of the periodic cell, m: one sleeper bay, the sleeper spacing d."""
        return self.sleeper_spacing

    @fill_doc(_SHARED)
    def propagation_constants(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Propagation constants ``mu = exp(-gamma d)`` of the two right-going waves per bay.

        Parameters
        ----------
        {f}

        Returns
        -------
        numpy.ndarray
            ``(n_freq, 2)``, ``|mu| <= 1`` (:attr:`TrackWaves.mu`), each row sorted
            least-attenuated first.
        """
        mu = self.waves(f).mu
        order = np.argsort(-np.abs(mu), axis=1, kind="stable")
        return np.asarray(np.take_along_axis(mu, order, axis=1), dtype=np.complex128)

    @fill_doc(_SHARED)
    def support_response(self, f: ArrayLike, x_load: float, n_supports: int) -> SupportResponse:
        """The rail seats nearest a unit load: rail and layer displacements, layer forces.

        The seats are the sleepers ``n d`` from ``n0 - n_supports`` to ``n0 + n_supports``,
        ``n0`` the sleeper nearest `x_load`; the rail displacement there is
        :meth:`receptance` and the layers follow from it (:meth:`seat_response`).

        Parameters
        ----------
        {f}
        x_load : float
            Position of the unit load, m.
        n_supports : int
            Seats on each side of the nearest one (>= 0).

        Returns
        -------
        SupportResponse
        """
        if not np.isfinite(x_load):
            raise CaseError("x_load", x_load, "a finite position (m)")
        if int(n_supports) != n_supports or n_supports < 0:
            raise CaseError("n_supports", n_supports, "an integer >= 0")
        f = _as_freq(f)
        d = self.sleeper_spacing
        nearest = int(_nearest_sleeper(np.array([x_load / d]))[0][0])
        x = np.asarray(
            (nearest + np.arange(-int(n_supports), int(n_supports) + 1)) * d, dtype=np.float64
        )
        rail = self.receptance(f, [x_load], x)[:, :, 0]
        return self.seat_response(f, x, rail)

    @fill_doc(_SHARED)
    def seat_response(
        self, f: ArrayLike, x: NDArray[np.float64], rail: NDArray[np.complex128]
    ) -> SupportResponse:
        """The layers of the rail seats at `x` from the rail displacement there.

        Here the pad alone, on a rigid base: it is compressed by the rail's displacement
        and carries ``K* w_r`` to the ground.

        Parameters
        ----------
        {f}
        x : numpy.ndarray
            Seat positions, m, ``(n_supports,)``.
        rail : numpy.ndarray
            Rail displacement at the seats per unit force, m/N, ``(n_freq, n_supports)``.

        Returns
        -------
        SupportResponse
        """
        k = self.support_stiffness(_as_freq(f))
        return SupportResponse(
            x=np.asarray(x, dtype=float),
            displacement={"rail": rail},
            compression={"pad": rail},
            force={"pad": k[:, None] * rail},
            stiffness={"pad": k},
            foundation="pad",
        )


def _warn_if_ill_conditioned(f: NDArray[np.float64], estimate: NDArray[np.float64]) -> None:
    """Warn where left- and right-going waves (nearly) coincide: the pinned-pinned resonance.

    There the undamped rail's mid-span receptance really diverges, as |f - f_pp|^(-1/2); the
    result is that of the vanishing rail loss (``VANISHING_LOSS_FACTOR``): finite and passive,
    but set by that loss (above ``CONDITION_WARNING`` by more than 1 %). `estimate` is
    ``4 max|M| max|M^-1|`` of the row-equilibrated wave matching ``M`` at each frequency.
    """
    bad = estimate > CONDITION_WARNING
    if np.any(bad):
        warnings.warn(
            f"{int(bad.sum())} frequencies (first {f[bad][0]:.6g} Hz) lie at a pinned-pinned "
            f"resonance of the undamped rail (wave-matching condition number "
            f"~{estimate.max():.1e}); the mid-span response there is physically unbounded "
            f"and is given for a rail loss factor of {VANISHING_LOSS_FACTOR:g}. "
            "Set track.rail.loss_factor (e.g. 0.01) or move the grid point.",
            SolverWarning,
            stacklevel=3,
        )


def _as_freq(f: ArrayLike) -> NDArray[np.float64]:
    f = np.atleast_1d(np.asarray(f, dtype=float))
    if f.ndim != 1 or not np.all(np.isfinite(f) & (f > 0)):
        raise CaseError("frequency", "non-positive or non-finite values", "finite and > 0 (Hz)")
    return f


def _nearest_sleeper(x: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Index of the nearest sleeper and the local coordinate in [-1/2, 1/2] from it.

    Mid-span points (local 1/2 exactly) go to the sleeper on their left.
    """
    bay = np.floor(x)
    local = x - bay
    ref = bay + (local > 0.5)
    return ref.astype(np.int64), x - ref


def _cell(half: NDArray[np.complex128], pad: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """Bay transfer matrix ``P B(1/2) B(1/2)`` from the half-span one, ``(n_freq, 4, 4)``.

    ``P`` is the pad's jump of the shear row, ``v -> v - pad w``.
    """
    t = half @ half
    t[:, 3, :] -= pad[:, None] * t[:, 0, :]
    return t


def _mirror(vec: NDArray[np.complex128], pad: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """Mirror images ``x -> -x`` of waves given just right of a sleeper, ``(n_freq, 4, n)``.

    The state just left of the sleeper is ``P^-1 y`` (``v + pad w``); mirrored it is the
    state just right of it of the wave reflected in ``x = 0``. A wave decaying to the
    right by ``mu`` per bay becomes one decaying to the left by ``mu``: eigenvector
    ``1/mu`` of the bay. The mirror is an involution.
    """
    out = vec * _MIRROR[None, :, None]
    out[:, 3, :] -= pad[:, None] * vec[:, 0, :]
    return out


def _propagation_constants(
    c1: NDArray[np.complex128], c2m2: NDArray[np.complex128]
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """The two small (``|mu| <= 1``) eigenvalues and their large partners ``1/mu``.

    The characteristic polynomial of a 4x4 symplectic matrix is palindromic, so
    ``lambda = mu + 1/mu`` solves ``lambda^2 - c1 lambda + (c2 - 2) = 0`` (``c1 = tr T``,
    ``c2`` the sum of its principal 2x2 minors). The larger root is formed without
    cancellation and the smaller one as ``(c2 - 2) / lambda_large``; ``lambda^2 - 4`` as
    ``(lambda - 2)(lambda + 2)``, which keeps the digits of ``mu`` near a band edge
    (``lambda = +-2``, the pinned-pinned frequency).
    """
    disc = np.sqrt(c1**2 - 4.0 * c2m2)
    disc = np.where(np.real(np.conj(c1) * disc) >= 0, disc, -disc)
    lam_big = 0.5 * (c1 + disc)
    lam_big = np.where(lam_big == 0, 1.0, lam_big)  # c1 = c2 - 2 = 0: both roots 0
    lam = np.stack([lam_big, c2m2 / lam_big], axis=1)
    root = np.sqrt((lam - 2.0) * (lam + 2.0))
    root = np.where(np.real(np.conj(lam) * root) >= 0, root, -root)
    big = 0.5 * (lam + root)  # no cancellation in the larger root
    return np.asarray(1.0 / big, dtype=np.complex128), np.asarray(big, dtype=np.complex128)


def _characteristic(t: NDArray[np.complex128]) -> tuple[NDArray[np.complex128], ...]:
    """``c1 = tr T`` and ``c2 - 2`` of a bay transfer matrix from its entries."""
    c1 = np.einsum("fii->f", t)
    c2 = 0.5 * (c1**2 - np.einsum("fij,fji->f", t, t))
    return c1, c2 - 2.0


def _euler_characteristic(
    beta4: NDArray[np.complex128], pad: NDArray[np.complex128]
) -> tuple[NDArray[np.complex128], ...]:
    """``c1`` and ``c2 - 2`` of the Euler bay in closed form (no cancellation).

    With ``z^4 = beta4``: ``c1 = 2 (cosh z + cos z) - pad (sinh z - sin z) / (2 z^3)``
    and ``c2 - 2 = 4 cos z cosh z + pad (cosh z sin z - cos z sinh z) / z^3``, i.e.
    ``4 (S + pad V)`` of the Krylov series at ``-4 beta4``. From the entries of ``T``
    (size ``cosh z``) ``c2`` would lose ``cosh^2 z`` of its digits to cancellation, and
    with them the propagating waves' ``lambda`` near a band edge above 2 kHz.
    """
    s0, _, _, s3 = krylov_series(beta4, 1.0)
    c1 = 4.0 * s0 - pad * s3
    small = np.abs(beta4) < 16.0  # |z| < 2: the alternating series loses < 2.3 ulp
    c2m2 = np.empty_like(c1)
    if np.any(small):
        q0, _, _, q3 = krylov_series(-4.0 * beta4[small], 1.0)
        c2m2[small] = 4.0 * (q0 + pad[small] * q3)
    large = ~small
    if np.any(large):
        z = beta4[large] ** 0.25  # any fourth root: both sums are even in z and in iz
        cos, cosh, sin, sinh = np.cos(z), np.cosh(z), np.sin(z), np.sinh(z)
        c2m2[large] = 4.0 * cos * cosh + pad[large] * (cosh * sin - cos * sinh) / z**3
    return c1, c2m2


def _bloch_vector(
    half: NDArray[np.complex128], pad: NDArray[np.complex128], mu: NDArray[np.complex128]
) -> NDArray[np.complex128]:
    """Unit eigenvectors of the bay for eigenvalues ``mu``: ``(n_freq, 4, 2)``.

    ``P B(1) y = mu y`` is solved as ``(B(1/2) - mu B(-1/2) P^-1) y = 0``: both half-span
    matrices grow only as ``exp(beta / 2)``, so the null vector (the generalised cross
    product of three rows) keeps its digits where ``T - mu I`` would lose
    ``exp(2 beta)`` of them to its nearly parallel rows. ``B(-1/2) = M B(1/2) M`` with
    ``M`` the mirror.
    """
    back = half * _MIRROR[None, :, None] * _MIRROR[None, None, :]
    back[:, :, 0] += pad[:, None] * back[:, :, 3]  # B(-1/2) P^-1
    m = half[:, None, :, :] - mu[:, :, None, None] * back[:, None, :, :]  # (n_freq, 2, 4, 4)
    m = m / np.linalg.norm(m, axis=3, keepdims=True)
    r0, r1, r2, r3 = (m[..., i, :] for i in range(4))
    # without row 0 or without row 3: the better of the two is within a factor 3 of the
    # best of all four choices of three rows (measured over 0.1 Hz - 5 kHz)
    first = _cross(r1, _minors(r2, r3))
    second = _cross(r2, _minors(r0, r1))
    norm_first = np.linalg.norm(first, axis=2)
    norm_second = np.linalg.norm(second, axis=2)
    better = norm_second > norm_first
    best = np.where(better[..., None], second, first)
    norm = np.where(better, norm_second, norm_first)
    best = best / norm[..., None]
    # near a band edge of a (nearly) lossless rail the rows span almost only a plane
    # (mu and 1/mu close): there the null vector is taken from an SVD instead
    weak = norm < WEAK_CROSS_PRODUCT
    if np.any(weak):
        best[weak] = np.conj(np.linalg.svd(m[weak])[2][:, -1, :])
    return np.swapaxes(best, 1, 2)


#: the column pairs of a 4-vector, for its 2x2 minors
_PAIRS = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))


def _minors(
    b: NDArray[np.complex128], c: NDArray[np.complex128]
) -> dict[tuple[int, int], NDArray[np.complex128]]:
    """The six 2x2 minors ``b_q c_r - b_r c_q`` of two 4-vectors on the last axis."""
    return {(q, r): b[..., q] * c[..., r] - b[..., r] * c[..., q] for q, r in _PAIRS}


def _cross(
    a: NDArray[np.complex128], minors: dict[tuple[int, int], NDArray[np.complex128]]
) -> NDArray[np.complex128]:
    """Generalised cross product of `a` and the two vectors of `minors`: orthogonal to all three.

    The three rows ``(a, b, c)`` are expanded along ``a``: component ``i`` is the signed
    3x3 minor without column ``i``; the 2x2 minors of ``(b, c)`` are shared by two
    expansions.
    """
    out = np.empty_like(a)
    for i in range(4):
        p, q, r = (k for k in range(4) if k != i)
        det = a[..., p] * minors[q, r] - a[..., q] * minors[p, r] + a[..., r] * minors[p, q]
        out[..., i] = det if i % 2 == 0 else -det
    return out


def _energy_flux(vec: NDArray[np.complex128]) -> NDArray[np.float64]:
    """Sign-carrying power flow to the right, ``Im(w''' conj(w) - w'' conj(w'))``, per wave."""
    w, w1, w2, w3 = vec[:, 0], vec[:, 1], vec[:, 2], vec[:, 3]
    return np.imag(w3 * np.conj(w) - w2 * np.conj(w1))


#: keys of the ``[track]`` table of the rigid-base track
RIGID_BASE_PARAMETERS = (
    Parameter("sleeper_spacing", "m", "sleeper spacing d", gt=0.0, le=3.0, typical=(0.5, 0.75)),
    Parameter("rail", "", "the rail beam", "table", table=Rail),
    Parameter("pad", "N/m", "railpad model of one rail seat", "member", family=PADS),
    Parameter(
        "pad_temperature_c",
        "degC",
        "pad temperature used by temperature-dependent pad models",
        default=None,
        gt=-273.15,
        le=1000.0,
    ),
)


def rigid_base_track(
    sleeper_spacing: float, rail: Rail, pad: PadModel, pad_temperature_c: float | None = None
) -> PeriodicTrack:
    """The rigid-base track of a ``[track]`` table's checked values (see :class:`PeriodicTrack`)."""
    return PeriodicTrack(rail, pad, sleeper_spacing, pad_temperature_c)


TRACKS.register("rigid_base", parameters=RIGID_BASE_PARAMETERS, build=rigid_base_track)(
    PeriodicTrack
)
