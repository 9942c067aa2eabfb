"""The force transmitted to a slab's continuous foundation per bay (issue 14).

The cell solution's foundation force under each slab bay (``k_f* int w_s dx`` over the span
between consecutive fasteners or slab ends, the exact slab deflection integrated) against
the finite slab track: its own Hermite slab DOFs solved by a sparse solve per frequency,
and the bay's foundation force formed here from its consistent Winkler load vector
(``k_f int N dx`` of each element, ``[h/2, h^2/12, h/2, -h^2/12]``, summed over the bay's
elements). Also the static balance: at a frequency far below every mode the bays together
carry the load.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import xarray as xr
from scipy.sparse.linalg import splu

from railvib.case import build_system, case_from_dict
from railvib.outputs.supports import support_force_variables
from railvib.pads import Hysteretic, SpringDamper
from railvib.track import FloatingSlabTrack, Rail, UnitSlabTrack
from railvib.track.cells import span_stiffness
from railvib.validation import FiniteCoupledSystem
from railvib.validation.finite_slab import FiniteSlabTrack

RAIL = Rail(6.42e6, 60.0, 0.02)
PAD = Hysteretic(3e8, 0.25)
FOUNDATION = Hysteretic(3e7, 0.1)  # N/m^2: 3e7 per metre of slab, the slab at 21 Hz
SLAB = {"slab_bending_stiffness": 1.2e8, "slab_mass_per_length": 1750.0, "slab_loss_factor": 0.05}
UNIT = {"slab_length": 4.8, "fasteners_per_slab": 8}
JOINT = {"joint_shear_stiffness": 1e8, "joint_bending_stiffness": 1e6}

#: (track keywords, load position): floating slab between fasteners; unit slabs (fasteners
#: at 0.3 + 0.6 j) at mid-slab between two fasteners
TYPES = {
    "floating": ({"foundation": FOUNDATION}, 0.2),
    "unit": ({"foundation": FOUNDATION, **UNIT}, 2.1),
    "jointed-unit": ({"foundation": FOUNDATION, **UNIT, **JOINT}, 2.1),
}


def _track(keywords):
    cls = UnitSlabTrack if "slab_length" in keywords else FloatingSlabTrack
    return cls(RAIL, PAD, 0.6, **keywords, **SLAB)


def _finite(keywords, x_load, margin, elements):
    return FiniteSlabTrack(
        RAIL,
        PAD,
        0.6,
        x_min=-margin * 0.6,
        x_max=margin * 0.6,
        elements_per_span=elements,
        nodes_at=(x_load,),
        absorber_length=margin * 0.4,
        absorber_damping=3e5,
        **keywords,
        **SLAB,
    )


def _winkler_bay_forces(finite, u, f, bays):
    """``k_f int w dx`` over each bay ``(a, b)`` (m) from the finite solution `u`."""
    k_f = complex(finite.foundation.stiffness(np.array([f]))[0])
    out = []
    for a, b in bays:
        total = 0j
        for (lo, hi), nodes, first in zip(
            finite.slabs, finite.slab_nodes, finite._slab_offsets, strict=True
        ):
            inside = np.flatnonzero((nodes >= a - 1e-9) & (nodes <= b + 1e-9))
            if lo > b - 1e-9 or hi < a + 1e-9 or inside.size < 2:
                continue
            for i in inside[:-1]:
                h = nodes[i + 1] - nodes[i]
                dofs = 2 * (first + i) + np.arange(4)
                total += np.dot([h / 2, h**2 / 12, h / 2, -(h**2) / 12], u[dofs])
        out.append(k_f * total)
    return np.array(out)


def _finite_forces(finite, f, x_load, bays):
    rhs = np.zeros(finite.n_dof, dtype=complex)
    rhs[finite.rail_dof(x_load)[0]] = 1.0
    return np.array(
        [
            _winkler_bay_forces(finite, splu(finite.dynamic_stiffness(fi)).solve(rhs), fi, bays)
            for fi in f
        ]
    )


def _bays_of(track, centres):
    """``(start, end)`` of the bays centred at `centres`, from the track's geometry."""
    d = track.sleeper_spacing
    if isinstance(track, FloatingSlabTrack):
        return [(x - d / 2, x + d / 2) for x in centres]
    ls, first = track.slab_length, (track.slab_length - 7 * d) / 2  # 8 fasteners
    edges = np.concatenate([[0.0], first + d * np.arange(8), [ls]])
    local = np.array([(a, b) for a, b in zip(edges[:-1], edges[1:], strict=True)])
    out = []
    for x in centres:
        k = np.floor(x / ls)
        j = int(np.argmin(np.abs(local.mean(axis=1) - (x - k * ls))))
        out.append(tuple(k * ls + local[j]))
    return out


