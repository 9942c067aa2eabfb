"""Draw lyapunov.png: the exact non-stationary PEM against the covariance equation.

Run from the repository root: ``python docs/figures/nonstationary/lyapunov.py``. The
quarter car and irregularity of tests/validation/test_nonstationary.py, braking from
72 km/h to a stop at 4 m/s^2.
"""

from pathlib import Path

import numpy as np

from railvib.io import new_figure, save_figure
from railvib.nonstationary import (
    RigidTrackVehicle,
    ShapingFilter,
    SpatialBand,
    SpeedProfile,
    covariance_response,
    exact_response,
    quasi_stationary_psd,
)
from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

quarter = Vehicle(
    (RigidBody("carbody", 400.0, None, 0.0), RigidBody("wheelset1", 40.0, None, 0.0)),
    (
        Suspension(
            "primary.1", Attachment("carbody", 0.0), Attachment("wheelset1", 0.0), 4e4, 1.5e3
        ),
    ),
    (Wheel("wheelset1", 0.0),),
)
model = RigidTrackVehicle(quarter, 2e5)
shaping = ShapingFilter.first_order(1e-4, 0.5)
band = SpatialBand.log_spaced(shaping, 0.02, 5000.0, 1500)
profile = SpeedProfile.uniform(20.0, 0.0, 4.0)
hist = exact_response(model, profile, band, 2e-3, map_times=2)
ref = covariance_response(model, shaping, profile, hist.t)
pick = np.linspace(0, hist.t.size - 1, 60).round().astype(int)
qs = quasi_stationary_psd(model, profile, band, hist.t[pick]).sum(axis=1)
fig, axes = new_figure((11, 4.0), ncols=2, layout="constrained")
for ax, (o, name, unit) in zip(
    axes, ((2, "body acceleration", "m/s^2"), (4, "tyre force", "N")), strict=True
):
    ax.plot(hist.t, np.sqrt(ref[:, o]), lw=3, color="0.75", label="covariance equation")
    ax.plot(hist.t, np.sqrt(hist.variance[:, o]), label="exact PEM")
    ax.plot(hist.t[pick], np.sqrt(qs[:, o]), "--", label="quasi-stationary")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"RMS {name} ({unit})")
    ax.set_title(f"Quarter car braking 72 -> 0 km/h at 4 m/s^2: {name}")
    ax.legend()
save_figure(fig, Path(__file__).with_name("lyapunov.png"), tight=False)
