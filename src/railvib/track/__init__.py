"""The rail as an infinite periodic structure (symplectic / wave method)."""

from railvib.track.ballasted import BallastedTrack
from railvib.track.base import DEFAULT_TRACK_MODEL, TRACKS, SupportResponse, TrackModel
from railvib.track.periodic import PeriodicTrack, Rail, TrackWaves
from railvib.track.slab import FloatingSlabTrack, SlabTrack, UnitSlabTrack

__all__ = [
    "DEFAULT_TRACK_MODEL",
    "TRACKS",
    "BallastedTrack",
    "FloatingSlabTrack",
    "PeriodicTrack",
    "Rail",
    "SlabTrack",
    "SupportResponse",
    "TrackModel",
    "TrackWaves",
    "UnitSlabTrack",
]
