"""Shared fixtures: non-interactive matplotlib, the paper's track and vehicle."""

import matplotlib

matplotlib.use("Agg")

import pytest  # noqa: E402

from railvib.pads import SpringDamper  # noqa: E402
from railvib.track import PeriodicTrack, Rail  # noqa: E402
from railvib.vehicle import PitchPlaneParameters, pitch_plane_10dof  # noqa: E402

#: the paper's Table 2 track (one CHN60 rail; pad damping read as 5e4 N s/m)
PAPER_RAIL = Rail(6.62e6, 60.64)
PAPER_PAD = SpringDamper(5.0e7, 5.0e4)
PAPER_SPACING = 0.6

#: the paper's Table 1 vehicle
PAPER_VEHICLE_PARAMS = PitchPlaneParameters(
    carbody_mass=21920.0,
    carbody_pitch_inertia=617310.0,
    bogie_mass=2550.0,
    bogie_pitch_inertia=1750.0,
    wheelset_mass=1420.0,
    primary_stiffness=1.7e6,
    primary_damping=5.0e3,
    secondary_stiffness=2.75e5,
    secondary_damping=3.0e4,
    bogie_half_spacing=6.3,
    wheelset_half_spacing=1.1,
)


@pytest.fixture
def paper_track():
    return PeriodicTrack(PAPER_RAIL, PAPER_PAD, PAPER_SPACING)


@pytest.fixture
def paper_vehicle():
    return pitch_plane_10dof(PAPER_VEHICLE_PARAMS)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")
