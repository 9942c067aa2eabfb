"""The slab tracks' cell solver against the finite slab track and against closed forms.

The finite model (:class:`railvib.validation.finite_slab.FiniteSlabTrack`) assembles the
rail and the slab (or each unit slab) as beams of Hermite elements with their own DOFs,
the pads between them and the foundation, bearings and joints as springs; it never forms
a cell, a span's exact stiffness or a semi-infinite chain. The closed forms are the
infinite two-layer beam on a Winkler foundation (a wavenumber integral done by residues)
and the infinite beam on an elastic foundation (Hetenyi).
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.pads import Hysteretic, SpringDamper
from railvib.track import FloatingSlabTrack, Rail, UnitSlabTrack
from railvib.validation.finite_slab import FiniteSlabTrack

RAIL = Rail(6.42e6, 60.0, 0.02)  # UIC60 with a small rail loss, so waves die out in the model
PAD, FOUNDATION = Hysteretic(3e8, 0.25), Hysteretic(7e6, 0.2)
SLAB = {"slab_bending_stiffness": 1.2e8, "slab_mass_per_length": 1750.0, "slab_loss_factor": 0.05}
D = 0.6
UNIT = {"slab_length": 4.8, "fasteners_per_slab": 8}
JOINT = {"joint_shear_stiffness": 1e8, "joint_bending_stiffness": 1e6}
BEARING = SpringDamper(2e7, 2e4)

#: the support and geometry of each track type, as (wave-model keywords, finite keywords)
TYPES = {
    "floating": ({"foundation": FOUNDATION}, {"foundation": FOUNDATION}),
    "bearings": (
        {"bearing": BEARING, "bearing_spacing_fasteners": 2},
        {"bearing": BEARING, "bearing_spacing_fasteners": 2},
    ),
    "unit": ({"foundation": FOUNDATION, **UNIT}, {"foundation": FOUNDATION, **UNIT}),
    "jointed": (
        {"foundation": FOUNDATION, **UNIT, **JOINT},
        {"foundation": FOUNDATION, **UNIT, **JOINT},
    ),
}
#: above a fastener and at mid-span between two (unit slabs: fasteners at 0.3 + 0.6 j)
POINTS = {"floating": [0.0, 0.3], "bearings": [0.0, 0.3], "unit": [2.1, 2.4], "jointed": [2.1, 2.4]}


def _pair(name, margin, elements, absorber):
    wave_kw, finite_kw = TYPES[name]
    x = POINTS[name]
    if "slab_length" in wave_kw:
        wave = UnitSlabTrack(RAIL, PAD, D, **wave_kw, **SLAB)
    else:
        wave = FloatingSlabTrack(RAIL, PAD, D, **wave_kw, **SLAB)
    finite = FiniteSlabTrack(
        RAIL,
        PAD,
        D,
        x_min=-margin * D,
        x_max=margin * D,
        elements_per_span=elements,
        nodes_at=tuple(x),
        absorber_length=absorber * D,
        absorber_damping=3e5,
        **finite_kw,
        **SLAB,
    )
    return wave, finite, x


def _error(wave, finite, f, x):
    a, b = wave.receptance(f, x, x), finite.receptance(f, x, x)
    return (np.abs(a - b) / np.abs(b).max(axis=(1, 2), keepdims=True)).max()


def test_floating_slab_matches_the_finite_model_at_low_frequency():
    # below 200 Hz, 8 Hermite elements per spacing are within 1e-7 of the exact beams;
    # the slab's waves above its ~10 Hz resonance travel far (|mu| = 0.99 per spacing at
    # 40 Hz), hence 720 m of track with 480 m of graded dashpots: measured 3e-7
    wave, finite, x = _pair("floating", margin=600, elements=8, absorber=400)
    f = np.array([1.0, 9.0, 20.0, 150.0])
    assert _error(wave, finite, f, x) < 1e-6


@pytest.mark.slow
@pytest.mark.parametrize("name", TYPES)
def test_receptances_match_the_finite_model_from_1_hz_to_2_khz(name):
    # two meshes, each where it is exact enough: below 200 Hz 12 elements per spacing
    # and 1440 m of track (the slab's long waves; the jointed slabs' travel furthest),
    # above it 48 elements and 480 m (the Hermite error falls as h^4: 1.3e-6 at 32 near
    # 2 kHz, 8e-7 at 8 near 200 Hz)
    wave, finite, x = _pair(name, margin=1200, elements=12, absorber=900)
    low = _error(wave, finite, np.geomspace(1.0, 200.0, 10), x)
    wave, finite, x = _pair(name, margin=400, elements=48, absorber=300)
    high = _error(wave, finite, np.geomspace(200.0, 2000.0, 10), x)
    assert max(low, high) < 1e-6, (low, high)


def _beam_green(q, x):
    """``(1/2 pi) int exp(i xi x) / (xi^4 - q) d xi`` by residues (the two roots with Im > 0)."""
    roots = np.asarray(q, dtype=complex)[:, None] ** 0.25 * np.array([1, 1j, -1, -1j])
    upper = roots.imag > 0
    return np.sum(np.where(upper, 1j * np.exp(1j * roots * abs(x)) / (4 * roots**3), 0), axis=1)


def _two_layer(f, x, ei_r, m_r, s, ei_s, m_s, k_f):
    """Rail receptance of the infinite two-layer beam on a Winkler foundation, m/N.

    ``[EI_r xi^4 - m_r w^2 + s, -s; -s, EI_s xi^4 - m_s w^2 + s + k_f] (W_r, W_s) = (F, 0)``
    with a continuous pad layer ``s`` (N/m^2): ``W_r = (EI_s Q + c_s) / (EI_r EI_s (Q - q1)
    (Q - q2))`` in ``Q = xi^4``, split into partial fractions.
    """
    w2 = (2 * np.pi * f) ** 2
    c_r, c_s = s - m_r * w2, s + k_f - m_s * w2
    a, b, c = ei_r * ei_s, ei_r * c_s + ei_s * c_r, c_r * c_s - s * s
    disc = np.sqrt(b * b - 4 * a * c)
    q1, q2 = (-b + disc) / (2 * a), (-b - disc) / (2 * a)
    a1, a2 = (ei_s * q1 + c_s) / (a * (q1 - q2)), (ei_s * q2 + c_s) / (a * (q2 - q1))
    return a1 * _beam_green(q1, x) + a2 * _beam_green(q2, x)


def test_dense_fasteners_are_the_continuous_two_layer_beam():
    # pads every 0.02 m with K_p = s d (s = 5e8 N/m^2, the 0.6 m set smeared): the
    # discrete pads differ from the continuous layer by their Floquet harmonics at
    # 2 pi / d; measured 2.7e-6 at d = 0.05, 8.1e-7 at 0.02 (below 0.02 the spans'
    # static stiffness EI / d^3, 1e5 times the track's, costs digits: 2.4e-5 at 0.01)
    d, s, eta = 0.02, 3e8 / 0.6, 0.25
    track = FloatingSlabTrack(RAIL, Hysteretic(s * d, eta), d, foundation=FOUNDATION, **SLAB)
    f = np.geomspace(1.0, 2000.0, 40)
    x = [0.0, d / 2, 1.0, 3.3]
    got = track.receptance(f, [0.0], x)[:, :, 0]
    ei_r = RAIL.bending_stiffness * (1 + 0.02j)
    ei_s = SLAB["slab_bending_stiffness"] * (1 + 0.05j)
    expected = np.stack(
        [
            _two_layer(f, xi, ei_r, 60.0, s * (1 + eta * 1j), ei_s, 1750.0, 7e6 * (1 + 0.2j))
            for xi in x
        ],
        axis=1,
    )
    err = np.abs(got - expected) / np.abs(expected[:, :1])
    assert err.max() < 2e-6, err.max()


def test_low_frequency_limit_is_the_beam_on_elastic_foundation():
    # below the slab's resonance (~10 Hz) with pads 1e5 times stiffer, rail and slab move
    # as one beam EI_r + EI_s, m_r + m_s on k_f: w = F / (8 EI lam^3), lam^4 = (k_f -
    # m w^2) / 4 EI (Hetenyi). The pads' compression (1/3e13 m/N against 2e-8 m/N) and the
    # coupling at discrete fasteners (lam d = 0.2) leave 1.6e-6 measured (1.2e-6 with
    # fasteners 0.05 m apart): 1e-5
    track = FloatingSlabTrack(RAIL, Hysteretic(3e13, 0.25), D, foundation=FOUNDATION, **SLAB)
    f = np.geomspace(0.1, 3.0, 20)
    got = track.receptance(f, [0.0], [0.0])[:, 0, 0]
    ei = RAIL.bending_stiffness * (1 + 0.02j) + SLAB["slab_bending_stiffness"] * (1 + 0.05j)
    m = 60.0 + SLAB["slab_mass_per_length"]
    lam = ((7e6 * (1 + 0.2j) - m * (2 * np.pi * f) ** 2) / (4 * ei)) ** 0.25
    np.testing.assert_allclose(got, 1 / (8 * ei * lam**3), rtol=1e-5)
