"""Irregularity samples: seeded, reproducible, and their PSD reproduces the target spectrum."""

import numpy as np
import pytest
from scipy import integrate, signal

from railvib.spectra import Combined, FRAClass, ShiTai
from railvib.validation import sample_profile, wheel_irregularities


def test_same_seed_same_profile_different_seed_different():
    a = sample_profile(FRAClass(5), 200.0, 0.1, seed=3)[1]
    b = sample_profile(FRAClass(5), 200.0, 0.1, seed=3)[1]
    c = sample_profile(FRAClass(5), 200.0, 0.1, seed=4)[1]
    np.testing.assert_array_equal(a, b)
    assert np.corrcoef(a, c)[0, 1] < 0.5


def test_variance_equals_integral_of_spectrum_over_the_band():
    # random phases, deterministic amplitudes: the sample variance is the sum of the line
    # variances, i.e. a Riemann sum of the spectrum; 1 % covers the discretisation of dn
    spec = FRAClass(5)
    lam = (1.0, 50.0)
    _, r = sample_profile(spec, 5000.0, 0.05, seed=1, wavelength_range=lam)
    exact, _ = integrate.quad(spec.psd, 2 * np.pi / lam[1], 2 * np.pi / lam[0])
    assert np.var(r) == pytest.approx(exact, rel=0.01)


@pytest.mark.parametrize("spec", [FRAClass(5), Combined(FRAClass(5), ShiTai())])
def test_welch_psd_of_samples_reproduces_target(spec):
    # Welch over 8 profiles x ~7 segments (nu ~ 100 per bin), averaged over hundreds of bins per
    # 0.28-decade band: scatter ~1 %, so 8 % bounds leakage and estimation error
    dx, length = 0.02, 2000.0
    n_seg = 5000
    ests = []
    for seed in range(8):
        _, r = sample_profile(spec, length, dx, seed=seed)
        n, p = signal.welch(r, fs=1 / dx, nperseg=n_seg)  # m^2/(cycle/m)
        ests.append(p)
    est = np.mean(ests, axis=0)
    target = spec.psd_cycles(n[1:])
    edges = np.geomspace(0.2, 10.0, 6)
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        m = (n[1:] >= lo) & (n[1:] < hi)
        ratio = np.mean(est[1:][m]) / np.mean(target[m])
        assert ratio == pytest.approx(1.0, rel=0.08), (lo, hi)


def test_wheel_inputs_are_the_same_profile_delayed():
    # a shift of an integer number of samples is exact: r_j(t) = r_0(t - t_j)
    dt, v = 1e-3, 20.0
    offsets = np.array([0.0, 2.0, 12.0])  # 100 and 600 samples
    r = wheel_irregularities(FRAClass(5), v, offsets, 10.0, dt, seed=5, realisations=[0, 1])
    for j, s in enumerate(offsets):
        k = int(round(s / (v * dt)))
        np.testing.assert_allclose(r[k:-1, j], r[: -1 - k, 0], atol=1e-14)
    assert not np.allclose(r[:, :, 0], r[:, :, 1])


def test_realisation_reproducible_alone():
    args = (FRAClass(5), 20.0, [0.0, 2.2], 5.0, 1e-3, 11)
    both = wheel_irregularities(*args, realisations=[0, 1])
    one = wheel_irregularities(*args, realisations=[1])
    np.testing.assert_array_equal(both[:, :, 1], one[:, :, 0])


def test_frequency_band_and_ramp():
    dt, v, dur = 1e-3, 20.0, 20.0
    r = wheel_irregularities(
        FRAClass(5), v, [0.0], dur, dt, seed=2, frequency_band=(1.0, 50.0), ramp=1.0
    )[:, 0, 0]
    assert r[0] == 0.0
    spec = np.abs(np.fft.rfft(r[int(2 / dt) : -1])) ** 2
    f = np.fft.rfftfreq(r[int(2 / dt) : -1].size, dt)
    assert spec[f > 60].max() < 1e-6 * spec.max()
