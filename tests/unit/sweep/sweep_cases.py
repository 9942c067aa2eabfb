"""Small sweeps shared by the sweep tests (coarse grids keep the suite fast)."""

import copy

import xarray as xr

#: a temperature-dependent pad, so that pad_temperature_c changes the track
TTS_PAD = {
    "model": "fractional_zener",
    "k0_n_per_m": 4.0e7,
    "k_inf_n_per_m": 2.0e8,
    "tau_s": 1.0e-3,
    "alpha": 0.4,
    "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -50.0},
}

BASE_CASE = {
    "preset": "wang2017_metro",
    "track": {"pad": TTS_PAD, "pad_temperature_c": 20.0},
    "frequency": {"spacing": "log", "f_min": 0.5, "f_max": 1000.0, "n": 60},
}


def small_sweep(**over):
    """A 3 x 4 temperature x speed sweep, chunks of 4 cases, plus overrides."""
    d = {
        "title": "test sweep",
        "chunk_size": 4,
        "variables": ["psd_acceleration", "psd_force"],
        "case": copy.deepcopy(BASE_CASE),
        "axes": [
            {"field": "track.pad_temperature_c", "values": [-30.0, 0.0, 30.0]},
            {"field": "speed_kmh", "start": 40.0, "stop": 160.0, "num": 4},
        ],
    }
    d.update(over)
    return d


def assert_recomputed(ds, reference):
    """A recomputed sweep equals the reference to rounding.

    Not to the bit: a chunk computed again may differ from its first computation in the
    last bits (measured at most ~3e-15 relative), as seen at the CI's lower bounds (numpy
    2.0, numba 0.60): a chunk takes the compiled kernels only where this worker has loaded
    them, and reductions may round differently from one allocation to the next. 1e-12 is
    300x that, and far below any change of the function computed.
    """
    xr.testing.assert_allclose(ds, reference, rtol=1e-12, atol=0.0)
    xr.testing.assert_identical(ds.coords.to_dataset(), reference.coords.to_dataset())
    assert ds.attrs == reference.attrs
