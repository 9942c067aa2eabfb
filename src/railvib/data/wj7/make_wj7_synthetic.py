"""Generate the SYNTHETIC WJ-7 railpad data in this folder (not measurements).

Run ``python make_wj7_synthetic.py`` here to rewrite the two CSV files. See README.md.

1. A fractional Zener master curve at 20 degC with the universal WLF constants at
   Tg = -40 degC (C1 = 17.44, C2 = 51.6 K; seed section 3.2.1) and the seed's vertical
   factor (a_f = 4.8e-4 /K) is calibrated by least squares to the facts the seed
   states for WJ-7: K'(5 Hz) = 31.0, 45.2 and 70.8 kN/mm at +20, -10 and -30 degC
   (the physical pairing of docs/paper-interpretation.md), log-log slope 0.07
   over 5-1000 Hz at those temperatures, and the loss-factor peak of the 0.3 Hz
   temperature sweep at Tg = -40 degC.
2. That model is sampled at the seed's protocol (0.3 Hz, -60 to +20 degC every
   2.5 degC) and, for WLF fitting, DMA-style at 7 frequencies over 0.1-100 Hz from
   -40 to +20 degC every 2.5 degC (colder windows no longer overlap after shifting);
   1 % seeded Gaussian noise is applied to K' and to the loss factor.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from railvib.pads import WLF, FractionalZener, TemperatureShifted

HERE = Path(__file__).parent
KN_PER_MM = 1e6  # N/m
TG_C = -40.0
T_REF_C = 20.0
TARGETS_KN_PER_MM = {20.0: 31.0, -10.0: 45.2, -30.0: 70.8}
SLOPE = 0.07
NOISE = 0.01
SEED = 7


def pad(x: np.ndarray) -> TemperatureShifted:
    """Return the TTS pad for ``x = [log10 K0, log10 (Kinf/K0 - 1), log10 tau, alpha]``."""
    k0 = 10.0 ** x[0]
    zener = FractionalZener(k0, k0 * (1 + 10.0 ** x[1]), 10.0 ** x[2], x[3])
    return TemperatureShifted(zener, WLF.universal(TG_C), T_REF_C, vertical_shift=True)


def residuals(x: np.ndarray) -> np.ndarray:
    """Return misfits to the seed's WJ-7 facts (relative stiffness, slope, Tg in 10 K units)."""
    p = pad(x)
    r = []
    band = np.geomspace(5.0, 1000.0, 30)
    for t, k in TARGETS_KN_PER_MM.items():
        r.append(p.storage(5.0, t) / (k * KN_PER_MM) - 1.0)
        slope = np.polyfit(np.log10(band), np.log10(p.storage(band, t)), 1)[0]
        r.append((slope - SLOPE) / SLOPE)
    # loss-factor peak of the 0.3 Hz sweep at Tg: zero central difference there
    eta = [float(p.loss_factor(0.3, TG_C + d)) for d in (-1.0, 0.0, 1.0)]
    r.append(100.0 * (eta[2] - eta[0]) / eta[1])
    return np.array(r, dtype=float)


def calibrate() -> TemperatureShifted:
    """Fit the master-curve parameters to the WJ-7 facts."""
    x0 = np.array([np.log10(25e6), 1.5, -9.0, 0.3])
    sol = least_squares(residuals, x0, bounds=([6, -1, -22, 0.05], [9, 4, -3, 1.0]), diff_step=1e-4)
    return pad(sol.x)


def table(p: TemperatureShifted, temps: np.ndarray, freqs: np.ndarray, rng) -> np.ndarray:
    """Rows ``(T degC, f Hz, K' kN/mm, loss factor)`` with multiplicative noise."""
    rows = []
    for t in temps:
        k = p.stiffness(freqs, t)
        for f, kk in zip(freqs, k, strict=True):
            ks = kk.real * (1 + NOISE * rng.standard_normal()) / KN_PER_MM
            eta = kk.imag / kk.real * (1 + NOISE * rng.standard_normal())
            rows.append((t, f, ks, eta))
    return np.array(rows)


def write(path: Path, rows: np.ndarray, p: TemperatureShifted, what: str) -> None:
    """Write one labelled CSV."""
    z = p.base
    header = [
        "SYNTHETIC DATA - not measurements. Made by make_wj7_synthetic.py (see README.md).",
        what,
        f"generator: fractional Zener at {T_REF_C:g} degC: K0 = {z.k0_n_per_m:.6g} N/m, "
        f"Kinf = {z.k_inf_n_per_m:.6g} N/m, tau = {z.tau_s:.6g} s, alpha = {z.alpha:.6g};",
        f"WLF universal at Tg = {TG_C:g} degC (C1 = 17.44, C2 = 51.6 K); vertical factor "
        f"a_f = 4.8e-4 /K; {100 * NOISE:g} % Gaussian noise on K' and loss factor, seed {SEED}.",
    ]
    with path.open("w") as fh:
        fh.writelines(f"# {line}\n" for line in header)
        fh.write("temperature_c,frequency_hz,storage_kn_per_mm,loss_factor\n")
        for t, f, k, eta in rows:
            fh.write(f"{t:g},{f:g},{k:.4f},{eta:.5f}\n")


def main() -> None:
    """Calibrate and write both files."""
    p = calibrate()
    rng = np.random.default_rng(SEED)
    sweep = table(p, np.arange(-60.0, 20.01, 2.5), np.array([0.3]), rng)
    write(HERE / "wj7_synthetic_0p3hz.csv", sweep, p, "Seed protocol: 0.3 Hz, -60..+20 degC.")
    dma = table(p, np.arange(-40.0, 20.01, 2.5), np.geomspace(0.1, 100.0, 7), rng)
    write(
        HERE / "wj7_synthetic_multifrequency.csv", dma, p, "DMA-style: 0.1-100 Hz, -40..+20 degC."
    )
    print(p.base)
    band = np.geomspace(5.0, 1000.0, 30)
    for t, k in TARGETS_KN_PER_MM.items():
        slope = np.polyfit(np.log10(band), np.log10(p.storage(band, t)), 1)[0]
        print(
            f"{t:+g} degC: K'(5 Hz) = {p.storage(5.0, t) / KN_PER_MM:.1f} kN/mm (seed {k}), "
            f"slope 5-1000 Hz = {slope:.3f} (seed {SLOPE})"
        )
    temps = np.arange(-60.0, 20.01, 0.5)
    eta = p.loss_factor(0.3, temps[0])
    peak = temps[np.argmax([p.loss_factor(0.3, t) for t in temps])]
    print(f"loss-factor peak of the 0.3 Hz sweep at {peak:g} degC (seed Tg {TG_C:g})")
    print(f"loss factor at -60 degC, 0.3 Hz: {eta:.3f}")


if __name__ == "__main__":
    main()
