"""A published receptance benchmark for the ballasted track: Thompson's ch. 3 parameter set.

Source: the reference data of the open-source package rolland ("Rolling Noise and
Dynamics", A. Nehls et al., 2025; its test of the analytical method ``TSDiscr2LSupp``, data
column ``TSDiscr2LSupp``): the point mobility magnitude of a Timoshenko rail on 241
discrete double-layer supports 0.6 m apart, the load above the middle sleeper, computed by
the method of D. Thompson, *Railway Noise and Vibration*, 2nd ed. (2024), eqs. 3.68-3.77
(after M. A. Heckl, "Railway noise - Can random sleeper spacings help?", Acta Acustica
1995): the free Timoshenko beam's Green's function and the supports' reaction forces
solved together. It shares nothing with railvib's periodic-cell solution.

Parameters (rolland's UIC60 and its test track), read here as railvib's keys:

* rail: E = 210 GPa, I = 3038.3e-8 m^4 (EI = 6.38043e6 N m^2), A = 76.7e-4 m^2, G = 81 GPa,
  shear coefficient 0.4 (kappa G A = 2.48508e8 N), rho = 7850 kg/m^3 (rho I = 0.2385 kg m),
  m = 60.2 kg/m; the method takes no rail loss factor (rolland's ``etar`` is not used);
* pad 300 MN/m, loss factor 0.25 (hysteretic); half sleeper 162 kg; ballast 50 MN/m,
  loss factor 1.0 (hysteretic); d = 0.6 m.

The values (|mobility|, m/(N s)) are at points of the grid ``linspace(20, 3000, 1500)``.
"""

from __future__ import annotations

import numpy as np

from railvib.pads import Hysteretic
from railvib.track import BallastedTrack, Rail

#: (frequency Hz, |point mobility| m/(N s)) from the source's data, as printed there
THOMPSON_CH3_MOBILITY = (
    (20.0, 9.63710422917563e-07),
    (99.51967978652435, 4.972745959551845e-06),
    (218.79919946631088, 1.98736552368905e-06),
    (338.0787191460974, 3.833612264765598e-06),
    (497.1180787191461, 1.3447430498818012e-05),
    (616.3975983989327, 8.264528222115344e-06),
    (695.917278185457, 6.4154752335875945e-06),
)

RAIL = Rail(
    210e9 * 3038.3e-8,
    60.2,
    0.0,
    shear_stiffness=0.4 * 81e9 * 76.7e-4,
    rotary_inertia=7850.0 * 3038.3e-8,
)


def test_point_mobility_matches_the_published_ballasted_track_benchmark():
    # Same physics by a different method: below 700 Hz every wave dies within the 72 m of
    # supports on each side of the source's load (ballast loss factor 1), so its finite
    # 241-sleeper track is the infinite one. Measured agreement 5.4e-12 (the source's
    # values printed to 16 digits; round-off of two solutions): 1e-9. Above ~800 Hz the rail
    # decouples from the sleepers and its waves reach the ends of the source's supports
    # (3e-6 at 900 Hz, 2.7e-4 at 1 kHz): not compared there.
    track = BallastedTrack(
        RAIL, Hysteretic(300e6, 0.25), 0.6, sleeper_mass=162.0, ballast=Hysteretic(50e6, 1.0)
    )
    f, expected = np.array(THOMPSON_CH3_MOBILITY).T
    receptance = track.receptance(f, [0.0], [0.0])[:, 0, 0]
    mobility = np.abs(2j * np.pi * f * receptance)
    np.testing.assert_allclose(mobility, expected, rtol=1e-9)
