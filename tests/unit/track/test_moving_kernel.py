"""The moving-load quadrature kernel (railvib.track.moving_kernel) and its refinement.

The numba node loop and the pure-Python run of the same source are checked against the
vectorised NumPy rules (a different arrangement of the same formulas: arrays of nodes x
harmonics, the lattice sum through ``sin z / z`` products); the adaptive integral is
checked against itself at a much tighter tolerance, and its cost by the nodes it uses.
"""

from __future__ import annotations

import numpy as np
import pytest

import railvib.track.moving as moving
import railvib.track.moving_kernel as kernel
from railvib.errors import CaseError
from railvib.pads import SpringDamper
from railvib.track import BallastedTrack, FloatingSlabTrack, PeriodicTrack, Rail
from railvib.track.moving import moving_load_receptance

NORDBORG = BallastedTrack(
    Rail(4.725e6, 60.0),
    SpringDamper(300e6, 18e3),
    0.6,
    sleeper_mass=150.0,
    ballast=SpringDamper(150e6, 48e3),
)
#: the paper's rigid-base track: an undamped rail (the vanishing loss factor)
PAPER = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)
RAIL = (6.62e6, 60.64, 1e-2, 0.6)  # EI, m, eta, d
SHIFT = 2.0 * np.pi * np.arange(-3, 4) / 0.6
R = np.array([0.0, 0.25, -0.4])


def _panels(n: int, seed: int = 0):
    """Random panels over |k| < 60 rad/m at load frequencies 0-2 kHz, both signs of omega."""
    rng = np.random.default_rng(seed)
    mid = rng.uniform(-60.0, 60.0, n)
    half = rng.uniform(1e-4, 2.0, n)
    omega_load = 2.0 * np.pi * rng.uniform(0.0, 2000.0, n)
    omega_load[:3] = 0.0  # a static load: |beta4| < 1 near k = 0 (the series branch)
    k = mid[:, None] + half[:, None] * kernel.NODES
    omega = omega_load[:, None] - k * 30.0
    support = 5e7 + 1j * 5e4 * omega  # a spring-damper pad, K(-omega) = conj K(omega)
    return mid, half, omega_load, support


def _relative(a, b):
    return np.abs(a - b).max() / np.abs(b).max()


def test_python_node_loop_equals_numpy_rules():
    """The source numba compiles, run as plain Python, against the NumPy rules."""
    mid, half, omega_load, support = _panels(6)
    ref_rule, ref_error = kernel.panel_rules(mid, half, omega_load, support, 30.0, RAIL, SHIFT, R)
    rule = np.empty_like(ref_rule)
    error = np.empty_like(ref_error)
    kernel._panels(
        mid, half, omega_load, support, 30.0, *RAIL, 0.0, 0.0, SHIFT,
        *kernel._filon_table(half, R), R, True, kernel.NODES,
        kernel._KRONROD, kernel._GAUSS, kernel.OMEGA_FLOOR, kernel._D1_SERIES,
        kernel._CSC2_SERIES, rule, error,
    )  # fmt: skip
    # the same sums in another order (and sin z from sin z/2 cos z/2): rounding, which the
    # near-singular denominators of the lattice sum amplify to ~1e-13 at worst
    assert _relative(rule, ref_rule) < 1e-11
    np.testing.assert_allclose(error, ref_error, rtol=1e-6, atol=1e-11 * np.abs(ref_rule).max())


def test_compiled_rules_equal_numpy_rules():
    pytest.importorskip("numba")
    if not kernel.compiled_available():
        pytest.skip("RAILVIB_COMPILED=0")
    mid, half, omega_load, support = _panels(100, seed=1)
    ref_rule, _ = kernel.panel_rules(mid, half, omega_load, support, 30.0, RAIL, SHIFT, R)
    rule, _ = kernel.panel_rules(
        mid, half, omega_load, support, 30.0, RAIL, SHIFT, R, compiled=True
    )
    # rounding, reassociated by fast-math (see the test above); measured 3e-15
    assert _relative(rule, ref_rule) < 1e-11