def _error(name, f, margin, elements):
    """Per frequency: max over 7 bays of |cell - finite| / the largest bay's, ``(n_f,)``."""
    keywords, x_load = TYPES[name]
    track = _track(keywords)
    support = track.support_response(f, x_load, 3)
    expected = _finite_forces(
        _finite(keywords, x_load, margin, elements), f, x_load, _bays_of(track, support.x)
    )
    got = support.foundation_force
    return (np.abs(got - expected) / np.abs(expected).max(axis=1, keepdims=True)).max(axis=1)


def test_foundation_forces_match_the_finite_slab_track():
    # below 200 Hz 8 Hermite elements per spacing hold the beams to ~1e-7, 600 spacings
    # (240 m absorbing) the slab's waves: measured 2.6e-7, relative to the largest bay's
    assert _error("floating", np.array([2.0, 21.0, 150.0]), margin=600, elements=8).max() < 1e-5


@pytest.mark.slow  # 16 frequencies on 2 x 600 spacings x 24 elements: ~3 s each
@pytest.mark.parametrize("name", TYPES)
def test_foundation_forces_match_the_finite_slab_track_to_2_khz(name):
    # 1 Hz - 2 kHz, 24 elements per spacing: measured at most 1.4e-6 below 1 kHz; above,
    # the Hermite elements' own error ((beta h)^4) dominates: at 2 kHz 3.7e-6 (floating),
    # 2.4e-5 (unit slabs), 16x less with 48 elements (2.3e-7, 1.5e-6), so it is the finite
    # model's. Bounds: 1e-5 below 1 kHz, 5e-5 at 1-2 kHz
    f = np.geomspace(1.0, 2000.0, 16)
    error = _error(name, f, margin=600, elements=24)
    assert error[f < 1000.0].max() < 1e-5
    assert error.max() < 5e-5


@pytest.mark.parametrize("name", TYPES)
def test_the_foundation_carries_the_static_load(name):
    # at 0.05 Hz the inertia of rail and slab (1810 kg/m, omega^2 m = 179 N/m^2) is 6e-6 of
    # k_f = 3e7 N/m^2: the bays' forces sum to 1 + 6e-6; the load spreads over
    # (4 EI_s / k_f)^(1/4) = 2 m of slab, so 150 bays (90 m) on each side hold it all
    keywords, x_load = TYPES[name]
    support = _track(keywords).support_response([0.05], x_load, 150)
    assert abs(support.foundation_force.sum() - 1.0) < 2e-5


def test_the_series_is_the_exact_bay_integral():
    # below |lambda| = 1 the bay integral comes from the shape functions' series; there it
    # equals the equilibrium quotient -(F_a + F_b) / (m omega^2 - k_f) of the exact span
    # stiffness (span_stiffness, its own transfer-matrix route), which loses 24 eps /
    # |lambda| (3e-14 at 0.9) to cancellation: agreement to 1e-12 checks the coefficients
    track = FloatingSlabTrack(RAIL, PAD, 0.6, foundation=SpringDamper(3e7, 0.0), **SLAB)
    ei = 1.2e8 * (1 + 0.05j)
    for lam in (0.9, -0.9, 0.5j):
        slab_load = lam * ei / 0.6**4  # m omega^2 - k_f
        k_f = np.array([1750.0 * (2 * np.pi * 30.0) ** 2 - slab_load])
        weights = track._bay_weights(np.array([30.0]), np.array([0.6]), {"foundation": k_f})
        k = span_stiffness(np.array([lam]), 0.6, ei)
        quotient = -(k[:, 0] + k[:, 2]) / slab_load
        assert np.abs(weights[0, 0] - quotient[0]).max() < 1e-12 * np.abs(quotient).max()


