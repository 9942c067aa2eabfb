"""The slab tracks: rigid-slab limits, reciprocity, passivity, propagation constants, checks."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import pytest
from numpy.typing import ArrayLike, NDArray

from railvib.case import load_preset_case
from railvib.case.build import build_system, build_track
from railvib.errors import CaseError
from railvib.pads import Hysteretic, SpringDamper
from railvib.pads.base import PadModel
from railvib.sweep.stacked import frf_stack
from railvib.track import FloatingSlabTrack, PeriodicTrack, Rail, UnitSlabTrack
from railvib.track.beam import dynamic_stiffness
from railvib.track.cells import span_stiffness

UIC60 = Rail(6.42e6, 60.0, 0.01)
TIMOSHENKO = Rail(6.42e6, 60.0, 0.01, 2.45e8, 0.25)
PAD = Hysteretic(3e8, 0.25)
D = 0.6
#: a 0.3 m x 3 m concrete slab, per rail (half): EI_s, m_s; a foundation giving ~10 Hz
SLAB = {"slab_bending_stiffness": 1.2e8, "slab_mass_per_length": 1750.0, "slab_loss_factor": 0.05}
FOUNDATION = Hysteretic(7e6, 0.2)


@dataclass(frozen=True)
class _Constant(PadModel):
    """A test-only support of any constant complex stiffness (beyond the pad family's bounds)."""

    k: complex = 0j

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        return np.full(np.shape(f), self.k, dtype=np.complex128)


@dataclass(frozen=True, eq=False)
class _PointwisePad(PadModel):
    """A pad given point by point: it answers only at exactly its own number of points."""

    values: NDArray[np.complex128]

    def __post_init__(self) -> None:
        """Nothing to check: the values come from a validated pad model."""

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        assert np.size(f) == self.values.size, "asked at another number of points"
        return self.values


def _tracks(rail: Rail = UIC60) -> dict[str, object]:
    return {
        "floating": FloatingSlabTrack(rail, PAD, D, foundation=FOUNDATION, **SLAB),
        "bearings": FloatingSlabTrack(
            rail, PAD, D, bearing=SpringDamper(2e7, 2e4), bearing_spacing_fasteners=2, **SLAB
        ),
        "unit": UnitSlabTrack(
            rail, PAD, D, foundation=FOUNDATION, slab_length=4.8, fasteners_per_slab=8, **SLAB
        ),
        "jointed": UnitSlabTrack(
            rail,
            PAD,
            D,
            foundation=FOUNDATION,
            slab_length=4.8,
            fasteners_per_slab=8,
            joint_shear_stiffness=1e8,
            joint_bending_stiffness=1e6,
            **SLAB,
        ),
    }


F_WIDE = np.geomspace(0.1, 5000.0, 120)
X = np.array([0.0, 0.3, 1.1, -2.7, 7.45])


def test_span_stiffness_series_and_closed_form_agree():
    # the two routes overlap around |beta L| = 2: both exact, each losing at most
    # ~16 ulp there (the closed form's 1 - cos cosh, the series' cosh^2): 1e-12
    beta4 = np.array([1.5, 2.5, 16.0, 40.0]) ** 4 * (1 + 0.01j)
    closed = (
        dynamic_stiffness(beta4, 1.0)
        * np.array([1, 0.7, 1, 0.7])[:, None]
        * np.array([1, 0.7, 1, 0.7])
        * (5e6 / 0.7**3)
    )
    mine = span_stiffness(beta4, 0.7, 5e6)
    # the first two use the series route, the last two the closed form
    np.testing.assert_allclose(mine, closed, rtol=1e-11, atol=1e-11 * np.abs(closed).max())


@pytest.mark.parametrize(
    "rail",
    [UIC60, pytest.param(TIMOSHENKO, marks=pytest.mark.slow)],  # expm per span: ~1 s
    ids=["euler", "timoshenko"],
)
@pytest.mark.parametrize("kind", ["continuous", "bearings", "unit"])
def test_rigid_slab_is_the_rigid_base_track(rail, kind):
    # slab EI, mass and support all 1e13 times the real ones: the slab's impedance seen
    # by a pad grows by 1e13 while its wavenumber is unchanged, so the rail sees a rigid
    # base to 1e-13 relative (times the receptance's order-1 sensitivity): below 1e-10
    lam = 1e13
    slab = {
        "slab_bending_stiffness": 1.2e8 * lam,
        "slab_mass_per_length": 1750.0 * lam,
        "slab_loss_factor": 0.05,
    }
    f = np.geomspace(1.0, 2000.0, 60)
    x = np.array([0.0, 0.3, 1.7, -2.1, 0.45])
    base = PeriodicTrack(rail, PAD, D).receptance(f, x, x)
    if kind == "continuous":
        track = FloatingSlabTrack(
            rail, PAD, D, foundation=_Constant(7e6 * lam * (1 + 0.2j)), **slab
        )
        shift = 0.0
    elif kind == "bearings":
        track = FloatingSlabTrack(
            rail,
            PAD,
            D,
            bearing=_Constant(2e7 * lam * (1 + 0.1j)),
            bearing_spacing_fasteners=3,
            **slab,
        )
        shift = 0.0
    else:  # 8 fasteners on a 4.8 m slab lie at (j + 1/2) d: the rigid-base track shifted
        track = UnitSlabTrack(
            rail,
            PAD,
            D,
            foundation=_Constant(7e6 * lam * (1 + 0.2j)),
            slab_length=4.8,
            fasteners_per_slab=8,
            **slab,
        )
        shift = D / 2
    limit = track.receptance(f, x + shift, x + shift)
    err = np.abs(limit - base) / np.abs(base).max(axis=(1, 2), keepdims=True)
    assert err.max() < 1e-10, err.max()


@pytest.mark.parametrize("name", ["floating", "bearings", "unit", "jointed"])
def test_reciprocity_and_passivity_from_0_1_hz_to_5_khz(name):
    track = _tracks()[name]
    with np.errstate(all="raise"):
        r = track.receptance(F_WIDE, X, X)
    assert np.all(np.isfinite(r))
    # reciprocity: the solve is symmetric in exact arithmetic; rounding in the doubling
    # and the condensations, amplified near the spans' clamped-clamped poles: 1e-9
    scale = np.abs(r).max(axis=(1, 2), keepdims=True)
    assert (np.abs(r - np.swapaxes(r, 1, 2)) / scale).max() < 1e-9
    # passivity: power into the track from any set of forces F is omega/2 F^H (-Im R) F
    # >= 0, i.e. -Im of the (symmetric) receptance matrix is positive semidefinite
    sym = 0.5 * (r + np.swapaxes(r, 1, 2))
    eig = np.linalg.eigvalsh(-0.5 * (sym - np.conj(sym)) / 1j)
    assert eig.min(axis=1).min() >= -1e-9 * scale.max()
    assert np.all(eig.min(axis=1) >= -1e-9 * scale[:, 0, 0])


@pytest.mark.parametrize("support", ["foundation", "bearing"])
def test_undamped_track_is_finite_passive_and_reciprocal(support):
    # no loss anywhere: the rail and the slab are solved at the loss factor 1e-9
    # (VANISHING_LOSS_FACTOR), so every wave decays within the doubling's 2^80 cells; a
    # far point (25 spacings away) carries the waves through many cells. The doubling of
    # nearly lossless waves loses digits near band edges: reciprocity measured 2.1e-6
    # (continuous foundation), 6.7e-7 (bearings) on 6000 frequencies; 1e-5
    layer = (
        {"foundation": SpringDamper(7e6)}
        if support == "foundation"
        else {
            "bearing": SpringDamper(6.9e6),
            "bearing_spacing_fasteners": 2,
        }
    )
    track = FloatingSlabTrack(
        Rail(6.62e6, 60.64),
        SpringDamper(4.2e6, 0.0),
        D,
        slab_bending_stiffness=1.6e8,
        slab_mass_per_length=1237.5,
        **layer,
    )
    x = [0.0, 0.3, 2.5, 14.9]
    r = track.receptance(np.geomspace(0.1, 5000.0, 1500), x, x)
    assert np.all(np.isfinite(r))
    point = np.diagonal(r, axis1=1, axis2=2)
    assert np.all(point.imag <= 1e-9 * np.abs(point))
    scale = np.abs(r).max(axis=(1, 2), keepdims=True)
    assert (np.abs(r - np.swapaxes(r, 1, 2)) / scale).max() < 1e-5


@pytest.mark.parametrize("name", ["floating", "bearings", "unit", "jointed"])
def test_propagation_constants_decay_and_are_sorted(name):
    track = _tracks()[name]
    mu = track.propagation_constants(F_WIDE)
    n_waves = 2 if name == "unit" else 4  # boundary DOFs per side: rail (+ slab)
    assert mu.shape == (F_WIDE.size, n_waves)
    assert np.all(np.abs(mu) < 1.0)
    assert np.all(np.diff(np.abs(mu), axis=1) <= 0)
    assert track.period == pytest.approx({"bearings": 2 * D, "floating": D}.get(name, 4.8))


def test_propagation_constants_of_the_rigid_slab_include_the_rails():
    # the rigid slab leaves the rail on pads over a rigid base, whose two right-going
    # waves are those of the rigid-base track (mu from the eigenvalues of its 4x4 transfer
    # matrix, an independent route); the other two are the slab's own waves (the scaling
    # keeps their wavenumbers). LAPACK's eig of the 4x4 transfer matrix and the
    # 1e-13 coupling left by the scaling: 1e-9
    lam = 1e13
    track = FloatingSlabTrack(
        UIC60,
        PAD,
        D,
        slab_bending_stiffness=1.2e8 * lam,
        slab_mass_per_length=1750.0 * lam,
        foundation=_Constant(7e6 * lam * (1 + 0.2j)),
        slab_loss_factor=0.05,
    )
    f = np.array([50.0, 300.0, 1200.0])
    mu = track.propagation_constants(f)
    eig = np.linalg.eigvals(PeriodicTrack(UIC60, PAD, D).transfer_matrix(f))
    for k in range(f.size):
        for rail_mu in eig[k][np.abs(eig[k]) < 1]:
            assert np.abs(mu[k] - rail_mu).min() < 1e-9 * abs(rail_mu), (mu[k], rail_mu)


KW = {"foundation": FOUNDATION, **SLAB}


@pytest.mark.parametrize(
    ("make", "field"),
    [
        (
            lambda: UnitSlabTrack(UIC60, PAD, D, slab_length=0.5, fasteners_per_slab=1, **KW),
            "track.slab_length_m",
        ),
        (
            lambda: UnitSlabTrack(UIC60, PAD, D, slab_length=4.8, fasteners_per_slab=9, **KW),
            "track.fasteners_per_slab",
        ),
        (
            lambda: UnitSlabTrack(UIC60, PAD, D, slab_length=4.8, fasteners_per_slab=0, **KW),
            "track.fasteners_per_slab",
        ),
        (lambda: FloatingSlabTrack(UIC60, PAD, D, **SLAB), "track.foundation"),
        (
            lambda: FloatingSlabTrack(UIC60, PAD, D, bearing=SpringDamper(2e7), **KW),
            "track.foundation",
        ),
        (
            lambda: FloatingSlabTrack(UIC60, PAD, D, bearing_spacing_fasteners=2, **KW),
            "track.bearing_spacing_fasteners",
        ),
        (
            lambda: FloatingSlabTrack(
                UIC60,
                PAD,
                D,
                foundation=FOUNDATION,
                slab_bending_stiffness=-1.0,
                slab_mass_per_length=1750.0,
            ),
            "track.slab_bending_stiffness",
        ),
        (
            lambda: UnitSlabTrack(
                UIC60,
                PAD,
                D,
                slab_length=4.8,
                fasteners_per_slab=8,
                joint_shear_stiffness=-1.0,
                **KW,
            ),
            "track.joint_shear_stiffness",
        ),
    ],
)
def test_inconsistent_slab_data_is_refused_naming_the_field(make, field):
    with pytest.raises(CaseError) as err:
        make()
    assert err.value.field == field


@pytest.mark.parametrize("layer", ["foundation", "bearing"])
def test_non_passive_support_is_refused_on_the_grid(layer):
    active = _Constant(7e6 - 1e5j)  # Im K < 0: it would feed power into the track
    track = FloatingSlabTrack(UIC60, PAD, D, **{layer: active}, **SLAB)
    with pytest.raises(CaseError) as err:
        track.check_frequencies(np.array([1.0, 10.0]))
    assert err.value.field == f"track.{layer}"
    with pytest.raises(CaseError):
        track.receptance([10.0], [0.0], [0.0])


def test_rigid_base_wave_methods_are_refused():
    # the slab couples the fasteners: no per-fastener support exists to hand to them
    with pytest.raises(CaseError) as err:
        _tracks()["floating"].cell_transfer([10.0])
    assert err.value.field == "track.model"


def test_pads_given_point_by_point_over_many_blocks():
    # a pad given point by point (stiffness only at exactly its own number of points) over
    # more points than one of the track's blocks (the support layers are evaluated once,
    # then sliced per block):
    # the same arithmetic as the pad model itself, so equal to rounding (1e-14)
    track = _tracks()["jointed"]
    f = np.geomspace(1.0, 500.0, 1500)  # > 495 points: the 46-DOF cell's block
    stacked = replace(track, pad=_PointwisePad(PAD.stiffness(f)))
    x = [0.3, 2.5]
    np.testing.assert_allclose(stacked.receptance(f, x, x), track.receptance(f, x, x), rtol=1e-14)
    np.testing.assert_allclose(
        stacked.propagation_constants(f), track.propagation_constants(f), rtol=1e-14
    )


def test_gpu_stacked_kernels_refuse_a_slab_track():
    # frf_stack holds the rigid-base rail's waves on a pad stiffness: a slab track cannot
    # be handed to it as one, and must not be solved as a rigid base silently
    case = load_preset_case("floating_slab_metro")
    system = build_system(case)
    with pytest.raises(CaseError) as err:
        frf_stack(system, np.array([1.0, 2.0]), np.full((1, 2), 4.2e6 + 0j), [20.0])
    assert err.value.field == "track.model"


def test_preset_builds_the_floating_slab_for_both_rails():
    case = load_preset_case("floating_slab_metro")
    track = build_track(case)
    assert isinstance(track, FloatingSlabTrack)
    # rail_pair: the beam stands for both rails, so the slab's share of each rail doubles
    assert track.rail.bending_stiffness == 2 * case.track.rail.bending_stiffness
    assert track.slab_bending_stiffness == 2 * case.track.slab_bending_stiffness
    assert track.slab_mass_per_length == 2 * case.track.slab_mass_per_length
