"""Slab tracks: the rail on pads on a floating (continuous) slab or on unit (discontinuous) slabs.

Both are periodic structures of two beams, solved by the general cell solver
(:mod:`railvib.track.cells`):

* ``floating_slab`` (:class:`FloatingSlabTrack`): the rail and a continuous slab beam
  (``EI_s``, ``m_s``) coupled by the railpads at every fastener ``x = n d``; the slab on a
  continuous elastic foundation ``k_f`` per unit length (folded exactly into the slab
  span's wavenumber, ``EI_s* beta^4 = m_s omega^2 - k_f``) or on discrete bearings at
  every ``bearing_spacing_fasteners``-th fastener. The cell is one fastener spacing (or
  one bearing spacing) and holds both beams' states: 8 states, 4 waves each way.
* ``unit_slab`` (:class:`UnitSlabTrack`): slabs of length ``L_s`` with ``n`` fasteners
  each, at ``d`` apart and centred on the slab, joints at ``x = k L_s``. A free joint
  leaves each slab inside its cell (the rail alone crosses the cell boundary: 4 states);
  a joint with a shear and/or bending stiffness couples the slab ends (8 states). The
  period is the slab.

The rail is an Euler or a Timoshenko beam, the slab an Euler beam; every value is per
rail (half of a slab carrying two rails; ``rail_pair`` doubles it with the rail). Pads,
foundation and bearings take any pad model (temperature-dependent ones at
``pad_temperature_c``) and are refused where they are not passive (``Im K < 0``) on the
grid. An undamped rail or slab is solved with the small loss factor
:data:`VANISHING_LOSS_FACTOR` (1e-9): the doubling needs every wave to decay, and with the
rigid-base track's 1e-12 the doubling of a lossless slab track overflows near its band edges
(measured: 71 of 3000 frequencies near the slab's cut-on).
"""

from __future__ import annotations

from abc import abstractmethod
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError, NonFiniteResult
from railvib.pads.base import PADS, PadModel
from railvib.registry import Parameter, check_value
from railvib.track import cells as cell_solver
from railvib.track.base import TRACKS, SupportResponse, passive_layer_stiffness
from railvib.track.cells import Cell, _where, cell_receptance, cell_waves, span_stiffness
from railvib.track.compiled_cells import fused_kernel
from railvib.track.periodic import RIGID_BASE_PARAMETERS, PeriodicTrack, Rail, TrackWaves
from railvib.track.slab_kernel import slab_receptance

__all__ = [
    "FLOATING_SLAB_PARAMETERS",
    "UNIT_SLAB_PARAMETERS",
    "VANISHING_LOSS_FACTOR",
    "FloatingSlabTrack",
    "SlabTrack",
    "UnitSlabTrack",
]

#: the smallest loss factor of the rail and the slab (an undamped beam is solved at it): the
#: doubling needs ``2^k`` cells to damp a wave, so that no frequency is left with a wave that
#: barely decays over the ``2^80`` cells of :data:`railvib.track.cells.MAX_DOUBLINGS`; it
#: changes a lossless track's receptance by ~1e-9 away from its resonances
VANISHING_LOSS_FACTOR = 1e-9

#: largest ``|beta| L`` of a Timoshenko rail span: its stiffness comes from the transfer
#: matrix, whose inversion loses ``exp(|beta| L)`` ulp (1.6e5 here: 4e-11)
MAX_TIMOSHENKO_SPAN_WAVENUMBER = 12.0

#: largest ``|beta| L`` of an Euler span (closed form: cosh stays far below overflow)
MAX_EULER_SPAN_WAVENUMBER = 300.0

#: complex entries of the cell matrices of one frequency block (16 MB): a block's working
#: set stays in the cache instead of streaming (n_freq, n_dof, n_dof) arrays through memory
CELL_BLOCK_ENTRIES = 2**20

#: the integrals ``a``, ``b`` of a slab bay's exact shape functions over ``[0, L]`` as
#: series in ``lambda = (m_s omega^2 - k_f) L^4 / EI_s*``: ``int w dx = L (a (w_a + w_b) +
#: b L (theta_a - theta_b))``, rows ``a``, ``b``, columns the powers 0-5 of ``lambda``.
#: Term by term: ``w = sum lambda^k w_k``, ``w_0`` the cubic Hermite shape function,
#: ``w_k'''' = w_k-1`` with zero end values and slopes, integrated exactly (rational
#: arithmetic); the first two terms are the consistent mass matrix's ``1/2``, ``1/12``.
#: The coefficients fall ~500-fold a power (the clamped bay's first eigenvalue
#: ``lambda = 4.73^4``), so below ``|lambda| = 1`` the omitted ``lambda^6`` term is < 1e-19
_BAY_SERIES = np.array(
    [
        [1 / 2, 1 / 1440, 1 / 725760, 2879 / 1046139494400, 3911 / 711374856192000,
         74070881 / 6744004366665646080000],
        [1 / 12, 1 / 6720, 71 / 239500800, 59 / 99632332800, 863449 / 729870602452992000,
         22217387 / 9400733359594536960000],
    ]
)  # fmt: skip

#: positions closer than this fraction of the period are one node
_MERGE = 1e-9

#: keys shared by the slab tracks (per rail: half of a slab under two rails)
_SLAB = (
    # a 0.3 m x 3 m concrete slab: 2.4e8 N m^2 and 2250 kg/m per track, half per rail; the
    # upper bounds are far beyond any slab, so that the rigid-slab limit can be computed
    Parameter(
        "slab_bending_stiffness",
        "N m^2",
        "bending stiffness EI_s of the slab beam per rail (half the slab of a track)",
        gt=0.0,
        le=1e22,
        typical=(2e7, 1e9),
        log=True,
    ),
    Parameter(
        "slab_mass_per_length",
        "kg/m",
        "mass per unit length of the slab beam per rail (half the slab of a track)",
        gt=0.0,
        le=1e18,
        typical=(300.0, 3000.0),
    ),
    Parameter(
        "slab_loss_factor",
        "-",
        "loss factor eta_s of the slab beam (EI_s -> EI_s (1 + i eta_s))",
        default=0.0,
        ge=0.0,
        le=1.0,
    ),
    Parameter(
        "foundation",
        "N/m^2",
        "continuous slab foundation: a pad model read as stiffness per metre of slab (per rail)",
        "member",
        default=None,
        family=PADS,
    ),
    Parameter(
        "bearing",
        "N/m",
        "discrete slab bearing (instead of a foundation): a pad model, one bearing per rail",
        "member",
        default=None,
        family=PADS,
    ),
)

#: keys of the ``[track]`` table of the floating slab track
FLOATING_SLAB_PARAMETERS = (
    *RIGID_BASE_PARAMETERS,
    *_SLAB,
    Parameter(
        "bearing_spacing_fasteners",
        "",
        "bearings under every n-th fastener (with bearing): the cell is n fastener spacings",
        "integer",
        default=1,
        ge=1,
        le=50,
    ),
)

