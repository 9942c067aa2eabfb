"""The rail as an infinite periodic structure (symplectic / wave method)."""

from railvib.track.periodic import PeriodicTrack, Rail, TrackWaves

__all__ = ["PeriodicTrack", "Rail", "TrackWaves"]
