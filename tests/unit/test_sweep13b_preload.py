"""The fork server loads the compiled kernels only for a sweep whose workers would load them."""

import importlib.util
import sys

import pytest

from railvib.sweep import sweep_from_dict
from railvib.sweep.runner import _workers_load_kernels
from railvib.sweep.stacked import load_compiled_kernels
from railvib.track.compiled import COMPILED_MIN_POINTS
from tests.unit.sweep.sweep_cases import small_sweep

needs_numba = pytest.mark.skipif(
    importlib.util.find_spec("numba") is None, reason="numba (the fast extra) not installed"
)


def _sweep(n_cases, n_freq):
    d = small_sweep()
    d["case"]["frequency"] = {"spacing": "log", "f_min": 1.0, "f_max": 1000.0, "n": n_freq}
    d["axes"] = [{"field": "speed_kmh", "start": 40.0, "stop": 160.0, "num": n_cases}]
    return sweep_from_dict(d)


@needs_numba
def test_a_sweep_whose_work_reaches_the_threshold_preloads_the_kernels(monkeypatch):
    monkeypatch.delenv("RAILVIB_COMPILED", raising=False)
    n_freq = 10000  # few cases reach it (each axis value is validated: ~5 ms each)
    n_cases = -(-COMPILED_MIN_POINTS // n_freq)  # the fewest cases reaching it
    assert _workers_load_kernels(_sweep(n_cases, n_freq))
    assert not _workers_load_kernels(_sweep(n_cases - 1, n_freq))


def test_the_kernels_turned_off_are_never_preloaded(monkeypatch):
    monkeypatch.setenv("RAILVIB_COMPILED", "0")
    assert not _workers_load_kernels(_sweep(60, 10000))
    assert not load_compiled_kernels()


def test_without_numba_nothing_is_preloaded(monkeypatch):
    monkeypatch.delenv("RAILVIB_COMPILED", raising=False)
    monkeypatch.setitem(sys.modules, "numba", None)  # find_spec raises, import fails
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None)
    monkeypatch.setattr("railvib.sweep.runner.find_spec", lambda name, *a: None)
    assert not _workers_load_kernels(_sweep(60, 10000))