#: keys of the ``[track]`` table of the unit slab track
UNIT_SLAB_PARAMETERS = (
    *RIGID_BASE_PARAMETERS,
    *_SLAB,
    Parameter(
        "slab_length_m",
        "m",
        "length L_s of one slab (the period); joints at x = k L_s",
        gt=0.0,
        le=100.0,
        typical=(3.0, 25.0),
    ),
    Parameter(
        "fasteners_per_slab",
        "",
        "fasteners on each slab, sleeper_spacing apart and centred on it",
        "integer",
        ge=1,
        le=500,
    ),
    Parameter(
        "joint_shear_stiffness",
        "N/m",
        "shear stiffness of the joint between slabs (omitted with the bending one: free joints)",
        default=None,
        ge=0.0,
        le=1e15,
    ),
    Parameter(
        "joint_bending_stiffness",
        "N m/rad",
        "bending stiffness of the joint between slabs (omitted with the shear one: free joints)",
        default=None,
        ge=0.0,
        le=1e15,
    ),
)

_BY_KEY = {p.key: p for p in (*FLOATING_SLAB_PARAMETERS, *UNIT_SLAB_PARAMETERS)}

#: the beams of a span in a cell's layout
_RAIL, _SLAB_BEAM = 0, 1


@dataclass(frozen=True)
class _Layout:
    """A cell's topology, without values (:meth:`SlabTrack._layout`).

    Attributes
    ----------
    n_nodes : int
        Nodes (count); node ``k`` has DOFs ``2k`` (w) and ``2k+1`` (theta).
    spans : tuple of (int, int, int, float)
        Each span's two nodes, its beam (``_RAIL`` or ``_SLAB_BEAM``) and length (m).
    springs : tuple of (int, int or None, int, str)
        Each spring's nodes (None: the ground), DOF (0: w, 1: theta) and layer name.
    left, right : tuple of int
        The boundary nodes at ``x = 0`` and at the period.
    rail_nodes : dict
        ``{local position (m): node}`` of the rail nodes.
    """

    n_nodes: int
    spans: tuple[tuple[int, int, int, float], ...]
    springs: tuple[tuple[int, int | None, int, str], ...]
    left: tuple[int, ...]
    right: tuple[int, ...]
    rail_nodes: dict[float, int]

    def dofs(self) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
        """``(boundary, interior)`` DOF indices, as :class:`railvib.track.cells.Cell`'s."""
        nodes = np.array(self.left + self.right)
        boundary = np.stack([2 * nodes, 2 * nodes + 1], axis=1).ravel()
        return boundary, np.setdiff1d(np.arange(2 * self.n_nodes), boundary)


