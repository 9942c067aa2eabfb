"""``railvib run``: one case to dataset, summary and plots."""

from __future__ import annotations

from pathlib import Path

import click

from railvib.case import load_case
from railvib.results import atomic_path, save_csv, save_netcdf, summary
from railvib.solve import LOSS_OF_CONTACT_NOTE, run

__all__ = ["run_case_command"]


def run_case_command(case_file: Path, outdir: Path, plots: bool = True) -> None:
    """Validate, run and write ``results.nc``, PSD CSVs, ``summary.csv/.md`` and PNGs."""
    case = load_case(case_file)
    ds = run(case)
    outdir.mkdir(parents=True, exist_ok=True)
    save_netcdf(ds, outdir / "results.nc")
    save_csv(ds, outdir / "psd_acceleration.csv")
    save_csv(ds, outdir / "psd_displacement.csv", variable="psd_displacement")
    table = summary(ds, bands=case.output.rms_bands).to_dataframe()
    with atomic_path(outdir / "summary.csv") as tmp:
        table.to_csv(tmp, float_format="%.6g")
    with atomic_path(outdir / "summary.md") as tmp:
        tmp.write_text(table.to_markdown(floatfmt=".4g") + "\n", encoding="utf-8")
    if plots:
        from railvib.plot.psd import save_overview

        save_overview(ds, outdir)
    click.echo(table.to_string(float_format=lambda v: f"{v:.4g}"))
    worst = float(ds.loss_of_contact_probability.max())
    if worst > LOSS_OF_CONTACT_NOTE:
        click.echo(
            f"\nnote: dynamic contact force RMS {float(ds.contact_force_rms.max()):.3g} N against "
            f"a static load of {float(ds.static_contact_load.min()):.3g} N: loss of wheel-rail "
            f"contact has probability {worst:.1%} (Gaussian estimate). PEM assumes permanent "
            "contact, so treat the results near the contact resonances with care."
        )
    click.echo(f"\nwritten to {outdir}/")
