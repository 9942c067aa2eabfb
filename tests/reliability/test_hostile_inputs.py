"""Hostile inputs (issue 11, part B): each is one line, exit 2, no traceback, nothing written.

The corpus below holds every bad input of the issue's fuzzing that used to end in a
traceback (``UnicodeDecodeError``, ``RecursionError``, ``MemoryError``,
``OverflowError``, ``TypeError``, a netCDF ``ValueError``), a misleading message
(``vehicle.wheels`` for a bogie spacing, ``K* = nan+nanj`` near the WLF singularity,
the first line of ``/etc/passwd``) or a silent no-op (a sweep axis over ``preset``).
Each runs the command in process through :func:`railvib.cli.main.main` (any exception
other than a handled one would escape it and fail the test) and must answer with
exactly one line ``error: ...`` naming the field or file, exit code 2, and leave the
folder as it was. Where the check belongs to validation, a Python-API test shows that
the library refuses it too, not only the command line.
"""

import os
import sys

import numpy as np
import pytest
import tomli_w

from railvib.case import case_from_dict
from railvib.case.schema import MAX_RMS_BANDS, Case
from railvib.cli.main import main
from railvib.errors import CaseError
from railvib.grid import MAX_GRID_SIZE, FrequencyGrid
from railvib.io import MAX_NESTING, MAX_TABLE_BYTES, MAX_TOML_BYTES
from railvib.pads import PADS, SpringDamper, fit_model, wj7_example_csv
from railvib.pads.tts import MAX_LOG10_SHIFT, TTS_PARAMETERS, WLF, TemperatureShifted
from railvib.registry import MAX_MEMBER_DEPTH, declared_parameters
from railvib.spectra import SPECTRA, Combined
from railvib.spectra.shitai import ShiTai
from railvib.spectra.tabulated import Tabulated
from railvib.sweep import sweep_from_dict
from railvib.track import TRACKS, Rail
from railvib.vehicle import VEHICLES

CASE = 'preset = "wang2017_metro"\n'
#: a small, valid irregularity table (wavelengths 0.1-10 m)
TABLE = "wavelength_m,psd_m2_per_cycle_per_m\n10.0,1e-5\n1.0,1e-7\n0.1,1e-9\n"
#: latin-1 text: "°" is 0xb0, not UTF-8 (a spreadsheet's export)
LATIN1_TABLE = "wavelength_m,psd_m2_per_cycle_per_m\n# 20 \xb0C\n10.0,1e-5\n1.0,1e-7\n".encode(
    "latin-1"
)
LATIN1_MEASUREMENTS = (
    "temperature_c,frequency_hz,storage_kn_per_mm,loss_factor\n# Pr\xfcfung\n20,1,31,0.1\n"
).encode("latin-1")


def _irregularity(**table):
    return CASE + "[irregularity]\n" + tomli_w.dumps(table)


def _sweep(**over):
    d = {"case": {"preset": "wang2017_metro"}, "axes": [{"field": "speed_kmh", "values": [40.0]}]}
    d.update(over)
    return tomli_w.dumps(d)


def _deep_combined(depth):
    lines = [CASE]
    head = "irregularity"
    for _ in range(depth):
        lines += [f"[{head}]", 'type = "combined"', f"[{head}.short_wave]", 'type = "shitai"']
        head += ".long_wave"
    lines += [f"[{head}]", 'type = "shitai"']
    return "\n".join(lines) + "\n"


def _tts_case(temperature):
    return CASE + tomli_w.dumps(
        {
            "track": {
                "pad_temperature_c": temperature,
                "pad": {
                    "model": "spring_damper",
                    "stiffness_n_per_m": 5e7,
                    "damping_ns_per_m": 5e4,
                    "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -10.0},
                },
            }
        }
    )


def _run(name="case.toml"):
    return ["run", name, "-o", "out", "--no-plots"]


def _sweep_cmd(name="sweep.toml"):
    return ["sweep", name, "-o", "out", "--no-progress", "-j", "1"]


def _pad_fit(name="data.csv", *extra):
    return ["pad", "fit", name, "-o", "out", "--tg", "-40", *extra]


