"""Assemble mass, stiffness and damping matrices of a vehicle from its parts."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.stack import PIVOT_THRESHOLD, put, stacked, to_numpy
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

__all__ = ["EliminationProgram", "Vehicle", "WheelCondensation"]

GRAVITY = 9.81  # m/s^2


@dataclass(frozen=True, eq=False)
class WheelCondensation:
    """A vehicle's dynamic stiffness condensed onto its wheel DOFs, in the stacked layout.

    Attributes
    ----------
    stiffness_entries : list of list of array
        ``S[a][b]``, each ``(n_freq,)``, N/m: wheel forces per wheel displacement with
        the bodies free (``n_wheel x n_wheel`` entries, symmetric).
    recovery_entries : list of list of array
        ``R[i][b]``, each ``(n_freq,)``: DOF ``i``'s displacement per displacement of
        wheel ``b`` (``n_dof x n_wheel`` entries).
    recovery_wheels : tuple of tuple of int, optional
        For each DOF, the wheels whose ``R[i][b]`` may be non-zero (a train's car on its
        own wheels); None: every wheel.
    """

    stiffness_entries: list[list[Any]]
    recovery_entries: list[list[Any]]
    recovery_wheels: tuple[tuple[int, ...], ...] | None = None

    @property
    def active_wheels(self) -> tuple[tuple[int, ...], ...]:
        """For each DOF, the wheels its recovery depends on (all, unless `recovery_wheels`)."""
        if self.recovery_wheels is not None:
            return self.recovery_wheels
        return (tuple(range(len(self.stiffness_entries))),) * len(self.recovery_entries)

    @property
    def stiffness(self) -> NDArray[np.complex128]:
        """``(n_freq, n_wheel, n_wheel)``, N/m."""
        return np.asarray(stacked(self.stiffness_entries))

    @property
    def recovery(self) -> NDArray[np.complex128]:
        """``(n_freq, n_dof, n_wheel)``: all DOF displacements per wheel displacement."""
        return np.asarray(stacked(self.recovery_entries))


@dataclass(frozen=True)
class Vehicle:
    """A pitch-plane multibody vehicle: bodies, suspensions and wheels, with named DOFs.

    Displacements are positive downward; a pitch rotation ``theta`` moves a point
    at longitudinal position ``x`` (relative to the body's centre) by ``x theta``.

    Parameters
    ----------
    bodies : tuple of RigidBody
        All bodies; wheelsets are bodies without a pitch DOF.
    suspensions : tuple of Suspension
        Spring-damper connections between body points.
    wheels : tuple of Wheel
        Contacts, listed from the leading wheel backwards, one per wheelset body
        (a body without a pitch DOF).
    cars : tuple of (Vehicle, int, int), optional
        Set by :func:`railvib.vehicle.make_train` for a train without couplers: each car,
        the index of its first DOF and of its first wheel. The cars do not interact but
        through the track, so each distinct car is condensed once.
    """

    bodies: tuple[RigidBody, ...]
    suspensions: tuple[Suspension, ...]
    wheels: tuple[Wheel, ...]
    cars: tuple[tuple[Vehicle, int, int], ...] = field(default=(), compare=False, repr=False)

    def __post_init__(self) -> None:
        names = [b.name for b in self.bodies]
        if len(set(names)) != len(names):
            raise CaseError("vehicle.bodies", names, "body names must be unique")
        for s in self.suspensions:
            for a in (s.upper, s.lower):
                if a.body not in names:
                    raise CaseError(f"vehicle.{s.name}", a.body, f"a body among {names}")
        xs = [w.x for w in self.wheels]
        if not self.wheels or any(np.diff(xs) >= 0):
            raise CaseError("vehicle.wheels", xs, "at least one wheel, listed front to back")
        for w in self.wheels:
            if w.body not in names:
                raise CaseError("vehicle.wheels", w.body, f"a body among {names}")
            if self._body(w.body).pitch_inertia is not None:
                raise CaseError("vehicle.wheels", w.body, "a body without a pitch DOF (a wheelset)")
        carriers = [w.body for w in self.wheels]
        if len(set(carriers)) != len(carriers):
            raise CaseError("vehicle.wheels", carriers, "one wheel per wheelset body")

    @cached_property
    def dofs(self) -> tuple[str, ...]:
        """DOF labels in matrix order."""
        return tuple(dof for body in self.bodies for dof in body.dofs)

    def _body(self, name: str) -> RigidBody:
        return next(b for b in self.bodies if b.name == name)

    def point_vector(self, point: Attachment) -> NDArray[np.float64]:
        """Row vector mapping the DOFs to the vertical displacement of `point`."""
        body = self._body(point.body)
        vec = np.zeros(len(self.dofs))
        vec[self.dofs.index(f"{body.name}.bounce")] = 1.0
        if body.pitch_inertia is not None:
            vec[self.dofs.index(f"{body.name}.pitch")] = point.x - body.x
        return vec

    @cached_property
    def mass_matrix(self) -> NDArray[np.float64]:
        """Mass matrix in kg and kg m^2, ``(n_dof, n_dof)``."""
        diag = []
        for b in self.bodies:
            diag.append(b.mass)
            if b.pitch_inertia is not None:
                diag.append(b.pitch_inertia)
        return np.diag(diag)

    def _spring_matrix(self, attr: str) -> NDArray[np.float64]:
        n = len(self.dofs)
        out = np.zeros((n, n))
        for s in self.suspensions:
            b = self.point_vector(s.upper) - self.point_vector(s.lower)
            out += getattr(s, attr) * np.outer(b, b)
        return out

    @cached_property
    def stiffness_matrix(self) -> NDArray[np.float64]:
        """Stiffness matrix of the springs (N/m, N, N m), ``(n_dof, n_dof)``.

        Without the frequency-dependent elements (:attr:`elements`).
        """
        return self._spring_matrix("stiffness")

    @cached_property
    def elements(self) -> tuple[tuple[Any, NDArray[np.float64]], ...]:
        """The frequency-dependent elements: ``(element, b)`` with ``b`` the DOF row vector.

        Element ``e`` adds ``K*_e(f) b b^T`` to the dynamic stiffness.
        """
        return tuple(
            (s.element, self.point_vector(s.upper) - self.point_vector(s.lower))
            for s in self.suspensions
            if s.element is not None
        )

    @cached_property
    def static_stiffness_matrix(self) -> NDArray[np.float64]:
        """Stiffness at ``f = 0`` (N/m, N, N m): the springs and the elements' ``Re K*(0)``."""
        out = self.stiffness_matrix.copy()
        for element, b in self.elements:
            out += float(np.real(element.stiffness(np.zeros(1))[0])) * np.outer(b, b)
        return out

    @cached_property
    def wheel_names(self) -> tuple[str, ...]:
        """Name of each wheel, front to back (``wheel<j>`` where the wheel has none)."""
        return tuple(w.name or f"wheel{j}" for j, w in enumerate(self.wheels, start=1))

    def scaled(self, factor: float) -> Vehicle:
        """The vehicle with every mass, inertia, stiffness, damping and element times `factor`.

        Half a car on one rail is ``scaled(0.5)`` of the whole car (same frequencies).

        Parameters
        ----------
        factor : float
            Scale factor (> 0), dimensionless.

        Returns
        -------
        Vehicle
        """
        bodies = tuple(
            replace(
                b,
                mass=factor * b.mass,
                pitch_inertia=None if b.pitch_inertia is None else factor * b.pitch_inertia,
            )
            for b in self.bodies
        )
        suspensions = tuple(
            replace(
                s,
                stiffness=factor * s.stiffness,
                damping=factor * s.damping,
                element=None if s.element is None else _ScaledElement(s.element, factor),
            )
            for s in self.suspensions
        )
        scaled_cars: dict[int, Vehicle] = {}
        for car, _, _ in self.cars:
            scaled_cars.setdefault(id(car), car.scaled(factor))
        cars = tuple((scaled_cars[id(car)], d0, w0) for car, d0, w0 in self.cars)
        return Vehicle(bodies, suspensions, self.wheels, cars)

    @cached_property
    def damping_matrix(self) -> NDArray[np.float64]:
        """Viscous damping matrix (N s/m, ...), ``(n_dof, n_dof)``."""
        return self._spring_matrix("damping")

    @cached_property
    def wheel_matrix(self) -> NDArray[np.float64]:
        """``B``, ``(n_dof, n_wheel)``: column j maps a force at wheel j onto the DOFs."""
        return np.stack([self.point_vector(Attachment(w.body, w.x)) for w in self.wheels], axis=1)

    @cached_property
    def wheel_offsets(self) -> NDArray[np.float64]:
        """Distance of each wheel behind the leading wheel, m (first is 0)."""
        xs = np.array([w.x for w in self.wheels])
        return xs[0] - xs

    def dynamic_stiffness(self, f: ArrayLike) -> NDArray[np.complex128]:
        """``K + i omega C - omega^2 M`` stacked over frequency, ``(n_freq, n_dof, n_dof)``.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, shape ``(n_freq,)`` (a scalar counts as one).

        Returns
        -------
        numpy.ndarray
            Complex dynamic stiffness in SI units (N/m, N/rad, N m/m, N m/rad by DOF pair),
            shape ``(n_freq, n_dof, n_dof)``.
        """
        out = _dynamic_stiffness(f, self.mass_matrix, self.damping_matrix, self.stiffness_matrix)
        for element, b in self.elements:
            k = np.asarray(element.stiffness(np.atleast_1d(np.asarray(f, dtype=float))))
            out += k[:, None, None] * np.outer(b, b)
        return out

    @cached_property
    def wheel_dofs(self) -> NDArray[np.int64]:
        """Index of the bounce DOF of each wheel's wheelset (``B`` is a selection)."""
        return np.array([self.dofs.index(f"{w.body}.bounce") for w in self.wheels])

    def condensed_to_wheels(self, f: ArrayLike, xp: Any = np) -> WheelCondensation:
        """Dynamic stiffness condensed onto the wheel DOFs, with the body recovery.

        With the DOFs split into bodies ``b`` and wheels ``w``,
        ``S = D_ww - D_wb D_bb^-1 D_bw`` and ``u = R u_w`` with ``R_b = -D_bb^-1 D_bw``.
        ``D_bb`` (the vehicle with its wheels held) is regular at every ``f > 0`` and at
        ``f = 0``, so no digits are lost at low frequency.

        The body DOFs are eliminated one by one in the stacked layout (each matrix
        entry one array over the frequencies; only the entries that are not zero for
        the vehicle's tree of bodies are formed), the fewest-coupled first (the
        bogies, then the car body), so each step is a few elementwise operations.
        Frequencies where a pivot fails the test of :data:`railvib.stack.PIVOT_THRESHOLD`
        are solved again densely, with LAPACK's pivoting.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, ``(n_freq,)`` (any stack of frequencies).
        xp : module
            Array namespace of the computation (:func:`railvib.stack.namespace`).

        Returns
        -------
        WheelCondensation
        """
        if self.cars:
            return self._condensed_by_car(f, xp)
        omega = 2.0 * np.pi * xp.asarray(np.atleast_1d(np.asarray(f, dtype=float)))
        omega2 = omega**2
        m, c, k = self._matrices
        d = {
            (i, j): _entry(k[i, j], m[i, j], c[i, j], omega, omega2, xp)
            for i, j in self._elimination.pattern
        }
        f_np = np.atleast_1d(np.asarray(f, dtype=float))
        for element, vec in self.elements:
            k_e = xp.asarray(np.asarray(element.stiffness(f_np), dtype=complex))
            for i, j in self._elimination.pattern:
                if vec[i] * vec[j] != 0.0:
                    d[(i, j)] = d[(i, j)] + k_e * (vec[i] * vec[j])
        bad = None
        factors = []
        for p, nb in self._elimination.steps:
            pivot = d[(p, p)]
            size = xp.abs(pivot)
            for j in nb:
                weak = size < PIVOT_THRESHOLD * xp.abs(d[_key(p, j)])
                bad = weak if bad is None else (bad | weak)
            with np.errstate(divide="ignore", invalid="ignore"):  # flagged above
                inv = 1.0 / pivot
            ell = {j: d[_key(p, j)] * inv for j in nb}
            for ia, a in enumerate(nb):
                for b in nb[ia:]:
                    update = ell[a] * d[_key(p, b)]
                    key = _key(a, b)
                    d[key] = d[key] - update if key in d else -update
            factors.append(ell)
        wheels = [int(w) for w in self.wheel_dofs]
        n_w = len(wheels)
        zero = xp.zeros_like(omega, dtype=complex)
        # back-substitution on the tree: a wheel's row is a unit vector, a body's row holds
        # only the wheels below it, so structural zeros (None) and ones are never multiplied
        rows: dict[int, list[Any]] = {
            w: [_UNIT if b == iw else None for b in range(n_w)] for iw, w in enumerate(wheels)
        }
        for (p, nb), ell in zip(reversed(self._elimination.steps), reversed(factors), strict=True):
            rows[p] = [_back([(ell[j], rows[j][b]) for j in nb]) for b in range(n_w)]
        stiffness = [[d.get(_key(a, b), zero) for b in wheels] for a in wheels]
        recovery = [
            [zero if r is None else zero + 1.0 if r is _UNIT else r for r in rows[i]]
            for i in range(len(self.dofs))
        ]
        if bad is not None and bool(xp.any(bad)):
            stiffness, recovery = self._dense_at(f, bad, stiffness, recovery, xp)
        return WheelCondensation(stiffness, recovery)

    def _condensed_by_car(self, f: ArrayLike, xp: Any) -> WheelCondensation:
        """The condensation of a train without couplers: block diagonal, one block per car."""
        done: dict[int, WheelCondensation] = {}
        n_w, n_dof = len(self.wheels), len(self.dofs)
        zero = xp.zeros(np.atleast_1d(np.asarray(f)).shape, dtype=complex)
        stiffness = [[zero] * n_w for _ in range(n_w)]
        recovery = [[zero] * n_w for _ in range(n_dof)]
        groups: list[tuple[int, ...]] = []
        for car, d0, w0 in self.cars:
            if id(car) not in done:
                done[id(car)] = car.condensed_to_wheels(f, xp)
            cond = done[id(car)]
            nw = len(car.wheels)
            for a in range(nw):
                stiffness[w0 + a][w0 : w0 + nw] = cond.stiffness_entries[a]
            for i in range(len(car.dofs)):
                recovery[d0 + i][w0 : w0 + nw] = cond.recovery_entries[i]
            groups += [tuple(range(w0, w0 + nw))] * len(car.dofs)
        return WheelCondensation(stiffness, recovery, tuple(groups))

    def _dense_at(
        self, f: ArrayLike, bad: Any, stiffness: list[list[Any]], recovery: list[list[Any]], xp: Any
    ) -> tuple[list[list[Any]], list[list[Any]]]:
        """The condensation at the frequencies `bad` solved densely (LAPACK, pivoting)."""
        f_bad = np.atleast_1d(np.asarray(f, dtype=float))[to_numpy(bad)]
        order = self._body_then_wheel_order
        n_dof, n_w = int(order.size), int(self.wheel_dofs.size)
        n_b = n_dof - n_w
        full = self.dynamic_stiffness(f_bad)[:, order][:, :, order]

        def block(rows: slice, cols: slice) -> NDArray[np.complex128]:
            return full[:, rows, cols]

        bodies, wheels = slice(0, n_b), slice(n_b, n_dof)
        x = np.linalg.solve(block(bodies, bodies), block(bodies, wheels))  # D_bb^-1 D_bw
        s_bad = block(wheels, wheels) - block(wheels, bodies) @ x
        r_bad = np.empty((f_bad.size, n_dof, n_w), dtype=np.complex128)
        r_bad[:, order[:n_b], :] = -x
        r_bad[:, order[n_b:], :] = np.eye(n_w)
        stiffness = [
            [put(stiffness[a][b], bad, s_bad[:, a, b], xp) for b in range(n_w)] for a in range(n_w)
        ]
        recovery = [
            [put(recovery[i][b], bad, r_bad[:, i, b], xp) for b in range(n_w)] for i in range(n_dof)
        ]
        return stiffness, recovery

    @cached_property
    def _body_then_wheel_order(self) -> NDArray[np.int64]:
        """DOF indices reordered: sprung-body DOFs first, then the wheel DOFs in wheel order."""
        w = self.wheel_dofs
        return np.concatenate([np.setdiff1d(np.arange(len(self.dofs)), w), w])

    @cached_property
    def _elimination(self) -> _Elimination:
        """The order in which the body DOFs are eliminated, and the entries it touches."""
        m, c, k = self._matrices
        nonzero = (m != 0) | (c != 0) | (k != 0)
        for _, b in self.elements:
            nonzero |= np.outer(b, b) != 0
        n = len(self.dofs)
        pattern = {(i, j) for i in range(n) for j in range(i, n) if nonzero[i, j]}
        linked = {i: {j for j in range(n) if j != i and nonzero[i, j]} for i in range(n)}
        bodies = set(range(n)) - {int(w) for w in self.wheel_dofs}
        steps = []
        while bodies:
            # minimum degree: the DOF coupled to the fewest others creates the least fill
            p = min(bodies, key=lambda i: (len(linked[i]), i))
            nb = sorted(linked[p])
            for a in nb:
                linked[a] |= set(nb) - {a}
                linked[a].discard(p)
            steps.append((p, tuple(nb)))
            bodies.remove(p)
            del linked[p]
        return _Elimination(tuple(sorted(pattern)), tuple(steps))

    @cached_property
    def elimination_program(self) -> EliminationProgram:
        """The condensation of :meth:`condensed_to_wheels` as integer tables, for a point kernel.

        The same minimum-degree elimination of the body DOFs, each entry it forms a slot
        of one point's working vector, so a compiled kernel
        (:func:`railvib.coupled_kernel.fused_points`) runs it point by point for any tree
        of bodies. Built once per vehicle.
        """
        m, c, k = self._matrices
        elim = self._elimination
        slots: dict[tuple[int, int], int] = {key: i for i, key in enumerate(elim.pattern)}
        for _, nb in elim.steps:  # the fill-in, in the order the elimination makes it
            for ia, a in enumerate(nb):
                for b in nb[ia:]:
                    slots.setdefault(_key(a, b), len(slots))
        n_slot = len(slots)
        base = np.zeros((3, n_slot))
        for (i, j), s in slots.items():
            if (i, j) in elim.pattern:
                base[:, s] = k[i, j], m[i, j], c[i, j]
        terms = [
            (slots[key], e, vec[key[0]] * vec[key[1]])
            for e, (_, vec) in enumerate(self.elements)
            for key in elim.pattern
            if vec[key[0]] * vec[key[1]] != 0.0
        ]
        nb_ptr, upd_ptr = [0], [0]
        nb_dof: list[int] = []
        nb_slot: list[int] = []
        upd: list[tuple[int, int, int]] = []
        for p, nb in elim.steps:
            first = len(nb_dof)
            nb_dof += list(nb)
            nb_slot += [slots[_key(p, j)] for j in nb]
            nb_ptr.append(len(nb_dof))
            for ia, a in enumerate(nb):
                upd += [(slots[_key(a, b)], first + ia, slots[_key(p, b)]) for b in nb[ia:]]
            upd_ptr.append(len(upd))
        wheels = [int(w) for w in self.wheel_dofs]
        wheel_slot = np.array(
            [[slots.get(_key(a, b), -1) for b in wheels] for a in wheels], dtype=np.int64
        )
        return EliminationProgram(
            n_dof=len(self.dofs),
            base=base,
            term_slot=np.array([t[0] for t in terms], dtype=np.int64),
            term_element=np.array([t[1] for t in terms], dtype=np.int64),
            term_factor=np.array([t[2] for t in terms], dtype=float),
            pivot_slot=np.array([slots[(p, p)] for p, _ in elim.steps], dtype=np.int64),
            pivot_dof=np.array([p for p, _ in elim.steps], dtype=np.int64),
            nb_ptr=np.array(nb_ptr, dtype=np.int64),
            nb_dof=np.array(nb_dof, dtype=np.int64),
            nb_slot=np.array(nb_slot, dtype=np.int64),
            update_ptr=np.array(upd_ptr, dtype=np.int64),
            update=np.array(upd, dtype=np.int64).reshape(-1, 3),
            wheel_dof=np.array(wheels, dtype=np.int64),
            wheel_slot=wheel_slot,
            column_ptr=np.concatenate([[0], np.cumsum((wheel_slot >= 0).sum(axis=0))]),
            column_wheel=np.nonzero((wheel_slot >= 0).T)[1].astype(np.int64),
            pivot_threshold=PIVOT_THRESHOLD,
        )

    def element_stiffness(self, f: ArrayLike) -> NDArray[np.complex128]:
        """``K*_e(f)`` of each frequency-dependent element (:attr:`elements`), N/m.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, ``(n_freq,)``.

        Returns
        -------
        numpy.ndarray
            ``(n_freq, n_element)``, complex (``n_element`` may be 0).
        """
        f_np = np.atleast_1d(np.asarray(f, dtype=float))
        out = np.empty((f_np.size, len(self.elements)), dtype=np.complex128)
        for e, (element, _) in enumerate(self.elements):
            out[:, e] = np.asarray(element.stiffness(f_np), dtype=complex)
        return out

    @property
    def _matrices(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        return self.mass_matrix, self.damping_matrix, self.stiffness_matrix

    def static_wheel_loads(self, gravity: float = GRAVITY) -> NDArray[np.float64]:
        """Static load carried at each wheel contact (N), wheels held rigidly.

        Solves the static equilibrium of the sprung bodies with the wheel points
        fixed; the contact reactions then balance the weight of everything.

        Parameters
        ----------
        gravity : float
            Gravitational acceleration in m/s^2 (default 9.81).

        Returns
        -------
        numpy.ndarray
            Contact load at each wheel in N, wheels front to back, shape ``(n_wheel,)``.
        """
        b = self.wheel_matrix
        weight = np.zeros(len(self.dofs))
        for body in self.bodies:
            weight[self.dofs.index(f"{body.name}.bounce")] = body.mass * gravity
        # Solve min over u of the energy with B^T u = 0 (wheels fixed): KKT system
        k = self.static_stiffness_matrix
        n, m = b.shape
        kkt = np.block([[k, b], [b.T, np.zeros((m, m))]])
        sol = np.linalg.solve(kkt, np.concatenate([weight, np.zeros(m)]))
        return sol[n:]


@dataclass(frozen=True)
class _ScaledElement:
    """A frequency-dependent element times a constant factor (half a car: 0.5)."""

    element: Any
    factor: float

    def stiffness(self, f: ArrayLike) -> NDArray[np.complex128]:
        """``factor K*(f)`` in N/m."""
        out: NDArray[np.complex128] = self.factor * np.asarray(
            self.element.stiffness(f), dtype=np.complex128
        )
        return out


#: marks a structural one of the recovery (a wheel's own displacement)
_UNIT: Any = object()


def _entry(k: float, m: float, c: float, omega: Any, omega2: Any, xp: Any) -> Any:
    """``k - omega^2 m + i omega c`` over the frequencies, the zero terms not formed."""
    real = k - omega2 * m if m != 0.0 else None
    if c == 0.0:
        return (xp.zeros_like(omega) + k if real is None else real) + 0j
    imag = (1j * c) * omega
    return imag + k if real is None else real + imag


def _back(terms: list[tuple[Any, Any]]) -> Any:
    """``-sum ell r`` over the terms whose ``r`` is not a structural zero (None); None if all are.

    ``r`` is an entry array or :data:`_UNIT` (then ``ell`` alone is the product).
    """
    products = [ell if r is _UNIT else ell * r for ell, r in terms if r is not None]
    if not products:
        return None
    out = products[0]
    for p in products[1:]:
        out = out + p
    return -out


def _key(i: int, j: int) -> tuple[int, int]:
    """Key of the symmetric entry ``(i, j)``: the upper triangle."""
    return (i, j) if i <= j else (j, i)


@dataclass(frozen=True)
class _Elimination:
    """The symbolic elimination of a vehicle's body DOFs.

    ``pattern``: the entries ``(i <= j)`` of the dynamic stiffness that are not zero;
    ``steps``: the pivots ``(dof, the dofs still coupled to it)`` in elimination order.
    """

    pattern: tuple[tuple[int, int], ...]
    steps: tuple[tuple[int, tuple[int, ...]], ...]


@dataclass(frozen=True, eq=False)
class EliminationProgram:
    """A vehicle's condensation onto its wheels as tables a point kernel executes.

    One point's working vector holds a slot per entry ``(i <= j)`` the elimination forms
    (the dynamic stiffness's non-zero entries, then the fill-in). All integer tables are
    ``int64``; ``*_ptr`` tables delimit each elimination step's rows of the next table.

    Attributes
    ----------
    n_dof : int
        The vehicle's DOFs.
    base : numpy.ndarray
        ``(3, n_slot)``: each slot's ``K`` (N/m, ...), ``M`` (kg, ...) and ``C``
        (N s/m, ...); zero for a fill-in slot.
    term_slot, term_element, term_factor : numpy.ndarray
        ``(n_term,)``: slot ``term_slot`` gains ``K*_e(f) * term_factor`` of element
        ``term_element`` (:meth:`Vehicle.element_stiffness`).
    pivot_slot, pivot_dof : numpy.ndarray
        ``(n_step,)``: each step's pivot entry and the DOF it eliminates.
    nb_ptr, nb_dof, nb_slot : numpy.ndarray
        The DOFs still coupled to each step's pivot, and the slot of their entry with it.
    update_ptr, update : numpy.ndarray
        ``update[u] = (target, neighbour, source)``: slot ``target`` loses
        ``ell[neighbour] * slot[source]`` (``ell``: the step's multipliers, indexed as
        `nb_dof`).
    wheel_dof : numpy.ndarray
        ``(n_wheel,)``: each wheel's DOF.
    wheel_slot : numpy.ndarray
        ``(n_wheel, n_wheel)``: the slot of the condensed entry ``S[a, b]``, -1 where it is
        a structural zero (a train's cars).
    column_ptr, column_wheel : numpy.ndarray
        The wheels ``a`` of each column ``b`` whose ``S[a, b]`` is not a structural zero
        (``S`` is symmetric: each row's too).
    pivot_threshold : float
        The pivot test of the stacked elimination (:data:`railvib.stack.PIVOT_THRESHOLD`):
        a point whose pivot is below this fraction of an entry of its row is flagged.
    """

    n_dof: int
    base: NDArray[np.float64]
    term_slot: NDArray[np.int64]
    term_element: NDArray[np.int64]
    term_factor: NDArray[np.float64]
    pivot_slot: NDArray[np.int64]
    pivot_dof: NDArray[np.int64]
    nb_ptr: NDArray[np.int64]
    nb_dof: NDArray[np.int64]
    nb_slot: NDArray[np.int64]
    update_ptr: NDArray[np.int64]
    update: NDArray[np.int64]
    wheel_dof: NDArray[np.int64]
    wheel_slot: NDArray[np.int64]
    column_ptr: NDArray[np.int64]
    column_wheel: NDArray[np.int64]
    pivot_threshold: float


def _dynamic_stiffness(
    f: ArrayLike, m: NDArray[np.float64], c: NDArray[np.float64], k: NDArray[np.float64]
) -> NDArray[np.complex128]:
    """``K + i omega C - omega^2 M`` for (blocks of) real matrices, ``(n_freq, rows, cols)``."""
    omega = 2.0 * np.pi * np.atleast_1d(np.asarray(f, dtype=float))[:, None, None]
    out = np.empty((int(omega.shape[0]),) + k.shape, dtype=np.complex128)
    out.real = k - omega**2 * m
    out.imag = omega * c
    return out
