"""The rail as an infinite periodic structure, solved by the symplectic (wave) method.

The cell is one sleeper bay: the rail span from just right of sleeper ``n`` to
just right of sleeper ``n+1`` (the pad at sleeper ``n+1`` belongs to the cell).
Its transfer matrix is symplectic, so its eigenvalues come in pairs
``(mu, 1/mu)``; the two waves with ``|mu| < 1`` decay to the right (where
``|mu| ~ 1`` the choice is made by the direction of energy flow) and their
partners decay to the left. A point load is matched by the decaying waves on
each side of it (the "loaded cell"), and the response anywhere follows by
propagating each wave with ``mu^k`` (never ``mu^-k``) and the exact beam field
inside the span. See ``docs/design/0002-track-solver.md``.

Positions ``x`` are measured along the rail in m, with sleepers at ``x = n d``.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.docstrings import fill_doc
from railvib.errors import CaseError, SolverWarning
from railvib.pads.base import PADS, PadModel
from railvib.registry import Parameter, check_parameters, check_value, parameter
from railvib.track.base import TRACKS, TrackModel
from railvib.track.beam import (
    dynamic_stiffness,
    field_transfer,
    krylov_series,
    timoshenko_transfer,
)

__all__ = ["MAX_BAY_WAVENUMBER", "PeriodicTrack", "Rail", "TrackWaves"]

#: parameter documentation shared by the track methods (:func:`railvib.docstrings.fill_doc`)
_SHARED = {
    "f": """f : array_like
    Frequencies in Hz (> 0), shape ``(n_freq,)``.""",
}


#: wave-matching condition number above which results are flagged with a SolverWarning
CONDITION_WARNING = 1e7

#: where ``| |mu| - 1 |`` is below this, waves are sorted by energy flow, not modulus
ENERGY_FLOW_TOLERANCE = 1e-6

#: largest bending wavenumber times sleeper spacing, ``|beta4|^(1/4) = (m omega^2 d^4 /
#: |EI*|)^(1/4)`` (dimensionless; CHN60 at d = 0.6 m: 5.9 at 5 kHz): the bay's power series
#: then needs terms up to 1/170!, the last factorial within float64, and the bay's
#: transfer matrix holds cosh(40) ~ 1e17, still finite
MAX_BAY_WAVENUMBER = 40.0


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
    """

    f: NDArray[np.float64]
    beta4: NDArray[np.complex128]
    mu: NDArray[np.complex128]
    right: NDArray[np.complex128]
    left: NDArray[np.complex128]
    scale: complex
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

    # -- dimensionless kernels ------------------------------------------------------------
    def _beta4(self, f: NDArray[np.float64]) -> NDArray[np.complex128]:
        self.check_frequencies(f)
        omega = 2.0 * np.pi * f
        d = self.sleeper_spacing
        beta4 = self.rail.mass_per_length * omega**2 * d**4 / self.rail.complex_bending_stiffness
        return np.asarray(beta4, dtype=np.complex128)

    def _pad_hat(self, f: NDArray[np.float64]) -> NDArray[np.complex128]:
        z = np.asarray(self.pad.stiffness(f, self.pad_temperature), dtype=complex)
        return np.asarray(
            z * self.sleeper_spacing**3 / self.rail.complex_bending_stiffness, dtype=np.complex128
        )

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
        d = self.sleeper_spacing
        ei = self.rail.complex_bending_stiffness
        kga = self.rail.shear_stiffness * (1.0 + 1j * self.rail.loss_factor)
        rotary = self.rail.rotary_inertia * (2.0 * np.pi * f) ** 2 * d**2 / ei
        return timoshenko_transfer(self._beta4(f), ei / (kga * d**2), rotary, length)

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
        t = self.span_transfer(f, 1.0)
        t[:, 3, :] -= self._pad_hat(f)[:, None] * t[:, 0, :]
        return t

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
        t = self.cell_transfer(f)
        mu_r, mu_l = _propagation_constants(t)
        vec_r = _bloch_vector(t, mu_r)
        vec_l = _bloch_vector(t, mu_l)
        # sort each pair by energy flow where the modulus cannot tell
        power_r = _energy_flux(vec_r)
        swap = (np.abs(np.abs(mu_r) - 1.0) < ENERGY_FLOW_TOLERANCE) & (power_r < 0)
        mu_small = np.where(swap, 1.0 / mu_l, mu_r)
        right = np.where(swap[:, None, :], vec_l, vec_r)
        left = np.where(swap[:, None, :], vec_r, vec_l)
        matching = np.concatenate([right, -left], axis=2)
        matching_inv = np.linalg.inv(matching)
        _warn_if_ill_conditioned(f, matching, matching_inv)
        return TrackWaves(
            f=f,
            beta4=self._beta4(f),
            mu=mu_small,
            right=right,
            left=left,
            scale=self.sleeper_spacing**3 / self.rail.complex_bending_stiffness,
            _matching_inv=matching_inv,
        )

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
        w = self.waves(f) if waves is None else waves
        d = self.sleeper_spacing
        x_load = np.atleast_1d(np.asarray(x_load, dtype=float)) / d
        x_obs = np.atleast_1d(np.asarray(x_obs, dtype=float)) / d
        for name, x in (("x_load", x_load), ("x_obs", x_obs)):
            if not np.all(np.isfinite(x)):
                raise CaseError(name, list(x * d), "finite positions (m)")
        bay_load, xi = _bay(x_load)
        bay_obs, eta = _bay(x_obs)
        xi_u, xi_of = _distinct(xi)
        eta_u, eta_of = _distinct(eta)
        # stacked layout: every small matrix as contiguous (n_freq,) arrays per entry
        minv = _entries(w._matching_inv)
        waves_at = (_entries(w.right), _entries(w.left))
        # wave amplitudes (a1, a2, b1, b2) for each distinct load coordinate: [R, -L] c =
        # B(-xi) e4, where the last column of B(-xi) is (s3, s2, s1, s0)(-xi)
        amps = []
        for u in xi_u:
            rhs = _entries(self._last_column(w, -float(u)))
            amps.append([_dot(minv[i], rhs) for i in range(4)])
        # displacement of each wave at each distinct observation coordinate, right and left
        disp = []
        for u in eta_u:
            row = _entries(self._first_row(w, float(u)))
            disp.append([[_dot(row, [s[k] for s in v]) for k in range(2)] for v in waves_at])
        mu = _entries(w.mu)
        powers: dict[int, list[NDArray[np.complex128]]] = {}
        out = np.empty((x_obs.size, x_load.size, w.f.size), dtype=np.complex128)
        for i in range(x_obs.size):
            for j in range(x_load.size):
                # right of the load the right-going waves (a1, a2), left of it (b1, b2)
                side = 0 if x_obs[i] >= x_load[j] else 1
                m = int(abs(bay_obs[i] - bay_load[j]))
                if m not in powers:
                    powers[m] = [mu_k**m for mu_k in mu]
                a = amps[xi_of[j]][2 * side : 2 * side + 2]
                d_k = disp[eta_of[i]][side]
                out[i, j] = a[0] * powers[m][0] * d_k[0] + a[1] * powers[m][1] * d_k[1]
        out = np.ascontiguousarray(np.moveaxis(out, -1, 0))
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
        ei = self.rail.complex_bending_stiffness
        k = dynamic_stiffness(self._beta4(f), 1.0)
        scale = np.array([1.0, d, 1.0, d])
        k = k * scale[:, None] * scale[None, :] * ei / d**3
        k[:, 2, 2] += self.pad.stiffness(f, self.pad_temperature)
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
        ei = self.rail.complex_bending_stiffness
        c = np.zeros((4, 4), dtype=complex)
        c[0, 0] = 1.0
        c[1, 1] = 1.0 / d
        c[2, 3] = ei / d**3
        c[3, 2] = -ei / d**2
        return c, np.asarray(np.linalg.inv(c), dtype=np.complex128)


