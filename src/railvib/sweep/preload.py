"""Imported by the fork server of a sweep on the compiled kernels: loads them once for all.

A sweep whose work reaches :data:`railvib.track.compiled.COMPILED_MIN_POINTS` solves its
chunks on the compiled kernels, which every process loads from numba's on-disk cache
before its first use (0.4-1 s of CPU, once per process). The fork server that starts the
sweep's workers (:func:`railvib.sweep.runner.run_sweep`) imports this module after
:mod:`railvib.sweep.batch`: the kernels are loaded there, once, and every worker forked
from it starts with them loaded, instead of each worker loading them itself.
"""

from __future__ import annotations

from railvib.sweep.stacked import load_compiled_kernels

__all__: list[str] = []

load_compiled_kernels()