#: id -> (files {name: text or bytes}, command line, what the line must name, what it must not)
CORPUS = {
    # ---- item 1: non-UTF-8 or binary input
    "case-latin1": (
        {"case.toml": CASE.encode() + b'title = "20 \xb0C"\n'},
        _run(),
        ("case.toml", "not UTF-8", f"offset {len(CASE) + 12} (line 2)"),  # after 'title = "20 '
        (),
    ),
    "sweep-latin1": (
        {"sweep.toml": _sweep().encode() + b'title = "\xe9t\xe9"\n'},
        _sweep_cmd(),
        ("sweep.toml", "not UTF-8"),
        (),
    ),
    "sweep-base-latin1": (
        {
            "sweep.toml": 'base = "case.toml"\n[[axes]]\nfield = "speed_kmh"\nvalues = [40.0]\n',
            "case.toml": CASE.encode() + b'title = "\xb0"\n',
        },
        _sweep_cmd(),
        ("case.toml", "not UTF-8"),
        (),
    ),
    "irregularity-latin1": (
        {"case.toml": _irregularity(type="tabulated", path="t.csv"), "t.csv": LATIN1_TABLE},
        _run(),
        ("irregularity.path", "t.csv", "not UTF-8", "line 2"),
        (),
    ),
    "irregularity-binary": (
        {
            "case.toml": _irregularity(type="tabulated", path="t.bin"),
            "t.bin": bytes(range(256)) * 4,
        },
        _run(),
        ("irregularity.path", "binary"),
        (),
    ),
    "pad-csv-latin1": (
        {"data.csv": LATIN1_MEASUREMENTS},
        _pad_fit(),
        ("data.csv", "not UTF-8", "line 2"),
        (),
    ),
    # ---- item 2: deep nesting
    "array-3000-deep": (
        {"case.toml": CASE + "title = " + "[" * 3000 + "]" * 3000 + "\n"},
        _run(),
        ("case.toml", f"at most {MAX_NESTING} levels"),
        (),
    ),
    "inline-table-3000-deep": (
        {"case.toml": CASE + "x = " + "{a = " * 3000 + "1" + "}" * 3000 + "\n"},
        _run(),
        ("case.toml", f"at most {MAX_NESTING} levels"),
        (),
    ),
    "table-header-5000-deep": (
        {"case.toml": CASE + "[" + ".".join(["a"] * 5000) + "]\nx = 1\n"},
        _run(),
        ("a.a.a.a", f"at most {MAX_NESTING} levels"),
        (),
    ),
    "combined-spectrum-500-deep": (
        {"case.toml": _deep_combined(500)},
        _run(),
        ("irregularity.long_wave.long_wave",),
        (),
    ),
    "combined-spectrum-20-deep": (  # within the TOML limit: refused by the spectra's own
        {"case.toml": _deep_combined(20)},
        _run(),
        ("irregularity.long_wave.long_wave", f"nested at most {MAX_MEMBER_DEPTH} deep"),
        (),
    ),
    "sweep-array-3000-deep": (
        {"sweep.toml": _sweep() + "variables = " + "[" * 3000 + "]" * 3000 + "\n"},
        _sweep_cmd(),
        ("sweep.toml", f"at most {MAX_NESTING} levels"),
        (),
    ),
    # ---- item 3: sizes
    "grid-n-1e12": (
        {"case.toml": CASE + '[frequency]\nspacing = "log"\nn = 1000000000000\n'},
        _run(),
        ("frequency.n",),
        (),
    ),
    "grid-step-1e-9": (
        {"case.toml": CASE + "[frequency]\nstep = 1e-9\n"},
        _run(),
        ("frequency.step", "2,000,000"),
        (),
    ),
    "grid-step-1e-9-forced": (
        {"case.toml": CASE + "[frequency]\nstep = 1e-9\n"},
        [*_run(), "--force"],
        ("frequency.step", f"{MAX_GRID_SIZE:,}", "even with --force"),
        (),
    ),
    "grid-step-5e-324-forced": (  # the count overflows an integer
        {"case.toml": CASE + "[frequency]\nstep = 5e-324\n"},
        [*_run(), "--force"],
        ("frequency.step",),
        (),
    ),
    "sweep-num-1e9": (
        {
            "sweep.toml": _sweep(
                axes=[{"field": "speed_kmh", "start": 10.0, "stop": 100.0, "num": 10**9}]
            )
        },
        _sweep_cmd(),
        ("axes[0].num",),
        (),
    ),
    "sweep-step-1e-9": (
        {
            "sweep.toml": _sweep(
                axes=[{"field": "speed_kmh", "start": 10.0, "stop": 100.0, "step": 1e-9}]
            )
        },
        _sweep_cmd(),
        ("axes[0].step", "values per axis"),
        (),
    ),
    "sweep-1e8-cases": (
        {
            "sweep.toml": _sweep(
                axes=[
                    {"field": "speed_kmh", "start": 10.0, "stop": 100.0, "num": 10_000},
                    {"field": "track.sleeper_spacing", "start": 0.5, "stop": 0.7, "num": 10_000},
                ]
            )
        },
        _sweep_cmd(),
        ("axes", "at most 1,000,000 cases"),
        (),
    ),
    "irregularity-dev-zero": (
        {"case.toml": _irregularity(type="tabulated", path="/dev/zero")},
        _run(),
        ("irregularity.path", "/dev/zero", "regular file"),
        (),
    ),
    "irregularity-too-large": (
        {"case.toml": _irregularity(type="tabulated", path="big.csv"), "big.csv": "sparse"},
        _run(),
        ("irregularity.path", "big.csv", f"at most {MAX_TABLE_BYTES / 2**20:g} MiB"),
        (),
    ),
    "case-too-large": (
        {"case.toml": CASE + "#" * MAX_TOML_BYTES + "\n"},
        _run(),
        ("case.toml", f"at most {MAX_TOML_BYTES / 2**20:g} MiB"),
        (),
    ),
    "rms-bands-too-many": (
        {"case.toml": CASE + "[output]\nrms_bands = " + str([[1.0, 900.0]] * 10**4) + "\n"},
        _run(),
        ("output.rms_bands", f"at most {MAX_RMS_BANDS} bands"),
        (),
    ),
    # ---- item 4: overflow and odd values
    "f-max-1e30": (
        {"case.toml": CASE + "[frequency]\nf_max = 1e30\nstep = 1e28\n"},
        _run(),
        ("frequency.f_max",),
        (),
    ),
    "sleeper-spacing-100": (
        {"case.toml": CASE + "[track]\nsleeper_spacing = 100.0\n"},
        _run(),
        ("track.sleeper_spacing",),
        (),
    ),
    "sleeper-spacing-1e300": (
        {"case.toml": CASE + "[track]\nsleeper_spacing = 1e300\n"},
        _run(),
        ("track.sleeper_spacing",),
        (),
    ),
    "pad-stiffness-1e300": (
        {"case.toml": CASE + "[track.pad]\nstiffness_n_per_m = 1e300\n"},
        _run(),
        ("track.pad.stiffness_n_per_m",),
        (),
    ),
    "bogie-half-spacing-1e300": (
        {"case.toml": CASE + "[vehicle]\nbogie_half_spacing = 1e300\n"},
        _run(),
        ("vehicle.bogie_half_spacing",),
        ("vehicle.wheels",),
    ),
    "speed-1e300": (
        {"case.toml": CASE + "speed_kmh = 1e300\n"},
        _run(),
        ("speed_kmh",),
        (),
    ),
    "rail-bending-stiffness-1e-30": (  # legal alone; the bay's series cannot hold 1 kHz
        {"case.toml": CASE + "[track.rail]\nbending_stiffness = 1e-30\n"},
        _run(),
        ("frequency.f_max", "for this rail and sleeper spacing"),
        (),
    ),
    "title-nul": (
        {"case.toml": CASE + 'title = "a\\u0000b"\n'},
        _run(),
        ("title", "U+0000"),
        (),
    ),
    "title-line-break": (
        {"case.toml": CASE + 'title = "a\\nb"\n'},
        _run(),
        ("title", "U+000A"),
        (),
    ),
    "sweep-title-nul": (
        {"sweep.toml": _sweep(title="a\x00b")},
        _sweep_cmd(),
        ("title", "U+0000"),
        (),
    ),
    "pad-fit-n-terms-negative": (
        {},
        [
            "pad",
            "fit",
            str(wj7_example_csv()),
            "-o",
            "out",
            "--tg",
            "-40",
            "--model",
            "generalized_maxwell",
            "--n-terms",
            "-3",
        ],
        ("--n-terms",),
        (),
    ),
    "csv-delimiter-two-characters": (
        {
            "case.toml": _irregularity(type="tabulated", path="t.csv", delimiter=";;"),
            "t.csv": TABLE,
        },
        _run(),
        ("irregularity.delimiter",),
        (),
    ),
    "csv-delimiter-integer": (
        {"case.toml": _irregularity(type="tabulated", path="t.csv", delimiter=5), "t.csv": TABLE},
        _run(),
        ("irregularity.delimiter",),
        (),
    ),
    # ---- item 5: WLF at and near its singularity (Tg = -10 degC: T0 - C2 = -61.6 degC)
    "wlf-at-the-singularity": (
        {"case.toml": _tts_case(-61.6)},
        _run(),
        ("track.pad_temperature_c", "-61.6", "singular"),
        ("nan",),
    ),
    "wlf-where-a-t-overflows": (
        {"case.toml": _tts_case(-59.0)},
        _run(),
        ("track.pad_temperature_c", "-59.0", f"{MAX_LOG10_SHIFT:g} decades"),
        ("nan",),
    ),
    # ---- item 6: no file contents in messages
    "irregularity-etc-passwd": (
        {"case.toml": _irregularity(type="tabulated", path="passwd")},
        _run(),
        ("irregularity.path", "not such a table"),
        ("root", "/bin/"),
    ),
    "irregularity-long-unknown-column": (
        {
            "case.toml": _irregularity(type="tabulated", path="t.csv"),
            "t.csv": "wavelength_m," + "secret" * 50 + "\n1,2\n3,4\n",
        },
        _run(),
        ("irregularity.column", "secretsecret"),
        ("secret" * 5,),
    ),
    "measurements-not-a-table": (
        {"data.csv": "root:x:0:0:root:/root:/bin/bash\ndaemon:x:1:1::/usr/sbin/nologin\n"},
        _pad_fit(),
        ("data.csv", "header row"),
        ("/bin/bash", "daemon"),
    ),
    # ---- item 7: a sweep axis over preset
    "sweep-axis-preset": (
        {
            "sweep.toml": _sweep(
                axes=[{"field": "preset", "values": ["wang2017_metro", "wang2017_temp_m10c"]}]
            )
        },
        _sweep_cmd(),
        ("axes[0].field", "preset", "would change nothing", "track.*"),
        (),
    ),
}


