"""Small sweeps shared by the sweep tests (coarse grids keep the suite fast)."""

import copy

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
