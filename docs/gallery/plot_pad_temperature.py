"""
A railpad over temperature
==========================

A fractional Zener pad with time-temperature superposition (the WLF shift with the
universal constants at Tg = -40 degC, reference 20 degC): the storage stiffness K' and
the loss factor eta = K''/K' against frequency at three pad temperatures. A colder pad
is stiffer and, near the glass transition, lossier.
"""

import matplotlib.pyplot as plt
import numpy as np

from railvib.pads import pad_from_dict

pad = pad_from_dict(
    {
        "model": "fractional_zener",
        "k0_n_per_m": 3.0e7,
        "k_inf_n_per_m": 6.0e8,
        "tau_s": 1.0e-7,
        "alpha": 0.35,
        "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -40.0},
    }
)
f = np.geomspace(1.0, 2000.0, 200)  # Hz

fig, (ax_k, ax_eta) = plt.subplots(1, 2, figsize=(9, 3.8), sharex=True)
for temperature in (-30.0, -10.0, 20.0):
    k = pad.stiffness(f, temperature)  # K' + i K'', N/m
    ax_k.plot(f, k.real / 1e6, label=f"{temperature:+.0f} °C")
    ax_eta.plot(f, k.imag / k.real)
ax_k.set(xscale="log", yscale="log", xlabel="frequency [Hz]", ylabel="K' [kN/mm]")
ax_eta.set(xscale="log", xlabel="frequency [Hz]", ylabel="loss factor [-]")
ax_k.legend(title="pad temperature")
fig.tight_layout()