def test_a_lossless_foundation_cut_on_stays_finite_and_smooth():
    # at m_s omega^2 = k_f (lambda = 0, the quotient's 0 / 0) the series holds: the bay's
    # force 1e-7 of the frequency either side differs by far less than 1e-4 of it
    track = FloatingSlabTrack(RAIL, PAD, 0.6, foundation=SpringDamper(3e7, 0.0), **SLAB)
    cut_on = np.sqrt(3e7 / 1750.0) / (2 * np.pi) * np.array([1 - 1e-7, 1.0, 1 + 1e-7])
    force = track.support_response(cut_on, 0.2, 0).foundation_force[:, 0]
    assert np.all(np.isfinite(force))
    assert np.abs(np.diff(force)).max() < 1e-4 * np.abs(force).max()


def _coupled(x0):
    """floating_slab_metro with the bearings replaced by a continuous foundation."""
    case = {"preset": "floating_slab_metro", "contact": {"leading_wheel_position": x0}}
    system = build_system(case_from_dict(case))
    t = system.track
    track = FloatingSlabTrack(
        t.rail,
        t.pad,
        t.sleeper_spacing,
        t.pad_temperature,
        slab_bending_stiffness=t.slab_bending_stiffness,
        slab_mass_per_length=t.slab_mass_per_length,
        slab_loss_factor=t.slab_loss_factor,
        foundation=SpringDamper(1.15e7, 1.25e5),  # the bearings' 6.9e6 N/m per 1.2 m, per m
    )
    return replace(system, track=track)


def test_the_coupled_run_has_the_foundation_forces():
    # the run's psd_support_force for a continuous foundation: the bay holding each wheel
    # (at its centre), layer "foundation", N^2/Hz (the values: the slow test below)
    system = _coupled(0.3)
    f = np.array([0.5, 5.0, 50.0])
    wave = system.frf(f)
    ds = xr.Dataset(
        {
            "frf_force": (("frequency", "wheel"), wave.contact_force),
            "irregularity_psd": (("frequency",), np.ones(f.size)),
        },
        coords={"frequency": f},
    )
    out = support_force_variables(system, ds)
    psd = out["psd_support_force"]
    assert list(psd["layer"].values) == ["foundation"]
    assert psd.attrs["units"] == "N^2/Hz"
    assert np.allclose(psd["support_position"].values % 0.6, 0.3)  # bay centres
    assert np.all(np.isfinite(psd.values))
    assert np.all(psd.values > 0)


@pytest.mark.slow  # two finite coupled systems of 500 spacings x 16 elements: ~4 s each
@pytest.mark.parametrize("x0", [0.0, 0.3], ids=["above-fastener", "mid-span"])
def test_coupled_foundation_force_psds_match_the_finite_model(x0):
    # the run's foundation force per bay per metre of irregularity (cell solution under the
    # wheels' contact forces) against the finite coupled system: its own contact forces on
    # its own slab DOFs (superposed unit loads at the wheels), each bay's force from the
    # consistent Winkler load vector; 240 spacings and 16 elements hold the coupled PSDs to
    # ~1e-5 below 500 Hz: measured 9.5e-6 (above a fastener), 8.5e-6 (mid-span)
    system = _coupled(x0)
    f = np.geomspace(1.0, 500.0, 6)
    wave = system.frf(f)
    ds = xr.Dataset(
        {
            "frf_force": (("frequency", "wheel"), wave.contact_force),
            "irregularity_psd": (("frequency",), np.ones(f.size)),
        },
        coords={"frequency": f},
    )
    got = support_force_variables(system, ds)["psd_support_force"].sel(layer="foundation")
    finite = FiniteCoupledSystem.from_system(
        system, margin_spans=240, elements_per_span=16, absorber_spans=200, absorber_damping=2e5
    )
    contact = finite.frf(f).contact_force  # (f, wheel), compressive positive: down on rail
    bays = _bays_of(system.track, got["support_position"].values)
    force = np.zeros((f.size, len(bays)), dtype=complex)
    for j, x in enumerate(system.wheel_positions):
        force += _finite_forces(finite.track, f, x, bays) * contact[:, j : j + 1]
    per_rail = system.track.pad.factor  # rail_pair: per bay of one rail
    expected = np.abs(force / per_rail) ** 2
    assert np.abs(got.values / expected - 1).max() < 1e-4