@pytest.mark.parametrize("compiled", [False, True], ids=["numpy", "numba"])
def test_node_at_the_removable_singularity(compiled):
    """A node exactly at omega = 0 and k_n = 0 (f = 3 v / d, k = 6 pi / d): 0/0 unguarded."""
    if compiled and not kernel.compiled_available():
        pytest.skip("numba not installed or RAILVIB_COMPILED=0")
    speed, k_star = 30.0, -float(SHIFT[0])  # SHIFT[0] = 2 pi (-3) / d
    rules = []
    for offset in (0.0, -1e-7):  # the centre node on the point, then beside it (omega > 0)
        mid, half = np.array([k_star + offset]), np.array([1e-3])
        omega_load = np.array([k_star * speed])
        k = mid[:, None] + half[:, None] * kernel.NODES
        support = 5e7 + 1j * 5e4 * (omega_load[:, None] - k * speed)
        rule, _ = kernel.panel_rules(
            mid, half, omega_load, support, speed, RAIL, SHIFT, R, compiled=compiled
        )
        rules.append(rule)
    assert np.all(np.isfinite(rules[0]))
    # the integrand is smooth there but for the sign of the hysteretic loss, which the
    # centre node decides (the others cancel in pairs): moving the panel by 1e-4 of its
    # width to the same side changes the rule by about that (NaN at an unguarded 0/0)
    assert _relative(rules[0], rules[1]) < 1e-3


@pytest.mark.parametrize("track", [NORDBORG, PAPER], ids=["ballasted", "paper"])
def test_receptance_compiled_equals_numpy(track):
    pytest.importorskip("numba")
    if not kernel.compiled_available():
        pytest.skip("RAILVIB_COMPILED=0")
    f = np.array([0.0, 40.0, 300.0, 1170.0, 1500.0])
    args = (track, f, 40.0)
    ref = moving_load_receptance(*args, order=3, r=[0.0, 0.3], compiled=False).amplitudes
    res = moving_load_receptance(*args, order=3, r=[0.0, 0.3], compiled=True).amplitudes
    # each panel's rule agrees to ~1e-13; a panel whose error estimate sits at the
    # tolerance may be bisected on one side only, which moves the result by less than
    # that tolerance (1e-6 of the largest harmonic): measured 7e-11
    assert _relative(res, ref) < 1e-8


@pytest.mark.parametrize(
    ("track", "speed"),
    [
        (PAPER, 80 / 3.6),
        (PeriodicTrack(Rail(6.62e6, 60.64, 0.01), SpringDamper(5e7, 5e4), 0.6), 60.0),
        (NORDBORG, 60.0),
    ],
    ids=["paper", "damped_rigid_base", "ballasted"],
)
def test_default_tolerance_against_a_tight_reference(track, speed):
    # from 0 Hz: next to the free beam's poles (k = omega = 0 for a static load) the
    # images m != 0 are summed directly, so a tight tolerance finds no round-off to chase
    f = np.concatenate([[0.0, 0.5, 5.0, 50.0, 1175.0, 1275.0], np.linspace(100.0, 2000.0, 9)])
    ref = moving_load_receptance(track, f, speed, order=5, r=[0.0, 0.2], tolerance=0.5,
                                 quadrature_tolerance=1e-9).amplitudes  # fmt: skip
    res = moving_load_receptance(track, f, speed, order=5, r=[0.0, 0.2], tolerance=0.5)
    scale = np.abs(ref).max(axis=(1, 2), keepdims=True)
    # default 1e-6 per panel: the harmonics move by about that (measured <= 2e-6)
    assert np.max(np.abs(res.amplitudes - ref) / scale) < 1e-5