def _make(tmp_path, files):
    for name, content in files.items():
        path = tmp_path / name
        if name == "big.csv":  # a sparse file: larger than the limit, without writing it
            with open(path, "wb") as fh:
                fh.truncate(MAX_TABLE_BYTES + 1)
        elif isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content, encoding="utf-8")


def _listing(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


#: inputs that take over a second (the 500-deep spectrum is a 2.6 MB file of table headers)
SLOW = {"combined-spectrum-500-deep"}


@pytest.mark.parametrize(
    ("files", "argv", "names", "absent"),
    [
        pytest.param(*entry, id=name, marks=[pytest.mark.slow] if name in SLOW else [])
        for name, entry in CORPUS.items()
    ],
)
def test_hostile_input_is_one_line_exit_2_and_writes_nothing(
    files, argv, names, absent, tmp_path, monkeypatch, capsys
):
    _make(tmp_path, files)
    if "passwd" in str(files):
        os.symlink("/etc/passwd", tmp_path / "passwd")
    monkeypatch.chdir(tmp_path)
    before = _listing(tmp_path)
    assert main(argv) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err[-2000:]
    line = lines[0]
    assert line.startswith("error: "), line
    assert "Traceback" not in captured.err + captured.out
    for name in names:
        assert name in line, f"{line!r} does not name {name!r}"
    for text in absent:
        assert text not in line, f"{line!r} shows {text!r}"
    assert len(line) < 600, line  # one readable line, not a dump
    assert _listing(tmp_path) == before  # no output folder, no temporary


def test_a_fifo_as_the_irregularity_table_is_refused_without_waiting(tmp_path):
    os.mkfifo(tmp_path / "pipe.csv")  # opening it for reading would block until a writer
    case = {"preset": "wang2017_metro", "irregularity": {"type": "tabulated", "path": "pipe.csv"}}
    with pytest.raises(CaseError, match="regular file") as info:
        case_from_dict(case, base_dir=tmp_path)
    assert info.value.field == "irregularity.path"


# ------------------------------------------------------------------ the Python API refuses too


def _nested(depth):
    d = {"x": 1}
    for _ in range(depth):
        d = {"a": d}
    return d


def test_case_from_dict_refuses_deep_nesting_before_it_recurses():
    assert sys.getrecursionlimit() < 5000  # so the dict below would overflow a recursion
    with pytest.raises(CaseError, match=f"at most {MAX_NESTING} levels"):
        case_from_dict({"preset": "wang2017_metro", "extra": _nested(5000)})
    with pytest.raises(CaseError, match=f"at most {MAX_NESTING} levels"):
        sweep_from_dict({"case": _nested(5000), "axes": []})


def test_spectra_nested_too_deep_are_refused_from_tables_and_objects():
    table = {"type": "shitai"}
    for _ in range(500):
        table = {"type": "combined", "long_wave": table, "short_wave": {"type": "shitai"}}
    with pytest.raises(CaseError, match=f"nested at most {MAX_MEMBER_DEPTH} deep"):
        SPECTRA.from_dict(table, "irregularity")
    spectrum = ShiTai()
    for _ in range(MAX_MEMBER_DEPTH):
        spectrum = Combined(spectrum, ShiTai())
    assert spectrum.depth == MAX_MEMBER_DEPTH  # at the limit: accepted
    with pytest.raises(CaseError, match="long_wave"):
        Combined(spectrum, ShiTai())


def test_frequency_grid_refuses_sizes_before_allocating():
    with pytest.raises(CaseError, match="frequency.step"):
        FrequencyGrid.linear(0.5, 1000.0, 1e-9)
    with pytest.raises(CaseError, match="frequency.n"):
        FrequencyGrid.logarithmic(0.5, 1000.0, 10**12)
    assert len(FrequencyGrid.linear(0.5, 1000.0, 0.5)) == 2000  # (1000 - 0.5) / 0.5 + 1


def test_tabulated_spectrum_checks_its_delimiter(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text(TABLE.replace(",", ";"))
    assert Tabulated.from_csv(path, delimiter=";").wavenumber_rad_per_m.size == 3
    for bad in (";;", 5, "", "\n", ".", "e"):
        with pytest.raises(CaseError, match="delimiter"):
            Tabulated.from_csv(path, delimiter=bad)


def test_fit_model_checks_the_number_of_prony_branches():
    f = np.array([1.0, 10.0, 100.0])
    k = np.array([3e7 + 3e6j, 4e7 + 4e6j, 5e7 + 5e6j])
    for bad in (-3, 0, 51, 2.5):
        with pytest.raises(CaseError, match="n_terms"):
            fit_model(f, k, "generalized_maxwell", n_terms=bad)


def _number_parameters():
    """(where, Parameter) of every number a case table can hold, nested tables included."""
    found = []

    def walk(where, params):
        for p in params:
            if p.kind in ("number", "numbers", "integer") and p.choices is None:
                found.append((f"{where}.{p.key}", p))
            if p.kind == "table" and p.table is not None:
                walk(f"{where}.{p.key}", declared_parameters(p.table))

    for family in (PADS, SPECTRA, TRACKS, VEHICLES):
        for member in family:
            walk(f"{family.tag}={member.name}", member.parameters)
    walk("tts", TTS_PARAMETERS)
    return found


@pytest.mark.parametrize(
    ("where", "p"), _number_parameters(), ids=lambda x: x if isinstance(x, str) else ""
)
def test_every_declared_number_has_finite_bounds(where, p):
    lower = p.gt if p.gt is not None else p.ge
    upper = p.lt if p.lt is not None else p.le
    assert lower is not None, f"{where}: no lower bound"
    assert upper is not None, f"{where}: no upper bound"
    assert np.isfinite([lower, upper]).all(), where


def _case_numbers(model, prefix=""):
    for name, info in model.model_fields.items():
        annotation = info.annotation
        if hasattr(annotation, "model_fields"):
            yield from _case_numbers(annotation, f"{prefix}{name}.")
        elif annotation in (float, float | None):
            yield f"{prefix}{name}", info


@pytest.mark.parametrize(
    ("field", "info"), list(_case_numbers(Case)), ids=lambda x: x if isinstance(x, str) else ""
)
def test_every_case_number_has_an_upper_bound(field, info):
    uppers = [getattr(m, "le", None) or getattr(m, "lt", None) for m in info.metadata]
    assert any(u is not None and np.isfinite(u) for u in uppers), f"{field}: no upper bound"


# ------------------------------------------------------------------ WLF near its singularity


def test_wlf_refuses_the_singular_temperature_for_every_glass_transition():
    # before, the check was made after a round trip through kelvin: 153 of these 801
    # let T = T0 - C2 through, returning log10 a_T ~ 1e17 instead of raising
    refused = 0
    for tg in np.linspace(-80.0, 0.0, 801):
        wlf = WLF.universal(float(tg))
        with pytest.raises(CaseError, match="singular"):
            wlf.log_shift(float(tg) - 51.6)
        refused += 1
    assert refused == 801


def test_wlf_matches_its_closed_form_up_to_the_limit_and_refuses_beyond():
    wlf = WLF.universal(-10.0)  # C1 = 17.44, C2 = 51.6 K, T0 = -10 degC
    # hand values of log10 a_T = -C1 (T - T0) / (C2 + T - T0)
    for t, expected in ((20.0, -17.44 * 30.0 / 81.6), (-30.0, 17.44 * 20.0 / 31.6)):
        assert wlf.log_shift(t) == pytest.approx(expected, rel=1e-14)  # a few roundings
    # the limit |log10 a_T| = 100 at T - T0 = -100 C2 / (C1 + 100) (solving the formula)
    t_lo = -10.0 - 100.0 * 51.6 / 117.44
    assert wlf.temperature_limits_c[0] == pytest.approx(t_lo, rel=1e-14)
    assert wlf.log_shift(t_lo + 1e-9) == pytest.approx(100.0, rel=1e-6)  # just inside
    for t in (t_lo - 1e-6, -59.0, -61.0, np.nextafter(-61.6, 0.0)):
        with pytest.raises(CaseError, match=f"more than {MAX_LOG10_SHIFT:g} decades") as info:
            wlf.log_shift(t)
        assert info.value.value == pytest.approx(t)
    # the pad's stiffness is finite at every temperature accepted, and refused beyond
    pad = TemperatureShifted(SpringDamper(5e7, 5e4), WLF.universal(-40.0), 20.0)
    assert np.all(np.isfinite(pad.stiffness([1.0, 1e3, 1e5], -83.0)))
    with pytest.raises(CaseError, match="temperature"):
        pad.stiffness([10.0], -85.0)


def test_a_case_at_the_wlf_singularity_is_refused_when_it_loads():
    text = _tts_case(-61.6).removeprefix(CASE)
    import tomllib

    data = {"preset": "wang2017_metro", **tomllib.loads(text)}
    with pytest.raises(CaseError) as info:
        case_from_dict(data)
    assert info.value.field == "track.pad_temperature_c"


def test_bogie_spacing_is_named_itself():
    with pytest.raises(CaseError) as info:
        case_from_dict({"preset": "wang2017_metro", "vehicle": {"bogie_half_spacing": 1e300}})
    assert info.value.field == "vehicle.bogie_half_spacing"


def test_a_rail_whose_bay_series_would_overflow_names_the_frequency_limit():
    from railvib.track import PeriodicTrack

    track = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7), 0.6)
    # (40^4 EI / (m d^4))^(1/2) / (2 pi): the bending wavenumber times d reaches 40
    limit = (40.0**4 * 6.62e6 / (60.64 * 0.6**4)) ** 0.5 / (2 * np.pi)
    assert track.max_frequency_hz == pytest.approx(limit, rel=1e-12)
    with pytest.raises(CaseError, match="frequency.f_max"):
        track.receptance([1.01 * limit], [0.3], [0.3])
