"""A new pad model and a new spectrum are one class each: defined here, used everywhere.

Nothing outside this file is touched: the toy members register themselves, and
the case file, its validation, the template, the model docs and the hypothesis
strategies all pick them up from their declarations.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from hypothesis import find, given, settings

import railvib
from railvib.case.template import render_template
from railvib.models import models_markdown
from railvib.pads import PADS, PadModel, SpringDamper, pad_from_dict, pad_to_dict
from railvib.registry import parameter
from railvib.spectra import SPECTRA, SpatialSpectrum
from railvib.testing.strategies import pad_tables


@dataclass(frozen=True)
class ToySeries(PadModel):
    """Toy pad: two springs in series, viscous damping in parallel."""

    k1_n_per_m: float = parameter("N/m", "first spring", gt=0.0, typical=(5e7, 5e8), log=True)
    k2_n_per_m: float = parameter("N/m", "second spring", gt=0.0, typical=(5e7, 5e8), log=True)
    damping_ns_per_m: float = parameter(
        "N s/m", "damping", default=0.0, ge=0.0, typical=(1e3, 1e5), log=True
    )

    @property
    def series_stiffness(self) -> float:
        return self.k1_n_per_m * self.k2_n_per_m / (self.k1_n_per_m + self.k2_n_per_m)

    def stiffness(self, f, temperature=None):
        f = np.asarray(f, dtype=float)
        return self.series_stiffness + 2j * np.pi * f * self.damping_ns_per_m


@dataclass(frozen=True)
class ToyFlat(SpatialSpectrum):
    """Toy spectrum: the same PSD at every wavenumber."""

    level_m2_per_rad_per_m: float = parameter("m^2/(rad/m)", "PSD level", gt=0.0)

    def psd(self, wavenumber):
        return np.full(np.shape(wavenumber), self.level_m2_per_rad_per_m)


@pytest.fixture
def toys():
    PADS.register("toy_series")(ToySeries)
    SPECTRA.register("toy_flat")(ToyFlat)
    yield
    PADS.unregister("toy_series")
    SPECTRA.unregister("toy_flat")


CASE_TOML = """
preset = "wang2017_metro"
speed_kmh = 72.0

[track.pad]
model = "toy_series"
k1_n_per_m = 1.0e8
k2_n_per_m = 4.0e8
damping_ns_per_m = 5.0e4

[irregularity]
type = "toy_flat"
level_m2_per_rad_per_m = 2.0e-9

[frequency]
f_min = 1.0
f_max = 300.0
step = 1.0
"""


def test_a_case_file_uses_the_toy_models(toys, tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(CASE_TOML)
    ds = railvib.run(railvib.load_case(path))
    # closed form of the temporal PSD of a flat spatial PSD: S_t = 2 pi / v * S, v = 20 m/s
    np.testing.assert_allclose(ds.irregularity_psd.values, 2 * np.pi / 20.0 * 2.0e-9, rtol=1e-15)
    # two springs in series: 1e8 * 4e8 / 5e8 = 8e7 N/m, the same as a single 8e7 N/m spring
    equivalent = railvib.case_from_dict(
        {
            "preset": "wang2017_metro",
            "speed_kmh": 72.0,
            "track": {
                "pad": {
                    "model": "spring_damper",
                    "stiffness_n_per_m": 8.0e7,
                    "damping_ns_per_m": 5.0e4,
                }
            },
            "irregularity": {"type": "toy_flat", "level_m2_per_rad_per_m": 2.0e-9},
            "frequency": {"f_min": 1.0, "f_max": 300.0, "step": 1.0},
        }
    )
    ref = railvib.run(equivalent)
    # 1e-12: 1e8*4e8/5e8 and 8e7 may differ in the last bit; the solve is well conditioned
    np.testing.assert_allclose(ds.psd_acceleration, ref.psd_acceleration, rtol=1e-12)


def test_the_toy_pad_is_validated_from_its_declarations(toys):
    with pytest.raises(railvib.CaseError) as err:
        pad_from_dict({"model": "toy_series", "k1_n_per_m": -1.0, "k2_n_per_m": 1e8})
    assert str(err.value) == "track.pad.k1_n_per_m = -1.0: must be > 0.0 (N/m)"
    with pytest.raises(railvib.CaseError, match=r"track\.pad\.k2_n_per_m = '<missing>': required"):
        pad_from_dict({"model": "toy_series", "k1_n_per_m": 1e8})
    with pytest.raises(railvib.CaseError, match=r"track\.pad\.k3 = 1: unknown key"):
        pad_from_dict({"model": "toy_series", "k1_n_per_m": 1e8, "k2_n_per_m": 1e8, "k3": 1})
    with pytest.raises(railvib.CaseError, match=r"k1_n_per_m = 'stiff': must be a finite number"):
        ToySeries("stiff", 1e8)  # the Python constructor checks the same declarations
    pad = ToySeries(1e8, 4e8, 5e4)
    assert pad_to_dict(pad) == {
        "model": "toy_series",
        "k1_n_per_m": 1e8,
        "k2_n_per_m": 4e8,
        "damping_ns_per_m": 5e4,
    }
    assert pad_from_dict(pad_to_dict(pad)) == pad


def test_the_toy_models_appear_in_the_docs_and_the_template(toys):
    text = models_markdown()
    assert "### `toy_series`" in text
    assert "| `k1_n_per_m` | N/m | required | > 0.0 | first spring |" in text
    assert "### `toy_flat`" in text
    assert "toy_series" in render_template()  # listed among the pad models


def test_unregistered_toys_are_gone(toys):
    PADS.unregister("toy_series")
    with pytest.raises(railvib.CaseError, match=r"track\.pad\.model = 'toy_series': one of"):
        pad_from_dict({"model": "toy_series", "k1_n_per_m": 1e8, "k2_n_per_m": 1e8})
    PADS.register("toy_series")(ToySeries)  # the fixture removes it again


def test_the_strategies_draw_the_toy_pad(toys):
    seen = []

    @settings(max_examples=60, deadline=None, database=None)
    @given(table=pad_tables())
    def draw(table):
        seen.append(table["model"])
        pad = pad_from_dict(table)
        if table["model"] == "toy_series":
            assert isinstance(pad, ToySeries)
            assert 5e7 <= pad.k1_n_per_m <= 5e8

    draw()
    assert seen  # the property above ran
    # the toy pad is drawn at all (a search, not the 60 draws above: the oldest hypothesis
    # allowed, 6.100, missed it in 60 draws at the CI's lower bounds)
    toy = find(
        pad_tables(),
        lambda table: table["model"] == "toy_series",
        settings=settings(max_examples=2000, database=None),
    )
    assert isinstance(pad_from_dict(toy), ToySeries)


def test_a_member_name_is_registered_once(toys):
    with pytest.raises(ValueError, match="registered already"):
        PADS.register("toy_series")(ToySeries)
    with pytest.raises(TypeError, match="must subclass PadModel"):
        PADS.register("not_a_pad")(SpringDamper.__mro__[-1])
