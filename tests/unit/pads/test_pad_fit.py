"""Master curves and fitting: shift a known master curve to many temperatures, fit it back."""

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.pads import (
    WLF,
    FractionalZener,
    LogLinear,
    Measurements,
    TemperatureShifted,
    build_master_curve,
    fit_log_linear,
    fit_model,
    fit_pad,
    read_measurements_csv,
    wj7_example_csv,
)

TRUE_BASE = FractionalZener(3e7, 6e8, 1e-7, 0.35)
TRUE_WLF = WLF(8.064, 111.6, 20.0)  # docs/reference-values.md §4: Tg = -40 degC at 20 degC


def synthetic(freqs=None, temps=None):
    freqs = np.geomspace(0.1, 100.0, 10) if freqs is None else freqs  # DMA-like window
    temps = np.arange(-40.0, 20.1, 5.0) if temps is None else temps
    pad = TemperatureShifted(TRUE_BASE, TRUE_WLF, 20.0)
    t, f = np.meshgrid(temps, freqs, indexing="ij")
    k = np.array([pad.stiffness(freqs, ti) for ti in temps])
    return Measurements(t.ravel(), f.ravel(), k.real.ravel(), k.imag.ravel())


def test_fit_recovers_wlf_and_zener_from_noise_free_data():
    fit = fit_pad(synthetic(), "zener", 20.0)
    w, z = fit.master.wlf, fit.model.base
    # Tolerances: noise-free data on 10 points/decade; the only errors are linear
    # interpolation inside the overlaps (shift errors << 0.01 decade) and optimiser
    # tolerances, so 1 % on the WLF constants and 2 % on the model (tau absorbs any
    # residual common shift) are generous.
    assert w.c1 == pytest.approx(8.064, rel=0.01)
    assert w.c2_k == pytest.approx(111.6, rel=0.01)
    assert z.k0_n_per_m == pytest.approx(3e7, rel=0.02)
    assert z.k_inf_n_per_m == pytest.approx(6e8, rel=0.02)
    assert z.tau_s == pytest.approx(1e-7, rel=0.02)
    assert z.alpha == pytest.approx(0.35, rel=0.02)
    assert fit.rms_storage < 1e-3
    assert fit.rms_loss < 1e-3
    # the free shifts lie on the generating law
    assert np.allclose(
        fit.master.free_log_shift,
        TRUE_WLF.log_shift(fit.master.free_shift_temperature_c),
        atol=0.02,
    )


def test_fit_with_given_wlf_from_single_frequency_sweep():
    data = synthetic(freqs=np.array([0.3]), temps=np.arange(-60.0, 20.1, 2.5))
    # universal constants at Tg = -40 degC are the same law as TRUE_WLF (Eqs. 23-25)
    fit = fit_pad(data, "fractional_zener", 20.0, WLF.universal(-40.0))
    z = fit.model.base
    # tolerance: exact WLF given, noise-free data; 1 % covers optimiser tolerance
    for got, true in [
        (z.k0_n_per_m, 3e7),
        (z.k_inf_n_per_m, 6e8),
        (z.tau_s, 1e-7),
        (z.alpha, 0.35),
    ]:
        assert got == pytest.approx(true, rel=0.01)


def test_single_frequency_data_cannot_fit_wlf():
    data = synthetic(freqs=np.array([0.3]))
    with pytest.raises(CaseError, match="give c1 and c2 or the glass transition"):
        build_master_curve(data, 20.0)


def test_master_curve_removes_vertical_factor():
    data = synthetic(freqs=np.array([1.0]), temps=np.array([-10.0, 20.0]))
    m = build_master_curve(data, 20.0, TRUE_WLF)
    a = TRUE_WLF.shift_factor(-10.0)
    assert m.reduced_frequency_hz[0] == pytest.approx(a)
    assert m.storage_n_per_m[0] == pytest.approx(TRUE_BASE.storage(a), rel=1e-12)


