"""The track solver at the frequencies where it used to break (issue 11, part C).

At the pinned-pinned frequency of an undamped rail the bay has a double eigenvalue
``mu = (-1)^n`` and the wave matching is singular: `CoupledSystem.frf` raised
``LinAlgError: Singular matrix`` and the receptance came out as ~1e7 m/N with Im > 0.
The solver now takes an undamped rail in the limit ``eta -> 0+`` (evaluated at
``VANISHING_LOSS_FACTOR``), so every answer is finite and passive.

References are closed forms (pinned-pinned frequencies) and the independent
finite-element track of :mod:`railvib.validation`; none comes from the solver itself.
"""

import warnings

import numpy as np
import pytest

from railvib.coupling import CoupledSystem
from railvib.errors import SolverWarning
from railvib.pads import Hysteretic, SpringDamper
from railvib.track import PeriodicTrack, Rail
from railvib.track.periodic import VANISHING_LOSS_FACTOR
from railvib.validation import FiniteTrack
from railvib.vehicle import pitch_plane_10dof
from tests.conftest import PAPER_VEHICLE_PARAMS

EI, M, D = 6.62e6, 60.64, 0.6
KGA, RHO_I = 0.4 * 7.9e10 * 7.745e-3, 7850.0 * 3.217e-5  # CHN60 (docs/reference-values.md)
LOSSLESS_PADS = [SpringDamper(5e7, 0.0), Hysteretic(5e7, 0.0)]
PADS = [*LOSSLESS_PADS, SpringDamper(5e7, 5e4)]


def pinned_pinned_hz(n, timoshenko=False):
    """n-th pinned-pinned frequency of one bay: closed form (Euler; Timoshenko, Rao Eq. 11.83)."""
    k = n * np.pi / D
    if not timoshenko:
        return k**2 * np.sqrt(EI / M) / (2 * np.pi)
    a = RHO_I * M / KGA
    b = -((EI * M / KGA + RHO_I) * k**2 + M)
    w2 = (-b - np.sqrt(b * b - 4 * a * EI * k**4)) / (2 * a)
    return np.sqrt(w2) / (2 * np.pi)


def rail(timoshenko):
    return Rail(EI, M, shear_stiffness=KGA, rotary_inertia=RHO_I) if timoshenko else Rail(EI, M)


@pytest.mark.parametrize("timoshenko", [False, True], ids=["euler", "timoshenko"])
@pytest.mark.parametrize("pad", PADS, ids=["viscous-lossless", "hysteretic-lossless", "viscous"])
def test_coupled_frf_at_the_exact_pinned_pinned_frequency(pad, timoshenko):
    track = PeriodicTrack(rail(timoshenko), pad, D)
    f_pp = pinned_pinned_hz(1, timoshenko)
    f = np.array([np.nextafter(f_pp, 0.0), f_pp, np.nextafter(f_pp, np.inf)])
    system = CoupledSystem(pitch_plane_10dof(PAPER_VEHICLE_PARAMS), track, 1e9, 0.3, 22.2)
    with pytest.warns(SolverWarning, match="pinned-pinned"):
        frf = system.frf(f)  # raised LinAlgError before (one of 200 random cases)
    for part in (frf.vehicle, frf.rail, frf.contact_force, frf.receptance):
        assert np.all(np.isfinite(part))
    driving = np.diagonal(frf.receptance, axis1=1, axis2=2)
    assert np.all(driving.imag <= 0)  # passive: was ~1e7 m/N with Im > 0
    # the coupled responses have a finite limit at f_pp (the wheel holds the rail under it)
    # and the value there is that limit: they approach it as sqrt|f - f_pp| or faster
    # (odd powers of the Bloch wavenumber, ~ sqrt|f - f_pp|, may vanish), so 1e-4 off f_pp
    # they differ from it at least 10x more than 1e-6 off; 5 leaves room for the next
    # term. A wrong value at f_pp would leave both differences alike (ratio ~1).
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SolverWarning)
        for side in (-1.0, 1.0):
            near = system.frf(f_pp * (1 + side * np.array([1e-4, 1e-6])))
            for at, off in ((frf.vehicle[1], near.vehicle), (frf.rail[1], near.rail)):
                far, close = np.abs(off - at).max(axis=1)
                assert far / close > 5.0


