"""Hypothesis strategies for physically plausible railvib inputs (for users' and our tests)."""

from __future__ import annotations

from typing import Any

from hypothesis import strategies as st

__all__ = ["case_overrides", "pad_tables"]


def _log_uniform(lo: float, hi: float) -> st.SearchStrategy[float]:
    import math

    return st.floats(math.log(lo), math.log(hi)).map(math.exp)


def pad_tables() -> st.SearchStrategy[dict[str, Any]]:
    """``[track.pad]`` tables of plausible railpads (N/m, N s/m)."""
    spring = st.fixed_dictionaries(
        {
            "model": st.just("spring_damper"),
            "stiffness_n_per_m": _log_uniform(1e7, 1e9),
            "damping_ns_per_m": _log_uniform(1e3, 2e5),
        }
    )
    hysteretic = st.fixed_dictionaries(
        {
            "model": st.just("hysteretic"),
            "stiffness_n_per_m": _log_uniform(1e7, 1e9),
            "loss_factor": st.floats(0.02, 0.6),
        }
    )
    loglinear = st.fixed_dictionaries(
        {
            "model": st.just("log_linear"),
            "k0_n_per_m": _log_uniform(1e7, 1e9),
            "f0_hz": st.floats(1.0, 10.0),
            "exponent": st.floats(0.0, 0.2),
            "damping_ns_per_m": _log_uniform(1e3, 2e5),
        }
    )
    return st.one_of(spring, hysteretic, loglinear)


def case_overrides() -> st.SearchStrategy[dict[str, Any]]:
    """Overrides of the default preset spanning plausible vehicles, tracks and speeds."""
    return st.fixed_dictionaries(
        {
            "speed_kmh": st.floats(20.0, 350.0),
            "rail_model": st.sampled_from(["single_rail", "rail_pair"]),
            "vehicle": st.fixed_dictionaries(
                {
                    "carbody_mass": _log_uniform(1e4, 6e4),
                    "bogie_mass": _log_uniform(1e3, 4e3),
                    "wheelset_mass": _log_uniform(8e2, 2.5e3),
                    "primary_stiffness": _log_uniform(3e5, 5e6),
                    "secondary_stiffness": _log_uniform(1e5, 1e6),
                    "primary_damping": _log_uniform(1e2, 5e4),
                    "secondary_damping": _log_uniform(1e3, 1e5),
                }
            ),
            "track": st.fixed_dictionaries(
                {
                    "sleeper_spacing": st.floats(0.5, 0.75),
                    "rail": st.fixed_dictionaries(
                        {
                            "bending_stiffness": _log_uniform(3e6, 1.2e7),
                            "mass_per_length": st.floats(40.0, 80.0),
                            "loss_factor": st.sampled_from([0.0, 0.01]),
                        }
                    ),
                    "pad": pad_tables(),
                }
            ),
            "contact": st.fixed_dictionaries({"leading_wheel_position": st.floats(0.0, 0.499)}),
        }
    )