@dataclass(frozen=True)
class SlabTrack(PeriodicTrack):
    """Rail on railpads on a slab beam on a foundation or bearings (base of the slab tracks).

    Parameters
    ----------
    rail : Rail
        The rail beam.
    pad : PadModel
        Railpad model, complex stiffness per fastener in N/m.
    sleeper_spacing : float
        Fastener spacing d in m (> 0).
    pad_temperature : float, optional
        Temperature in degrees Celsius, passed to the pad, foundation and bearing models.
    slab_bending_stiffness : float
        EI_s of the slab beam per rail, N m^2.
    slab_mass_per_length : float
        m_s of the slab beam per rail, kg/m.
    slab_loss_factor : float
        eta_s of the slab (>= 0).
    foundation : PadModel, optional
        Continuous foundation, complex stiffness per metre of slab, N/m^2.
    bearing : PadModel, optional
        Discrete bearing, complex stiffness per bearing, N/m (instead of `foundation`).
    slab_damping_time : float
        Viscous (Kelvin-Voigt) slab damping tau_s in s (>= 0; not a case-file key):
        ``EI_s* = EI_s (1 + i eta_s + i omega tau_s)``, the causal stand-in for a loss
        factor that ``railvib validate`` puts in its time-domain model and in the
        frequency-domain solution it compares with it.
    """

    slab_bending_stiffness: float = 0.0
    slab_mass_per_length: float = 0.0
    slab_loss_factor: float = 0.0
    foundation: PadModel | None = None
    bearing: PadModel | None = None
    slab_damping_time: float = 0.0

    def __post_init__(self) -> None:
        super().__post_init__()
        for key in ("slab_bending_stiffness", "slab_mass_per_length", "slab_loss_factor"):
            check_value(_BY_KEY[key], getattr(self, key), f"track.{key}")
        for key in ("foundation", "bearing"):
            model = getattr(self, key)
            if model is not None and not isinstance(model, PadModel):
                raise CaseError(f"track.{key}", model, "a PadModel")
        if not (np.isfinite(self.slab_damping_time) and self.slab_damping_time >= 0.0):
            raise CaseError("track.slab_damping_time", self.slab_damping_time, ">= 0 (s)")
        if (self.foundation is None) == (self.bearing is None):
            raise CaseError(
                "track.foundation",
                "given with track.bearing" if self.foundation is not None else "<missing>",
                "exactly one of [track.foundation] (continuous, N/m per m) and "
                "[track.bearing] (discrete, N/m)",
            )

    # -- geometry, by the subclasses ------------------------------------------------------
    @property
    @abstractmethod
    def period(self) -> float:
        """Length of the periodic cell, m."""

    @abstractmethod
    def _fasteners(self) -> NDArray[np.float64]:
        """Fastener positions in the cell ``[0, period)``, m."""

    @abstractmethod
    def _slab_nodes(self) -> NDArray[np.float64]:
        """Slab node positions in the cell (fasteners and slab ends), m."""

    @abstractmethod
    def _bearings(self) -> NDArray[np.float64]:
        """Bearing positions in the cell, m (with :attr:`bearing`)."""

    def _joints(self) -> tuple[float, float] | None:
        """``(shear N/m, bending N m/rad)`` of a joint; None: a continuous slab or free joints."""
        return None

    # -- checks -----------------------------------------------------------------------------
    def _rail_spans(self, extra: NDArray[np.float64]) -> NDArray[np.float64]:
        return _merged(np.concatenate([[0.0, self.period], self._fasteners(), extra]), self.period)

    def layer_stiffness(self, f: ArrayLike) -> dict[str, NDArray[np.complex128]]:
        """The pad and the foundation or bearing stiffness, checked finite and passive.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Returns
        -------
        dict
            ``{"pad": K_p (N/m), "foundation": k_f (N/m^2)}`` or ``{"pad", "bearing"
            (N/m)}``, each ``(n_freq,)``.

        Raises
        ------
        CaseError
            A model has ``Im K < 0`` or is not finite at a frequency of the grid, named
            ``track.<layer>``.
        """
        models = {"pad": self.pad, "foundation": self.foundation, "bearing": self.bearing}
        # Im K down to -16 eps |K| is round-off of a passive model, not a source of power
        tolerance = 16 * np.finfo(float).eps
        return passive_layer_stiffness(models, f, self.pad_temperature, tolerance=tolerance)

    def check_frequencies(self, f: ArrayLike) -> None:
        """Refuse a grid the spans cannot be solved at, or where a support is not passive.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Raises
        ------
        CaseError
            ``frequency.f_max`` beyond a span's limit (:data:`MAX_EULER_SPAN_WAVENUMBER`,
            :data:`MAX_TIMOSHENKO_SPAN_WAVENUMBER`), or ``track.<layer>`` of a
            non-passive pad, foundation or bearing.
        """
        super().check_frequencies(f)
        f = np.atleast_1d(np.asarray(f, dtype=float))
        layers = self.layer_stiffness(f)
        omega2 = (2.0 * np.pi * f) ** 2
        rail = self.rail
        longest_rail = float(np.diff(self._rail_spans(np.zeros(0))).max())
        beta_r = (rail.mass_per_length * omega2.max(initial=0.0) / rail.bending_stiffness) ** 0.25
        limit = MAX_TIMOSHENKO_SPAN_WAVENUMBER if rail.is_timoshenko else MAX_EULER_SPAN_WAVENUMBER
        longest_slab = float(np.diff(self._slab_nodes()).max(initial=0.0))
        k_f = layers.get("foundation", np.zeros(1))
        beta4_s = np.abs(self.slab_mass_per_length * omega2 - k_f) / self.slab_bending_stiffness
        beta_s = float(beta4_s.max(initial=0.0)) ** 0.25
        for beta, span, lim, what in (
            (beta_r, longest_rail, limit, "rail"),
            (beta_s, longest_slab, MAX_EULER_SPAN_WAVENUMBER, "slab"),
        ):
            if beta * span > lim:
                raise CaseError(
                    "frequency.f_max",
                    float(f.max()),
                    f"lower: the {what}'s wavenumber times its longest span ({span:.4g} m) "
                    f"reaches {beta * span:.4g} there, beyond {lim:g} (Hz)",
                )

    def support_positions(self, x: ArrayLike) -> NDArray[np.float64]:
        """The support of each rail position `x` (m): its nearest bearing or its bay, m.

        On bearings, the bearing nearest `x` (the one ahead at a tie); on a continuous
        foundation, the centre of the slab bay (span between consecutive slab nodes: the
        fasteners and the slab ends) that holds `x` (the one ahead at a node).

        Parameters
        ----------
        x : array_like
            Positions along the rail, m.

        Returns
        -------
        numpy.ndarray
            Bearing positions or bay centres, m, shape of `x`.
        """
        x = np.asarray(x, dtype=float)
        return np.asarray(
            [self._supports_around(float(v), 0)[0] for v in x.ravel()], dtype=float
        ).reshape(x.shape)

    def _bays(self) -> tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.float64]]:
        """The slab bays in the cell: ``(first slab node, start m, end m)`` of each.

        A bay is a slab span between consecutive slab nodes (a joint's two coincident slab
        ends bound none).
        """
        slab_x = self._slab_nodes()
        first = np.flatnonzero(np.diff(slab_x) > _MERGE * self.period)
        return first, slab_x[first], slab_x[first + 1]

    def _supports_around(self, x: float, n: int) -> NDArray[np.float64]:
        """The support of `x` (m) and `n` on each side of it, m, increasing.

        Bearings (the nearest, the one ahead at a tie) or bay centres (the bay holding `x`).
        """
        period = self.period
        cells = np.floor(x / period) + np.arange(-n - 1, n + 2)
        if self.bearing is not None:
            every = np.sort((cells[:, None] * period + self._bearings()[None, :]).ravel())
            # the one ahead at a tie: 1e-9 of the period of rounding still counts as a tie
            nearest = int(np.argmin(np.abs(every - x) - 1e-9 * period * (every > x)))
            return every[nearest - n : nearest + n + 1]
        _, start, end = self._bays()
        starts = (cells[:, None] * period + start[None, :]).ravel()
        centres = (cells[:, None] * period + (start + end)[None, :] / 2.0).ravel()
        # the bay ahead at a node: 1e-9 of the period of rounding still counts as the node
        holding = int(np.flatnonzero(starts <= x + 1e-9 * period)[-1])
        return centres[holding - n : holding + n + 1]

    def _seat_transfer(
        self, f: NDArray[np.float64], x_load: NDArray[np.float64], x_seat: NDArray[np.float64]
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128], dict[str, NDArray]]:
        """Rail and slab displacement at the supports `x_seat` per unit rail loads at `x_load`.

        On bearings the slab's at each bearing; on a foundation its mean over each bay
        (:meth:`_bay_weights`; `x_seat` the bays' centres, where the rail's is taken).
        Returns ``(rail, slab, layers)``: m/N, ``(n_freq, n_seat, n_load)`` each, and
        :meth:`layer_stiffness` at `f`.
        """
        self.check_frequencies(f)
        load_cell, load_x = self._locate(x_load)
        seat_cell, seat_x = self._locate(x_seat)
        layers = self.layer_stiffness(f)
        slab_x = self._slab_nodes()
        bays = self.foundation is not None
        extra = np.concatenate([load_x, seat_x]) if bays else load_x
        n_rail = self._rail_spans(extra).size
        if bays:
            first, start, end = self._bays()
            # the bay of each seat (its centre), its four slab DOFs (w, theta at both ends)
            bay = np.array([int(np.argmin(np.abs((start + end) / 2 - x))) for x in seat_x])
            node = n_rail + first[bay]
            slab_dofs = (2 * node[:, None] + np.array([0, 1, 2, 3])[None, :]).ravel()
            lengths = (end - start)[bay]
        else:
            slab_dofs = np.array([2 * (n_rail + _at(slab_x, x)) for x in seat_x], dtype=np.intp)
        n_seat = x_seat.size
        rail_nodes = self._layout(extra).rail_nodes
        load = (load_cell, _rail_dofs(rail_nodes, load_x))
        obs = (
            np.concatenate([seat_cell, np.repeat(seat_cell, slab_dofs.size // n_seat)]),
            np.concatenate([_rail_dofs(rail_nodes, seat_x), slab_dofs]),
        )
        kernel = fused_kernel()
        fused = None
        if self.rail.shear_stiffness is None and kernel is not None:
            fused = self._fused_receptance(f, layers, extra, load, obs, kernel)
        rail = np.empty((f.size, n_seat, x_load.size), dtype=np.complex128)
        slab = np.empty_like(rail)
        for block in self._blocks(f, extra):
            part = {name: k[block] for name, k in layers.items()}
            if fused is None:
                both = cell_receptance(cell_waves(self._cell(f[block], extra, part)[0]), load, obs)
            else:
                both = fused[block]
            rail[block], slab_block = both[:, :n_seat], both[:, n_seat:]
            if bays:
                # the mean over each bay: its integral (the weights times its end DOFs) / L
                q = slab_block.reshape(slab_block.shape[0], n_seat, 4, -1)
                weights = self._bay_weights(f[block], lengths, part)
                slab_block = np.einsum("fsd,fsdl->fsl", weights, q) / lengths[None, :, None]
            slab[block] = slab_block
        return rail, slab, layers

    def _bay_weights(
        self,
        f: NDArray[np.float64],
        lengths: NDArray[np.float64],
        layers: dict[str, NDArray[np.complex128]],
    ) -> NDArray[np.complex128]:
        """``int w dx`` over slab bays of `lengths` (m) per unit end DOF, ``(n_f, n_bay, 4)``.

        The bay's exact deflection (``EI_s* w'''' = (m_s omega^2 - k_f) w``, as in the cell)
        integrated: by the bay's vertical equilibrium ``int w dx = -(F_a + F_b) / (m_s
        omega^2 - k_f)``, ``F_a + F_b`` the shear rows of its exact dynamic stiffness
        (:func:`railvib.track.cells.span_stiffness`) times ``(w_a, theta_a, w_b,
        theta_b)``; where ``|lambda| = |(m_s omega^2 - k_f) L^4 / EI_s*| <`` 1 (the static
        limit, a lossless foundation's cut-on) that quotient loses ``1 / |lambda|`` of its
        digits, and the exact shape functions' integrals are taken from their series in
        ``lambda`` (:data:`_BAY_SERIES`), m (per m) and m^2 (per rad).
        """
        ei_s = self._slab_stiffness(f)
        slab_load = np.asarray(
            self.slab_mass_per_length * (2.0 * np.pi * f) ** 2 - layers["foundation"],
            dtype=np.complex128,
        )
        out = np.empty((f.size, lengths.size, 4), dtype=np.complex128)
        for j, length in enumerate(lengths):
            lam = slab_load * length**4 / ei_s
            small = np.abs(lam) < 1.0
            k = _slab_span(slab_load[~small], length, ei_s[~small])
            out[~small, j] = -(k[:, 0] + k[:, 2]) / slab_load[~small, None]
            powers = lam[small, None] ** np.arange(_BAY_SERIES.shape[1])[None, :]
            a, b = (powers @ _BAY_SERIES[0]), (powers @ _BAY_SERIES[1]) * length
            out[small, j] = length * np.stack([a, b, a, -b], axis=1)
        return out

    @staticmethod
    def _bearing_layers(
        x: NDArray[np.float64],
        rail: NDArray[np.complex128],
        slab: NDArray[np.complex128],
        layers: dict[str, NDArray[np.complex128]],
    ) -> SupportResponse:
        """The pad and the bearing at the seats `x` from the rail and slab displacements."""
        kp, kb = layers["pad"][:, None], layers["bearing"][:, None]
        compression = {"pad": rail - slab, "bearing": slab}
        return SupportResponse(
            x=np.asarray(x, dtype=float),
            displacement={"rail": rail, "slab": slab},
            compression=compression,
            force={"pad": kp * compression["pad"], "bearing": kb * slab},
            stiffness={"pad": layers["pad"], "bearing": layers["bearing"]},
            foundation="bearing",
        )

    def _foundation_layers(
        self,
        x: NDArray[np.float64],
        rail: NDArray[np.complex128],
        slab: NDArray[np.complex128],
        layers: dict[str, NDArray[np.complex128]],
    ) -> SupportResponse:
        """The foundation under the bays centred at `x` from the slab's mean over each."""
        lengths = np.array([self._bay_length(float(v)) for v in x])
        k_bay = layers["foundation"][:, None] * lengths[None, :]  # N/m of each bay
        return SupportResponse(
            x=np.asarray(x, dtype=float),
            displacement={"rail": rail, "slab": slab},
            compression={"foundation": slab},
            force={"foundation": k_bay * slab},
            stiffness={"foundation": k_bay},
            foundation="foundation",
        )

    def _bay_length(self, x: float) -> float:
        """Length in m of the bay centred at `x` (m)."""
        _, local = self._locate(np.array([x]))
        _, start, end = self._bays()
        return float((end - start)[np.argmin(np.abs((start + end) / 2 - local[0]))])

    def _layers(
        self,
        x: NDArray[np.float64],
        rail: NDArray[np.complex128],
        slab: NDArray[np.complex128],
        layers: dict[str, NDArray[np.complex128]],
    ) -> SupportResponse:
        """The support layers from :meth:`_seat_transfer`'s rail and slab displacements."""
        if self.bearing is not None:
            return self._bearing_layers(x, rail, slab, layers)
        return self._foundation_layers(x, rail, slab, layers)

    def support_response(self, f: ArrayLike, x_load: float, n_supports: int) -> SupportResponse:
        """The supports nearest a unit rail load: rail and slab displacements, layer forces.

        On bearings the supports are the bearings (every one carries a fastener above it):
        the nearest to `x_load` and `n_supports` on each side; the rail and slab
        displacements there come from the cell's solution (the slab's DOF at the bearing),
        the pad carries ``K_p (w_r - w_s)``, the bearing ``K_b w_s`` to the ground. On a
        continuous foundation the supports are the slab bays (spans between consecutive
        fasteners or slab ends: a fastener spacing of a floating slab), the one holding
        `x_load` and `n_supports` on each side, at their centres: the foundation under a
        bay carries ``k_f* int w_s dx`` over it (the exact slab deflection integrated,
        :meth:`_bay_weights`), ``"slab"`` is the slab's mean displacement over the bay and
        ``"rail"`` the rail's at its centre.

        Parameters
        ----------
        f : array_like
            Frequencies, Hz.
        x_load : float
            Position of the unit load along the rail, m.
        n_supports : int
            Supports on each side of the one nearest the load (>= 0).

        Returns
        -------
        SupportResponse
            Masses ``"rail"``, ``"slab"``; layers ``"pad"``, ``"bearing"`` (the foundation)
            on bearings, ``"foundation"`` (N/N per bay; stiffness ``k_f* L_bay``, N/m) on a
            continuous foundation.
        """
        if not np.isfinite(x_load):
            raise CaseError("x_load", x_load, "a finite position (m)")
        if int(n_supports) != n_supports or n_supports < 0:
            raise CaseError("n_supports", n_supports, "an integer >= 0")
        f = _as_freq(f)
        x = self._supports_around(float(x_load), int(n_supports))
        rail, slab, layers = self._seat_transfer(f, np.array([float(x_load)]), x)
        return self._layers(x, rail[:, :, 0], slab[:, :, 0], layers)

    def seat_forces(
        self, f: ArrayLike, x_load: ArrayLike, loads: NDArray[np.complex128]
    ) -> SupportResponse:
        """The support of each load under all the loads together (the coupled run).

        The bearing nearest each load, or on a continuous foundation the slab bay holding
        it (:meth:`support_positions`).

        Parameters
        ----------
        f : array_like
            Frequencies, Hz, ``(n_freq,)``.
        x_load : array_like
            Positions of the rail loads (the wheels), m, ``(n_load,)``.
        loads : numpy.ndarray
            Complex rail loads, N (or N per unit input), ``(n_freq, n_load)``.

        Returns
        -------
        SupportResponse
            At the support of each load, ``(n_freq, n_load)``: in the units of `loads` for
            forces, m per unit of `loads` for displacements.
        """
        f = _as_freq(f)
        x_load = np.atleast_1d(np.asarray(x_load, dtype=float))
        seats = self.support_positions(x_load)
        rail, slab, layers = self._seat_transfer(f, x_load, seats)
        return self._layers(
            seats,
            np.einsum("fsl,fl->fs", rail, loads),
            np.einsum("fsl,fl->fs", slab, loads),
            layers,
        )

    def seat_response(
        self, f: ArrayLike, x: NDArray[np.float64], rail: NDArray[np.complex128]
    ) -> SupportResponse:
        """Not defined for a slab track: its seats share the slab (NotImplementedError).

        The slab's displacement at a seat is not a function of the rail's there alone; the
        coupled run takes :meth:`seat_forces`.

        Parameters
        ----------
        f : array_like
            Frequencies, Hz.
        x : numpy.ndarray
            Seat positions, m.
        rail : numpy.ndarray
            Rail displacement at the seats, m.

        Raises
        ------
        NotImplementedError
            Always.
        """
        raise NotImplementedError(f"{type(self).__name__}: use seat_forces (the slab couples)")

    def support_stiffness(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Not defined for a slab track: the slab couples the fasteners (raises CaseError).

        Parameters
        ----------
        f : array_like
            Frequencies in Hz.

        Raises
        ------
        CaseError
            Always: the rigid-base wave methods (``waves``, ``cell_transfer``, ...) do not
            apply; use :meth:`receptance` or :meth:`propagation_constants`.
        """
        raise CaseError(
            "track.model",
            type(self).__name__,
            "a track whose fasteners have independent supports (the slab couples them): "
            "use receptance or propagation_constants",
        )

    # -- the cell ---------------------------------------------------------------------------
    def _layout(self, extra: NDArray[np.float64]) -> _Layout:
        """The period's nodes, spans and springs with extra rail nodes at local `extra` (m)."""
        period = self.period
        rail_x = self._rail_spans(extra)
        slab_x = self._slab_nodes()
        n_rail = rail_x.size
        # nodes: the rail, then the slab; a continuous or jointed slab also has its right
        # boundary node (the next slab's left end): its last node, at the period
        slab_nodes = n_rail + np.arange(slab_x.size)
        spans = [(i, i + 1, _RAIL, float(length)) for i, length in enumerate(np.diff(rail_x))]
        for i, length in enumerate(np.diff(slab_x)):
            if length <= _MERGE * period:
                continue  # the joint: two slab ends at one place, joined by springs below
            spans.append((int(slab_nodes[i]), int(slab_nodes[i + 1]), _SLAB_BEAM, float(length)))
        springs: list[tuple[int, int | None, int, str]] = []
        for x in self._fasteners():
            rail_node = int(np.argmin(np.abs(rail_x - x)))
            springs.append((rail_node, int(slab_nodes[_at(slab_x, x)]), 0, "pad"))
        if self.bearing is not None:
            for x in self._bearings():
                springs.append((int(slab_nodes[_at(slab_x, x)]), None, 0, "bearing"))
        if self._joints() is not None:
            a, b = int(slab_nodes[-2]), int(slab_nodes[-1])
            springs += [(a, b, 0, "joint_shear"), (a, b, 1, "joint_bending")]
        left: tuple[int, ...] = (0,)
        right: tuple[int, ...] = (n_rail - 1,)
        if self._slab_crosses():
            left, right = (0, int(slab_nodes[0])), (n_rail - 1, int(slab_nodes[-1]))
        return _Layout(
            n_rail + slab_x.size,
            tuple(spans),
            tuple(springs),
            left,
            right,
            {float(x): i for i, x in enumerate(rail_x)},
        )

    def _spring_values(
        self, f: NDArray[np.float64], layers: dict[str, NDArray[np.complex128]]
    ) -> dict[str, NDArray[np.complex128]]:
        """The springs' complex stiffness at `f` by layer name (N/m, N m/rad), ``(n_freq,)``."""
        values = dict(layers)
        joints = self._joints()
        if joints is not None:
            for name, value in zip(("joint_shear", "joint_bending"), joints, strict=True):
                values[name] = np.full(f.shape, value, dtype=np.complex128)
        return values

    def _beams(
        self, f: NDArray[np.float64], layers: dict[str, NDArray[np.complex128]]
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
        """``(m omega^2 - k_f, EI*)`` of the rail and the slab at `f`, ``(2, n_freq)`` each.

        N/m^2 and N m^2; the rail's ``EI*`` with :data:`VANISHING_LOSS_FACTOR` at least.
        """
        omega2 = (2.0 * np.pi * f) ** 2
        rail = self.rail
        ei_r = rail.bending_stiffness * (1.0 + 1j * max(rail.loss_factor, VANISHING_LOSS_FACTOR))
        k_f = layers.get("foundation", 0.0)
        slab_load = np.asarray(self.slab_mass_per_length * omega2 - k_f, dtype=np.complex128)
        load = np.stack([rail.mass_per_length * omega2 + 0j, slab_load])
        return load, np.stack([np.full(f.shape, ei_r), self._slab_stiffness(f)])

    def _cell(
        self,
        f: NDArray[np.float64],
        extra: NDArray[np.float64],
        layers: dict[str, NDArray[np.complex128]],
    ) -> tuple[Cell, dict[float, int]]:
        """The period at frequencies `f` with extra rail nodes at local positions `extra` (m).

        `layers` holds :meth:`layer_stiffness` at `f`. Returns the cell and ``{local
        position: node}`` of its rail nodes.
        """
        layout = self._layout(extra)
        omega2 = (2.0 * np.pi * f) ** 2
        rail = self.rail
        ei_r = rail.bending_stiffness * (1.0 + 1j * max(rail.loss_factor, VANISHING_LOSS_FACTOR))
        ei_s = self._slab_stiffness(f)
        k_f = layers.get("foundation", 0.0)
        slab_load = np.asarray(self.slab_mass_per_length * omega2 - k_f, dtype=np.complex128)
        spans: list[tuple[int, int, NDArray[np.complex128]]] = []
        for a, b, beam, length in layout.spans:
            if beam == _SLAB_BEAM:
                k = _slab_span(slab_load, length, ei_s)
                spans.append((a, b, k))
                continue
            beta4 = np.asarray(rail.mass_per_length * omega2 * length**4 / ei_r, np.complex128)
            if rail.shear_stiffness is None:
                k = span_stiffness(beta4, length, ei_r)
            else:
                kga = rail.shear_stiffness * (ei_r / rail.bending_stiffness)
                rotary = np.asarray(rail.rotary_inertia * omega2 * length**2 / ei_r, np.complex128)
                k = span_stiffness(beta4, length, ei_r, ei_r / (kga * length**2), rotary)
            spans.append((a, b, k))
        values = self._spring_values(f, layers)
        springs = [(a, b, dof, values[name]) for a, b, dof, name in layout.springs]
        cell = Cell(self.period, layout.n_nodes, spans, springs, layout.left, layout.right)
        return cell, layout.rail_nodes

    def _slab_crosses(self) -> bool:
        """True if the slab's DOFs cross the cell boundary (continuous or jointed slab)."""
        return True

    def _slab_stiffness(self, f: NDArray[np.float64]) -> NDArray[np.complex128]:
        """``EI_s* = EI_s (1 + i eta_s + i omega tau_s)`` at `f` (Hz), N m^2, ``(n_freq,)``.

        An undamped slab takes the loss factor :data:`VANISHING_LOSS_FACTOR`.
        """
        eta = max(self.slab_loss_factor, VANISHING_LOSS_FACTOR)
        viscous = 2.0 * np.pi * f * self.slab_damping_time
        return np.asarray(
            self.slab_bending_stiffness * (1.0 + 1j * (eta + viscous)), dtype=np.complex128
        )

    def _locate(self, x: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """Cell index and local position in ``[0, period)`` of each rail position (m)."""
        period = self.period
        cell = np.floor(x / period)
        local = x - cell * period
        wrap = local > period * (1.0 - _MERGE)
        cell = cell + wrap
        local = np.where(wrap | (local < period * _MERGE), 0.0, local)
        return cell.astype(np.int64), local

    # -- public physics -----------------------------------------------------------------------
    def receptance(
        self, f: ArrayLike, x_load: ArrayLike, x_obs: ArrayLike, *, waves: TrackWaves | None = None
    ) -> NDArray[np.complex128]:
        """Rail receptance (vertical displacement per unit vertical force) between points.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, ``(n_freq,)`` (any order, repeats allowed).
        x_load : array_like
            Positions of the unit loads along the rail, m.
        x_obs : array_like
            Positions of the observation points, m.
        waves : None
            Not used by a slab track (its waves are those of its cell); must be None.

        Returns
        -------
        numpy.ndarray
            Complex receptance in m/N, ``(n_freq, n_obs, n_load)``.

        Raises
        ------
        NonFiniteResult
            Where a value is not finite (the doubling overflowed: no frequency of the
            validation grids does with the loss factor :data:`VANISHING_LOSS_FACTOR`).
        """
        if waves is not None:
            raise CaseError("waves", "given", "None for a slab track (its cell is solved here)")
        f = _as_freq(f)
        x_load = np.atleast_1d(np.asarray(x_load, dtype=float))
        x_obs = np.atleast_1d(np.asarray(x_obs, dtype=float))
        for name, x in (("x_load", x_load), ("x_obs", x_obs)):
            if not np.all(np.isfinite(x)):
                raise CaseError(name, list(x), "finite positions (m)")
        self.check_frequencies(f)
        load_cell, load_x = self._locate(x_load)
        obs_cell, obs_x = self._locate(x_obs)
        # the layers once over all of f (a stacked sweep's pads are given point by point)
        layers = self.layer_stiffness(f)
        extra = np.concatenate([load_x, obs_x])
        rail_nodes = self._layout(extra).rail_nodes
        load = (load_cell, _rail_dofs(rail_nodes, load_x))
        obs = (obs_cell, _rail_dofs(rail_nodes, obs_x))
        kernel = fused_kernel()
        if self.rail.shear_stiffness is None and kernel is not None:
            out = self._fused_receptance(f, layers, extra, load, obs, kernel)
        else:
            out = self._cell_receptance(f, layers, extra, load, obs)
        bad = ~np.isfinite(out).all(axis=(1, 2))
        if np.any(bad):
            raise NonFiniteResult(
                f"track receptance: {int(bad.sum())} frequencies (first {f[bad][0]:.6g} Hz) "
                "are not finite: the doubling did not resolve the slab track's waves there; "
                "give track.rail.loss_factor or track.slab_loss_factor (e.g. 0.01)"
            )
        return out

    def _cell_receptance(
        self,
        f: NDArray[np.float64],
        layers: dict[str, NDArray[np.complex128]],
        extra: NDArray[np.float64],
        load: tuple[NDArray[np.int64], NDArray[np.intp]],
        obs: tuple[NDArray[np.int64], NDArray[np.intp]],
    ) -> NDArray[np.complex128]:
        """The receptance by the cell solver (:mod:`railvib.track.cells`), block by block.

        `layers` is :meth:`layer_stiffness` at `f` (Hz); `extra` the local positions (m) of
        the loaded cell's extra rail nodes; `load` and `obs` each point's cell and DOF in
        that cell. Returns m/N, ``(n_freq, n_obs, n_load)``.
        """
        out = np.empty((f.size, obs[1].size, load[1].size), dtype=np.complex128)
        for block in self._blocks(f, extra):
            part = {name: k[block] for name, k in layers.items()}
            # the waves on the cell without the points' nodes (fewer DOFs to condense)
            chain = cell_waves(self._cell(f[block], np.zeros(0), part)[0])
            cell = self._cell(f[block], extra, part)[0]
            out[block] = cell_receptance(chain, load, obs, cell)
        return out

    def _fused_receptance(
        self,
        f: NDArray[np.float64],
        layers: dict[str, NDArray[np.complex128]],
        extra: NDArray[np.float64],
        load: tuple[NDArray[np.int64], NDArray[np.intp]],
        obs: tuple[NDArray[np.int64], NDArray[np.intp]],
        kernel: Any,
    ) -> NDArray[np.complex128]:
        """:meth:`_cell_receptance` on the fused `kernel` (:mod:`railvib.track.slab_kernel`).

        The same cells, the same algorithm, in one pass; the frequencies it flags (a weak
        pivot of its elimination without row exchanges, or a doubling not converged) are
        solved again by :meth:`_cell_receptance`.
        """
        (load_cell, load_dof), (obs_cell, obs_dof) = load, obs
        waves = self._layout(np.zeros(0))
        loaded = self._layout(extra)
        values = self._spring_values(f, layers)
        names = sorted({name for *_, name in waves.springs + loaded.springs})
        kinds = sorted({(beam, length) for *_, beam, length in waves.spans + loaded.spans})
        tables = [_kernel_tables(layout, kinds, names) for layout in (waves, loaded)]
        bnd, inner = loaded.dofs()
        dofs = load_dof, obs_dof
        # the points' DOFs eliminated last: a point close to a node (a short rail span)
        # leaves a weak pivot in its column otherwise (a unit slab of 8 fasteners with a
        # load 5 cm from one, 0.1 Hz-2 kHz: 1989 of 2000 frequencies flagged, 218 so)
        points = inner[_where(bnd, inner, *dofs)[0]]
        inner = np.concatenate([np.setdiff1d(inner, points), points])
        where = _where(bnd, inner, *dofs)
        tables[1] = (*tables[1][:3], inner.astype(np.int64))
        out, bad = slab_receptance(
            *self._beams(f, layers),
            np.stack([values[name] for name in names]),
            (
                np.array([beam for beam, _ in kinds], dtype=np.int64),
                np.array([length for _, length in kinds]),
            ),
            tables[0],
            tables[1],
            where,
            obs_cell[:, None] - load_cell[None, :],
            cell_solver.MAX_DOUBLINGS,
            cell_solver.CONVERGED,
            cell_solver.CLOSED_FORM_WAVENUMBER**4,
            kernel,
        )
        if np.any(bad):
            out[bad] = self._cell_receptance(
                f[bad], {name: k[bad] for name, k in layers.items()}, extra, load, obs
            )
        return out

    def _blocks(self, f: NDArray[np.float64], extra: NDArray[np.float64]) -> list[slice]:
        """Frequency blocks whose cell matrices (``n_dof^2`` each) fill about 16 MB."""
        n_dof = 2 * (self._rail_spans(extra).size + self._slab_nodes().size)
        size = max(64, CELL_BLOCK_ENTRIES // n_dof**2)
        return [slice(i, i + size) for i in range(0, f.size, size)]

    def propagation_constants(self, f: ArrayLike) -> NDArray[np.complex128]:
        """Propagation constants ``mu = exp(-gamma L)`` of the right-going waves per period.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, ``(n_freq,)``.

        Returns
        -------
        numpy.ndarray
            ``(n_freq, n_waves)``, ``|mu| <= 1``, least attenuated first; ``n_waves`` is the
            number of boundary DOFs per side: 4 with the slab crossing the cell boundary,
            2 for unit slabs with free joints.
        """
        f = _as_freq(f)
        self.check_frequencies(f)
        layers = self.layer_stiffness(f)
        none = np.zeros(0)
        parts = [
            cell_waves(
                self._cell(f[block], none, {k: v[block] for k, v in layers.items()})[0]
            ).propagation_constants()
            for block in self._blocks(f, none)
        ]
        return np.concatenate(parts)


@dataclass(frozen=True)
class FloatingSlabTrack(SlabTrack):
    """Rail on railpads on a continuous floating slab (see the module docstring).

    Parameters
    ----------
    rail, pad, sleeper_spacing, pad_temperature : object
        As :class:`SlabTrack` (fasteners at ``x = n d``; spacing in m, temperature in degC).
    slab_bending_stiffness, slab_mass_per_length, slab_loss_factor : float
        As :class:`SlabTrack` (N m^2, kg/m, -).
    slab_damping_time : float
        As :class:`SlabTrack` (s; ``railvib validate``'s viscous slab).
    foundation, bearing : PadModel, optional
        As :class:`SlabTrack` (N/m^2, N/m).
    bearing_spacing_fasteners : int
        With `bearing`: a bearing under every this many fasteners (>= 1), at ``x = 0``
        among them; the cell is this many fastener spacings.

    Examples
    --------
    >>> from railvib.pads import Hysteretic
    >>> track = FloatingSlabTrack(
    ...     Rail(6.42e6, 60.0), Hysteretic(4e7, 0.2), 0.6,
    ...     slab_bending_stiffness=1.2e8, slab_mass_per_length=1750.0,
    ...     foundation=Hysteretic(7e6, 0.1),
    ... )
    >>> track.receptance([10.0, 100.0], x_load=[0.3], x_obs=[0.3]).shape
    (2, 1, 1)
    """

    bearing_spacing_fasteners: int = 1

    def __post_init__(self) -> None:
        super().__post_init__()
        check_value(
            _BY_KEY["bearing_spacing_fasteners"],
            self.bearing_spacing_fasteners,
            "track.bearing_spacing_fasteners",
        )
        if self.foundation is not None and self.bearing_spacing_fasteners != 1:
            raise CaseError(
                "track.bearing_spacing_fasteners",
                self.bearing_spacing_fasteners,
                "1 (the default) with a continuous [track.foundation]; it spaces bearings",
            )

    @property
    def period(self) -> float:
        """Length of the periodic cell, m: one fastener spacing (one bearing spacing)."""
        return self.sleeper_spacing * self.bearing_spacing_fasteners

    def _fasteners(self) -> NDArray[np.float64]:
        return self.sleeper_spacing * np.arange(self.bearing_spacing_fasteners, dtype=float)

    def _slab_nodes(self) -> NDArray[np.float64]:
        return np.append(self._fasteners(), self.period)

    def _bearings(self) -> NDArray[np.float64]:
        return np.zeros(1)


@dataclass(frozen=True)
class UnitSlabTrack(SlabTrack):
    """Rail on railpads on unit slabs of length L_s with n fasteners each (module docstring).

    Slab ``k`` spans ``[k L_s, (k + 1) L_s]``; its fasteners lie at ``k L_s + x_0 + j d``,
    ``j = 0 ... n - 1``, ``x_0 = (L_s - (n - 1) d) / 2``. Bearings (with `bearing`) lie
    under every fastener.

    Parameters
    ----------
    rail, pad, sleeper_spacing, pad_temperature : object
        As :class:`SlabTrack` (spacing in m, temperature in degC).
    slab_bending_stiffness, slab_mass_per_length, slab_loss_factor : float
        As :class:`SlabTrack` (N m^2, kg/m, -).
    slab_damping_time : float
        As :class:`SlabTrack` (s; ``railvib validate``'s viscous slab).
    foundation, bearing : PadModel, optional
        As :class:`SlabTrack` (N/m^2, N/m; bearings under every fastener).
    slab_length : float
        L_s in m (>= d and >= n d).
    fasteners_per_slab : int
        n (>= 1).
    joint_shear_stiffness : float, optional
        Shear stiffness of each joint, N/m (>= 0).
    joint_bending_stiffness : float, optional
        Bending stiffness of each joint, N m/rad (>= 0); both omitted: free joints.

    Examples
    --------
    >>> from railvib.pads import Hysteretic
    >>> track = UnitSlabTrack(
    ...     Rail(6.42e6, 60.0), Hysteretic(4e7, 0.2), 0.6,
    ...     slab_bending_stiffness=1.2e8, slab_mass_per_length=1750.0,
    ...     foundation=Hysteretic(7e6, 0.1), slab_length=4.8, fasteners_per_slab=8,
    ... )
    >>> track.propagation_constants([50.0]).shape
    (1, 2)
    """

    slab_length: float = 0.0
    fasteners_per_slab: int = 0
    joint_shear_stiffness: float | None = None
    joint_bending_stiffness: float | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        check_value(_BY_KEY["slab_length_m"], self.slab_length, "track.slab_length_m")
        check_value(
            _BY_KEY["fasteners_per_slab"], self.fasteners_per_slab, "track.fasteners_per_slab"
        )
        for key in ("joint_shear_stiffness", "joint_bending_stiffness"):
            if getattr(self, key) is not None:
                check_value(_BY_KEY[key], getattr(self, key), f"track.{key}")
        d = self.sleeper_spacing
        if self.slab_length < d:
            raise CaseError(
                "track.slab_length_m",
                self.slab_length,
                f">= track.sleeper_spacing = {d:g} m: a slab holds at least one fastener (m)",
            )
        n = self.fasteners_per_slab
        if n * d > self.slab_length * (1.0 + _MERGE):
            raise CaseError(
                "track.fasteners_per_slab",
                n,
                f"at most {int(self.slab_length / d * (1.0 + _MERGE))}: n fasteners "
                f"{d:g} m apart need n x {d:g} <= slab_length_m = {self.slab_length:g} m "
                "(half a spacing to each slab end at least)",
            )

    @property
    def period(self) -> float:
        """Length of the periodic cell, m: one slab."""
        return self.slab_length

    def _fasteners(self) -> NDArray[np.float64]:
        d, n = self.sleeper_spacing, self.fasteners_per_slab
        return (self.slab_length - (n - 1) * d) / 2.0 + d * np.arange(n, dtype=float)

    def _slab_nodes(self) -> NDArray[np.float64]:
        inner = np.concatenate([[0.0], self._fasteners(), [self.slab_length]])
        if self._joints() is None:
            return inner
        return np.append(inner, self.slab_length)  # the next slab's left end

    def _bearings(self) -> NDArray[np.float64]:
        return self._fasteners()

    def _joints(self) -> tuple[float, float] | None:
        shear, bending = self.joint_shear_stiffness, self.joint_bending_stiffness
        if shear is None and bending is None:
            return None
        return (shear or 0.0, bending or 0.0)

    def _slab_crosses(self) -> bool:
        return self._joints() is not None


def _slab_span(
    slab_load: NDArray[np.complex128], length: float, ei_s: NDArray[np.complex128]
) -> NDArray[np.complex128]:
    """Exact dynamic stiffness of a slab span, ``(n_freq, 4, 4)``, SI.

    `slab_load` is ``m_s omega^2 - k_f`` (N/m^2) and `ei_s` the complex ``EI_s*`` (N m^2)
    per frequency: :func:`railvib.track.cells.span_stiffness` at unit ``EI``, scaled by
    each frequency's ``EI_s*``.
    """
    if np.all(ei_s == ei_s[:1]):  # no viscous part: one EI_s*, as a loss factor alone
        one = complex(ei_s[0]) if ei_s.size else 1.0  # (no frequency: any)
        return span_stiffness(slab_load * length**4 / ei_s, length, one)
    unit = span_stiffness(slab_load * length**4 / ei_s, length, 1.0)
    return np.asarray(unit * ei_s[:, None, None], dtype=np.complex128)


def _kernel_tables(
    layout: _Layout, kinds: list[tuple[int, float]], names: list[str]
) -> tuple[NDArray[np.int64], ...]:
    """A cell's ``(spans, springs, boundary, interior)`` tables for the fused kernel.

    `kinds` are the distinct ``(beam, length m)`` of the spans, `names` the springs'
    layers, in the order of the kernel's rows.
    """
    spans = [(a, b, kinds.index((beam, length))) for a, b, beam, length in layout.spans]
    springs = [
        (2 * a + dof, -1 if b is None else 2 * b + dof, names.index(name))
        for a, b, dof, name in layout.springs
    ]
    bnd, inner = layout.dofs()
    return (
        np.array(spans, dtype=np.int64).reshape(-1, 3),
        np.array(springs, dtype=np.int64).reshape(-1, 3),
        bnd.astype(np.int64),
        inner.astype(np.int64),
    )


def _merged(x: NDArray[np.float64], period: float) -> NDArray[np.float64]:
    """Sorted unique positions, merging those within ``_MERGE`` of the period."""
    x = np.sort(np.asarray(x, dtype=float))
    keep = np.concatenate([[True], np.diff(x) > _MERGE * period])
    return x[keep]


def _rail_dofs(rail_nodes: dict[float, int], local: NDArray[np.float64]) -> NDArray[np.intp]:
    """The displacement DOF of the rail node nearest each local position (m)."""
    keys = np.array(list(rail_nodes))
    nodes = [rail_nodes[float(keys[np.argmin(np.abs(keys - x))])] for x in local]
    return 2 * np.array(nodes, dtype=np.intp)


def _at(nodes: NDArray[np.float64], x: float) -> int:
    """Index of the first node at position `x`."""
    return int(np.flatnonzero(np.abs(nodes - x) <= 2 * _MERGE * max(1.0, abs(x)))[0])


def _as_freq(f: ArrayLike) -> NDArray[np.float64]:
    f = np.atleast_1d(np.asarray(f, dtype=float))
    if f.ndim != 1 or not np.all(np.isfinite(f) & (f > 0)):
        raise CaseError("frequency", "non-positive or non-finite values", "finite and > 0 (Hz)")
    return f


def floating_slab_track(
    sleeper_spacing: float,
    rail: Rail,
    pad: PadModel,
    slab_bending_stiffness: float,
    slab_mass_per_length: float,
    pad_temperature_c: float | None = None,
    slab_loss_factor: float = 0.0,
    foundation: PadModel | None = None,
    bearing: PadModel | None = None,
    bearing_spacing_fasteners: int = 1,
) -> FloatingSlabTrack:
    """The floating slab track of a ``[track]`` table's checked values (:class:`FloatingSlabTrack`).

    Parameters
    ----------
    sleeper_spacing : float
        Fastener spacing d in m.
    rail : Rail
        The rail beam.
    pad : PadModel
        Railpad per fastener, N/m.
    slab_bending_stiffness : float
        EI_s per rail, N m^2.
    slab_mass_per_length : float
        m_s per rail, kg/m.
    pad_temperature_c : float, optional
        Temperature of the pad, foundation and bearing models, degC.
    slab_loss_factor : float
        eta_s (-).
    foundation : PadModel, optional
        Continuous foundation per metre of slab, N/m^2.
    bearing : PadModel, optional
        Discrete bearing, N/m.
    bearing_spacing_fasteners : int
        Fasteners per bearing.

    Returns
    -------
    FloatingSlabTrack
        The track.
    """
    return FloatingSlabTrack(
        rail,
        pad,
        sleeper_spacing,
        pad_temperature_c,
        slab_bending_stiffness=slab_bending_stiffness,
        slab_mass_per_length=slab_mass_per_length,
        slab_loss_factor=slab_loss_factor,
        foundation=foundation,
        bearing=bearing,
        bearing_spacing_fasteners=bearing_spacing_fasteners,
    )


def unit_slab_track(
    sleeper_spacing: float,
    rail: Rail,
    pad: PadModel,
    slab_bending_stiffness: float,
    slab_mass_per_length: float,
    slab_length_m: float,
    fasteners_per_slab: int,
    pad_temperature_c: float | None = None,
    slab_loss_factor: float = 0.0,
    foundation: PadModel | None = None,
    bearing: PadModel | None = None,
    joint_shear_stiffness: float | None = None,
    joint_bending_stiffness: float | None = None,
) -> UnitSlabTrack:
    """The unit slab track of a ``[track]`` table's checked values (:class:`UnitSlabTrack`).

    Parameters
    ----------
    sleeper_spacing : float
        Fastener spacing d in m.
    rail : Rail
        The rail beam.
    pad : PadModel
        Railpad per fastener, N/m.
    slab_bending_stiffness : float
        EI_s per rail, N m^2.
    slab_mass_per_length : float
        m_s per rail, kg/m.
    slab_length_m : float
        L_s, m.
    fasteners_per_slab : int
        n.
    pad_temperature_c : float, optional
        Temperature of the pad, foundation and bearing models, degC.
    slab_loss_factor : float
        eta_s (-).
    foundation : PadModel, optional
        Continuous foundation per metre of slab, N/m^2.
    bearing : PadModel, optional
        Bearing under each fastener, N/m.
    joint_shear_stiffness : float, optional
        Joint shear stiffness, N/m.
    joint_bending_stiffness : float, optional
        Joint bending stiffness, N m/rad.

    Returns
    -------
    UnitSlabTrack
        The track.
    """
    return UnitSlabTrack(
        rail,
        pad,
        sleeper_spacing,
        pad_temperature_c,
        slab_bending_stiffness=slab_bending_stiffness,
        slab_mass_per_length=slab_mass_per_length,
        slab_loss_factor=slab_loss_factor,
        foundation=foundation,
        bearing=bearing,
        slab_length=slab_length_m,
        fasteners_per_slab=fasteners_per_slab,
        joint_shear_stiffness=joint_shear_stiffness,
        joint_bending_stiffness=joint_bending_stiffness,
    )


TRACKS.register("floating_slab", parameters=FLOATING_SLAB_PARAMETERS, build=floating_slab_track)(
    FloatingSlabTrack
)
TRACKS.register("unit_slab", parameters=UNIT_SLAB_PARAMETERS, build=unit_slab_track)(UnitSlabTrack)