def test_static_load_at_tight_tolerances():
    """A_0(f = 0) does not move as the tolerance tightens (the first version's moved 4 %)."""
    a0 = [
        moving_load_receptance(
            PAPER, [0.0], 80 / 3.6, order=2, tolerance=0.5, quadrature_tolerance=qt
        ).mean[0, 0]
        for qt in (1e-6, 1e-9, 1e-11)
    ]
    # each within its tolerance of the tightest (x the ~50 panels a frequency refines;
    # measured 5e-13 and 2e-13)
    assert abs(a0[0] - a0[2]) < 1e-4 * abs(a0[2])
    assert abs(a0[1] - a0[2]) < 1e-7 * abs(a0[2])


def test_static_load_is_the_limit_of_a_slow_harmonic_load():
    """A_n(f = 0) against A_n(10 uHz): A_n is smooth in f (no track resonance near 0 Hz)."""
    res = moving_load_receptance(PAPER, [0.0, 1e-5], 80 / 3.6, order=2, tolerance=0.5)
    a0, a1 = res.amplitudes[0, 0], res.amplitudes[1, 0]
    # the change over 10 uHz is first order in f, led by the pad's damping omega c / K =
    # 6e-8 (measured 5e-8 of the largest harmonic); a closed-form S - G_0 next to the
    # free beam's pole at k = 0 would lose ~1e-2 where a tight tolerance takes the nodes
    assert np.abs(a0 - a1).max() / np.abs(a0).max() < 1e-6


def test_nodes_per_frequency():
    """The cost: wavenumber nodes a frequency needs (the benchmark's case, |n| <= 5)."""
    f = np.geomspace(1.0, 2000.0, 40)
    counted = []
    original = moving.panel_rules

    def counting(mid, *args, **kwargs):
        counted.append(mid.size)
        return original(mid, *args, **kwargs)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(moving, "panel_rules", counting)
        moving_load_receptance(PAPER, f, 80 / 3.6, order=5, tolerance=0.5, compiled=False)
    nodes = 15 * sum(counted) / f.size
    # 56 starting panels (840 nodes) and their refinement: measured 2 100 a frequency,
    # against 13 800 of the first version (16 frequencies sharing pi/(20 d) panels)
    assert nodes < 3000


def test_slab_track_refused_in_one_line():
    slab = FloatingSlabTrack(
        Rail(6.62e6, 60.64),
        SpringDamper(5e7, 5e4),
        0.6,
        foundation=SpringDamper(7e6, 1e4),
        slab_bending_stiffness=1.2e8,
        slab_mass_per_length=1750.0,
    )
    with pytest.raises(CaseError) as err:
        moving_load_receptance(slab, [100.0], 30.0)
    assert err.value.field == "track.model"
    assert "\n" not in str(err.value)
    assert "slab" in str(err.value)


@pytest.mark.parametrize("value", [0.0, 1e-2, float("nan")])
def test_quadrature_tolerance_out_of_range(value):
    with pytest.raises(CaseError) as err:
        moving_load_receptance(NORDBORG, [100.0], 30.0, quadrature_tolerance=value)
    assert err.value.field == "moving.quadrature_tolerance"


def test_compiled_asked_without_the_kernel(monkeypatch):
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    with pytest.raises(CaseError) as err:
        moving_load_receptance(NORDBORG, [100.0], 30.0, compiled=True)
    assert err.value.field == "moving.compiled"
    assert "\n" not in str(err.value)


def test_no_frequency_refused_in_one_line():
    with pytest.raises(CaseError) as err:  # was a ValueError from the order check
        moving_load_receptance(NORDBORG, [], 30.0)
    assert err.value.field == "frequency"
    assert "\n" not in str(err.value)


def test_frequency_order_does_not_matter():
    """Frequencies are batched in ascending order and put back where they were given."""
    f = np.array([1500.0, 3.0, 800.0, 3.0, 0.0])
    given = moving_load_receptance(NORDBORG, f, 40.0, order=2).amplitudes
    ascending = np.argsort(f)
    sorted_ = moving_load_receptance(NORDBORG, f[ascending], 40.0, order=2).amplitudes
    # the same panels for each frequency (one batch): equal to the last bit
    np.testing.assert_array_equal(given[ascending], sorted_)
