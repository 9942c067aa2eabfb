"""Plausibility of a validated case: legal but suspicious values warn, huge grids are refused.

A case that passes validation may still hold a value no railway has, most often a
unit slip (kN/mm typed as N/m, a Kelvin temperature typed as degC) or a typo (a
step of 0.0001 Hz). :func:`plausibility_warnings` lists those as
:class:`~railvib.errors.PlausibilityWarning`; the case still runs. A grid too
large to run in reasonable time and memory is refused by :func:`check_grid_size`
unless the caller forces it. Both run where a case is loaded
(:func:`railvib.case.case_from_dict`), from the declarations where the check is
about one field (a field's ``plausible`` range in the schema, e.g. ``speed_kmh``)
and from the built pad where it is about the model (its K' on the grid, its
temperature dependence).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

import numpy as np
from numpy.typing import NDArray
from pydantic import BaseModel

from railvib.case.schema import Case
from railvib.errors import CaseError, PlausibilityWarning
from railvib.grid import MAX_GRID_SIZE, FrequencyGrid
from railvib.pads import PadModel

__all__ = [
    "BYTES_PER_FREQUENCY",
    "MAX_FREQUENCIES",
    "MAX_PAD_STIFFNESS_N_PER_M",
    "MIN_PAD_STIFFNESS_N_PER_M",
    "ROOM_TEMPERATURE_C",
    "SECONDS_PER_FREQUENCY",
    "WARN_FREQUENCIES",
    "check_grid_size",
    "grid_cost",
    "grid_size",
    "physical_memory_bytes",
    "plausibility_warnings",
]

#: storage stiffness K' of one rail seat below which a pad is implausible, N/m (1 kN/mm);
#: railpads are about 10 to 1000 kN/mm
MIN_PAD_STIFFNESS_N_PER_M = 1.0e6
#: K' of one rail seat above which a pad is implausible, N/m (5000 kN/mm)
MAX_PAD_STIFFNESS_N_PER_M = 5.0e9

#: a grid with more frequencies than this loads with a warning
WARN_FREQUENCIES = 1_000_000
#: a grid with more frequencies than this is refused unless forced
MAX_FREQUENCIES = 2_000_000
#: peak memory of one case per frequency, bytes (``benchmarks/bench_startup.py --cost``:
#: 2,021 B from the difference of runs at 1e5 and 3e5 frequencies)
BYTES_PER_FREQUENCY = 2_000
#: wall time of one ``railvib run`` per frequency (solve, files, plots), s (idem: 30 us on
#: two cores; the solve alone is about 10 us)
SECONDS_PER_FREQUENCY = 3.0e-5

#: pad temperatures (degC) taken as recording the temperature a temperature-independent
#: pad's parameters describe (room temperature, where pads are tested); not warned
ROOM_TEMPERATURE_C = (18.0, 28.0)


def grid_size(case: Case) -> int:
    """Number of frequencies of the case's grid, from its ``[frequency]`` table alone.

    Parameters
    ----------
    case : Case
        A validated case.

    Returns
    -------
    int
        The grid's length (the grid is not built).
    """
    fr = case.frequency
    if fr.spacing == "log":
        assert fr.n is not None, "a log grid has n (validated)"
        return int(fr.n)
    assert fr.step is not None, "a linear grid has a step (validated)"
    return FrequencyGrid.linear_size(fr.f_min, fr.f_max, fr.step)


def grid_cost(n_frequencies: float) -> str:
    """What running `n_frequencies` frequencies costs, in words.

    Parameters
    ----------
    n_frequencies : float
        Grid length (a count; a float where it is too large for an integer).

    Returns
    -------
    str
        E.g. ``"about 4.2 GB of memory and 60 s per case"``, from
        :data:`BYTES_PER_FREQUENCY` and :data:`SECONDS_PER_FREQUENCY`.
    """
    memory = _scaled(
        n_frequencies * BYTES_PER_FREQUENCY,
        [(1e15, "PB"), (1e12, "TB"), (1e9, "GB"), (1e6, "MB"), (1e3, "kB"), (1.0, "B")],
    )
    seconds = n_frequencies * SECONDS_PER_FREQUENCY
    when = _scaled(seconds, [(86400.0, "days"), (3600.0, "h"), (60.0, "min"), (1.0, "s")], 2.0)
    return f"about {memory} of memory and {when} per case"


def _scaled(value: float, units: list[tuple[float, str]], at_least: float = 1.0) -> str:
    """`value` in the largest of `units` (factor, name) it reaches `at_least` times."""
    factor, name = next(((f, n) for f, n in units if value >= at_least * f), units[-1])
    scaled = value / factor
    return f"{scaled:,.0f} {name}" if scaled >= 10 else f"{scaled:.2g} {name}"


def _grid_field(case: Case) -> tuple[str, Any]:
    if case.frequency.spacing == "log":
        return "frequency.n", case.frequency.n
    return "frequency.step", case.frequency.step


def physical_memory_bytes() -> int | None:
    """Physical memory of this machine, bytes (None where the system does not tell)."""
    try:
        return int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):  # not POSIX, or no such sysconf name
        return None


def check_grid_size(case: Case, *, force: bool = False) -> None:
    """Refuse a grid of more than :data:`MAX_FREQUENCIES` frequencies unless `force`.

    A forced grid is still refused when the memory it needs (:data:`BYTES_PER_FREQUENCY`
    per frequency) exceeds this machine's physical memory, or when it has more than
    :data:`railvib.grid.MAX_GRID_SIZE` frequencies: it could not run.

    Parameters
    ----------
    case : Case
        A validated case.
    force : bool
        Run a grid of any size that fits in memory (``railvib run --force``).

    Raises
    ------
    CaseError
        ``frequency.step`` (or ``frequency.n``) naming the grid's length, memory and time.
    """
    field, value = _grid_field(case)
    fr = case.frequency
    # counted in floats: a step of 1e-300 Hz gives more frequencies than an int() can take
    n = float(value) if fr.spacing == "log" else np.floor((fr.f_max - fr.f_min) / value + 1e-9) + 1
    if n > MAX_FREQUENCIES and not force:
        raise CaseError(
            field,
            value,
            f"a grid of at most {MAX_FREQUENCIES:,} frequencies; this one has {n:,.0f} "
            f"({grid_cost(n)}); pass force=True (railvib run --force) to run it anyway",
        )
    memory = physical_memory_bytes()
    if n > MAX_GRID_SIZE or (memory is not None and n * BYTES_PER_FREQUENCY > memory):
        room = "" if memory is None else f" and fits in this machine's {memory / 1e9:.3g} GB"
        raise CaseError(
            field,
            value,
            f"a grid of at most {MAX_GRID_SIZE:,} frequencies{room}: this one has {n:,.0f} "
            f"({grid_cost(n)}), too many even with --force",
        )


def _fields(model: BaseModel, prefix: str = "") -> Iterator[tuple[str, Any, dict[str, Any]]]:
    """``(dotted name, value, json_schema_extra)`` of every field of the fixed sections."""
    for name, info in type(model).model_fields.items():
        value = getattr(model, name)
        if isinstance(value, BaseModel):
            yield from _fields(value, f"{prefix}{name}.")
        elif isinstance(info.json_schema_extra, dict):
            yield f"{prefix}{name}", value, info.json_schema_extra


def _declared(case: Case) -> Iterator[PlausibilityWarning]:
    """Fields outside the ``plausible`` range their schema declares."""
    for field, value, extra in _fields(case):
        if "plausible" not in extra or not isinstance(value, int | float):
            continue
        lo, hi = extra["plausible"]
        if not lo <= value <= hi:
            unit = extra.get("unit", "")
            side = "below" if value < lo else "above"
            yield PlausibilityWarning(
                field,
                value,
                f"{side} {lo:g}-{hi:g} {unit}, {extra['plausible_why']}",
            )


def _e(x: float) -> str:
    """``1e6`` for 1e6 (one significant digit, no ``+0`` in the exponent)."""
    mantissa, exponent = f"{x:.0e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def _pad_stiffness(
    pad: PadModel, f: NDArray[np.float64], temperature: float | None
) -> Iterator[PlausibilityWarning]:
    """K' of one rail seat outside 1 MN/m to 5 GN/m anywhere on the grid."""
    storage = np.real(pad.stiffness(f, temperature))
    at = "" if temperature is None or not pad.temperature_dependent else f" at {temperature:g} degC"
    i_lo, i_hi = int(np.argmin(storage)), int(np.argmax(storage))
    if storage[i_lo] < MIN_PAD_STIFFNESS_N_PER_M:
        yield PlausibilityWarning(
            "track.pad",
            f"K'({f[i_lo]:g} Hz) = {storage[i_lo]:.4g} N/m{at}",
            f"below {_e(MIN_PAD_STIFFNESS_N_PER_M)} N/m (1 kN/mm) per rail seat; railpads are "
            "about 10-1000 kN/mm (1e7-1e9 N/m): likely a value in kN/mm or N/mm given as N/m",
        )
    if storage[i_hi] > MAX_PAD_STIFFNESS_N_PER_M:
        yield PlausibilityWarning(
            "track.pad",
            f"K'({f[i_hi]:g} Hz) = {storage[i_hi]:.4g} N/m{at}",
            f"above {_e(MAX_PAD_STIFFNESS_N_PER_M)} N/m (5000 kN/mm) per rail seat, stiffer "
            "than any railpad (about 10-1000 kN/mm, 1e7-1e9 N/m): likely a typo or a value "
            "in another unit",
        )


