"""The Timoshenko span's closed-form transfer matrix (railvib.track.beam.timoshenko_transfer).

The reference is ``exp(A x)`` evaluated independently in extended precision (x87 long
double, eps = 1.1e-19): the first-order system balanced (``D^-1 A D``, Osborne's
iteration, so that no entry dominates), then a Taylor series with scaling and squaring.
Checked against mpmath's ``expm`` at 50 digits over these rails: it holds 1.3e-14 of the
matrix norm (2e-16 except near the cut-off of 3 m bays, where the squarings lose more).
The closed form is compared with ``rho eps`` formed from the rounded ``rho`` and ``eps``,
as the reference's matrix holds them.
"""

import numpy as np
import pytest

from railvib.pads import SpringDamper
from railvib.track import PeriodicTrack, Rail
from railvib.track.beam import field_transfer, timoshenko_transfer

pytestmark = pytest.mark.skipif(
    np.finfo(np.longdouble).eps > 1e-18, reason="needs an extended-precision long double"
)

#: CHN60 and UIC60 (cut-off 4958 and 4981 Hz), a soft undamped rail (cut-off 3008 Hz, both
#: wave pairs propagate above it), a soft damped one, and one whose two wavenumbers nearly
#: meet at high frequency (``rho_I kGA / (m EI) = 0.73``, where the closed form's divided
#: difference cancels most)
RAILS = {
    "chn60": Rail(6.62e6, 60.64, shear_stiffness=2.45e8, rotary_inertia=0.2525),
    "uic60": Rail(6.42e6, 60.21, shear_stiffness=2.4e8, rotary_inertia=0.245),
    "soft": Rail(3.1e6, 45.0, shear_stiffness=1.5e8, rotary_inertia=0.42),
    "soft_damped": Rail(3.0e6, 80.0, loss_factor=0.02, shear_stiffness=1.2e8, rotary_inertia=0.5),
    "near_degenerate": Rail(3.0e6, 40.0, shear_stiffness=2.0e8, rotary_inertia=0.44),
}

#: the closed form against the reference, relative to the matrix norm: the target of
#: issue 13. Measured against mpmath over this grid: 9.2e-15 (scipy's expm, the previous
#: kernel, 2.1e-14); with the reference's own 1.3e-14 the two differ by up to 1.4e-14
TOLERANCE = 1e-13


def reference(beta4, eps, rho, x):
    """``exp(A x)`` in long double, ``(n_freq, 4, 4)`` (rounded to complex double)."""
    a = np.zeros((beta4.size, 4, 4), dtype=np.clongdouble)
    a[:, 0, 1] = a[:, 1, 2] = a[:, 2, 3] = 1
    a[:, 0, 3] = -np.clongdouble(eps)
    a[:, 2, 1] = -rho.astype(np.clongdouble)
    a[:, 3, 0] = beta4.astype(np.clongdouble)
    # Osborne's balancing: D^-1 A D with D chosen so that each row and column match in size
    d = np.ones((beta4.size, 4))
    size = np.abs(a).astype(float)
    for _ in range(30):
        b = size * d[:, None, :] / d[:, :, None]
        d *= np.sqrt(b.sum(axis=2) / b.sum(axis=1))  # row i over column i
    balance = (d[:, None, :] / d[:, :, None]).astype(np.longdouble)
    m = a * balance * np.longdouble(x)
    norm = float(np.abs(m).sum(axis=2).max())
    squarings = max(0, int(np.ceil(np.log2(max(norm, 1e-300) / 0.125))))
    term = m / np.longdouble(2.0) ** squarings
    total = np.broadcast_to(np.eye(4, dtype=np.clongdouble), m.shape).copy()
    power = total.copy()
    for j in range(1, 24):  # 0.125^24 / 24! ~ 1e-46
        power = power @ term / j
        total = total + power
    for _ in range(squarings):
        total = total @ total
    return (total / balance).astype(np.complex128)


def frequencies(rail):
    """0.1 Hz - 5 kHz, and the cut-off (``b = 0``) and points 1e-12 and 1e-6 from it."""
    f_c = rail.cut_off_frequency_hz
    near = f_c * (1.0 + np.array([-1e-6, -1e-12, 0.0, 1e-12, 1e-6]))
    return np.sort(np.concatenate([np.geomspace(0.1, 5000.0, 40), near[near <= 5000.0]]))


def terms(rail, spacing, f):
    """``(beta4, eps, rho, rho eps)`` of `rail` on bays of `spacing` m, as the solver forms them."""
    return PeriodicTrack(rail, SpringDamper(5e7, 5e4), spacing)._timoshenko_terms(f)


def relative_error(t, ref):
    """Largest entry error of each matrix over its largest reference entry, ``(n_freq,)``."""
    return np.abs(t - ref).max(axis=(1, 2)) / np.abs(ref).max(axis=(1, 2))


