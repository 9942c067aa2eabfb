"""``railvib run`` of a ``mode = "nonstationary"`` case: dataset, summary, figures, atomically."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from railvib.case import Case, case_header, load_case
from railvib.errors import CaseError
from railvib.io import staged_folder, write_text
from railvib.nonstationary.build import build_run
from railvib.nonstationary.dataset import nonstationary_dataset
from railvib.nonstationary.quasi import QS_LIMIT
from railvib.results.dataset import check_finite, save_netcdf
from railvib.results.units import quantity_unit

__all__ = [
    "NONSTATIONARY_FILES",
    "NonstationaryOutput",
    "run_nonstationary",
    "run_nonstationary_to_folder",
    "summary_lines",
]

#: every file a non-stationary run may write to its folder (a later run replaces them)
NONSTATIONARY_FILES = ("results.nc", "rms_time.csv", "summary.md", "psd_map.png", "rms_time.png")


def run_nonstationary(
    case: Case | str | Path, *, progress: Callable[[int], None] | None = None
) -> xr.Dataset:
    """Run a ``mode = "nonstationary"`` case (a validated case or a TOML path).

    Parameters
    ----------
    case : Case, str or pathlib.Path
        The case.
    progress : callable, optional
        Called with the number of time steps just integrated.

    Returns
    -------
    xarray.Dataset
        See :func:`railvib.nonstationary.dataset.nonstationary_dataset`.

    Raises
    ------
    CaseError
        Bad input (before anything is computed).
    """
    if not isinstance(case, Case):
        case = load_case(case)
    if case.mode != "nonstationary":
        raise CaseError("mode", case.mode, 'must be "nonstationary" for a non-stationary run')
    run = build_run(case)
    attrs = {"title": case.title, "case_toml": case.to_toml(), "rail_model": case.rail_model}
    ds = nonstationary_dataset(run, attrs=attrs, progress=progress)
    check_finite(ds.drop_vars("quasi_stationary_parameter"))  # infinite at a stop, by definition
    return ds


def summary_lines(ds: xr.Dataset) -> list[str]:
    """The summary of a non-stationary dataset: largest RMS, where, and the validity.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`run_nonstationary`.

    Returns
    -------
    list of str
        Markdown lines (a table per quantity, then notes).
    """
    v = 3.6 * ds["speed"].values
    lines = [
        f"non-stationary run: {v[0]:.1f} -> {v[-1]:.1f} km/h (from {v.min():.1f} to "
        f"{v.max():.1f}) over {float(ds.time[-1]):.4g} s and {float(ds.position[-1]):.4g} m, "
        "on a rigid track (the case's [track] and speed_kmh are not used)",
    ]
    for name, dim in (("acceleration", "response"), ("force", "wheel")):
        exact, qs = ds.get(f"rms_{name}"), ds.get(f"rms_{name}_qs")
        if exact is None and qs is None:
            continue
        lines += [
            "",
            f"| {dim} | largest RMS {name} (exact) | at t (s) | at x (m) | at v (km/h) "
            f"| largest RMS (quasi-stationary) | P(first passage, {_levels(ds)}) |",
            "|---|---|---|---|---|---|---|",
        ]
        for label in ds[dim].values:
            cells = [str(label)]
            if exact is not None:
                da = exact.sel({dim: label})
                i = int(np.argmax(da.values))
                unit = quantity_unit(name, str(label)) if dim == "response" else "N"
                cells += [
                    f"{float(da[i]):.4g} {unit}",
                    f"{float(ds.time[i]):.3f}",
                    f"{float(ds.position[i]):.1f}",
                    f"{3.6 * float(ds.speed[i]):.1f}",
                ]
            else:
                cells += ["-"] * 4
            cells.append("-" if qs is None else f"{float(qs.sel({dim: label}).max()):.4g}")
            p = ds.get(f"first_passage_probability_{name}")
            cells.append(
                "-"
                if p is None
                else ", ".join(
                    f"{float(x):.3g}"
                    for x in p.sel({dim: label, "crossing_model": "vanmarcke"}).values
                )
            )
            lines.append("| " + " | ".join(cells) + " |")
    eps = float(ds.attrs["quasi_stationary_parameter_max"])
    frac = float(ds.attrs["quasi_stationary_valid_fraction"])
    f_1, dt = float(ds.attrs["slowest_mode_hz"]), float(ds.attrs["time_step_s"])
    phase = float(ds.attrs["phase_error_bound_rad"])
    lines += [
        "",
        f"Quasi-stationary validity: |dv/dt| / (v f_1) <= {QS_LIMIT} over {100 * frac:.0f} % of "
        f"the run (largest {eps:.3g}; slowest mode f_1 = {f_1:.3g} Hz).",
        f"Time step {dt:.4g} s, {int(ds.attrs['n_wavenumbers'])} wavenumbers, integrator "
        f"phase error <= {phase:.2g} rad.",
    ]
    return lines


def _levels(ds: xr.Dataset) -> str:
    if "level" not in ds.coords:
        return "-"
    return (
        "b = " + ", ".join(f"{float(k):g}" for k in ds.level.values) + " x largest RMS, Vanmarcke"
    )


@dataclass(frozen=True, eq=False)
class NonstationaryOutput:
    """What :func:`run_nonstationary_to_folder` computed and wrote.

    Parameters
    ----------
    dataset : xarray.Dataset
        The result.
    files : tuple of pathlib.Path
        Every file written.
    lines : tuple of str
        The summary: the case header, then :func:`summary_lines`.
    """

    dataset: xr.Dataset
    files: tuple[Path, ...]
    lines: tuple[str, ...]

    def text(self) -> str:
        """The summary as printed by ``railvib run``."""
        return "\n".join(self.lines)


def run_nonstationary_to_folder(
    case: Case | str | Path,
    outdir: str | Path,
    *,
    plots: bool = True,
    progress: Callable[[int], None] | None = None,
) -> NonstationaryOutput:
    """Run a non-stationary case and write ``results.nc``, ``rms_time.csv``, ``summary.md``, plots.

    The files are written into a staging folder put in place at the end
    (:func:`railvib.io.staged_folder`): a run that fails or is stopped leaves `outdir`
    as it was; bad input is refused before anything is computed or written.

    Parameters
    ----------
    case : Case, str or pathlib.Path
        The case (``mode = "nonstationary"``).
    outdir : str or pathlib.Path
        Output folder (created if needed).
    plots : bool
        Draw ``psd_map.png`` and ``rms_time.png``.
    progress : callable, optional
        Called with the number of time steps just integrated.

    Returns
    -------
    NonstationaryOutput
    """
    if not isinstance(case, Case):
        case = load_case(case)
    if case.mode != "nonstationary":
        raise CaseError("mode", case.mode, 'must be "nonstationary" for a non-stationary run')
    build_run(case)  # every check before the folder is touched
    with staged_folder(outdir, NONSTATIONARY_FILES) as stage:
        ds = run_nonstationary(case, progress=progress)
        lines = [*case_header(case), *summary_lines(ds)]
        files = [
            save_netcdf(ds, stage.path / "results.nc"),
            write_text(stage.path / "rms_time.csv", _rms_csv(ds)),
            write_text(
                stage.path / "summary.md", "\n".join([f"# {case.title}", "", *lines]) + "\n"
            ),
        ]
        if plots:
            from railvib.plot.nonstationary import save_nonstationary_plots  # matplotlib

            files += save_nonstationary_plots(ds, stage.path)
    return NonstationaryOutput(ds, tuple(stage.finals(files)), tuple(lines))


def _rms_csv(ds: xr.Dataset) -> str:
    """RMS against time and position (exact PEM), one column per response, with units."""
    cols = ["time (s)", "position (m)", "speed (m/s)"]
    values = [ds.time.values, ds.position.values, ds.speed.values]
    for name, dim in (
        ("displacement", "response"),
        ("acceleration", "response"),
        ("force", "wheel"),
    ):
        da = ds.get(f"rms_{name}")
        if da is None:
            continue
        for label in ds[dim].values:
            unit = quantity_unit(name, str(label)) if dim == "response" else "N"
            tag = f"wheel{label}" if dim == "wheel" else str(label)
            cols.append(f"rms {name} {tag} ({unit})")
            values.append(da.sel({dim: label}).values)
    rows = [",".join(cols)]
    table = np.column_stack(values) if values[0].size else np.zeros((0, len(cols)))
    rows += [",".join(f"{x:.6g}" for x in row) for row in table]
    return "\n".join(rows) + "\n"