def _temperature(
    pad: PadModel, temperature: float | None, temperature_given: bool
) -> Iterator[PlausibilityWarning]:
    """A temperature the pad ignores, or one outside the range its shift law holds."""
    field = "track.pad_temperature_c"
    if temperature is None:
        return
    if not pad.temperature_dependent:
        lo, hi = ROOM_TEMPERATURE_C
        if temperature_given and not lo <= temperature <= hi:
            yield PlausibilityWarning(
                field,
                temperature,
                f"ignored: pad model {pad.model_name!r} does not depend on temperature (the "
                "pad is the one its parameters describe); give [track.pad] a [track.pad.tts] "
                "table (e.g. from `railvib pad fit`) to shift it to this temperature",
            )
        return
    window = pad.temperature_range_c
    if window is not None and not window[0] <= temperature <= window[1]:
        yield PlausibilityWarning(
            field,
            temperature,
            f"outside {window[0]:g} to {window[1]:g} degC, where the pad's WLF shift holds "
            "(TemperatureShifted.temperature_range_c): its stiffness here is an extrapolation",
        )


def plausibility_warnings(
    case: Case,
    pad: PadModel,
    f: NDArray[np.float64],
    *,
    temperature_given: bool = True,
) -> list[PlausibilityWarning]:
    """Every legal but suspicious value of a validated case.

    * a field outside the ``plausible`` range its schema declares (``speed_kmh``:
      10-450 km/h);
    * the pad's storage stiffness K' (one rail seat, at the case's temperature)
      below :data:`MIN_PAD_STIFFNESS_N_PER_M` or above :data:`MAX_PAD_STIFFNESS_N_PER_M`
      somewhere on the grid;
    * ``track.pad_temperature_c`` given by the case itself (`temperature_given`: not
      inherited from a preset, which records the temperature its pad values describe)
      while the pad ignores temperature, unless it is room temperature
      (:data:`ROOM_TEMPERATURE_C`: a temperature-independent pad is taken to be
      described at room temperature, as the shipped template does);
    * a pad temperature outside the range where the pad's temperature shift holds
      (:attr:`railvib.pads.PadModel.temperature_range_c`);
    * a grid of more than :data:`WARN_FREQUENCIES` frequencies (with its cost).

    Parameters
    ----------
    case : Case
        A validated case.
    pad : PadModel
        Its pad (:func:`railvib.case.build_pad`), complex stiffness per rail seat in N/m.
    f : numpy.ndarray
        Its grid's frequencies, Hz.
    temperature_given : bool
        Whether the case's own tables set ``track.pad_temperature_c``.

    Returns
    -------
    list of PlausibilityWarning
        Empty for a plausible case.
    """
    temperature = case.track.pad_temperature_c
    out = [
        *_declared(case),
        *_pad_stiffness(pad, f, temperature),
        *_temperature(pad, temperature, temperature_given),
    ]
    if f.size > WARN_FREQUENCIES:
        field, value = _grid_field(case)
        out.append(
            PlausibilityWarning(
                field,
                value,
                f"gives {f.size:,} frequencies, more than {WARN_FREQUENCIES:,}: "
                f"{grid_cost(f.size)}",
            )
        )
    return out