def _warn_if_ill_conditioned(
    f: NDArray[np.float64], matching: NDArray[np.complex128], inverse: NDArray[np.complex128]
) -> None:
    """Warn where left- and right-going waves (nearly) coincide: the pinned-pinned resonance.

    There the undamped rail's mid-span receptance really diverges, as |f - f_pp|^(-1/2); the
    result stays finite but carries fewer correct digits.
    """
    estimate = np.abs(matching).max(axis=(1, 2)) * np.abs(inverse).max(axis=(1, 2)) * 4.0
    bad = estimate > CONDITION_WARNING
    if np.any(bad):
        warnings.warn(
            f"{int(bad.sum())} frequencies (first {f[bad][0]:.6g} Hz) lie at a pinned-pinned "
            f"resonance of the undamped rail (wave-matching condition number "
            f"~{estimate.max():.1e}); the mid-span response there is physically unbounded. "
            "Set track.rail.loss_factor (e.g. 0.01) or move the grid point.",
            SolverWarning,
            stacklevel=3,
        )


def _as_freq(f: ArrayLike) -> NDArray[np.float64]:
    f = np.atleast_1d(np.asarray(f, dtype=float))
    if f.ndim != 1 or not np.all(np.isfinite(f) & (f > 0)):
        raise CaseError("frequency", "non-positive or non-finite values", "finite and > 0 (Hz)")
    return f


