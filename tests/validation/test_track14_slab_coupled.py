"""Coupled PSDs of the slab tracks against the finite slab track with its own slab DOFs.

The vehicle on the slab track's cell solution (:meth:`CoupledSystem.frf`) against the same
vehicle on :class:`~railvib.validation.finite_slab.FiniteSlabTrack` (rail and slab beams of
Hermite elements, pads, bearings and joints as springs, one sparse solve per frequency),
built by :meth:`FiniteCoupledSystem.from_system` from the system's parameters only.
Compared: ``|FRF|^2`` of every vehicle DOF, the rail under each wheel and each contact force
(the PSDs per unit irregularity spectrum), pointwise relative, for a leading wheel above a
support and at mid-span between two.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from railvib.case import build_system, case_from_dict
from railvib.track import UnitSlabTrack
from railvib.validation import FiniteCoupledSystem


def _floating(x0):
    """floating_slab_metro (bearings under every second fastener, x = 1.2 n)."""
    case = {"preset": "floating_slab_metro", "contact": {"leading_wheel_position": x0}}
    return build_system(case_from_dict(case))


def _unit(x0):
    """The same rail, pads, slab and bearings as 4.8 m unit slabs with 8 fasteners and joints."""
    system = _floating(0.3)
    t = system.track
    track = UnitSlabTrack(
        t.rail,
        t.pad,
        t.sleeper_spacing,
        t.pad_temperature,
        slab_bending_stiffness=t.slab_bending_stiffness,
        slab_mass_per_length=t.slab_mass_per_length,
        slab_loss_factor=t.slab_loss_factor,
        bearing=t.bearing,
        slab_length=4.8,
        fasteners_per_slab=8,
        joint_shear_stiffness=2e8,
        joint_bending_stiffness=2e6,
    )
    return replace(system, track=track, leading_wheel_position=x0)


#: (system, leading wheel position): above a bearing and at mid-span between fasteners
#: (floating: bearings at 1.2 n; unit slabs: fasteners, each on a bearing, at 0.3 + 0.6 j,
#: so that the unit slabs' mid-span x = 0 is over a joint)
CASES = {
    "floating-above-bearing": (_floating, 0.0),
    "floating-mid-span": (_floating, 0.3),
    "unit-above-bearing": (_unit, 0.3),
    "unit-mid-span-over-joint": (_unit, 0.0),
}


def _psd_error(name, f, margin, elements):
    build, x0 = CASES[name]
    system = build(x0)
    finite = FiniteCoupledSystem.from_system(
        system,
        margin_spans=margin,
        elements_per_span=elements,
        absorber_spans=margin * 5 // 6,
        absorber_damping=2e5,
    ).frf(f)
    wave = system.frf(f)
    errors = []
    for part in ("vehicle", "rail", "contact_force"):
        a, b = np.abs(getattr(wave, part)) ** 2, np.abs(getattr(finite, part)) ** 2
        errors.append(float((np.abs(a - b) / b).max()))
    return max(errors)


def test_coupled_psds_match_the_finite_slab_track_below_500_hz():
    # 16 Hermite elements per fastener spacing are within 1e-6 of the exact beams below
    # 500 Hz and 240 spacings of margin (200 absorbing) hold the slab's waves (the preset's
    # slab loss factor 0.02): measured 8.5e-6 pointwise (unit slabs: 1.7e-6)
    f = np.geomspace(1.0, 500.0, 6)
    assert _psd_error("floating-mid-span", f, margin=240, elements=16) < 1e-4


@pytest.mark.slow  # 960 spacings x 32 elements, two beams: ~2 s per case
@pytest.mark.parametrize("name", CASES)
def test_coupled_psds_match_the_finite_slab_track_to_2_khz(name):
    # the 1e-4 over 1 Hz - 2 kHz: the Hermite error falls as h^4 (2.3e-4 at 16
    # elements per spacing near 2 kHz, 1.9e-5 at 32) and 480 spacings of margin hold the
    # slab's far-travelling waves (measured near 30 Hz: 1.8e-5 with 240 spacings, 2e-7
    # with 480); measured maximum 1.9e-5
    f = np.geomspace(1.0, 2000.0, 16)
    assert _psd_error(name, f, margin=480, elements=32) < 1e-4
