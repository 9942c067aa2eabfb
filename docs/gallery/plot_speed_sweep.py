"""
Speed and track quality
=======================

The RMS acceleration of a wheelset over 1-200 Hz against speed, on the paper's
irregularity (FRA class 5 for wavelengths above 1 m, Shi-tai below) and on a better
track (FRA class 6 above 1 m). Each case runs in a fraction of a second;
``railvib sweep`` does the same from a file, in parallel and resumably (see the
sweeps page).
"""

import matplotlib.pyplot as plt
import numpy as np

import railvib

speeds = np.array([40.0, 60.0, 80.0, 100.0, 120.0])  # km/h
grid = {"f_min": 1.0, "f_max": 200.0, "spacing": "log", "n": 200}


def irregularity(fra_class):
    """The paper's combined spectrum with FRA class `fra_class` for the long waves."""
    return {
        "type": "combined",
        "split_wavelength_m": 1.0,
        "long_wave": {"type": "fra", "class_number": fra_class},
        "short_wave": {"type": "shitai"},
    }


fig, ax = plt.subplots(figsize=(6, 4))
for fra_class, name in ((5, "FRA class 5 (the paper's)"), (6, "FRA class 6")):
    rms = []
    for speed in speeds:
        case = railvib.case_from_dict(
            {
                "preset": "wang2017_metro",
                "speed_kmh": float(speed),
                "irregularity": irregularity(fra_class),
                "frequency": grid,
            }
        )
        ds = railvib.run(case)
        rms.append(float(railvib.summary(ds).rms.sel(response="wheelset2.bounce")))
    ax.plot(speeds, rms, "o-", label=name)
ax.set(xlabel="speed [km/h]", ylabel="RMS acceleration [m/s$^2$]", title="wheelset 2")
ax.legend()