@pytest.mark.parametrize("name", sorted(RAILS))
@pytest.mark.parametrize("spacing", [0.05, 0.6, 3.0])
def test_closed_form_matches_the_extended_precision_exponential(name, spacing):
    rail = RAILS[name]
    f = frequencies(rail)
    beta4, eps, rho, rho_eps = terms(rail, spacing, f)
    for x in (1.0, 0.5, -0.5, 0.3, -0.13):  # bays, half spans, local coordinates
        t = timoshenko_transfer(beta4, eps, rho, x)
        error = relative_error(t, reference(beta4, eps, rho, x))
        assert error.max() < TOLERANCE, (x, f[np.argmax(error)], error.max())


@pytest.mark.parametrize("spacing", [0.6, 3.0])
def test_rho_eps_formed_directly_moves_the_span_by_its_rounding_only(spacing):
    """``rho eps`` as the solver forms it (1 at the cut-off) against the product of the
    rounded factors: 2 ulp of ``1 - rho eps``, i.e. of ``b^2``; measured 5.6e-15 of the norm
    at the cut-off of 3 m bays."""
    rail = RAILS["uic60"]
    f = frequencies(rail)
    beta4, eps, rho, rho_eps = terms(rail, spacing, f)
    t = timoshenko_transfer(beta4, eps, rho, 1.0)
    assert relative_error(t, timoshenko_transfer(beta4, eps, rho, 1.0, rho_eps)).max() < 1e-13


def test_series_and_closed_form_meet_at_their_switch():
    """Either side of ``max(|a|^2, |b|^2) x^2 = 4`` (D1's series / closed form) the error holds.

    A jump of the method there would show as an error far above the round-off of either.
    """
    rail = RAILS["chn60"]
    f = np.geomspace(50.0, 2000.0, 4000)
    beta4, eps, rho, rho_eps = terms(rail, 0.6, f)
    a2 = 0.5 * (rho + eps * beta4 + np.sqrt((rho - eps * beta4) ** 2 + 4 * beta4))
    crossing = np.flatnonzero(np.diff(np.abs(a2) > 4.0))
    assert crossing.size == 1  # |a|^2 > |b|^2 here: the switch is crossed once
    near = np.arange(crossing[0] - 2, crossing[0] + 3)
    b4, rh, re = beta4[near], rho[near], rho_eps[near]
    error = relative_error(timoshenko_transfer(b4, eps, rh, 1.0, re), reference(b4, eps, rh, 1.0))
    assert error.max() < 1e-15  # the span at ~0.3 kHz: entries of size 1, nothing cancels


def test_euler_limit_is_the_krylov_series():
    """``eps = rho = 0``: the Euler-Bernoulli transfer matrix, an independent power series."""
    beta4 = np.geomspace(1e-10, 1e5, 200) * (1 - 0.01j)
    zero = np.zeros_like(beta4)
    for x in (1.0, -0.5):
        t = timoshenko_transfer(beta4, 0.0, zero, x, zero)
        # both to ~1e-16 of the norm; the series sums terms of one sign
        assert relative_error(t, field_transfer(beta4, x)).max() < 1e-14


def test_group_property_and_unit_determinant():
    """``exp(A/2)^2 = exp(A)``, ``exp(A) exp(-A) = I`` and ``det exp(A) = 1`` (``tr A = 0``)."""
    rail = RAILS["soft_damped"]
    f = frequencies(rail)
    beta4, eps, rho, rho_eps = terms(rail, 0.6, f)
    half = timoshenko_transfer(beta4, eps, rho, 0.5, rho_eps)
    full = timoshenko_transfer(beta4, eps, rho, 1.0, rho_eps)
    back = timoshenko_transfer(beta4, eps, rho, -1.0, rho_eps)
    norm = np.abs(full).max(axis=(1, 2))
    # products of two matrices: ~4 ulp of |T|^2, and |T| < 40 here
    assert (np.abs(half @ half - full).max(axis=(1, 2)) / norm).max() < 1e-13
    assert np.abs(full @ back - np.eye(4)).max() < 1e-12
    assert np.abs(np.linalg.det(full) - 1.0).max() < 1e-11


def test_largest_bay_wavenumber_stays_finite_and_accurate():
    """At ``|beta| d = 40`` (``MAX_BAY_WAVENUMBER``: ``cosh 40 ~ 1e17``) no overflow, and exact."""
    beta4 = np.array([40.0**4 * (1 - 1e-12j), 40.0**4 * (1 - 0.05j)])
    # (eps, rho / beta4): CHN60 on 3 m bays, and a rail ten times as shear-flexible with
    # 100 times its rotary inertia
    for eps, rotary in ((0.003, 5e-4), (0.07, 0.05)):
        rho = rotary * beta4
        t = timoshenko_transfer(beta4, eps, rho, 1.0)
        assert np.all(np.isfinite(t))
        # entries up to 1e20; the reference holds 2e-14 here (against mpmath), the closed
        # form 1.4e-14
        assert relative_error(t, reference(beta4, eps, rho, 1.0)).max() < 1e-13