def _bay(x: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Bay index and local coordinate in [0, 1) of dimensionless positions."""
    bay = np.floor(x).astype(np.int64)
    return bay, x - bay


def _entries(a: NDArray[np.complex128]) -> Any:
    """Entries of a stack ``(n, *shape)`` as contiguous ``(n,)`` arrays in lists nested by `shape`.

    The stacked layout of the kernels (docs/design/0006-stacked-batches.md): each entry of
    the small matrices is one contiguous array over the stack, so every operation is one
    vectorised pass instead of a loop over tiny matrices.
    """
    return _nest(np.ascontiguousarray(np.moveaxis(a, 0, -1)))


def _nest(a: NDArray[np.complex128]) -> Any:
    return a if a.ndim == 1 else [_nest(x) for x in a]


def _dot(u: list[NDArray[np.complex128]], v: list[NDArray[np.complex128]]) -> Any:
    """``sum_k u[k] v[k]`` of entry arrays."""
    out = u[0] * v[0]
    for x, y in zip(u[1:], v[1:], strict=True):
        out = out + x * y
    return out


def _distinct(
    x: NDArray[np.float64], decimals: int = 12
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Distinct local coordinates (equal to `decimals` places), and the one of each entry.

    Wheel positions a whole number of bays apart give local coordinates that differ
    by float noise (``0.5`` and ``0.4999999999999991``); they are one coordinate.
    """
    _, first, inverse = np.unique(np.round(x, decimals), return_index=True, return_inverse=True)
    return x[first], inverse.ravel()


def _propagation_constants(
    t: NDArray[np.complex128],
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """The two small (``|mu| <= 1``) eigenvalues and their large partners ``1/mu``.

    The characteristic polynomial of a 4x4 symplectic matrix is palindromic, so
    ``lambda = mu + 1/mu`` solves ``lambda^2 - c1 lambda + (c2 - 2) = 0`` with
    ``c1 = tr T`` and ``c2 = (c1^2 - tr T^2) / 2``.
    """
    c1 = np.einsum("fii->f", t)
    c2 = 0.5 * (c1**2 - np.einsum("fij,fji->f", t, t))
    disc = np.sqrt(c1**2 - 4.0 * (c2 - 2.0))
    lam = np.stack([0.5 * (c1 + disc), 0.5 * (c1 - disc)], axis=1)
    root = np.sqrt(lam**2 - 4.0)
    m1 = 0.5 * (lam + root)
    m2 = 0.5 * (lam - root)
    big = np.where(np.abs(m1) >= np.abs(m2), m1, m2)  # no cancellation in the larger root
    return np.asarray(1.0 / big, dtype=np.complex128), np.asarray(big, dtype=np.complex128)


def _bloch_vector(t: NDArray[np.complex128], mu: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """Unit eigenvectors of ``t`` for eigenvalues ``mu``: ``(n_freq, 4, 2)``.

    The null vector of ``t - mu I`` is the generalised cross product of three of
    its rows. Rows 0-2 (pure beam rows, untouched by the pad) are used; where
    they are nearly dependent, rows 1-3 are used instead.
    """
    m = t[:, None, :, :] - mu[:, :, None, None] * np.eye(4)  # (n_freq, 2, 4, 4)
    m = m / np.linalg.norm(m, axis=3, keepdims=True)
    vec = _cross3(m[..., 0, :], m[..., 1, :], m[..., 2, :])
    norm = np.linalg.norm(vec, axis=2)
    weak = norm < 1e-3  # |cross product| of unit rows: sine of their spanned volume
    if np.any(weak):
        alt = _cross3(m[weak][:, 1, :], m[weak][:, 2, :], m[weak][:, 3, :])
        alt_norm = np.linalg.norm(alt, axis=1)
        better = alt_norm > norm[weak]
        idx = tuple(i[better] for i in np.nonzero(weak))
        vec[idx] = alt[better]
        norm[idx] = alt_norm[better]
    return np.swapaxes(vec / norm[..., None], 1, 2)


def _cross3(
    a: NDArray[np.complex128], b: NDArray[np.complex128], c: NDArray[np.complex128]
) -> NDArray[np.complex128]:
    """Generalised cross product of three 4-vectors stored on the last axis."""
    out = np.empty_like(a)
    cols = (0, 1, 2, 3)
    for i in cols:
        p, q, r = (k for k in cols if k != i)
        det = (
            a[..., p] * (b[..., q] * c[..., r] - b[..., r] * c[..., q])
            - a[..., q] * (b[..., p] * c[..., r] - b[..., r] * c[..., p])
            + a[..., r] * (b[..., p] * c[..., q] - b[..., q] * c[..., p])
        )
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