@pytest.mark.parametrize(
    "name", ["generalized_maxwell", "spring_damper", "hysteretic", "log_linear", "constant_phase"]
)
def test_every_model_fits_and_reports_residuals(name):
    f = np.geomspace(1.0, 1e4, 40)
    k = TRUE_BASE.stiffness(f)
    fit = fit_model(f, k, name)
    assert fit.model.model_name == name
    assert fit.residual_storage.shape == f.shape
    assert np.isfinite(fit.rms_loss)
    if name == "generalized_maxwell":
        # two branches per decade over the widened band: a Prony series is then a
        # near-continuous relaxation spectrum; 1 % on K' and 2 % on K'' allow for its ripple
        assert fit.rms_storage < 0.01
        assert fit.rms_loss < 0.02


def test_log_linear_fit_recovers_k0_and_exponent():
    pad = LogLinear(3.1e7, 5.0, 0.07, hold_below_f0=False)
    fit = fit_log_linear(pad, 20.0, (1.0, 1000.0), f0_hz=5.0)
    # exact power law: recovery to rounding
    assert fit.model.k0_n_per_m == pytest.approx(3.1e7, rel=1e-10)
    assert fit.model.exponent == pytest.approx(0.07, rel=1e-10)
    assert fit.rms_log10 < 1e-12


def test_shipped_wj7_chain_reproduces_seed_stiffnesses():
    data = read_measurements_csv(wj7_example_csv())
    assert data.temperature_c.size == 33
    assert np.all(data.frequency_hz == 0.3)
    fit = fit_pad(data, "zener", 20.0, WLF.universal(-40.0))
    # tolerance: the synthetic generator honours the seed's 31.0/45.2/70.8 kN/mm within
    # 3.5 % (data/wj7/README.md) and the data carry 1 % noise: 6 %
    for t, k in [(20.0, 31.0e6), (-10.0, 45.2e6), (-30.0, 70.8e6)]:
        ll = fit_log_linear(fit.model, t, (1.0, 1000.0), f0_hz=5.0)
        assert ll.model.k0_n_per_m == pytest.approx(k, rel=0.06)
        assert ll.model.exponent == pytest.approx(0.07, abs=0.012)  # generator 0.063-0.074


def test_csv_reader_units_and_loss_factor(tmp_path):
    p = tmp_path / "d.csv"
    p.write_text(
        "# comment\ntemperature_c,frequency_hz,storage_kn_per_mm,loss_factor\n20,1,31,0.1\n"
    )
    m = read_measurements_csv(p)
    assert m.storage_n_per_m[0] == 31e6
    assert m.loss_n_per_m[0] == pytest.approx(3.1e6)
    p.write_text("temperature_c,frequency_hz,storage_n_per_m\n20,1,3e7\n")
    with pytest.raises(CaseError, match="data.loss_n_per_m"):
        read_measurements_csv(p)
    p.write_text("temperature_c,frequency_hz,storage_n_per_m,loss_n_per_m\n20,1,3e7,-1\n")
    with pytest.raises(CaseError, match=r"measurements.loss_n_per_m\[0\] = -1.0"):
        read_measurements_csv(p)


def test_a_parameter_ending_at_a_search_bound_is_noted():
    # a standard (alpha = 1) Zener solid: the fractional order is pushed to its bound 1
    f = np.geomspace(1.0, 1000.0, 40)
    standard = FractionalZener(3e7, 3e8, 1e-3, 1.0)
    fit = fit_model(f, standard.stiffness(f), "zener")
    assert fit.model.alpha == pytest.approx(1.0, abs=1e-4)  # the optimiser stays inside
    assert fit.notes == (
        "alpha = 1 ended at its upper search bound (1): the data push it there, so this model "
        "may not suit them",
    )
    assert f"note: {fit.notes[0]}" in fit.summary()


def test_no_note_when_the_fit_is_inside_its_bounds():
    f = np.geomspace(1.0, 1000.0, 40)
    fit = fit_model(f, TRUE_BASE.stiffness(f), "zener")
    assert fit.notes == ()
