"""Adapter kept for ``benchmarks/bench_core.py`` only: the old constructor on the package model.

The tests' finite-track reference is :class:`railvib.validation.FiniteTrack` (see the
docstring of ``tests/validation/test_track_periodic.py`` for why it is independent of
the symplectic solver). This module used to hold a second Hermite-element model; it
now maps the old constructor onto the package model with the same mesh (sleepers
``-n_bays..n_bays``, ``n_sub`` elements per bay, ``absorber_bays``-bay absorbing ends
reaching 40 times the pad damping; graded quadratically, the old model cubically:
the two agree to 1e-11 relative). Delete it once ``bench_core.py`` builds
``railvib.validation.FiniteTrack`` directly; nothing in ``tests/`` imports it.
"""

from __future__ import annotations

from railvib.pads import SpringDamper
from railvib.track import Rail
from railvib.validation import FiniteTrack as _PackageFiniteTrack

__all__ = ["FiniteTrack"]


def FiniteTrack(  # the old class name, kept for its one caller
    ei: float,
    m: float,
    pad_k: float,
    pad_c: float,
    d: float,
    n_bays: int = 300,
    n_sub: int = 12,
    absorber_bays: int = 100,
) -> _PackageFiniteTrack:
    """Rail from sleeper ``-n_bays`` to ``+n_bays`` on pads (N/m, N s/m) at spacing `d` (m)."""
    return _PackageFiniteTrack(
        Rail(ei, m),
        SpringDamper(pad_k, pad_c),
        d,
        -n_bays,
        n_bays,
        elements_per_span=n_sub,
        absorber_spans=absorber_bays,
        absorber_damping=40.0 * pad_c,
    )
