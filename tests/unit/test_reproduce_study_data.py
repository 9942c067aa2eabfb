"""The paper's study data file (reproduce/paper_wang2017.toml) and its loader.

Paper: Wang, Yang, Wei, Zhou, "Stationary random vibration analysis of vehicle-track
coupled system with nonlinear stiffness of railpads", J. Vibroengineering 19(6), 2017,
DOI 10.21595/jve.2017.17947. Expected values in the spot checks are the paper's printed
numbers (cited per test), not output of the code.
"""

import copy
import inspect
import tomllib
from importlib import resources
from types import MappingProxyType

import pytest
import tomli_w

from railvib.errors import CaseError
from railvib.presets import list_presets
from railvib.reproduce.metrics import METRICS
from railvib.reproduce.study import (
    CASES,
    COMPARISONS,
    DATA_FILE,
    FIGURES,
    PAPER_NUMBERS,
    load_study,
)

CASE_KEYS = {c.key for c in CASES}
NUMBERS = {n.id: n for n in PAPER_NUMBERS}


def _shipped() -> dict:
    text = resources.files("railvib.reproduce").joinpath(DATA_FILE).read_text(encoding="utf-8")
    return tomllib.loads(text)


def test_identifiers_are_unique():
    for keys in (
        [n.id for n in PAPER_NUMBERS],
        [c.key for c in CASES],
        [c.key for c in COMPARISONS],
        [(f.number, f.comparison) for f in FIGURES],
    ):
        assert len(keys) == len(set(keys)), keys


def test_the_study_covers_figs_9_to_16():
    # Wang et al. 2017, §3.3 (Figs. 9-12) and §3.4 (Figs. 13-16); Figs. 13-16 once more on
    # the pads predicted by its §3.2 procedure
    assert [f.number for f in FIGURES] == [*range(9, 17), *range(13, 17)]
    assert [f.comparison for f in FIGURES[8:]] == ["predicted"] * 4
    stems = [f.stem for f in FIGURES]
    assert len(set(stems)) == len(stems)  # one file per figure


def test_fig8_rows_are_the_papers_stated_pad_law():
    # Wang et al. 2017, §3.2.3: slope 0.07 at -30, -10 and +20 °C; initial stiffness 70.8,
    # 45.2 and 31.0 kN/mm (paired physically, docs/paper-interpretation.md), read off the
    # predicted pads of those temperatures
    for key, k0 in (("m30", 70.8), ("m10", 45.2), ("p20", 31.0)):
        assert NUMBERS[f"fig8.k0.{key}"].paper == k0
        assert NUMBERS[f"fig8.kappa.{key}"].paper == 0.07
        assert NUMBERS[f"fig8.k0.{key}"].args["case"] == f"p{key}"
    presets = {c.key: c.preset for c in CASES}
    assert presets["pm30"] == "wang2017_predicted_m30c"
    assert presets["pp20"] == "wang2017_predicted_p20c"


@pytest.mark.parametrize("number", PAPER_NUMBERS, ids=lambda n: n.id)
def test_metric_exists_and_accepts_the_args(number):
    assert number.metric in METRICS
    inspect.signature(METRICS[number.metric]).bind(None, **number.args)  # None: the results


@pytest.mark.parametrize("number", PAPER_NUMBERS, ids=lambda n: n.id)
def test_args_are_immutable(number):
    assert isinstance(number.args, MappingProxyType)
    for key in ("band", "cases"):
        if key in number.args:
            assert isinstance(number.args[key], tuple)
    if "band" in number.args:
        assert all(isinstance(f, float) for f in number.args["band"])
    if number.claim is not None:
        op, bound = number.claim
        assert op in ("<", "<=", ">", ">=")
        assert isinstance(bound, float)
    # a qualitative statement is only checked through its claim
    assert number.paper is not None or number.claim is not None


def test_every_referenced_case_exists():
    for comparison in COMPARISONS:
        assert set(comparison.cases) <= CASE_KEYS, comparison.key
    comparisons = {c.key: c for c in COMPARISONS}
    for figure in FIGURES:
        assert figure.comparison in comparisons
        shown = set(comparisons[figure.comparison].cases)
        assert {p.case for p in figure.paper_points} <= shown, figure.number
    for number in PAPER_NUMBERS:
        referenced = set(number.args.get("cases", ()))
        referenced |= {number.args[k] for k in ("case", "reference") if k in number.args}
        assert referenced, number.id
        assert referenced <= CASE_KEYS, number.id


def test_every_preset_exists():
    presets = set(list_presets())
    for case in CASES:
        assert case.preset in presets, case


def test_every_shared_note_is_used():
    data = _shipped()
    used = set()
    for row in data["number"]:
        note = row.get("note", [])
        used |= {p[1:] for p in ([note] if isinstance(note, str) else note) if p.startswith("@")}
    assert used == set(data["notes"])


def test_fig11_wheelset_peaks():
    # Wang et al. 2017, J. Vibroengineering 19(6), §3.3, Fig. 11: highest 2nd-wheelset PSD
    # 8.82 m^2/s^4/Hz at 47.9 Hz (constant stiffness) and 13.5 m^2/s^4/Hz at 57.1 Hz
    # (frequency-dependent stiffness).
    assert NUMBERS["fig11.peak.constant"].paper == 8.82
    assert NUMBERS["fig11.frequency.constant"].paper == 47.9
    assert NUMBERS["fig11.peak.freqdep"].paper == 13.5
    assert NUMBERS["fig11.frequency.freqdep"].paper == 57.1
    fig11 = next(f for f in FIGURES if f.number == 11)
    assert [(p.case, p.frequency_hz, p.psd) for p in fig11.paper_points] == [
        ("constant", 47.9, 8.82),
        ("freqdep", 57.1, 13.5),
    ]
    # derived from those printed numbers, exactly (not a copied computed value)
    ratio = NUMBERS["fig11.peak_ratio"]
    assert ratio.derived
    assert ratio.paper == 13.5 / 8.82
    shift = NUMBERS["fig11.frequency_shift"]
    assert shift.derived
    assert shift.paper == 57.1 - 47.9