@pytest.mark.parametrize("pad", PADS, ids=["viscous-lossless", "hysteretic-lossless", "viscous"])
@pytest.mark.parametrize("n", [1, 2, 3])
def test_band_edges_of_the_euler_rail_at_the_pinned_pinned_frequencies(pad, n):
    # at f_pp,n = n^2 f_pp the pads do not move: a Bloch wave mu = (-1)^n whatever the
    # pad; the vanishing rail loss (1e-12) moves it by about sqrt(1e-12) = 1e-6 only,
    # while 1e-3 away from f_pp,n the propagation constant is at least 1e-3 from it
    track = PeriodicTrack(Rail(EI, M), pad, D)
    f = pinned_pinned_hz(n) * np.array([1 - 1e-2, 1.0, 1 + 1e-2])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SolverWarning)
        mu = track.waves(f).mu
    distance = np.abs(mu - (-1.0) ** n).min(axis=1)
    assert distance[1] < 5 * np.sqrt(VANISHING_LOSS_FACTOR)
    assert distance[0] > 1e-3
    assert distance[2] > 1e-3


@pytest.fixture(scope="module")
def lossless_finite_track():
    # 600 bays, 8 Hermite elements per bay, graded absorbing pads over the outer 120 bays
    return FiniteTrack(
        Rail(EI, M),
        SpringDamper(5e7, 0.0),
        D,
        -300,
        300,
        elements_per_span=8,
        nodes_at=(0.3, 0.0, -1.9, 2.45),
        absorber_spans=120,
        absorber_damping=2e6,
    )


@pytest.mark.validation
def test_lossless_pad_pass_band_matches_the_finite_track(lossless_finite_track):
    # in the pass bands of a lossless track the right-going wave is the one carrying power
    # to the right; it was given the propagation constant of its partner (O(1) errors:
    # 1.4, 1.1, 1.2 relative at 600, 1000, 4000 Hz). The finite model agrees to ~1e-3
    # (Hermite error at 4 kHz, end reflections left by the absorbing layers), so 5e-3.
    # 1250-1441 Hz is left out: there the waves are slow and reach the ends too strongly.
    f = np.array([250.0, 600.0, 1000.0, 3254.7, 4000.0])
    x = [0.3, 0.0, -1.9, 2.45]
    got = PeriodicTrack(Rail(EI, M), SpringDamper(5e7, 0.0), D).receptance(f, [0.3], x)
    ref = lossless_finite_track.receptance(f, [0.3], x)
    err = np.abs(got - ref)[:, :, 0].max(axis=1) / np.abs(ref[:, 0, 0])
    assert err.max() < 5e-3, err


CORNERS = [  # the extremes of the plausible ranges: soft rail, heavy, wide bays; stiff pads
    (Rail(3e6, 80.0), Hysteretic(1e7, 0.0), 0.75),
    (Rail(3e6, 80.0), SpringDamper(1e8, 5e4), 0.75),
    (Rail(3e6, 80.0), SpringDamper(1e9, 0.0), 0.75),
    (Rail(1.2e7, 40.0, shear_stiffness=1e8, rotary_inertia=0.4), SpringDamper(1e9, 1e5), 0.5),
]


@pytest.mark.parametrize(("rail_", "pad", "d"), CORNERS)
def test_reciprocity_and_passivity_to_5_khz(rail_, pad, d):
    # was 5.8e-6 above 2 kHz for the first corners (the decaying wave carried over a whole
    # bay from cancelling growing parts, eigenvectors from nearly parallel rows of T)
    track = PeriodicTrack(rail_, pad, d)
    f_pp = (np.pi / d) ** 2 * np.sqrt(rail_.bending_stiffness / rail_.mass_per_length) / (2 * np.pi)
    near = [
        n * n * f_pp * (1 + s * np.geomspace(1e-15, 1e-3, 13)) for n in (1, 2, 3) for s in (-1, 1)
    ]
    f = np.sort(np.concatenate([np.geomspace(0.1, 5000.0, 300), *near]))
    f = f[f <= 5000.0]
    x = d * np.array([0.0, 0.13, 0.5, 0.93, 0.99, 1.37, 2.2, 2.9]) + 0.21
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SolverWarning)
        a = track.receptance(f, x, x)
    assert np.all(np.isfinite(a))
    driving = np.diagonal(a, axis1=1, axis2=2)
    assert np.all(driving.imag < 0)  # strictly: the rail always dissipates (eta >= 1e-12)
    scale = np.sqrt(np.abs(driving[:, :, None] * driving[:, None, :]))
    assert (np.abs(a - np.swapaxes(a, 1, 2)) / scale).max() <= 1e-9
