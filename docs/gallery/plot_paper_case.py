"""
The paper's case: response PSDs of the vehicle
==============================================

The built-in default case (Wang et al. 2017: the type-B metro car at 80 km/h on the
embedded-sleeper slab track with WJ-7 pads) run on a coarser grid than the preset's,
and the acceleration PSDs of the car body, a bogie and a wheelset drawn against
frequency. PSDs are one-sided, per Hz.
"""

import matplotlib.pyplot as plt

import railvib

case = railvib.case_from_dict(
    {
        "preset": "wang2017_metro",
        "frequency": {"f_min": 0.5, "f_max": 200.0, "spacing": "log", "n": 300},
    }
)
ds = railvib.run(case)

fig, ax = plt.subplots(figsize=(7, 4))
for label in ("carbody.bounce", "bogie1.bounce", "wheelset2.bounce"):
    ds.psd_acceleration.sel(response=label).plot(ax=ax, label=label)
ax.set(xscale="log", yscale="log", title="acceleration PSD, paper's case")
ax.set_ylabel("PSD [(m/s$^2$)$^2$/Hz]")
ax.legend()

# %%
# The summary statistics of the same run: peak, the frequency of the peak and the RMS
# over the grid and over a band (20-100 Hz here).
table = railvib.summary(ds, bands=[(20.0, 100.0)])
print(table[["peak", "dominant_frequency"]].to_dataframe().head(8))