def test_fig15_wheelset_peaks_by_temperature():
    # Wang et al. 2017, §3.4, Fig. 15: 2nd-wheelset peaks 63.4 / 27.5 / 13.1 m^2/s^4/Hz at
    # 73.4 / 63.1 / 50.3 Hz for -30 / -10 / +20 degC.
    for key, peak, freq in (("m30", 63.4, 73.4), ("m10", 27.5, 63.1), ("p20", 13.1, 50.3)):
        assert NUMBERS[f"fig15.peak.{key}"].paper == peak
        assert NUMBERS[f"fig15.frequency.{key}"].paper == freq
    assert NUMBERS["fig15.peak_ratio"].paper == 63.4 / 13.1
    assert NUMBERS["fig15.frequency_shift"].paper == 73.4 - 50.3


def test_fig14_bogie_peak_a_and_abstract():
    # Wang et al. 2017, §3.4, Fig. 14(b): bogie peak A 4.51e-3 / 1.78e-3 / 4.60e-4
    # m^2/s^4/Hz at 71.2 / 70.0 / 70.0 Hz (-30 / -10 / +20 degC); Abstract and
    # Conclusion 4: peak raised "3.3 times at least", dominant frequency by "20.6 Hz".
    for key, psd, freq in (("m30", 4.51e-3, 71.2), ("m10", 1.78e-3, 70.0), ("p20", 4.60e-4, 70.0)):
        assert NUMBERS[f"fig14b.peak_a.{key}"].paper == psd
        assert NUMBERS[f"fig14b.frequency_a.{key}"].paper == freq
    assert NUMBERS["headline.peak_increase"].paper == 3.3
    assert NUMBERS["headline.frequency_increase"].paper == 20.6


# --- the loader on files of our own ------------------------------------------------------


def _write(tmp_path, data, name="bad.toml"):
    path = tmp_path / name
    path.write_text(tomli_w.dumps(data), encoding="utf-8")
    return path


def test_loader_reads_a_copy_of_the_shipped_file(tmp_path):
    study = load_study(_write(tmp_path, _shipped(), "copy.toml"))
    assert study.numbers == PAPER_NUMBERS
    assert study.cases == CASES
    assert study.figures == FIGURES


def _set(path, value):
    def mutate(data):
        *head, last = path
        target = data
        for key in head:
            target = target[key]
        target[last] = value

    return mutate


def _drop(path):
    def mutate(data):
        *head, last = path
        target = data
        for key in head:
            target = target[key]
        del target[last]

    return mutate


@pytest.mark.parametrize(
    ("mutate", "field"),
    [
        (_set(("number", 12, "metric"), "peek"), "number[12].metric"),
        (_set(("number", 3, "colour"), "red"), "number[3].colour"),
        (_drop(("number", 5, "reading")), "number[5].reading"),
        (_set(("number", 0, "args", "bands"), [0.5, 20.0]), "number[0].args.bands"),
        (_drop(("number", 0, "args", "response")), "number[0].args.response"),
        (_set(("number", 1, "args", "case"), "m40"), "number[1].args.case"),
        (_set(("number", 1, "args", "band"), [20.0, 0.5]), "number[1].args.band"),
        (_set(("number", 6, "note"), "@levle"), "number[6].note"),
        (_set(("number", 0, "claim"), ["=", 3.0]), "number[0].claim"),
        (_drop(("number", 0, "claim")), "number[0].claim"),
        (_drop(("number", 10, "paper_expr")), "number[10].paper_expr"),
        (_set(("number", 1, "id"), "fig9.body.spread"), "number[1].id"),
        (_set(("case", 0, "preset"), 3), "case[0].preset"),
        (_set(("comparison", 1, "cases"), ["m30", "m20"]), "comparison[1].cases[1]"),
        (_set(("figure", 2, "response"), "wheelset9.bounce"), "figure[2].response"),
        (_set(("figure", 2, "comparison"), "speed"), "figure[2].comparison"),
        (_drop(("components", "rail")), "components.rail"),
        (_set(("extra",), 1), "(top level).extra"),
    ],
)
def test_malformed_file_names_the_field(tmp_path, mutate, field):
    data = copy.deepcopy(_shipped())
    mutate(data)
    with pytest.raises(CaseError) as info:
        load_study(_write(tmp_path, data))
    assert info.value.field == f"bad.toml: {field}"


def test_unknown_metric_error_lists_the_metrics(tmp_path):
    data = copy.deepcopy(_shipped())
    data["number"][12]["metric"] = "peek"
    with pytest.raises(CaseError, match=r"bad\.toml: number\[12\]\.metric = 'peek': .*peak_ratio"):
        load_study(_write(tmp_path, data))


def test_invalid_toml_and_missing_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[[number]\nid = 1\n", encoding="utf-8")
    with pytest.raises(CaseError, match="valid TOML") as info:
        load_study(bad)
    assert info.value.field == "bad.toml"
    with pytest.raises(CaseError, match="readable"):
        load_study(tmp_path / "absent.toml")
