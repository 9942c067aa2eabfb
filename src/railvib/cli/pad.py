"""``railvib pad``: railpad master curves and models from measurements (thin CLI layer)."""

from __future__ import annotations

from pathlib import Path

import click

from railvib.cli.options import output_option, vertical_shift_options
from railvib.errors import CaseError

__all__ = ["pad"]


class _ModelOption(click.Option):
    """``--model``, whose help lists the fittable models when shown (not at start-up)."""

    def get_help_record(self, ctx: click.Context) -> tuple[str, str] | None:
        from railvib.pads import fittable_models

        self.help = f"pad model: {', '.join(fittable_models())} (aliases zener, prony)"
        return super().get_help_record(ctx)


def _floats(text: str, name: str) -> list[float]:
    try:
        return [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise CaseError(name, text, "comma-separated numbers") from None


@click.group()
def pad() -> None:
    """Railpad models: fit master curves and pad models to measurements.

    Start with "railvib pad example" (writes a synthetic measurements CSV here), then
    "railvib pad predict wj7_synthetic_0p3hz.csv --temperature -10" (the paper's
    prediction) or "railvib pad fit wj7_synthetic_0p3hz.csv --model zener --tg -40".
    """


@pad.command()
@click.option(
    "--multifrequency",
    is_flag=True,
    help="the DMA-style file (7 frequencies per temperature; enough to fit WLF C1, C2)",
)
@output_option(Path("."), "folder to write the CSV into")
def example(multifrequency: bool, outdir: Path) -> None:
    """Write a shipped example measurements CSV (synthetic WJ-7 pad) to OUTPUT."""
    from railvib.padfit import write_example_data

    path = write_example_data(outdir, multifrequency=multifrequency)
    click.echo(f"wrote {path} (synthetic data: see the header lines)")
    tg = "" if multifrequency else " --tg -40"
    if not multifrequency:
        click.echo(f"next: railvib pad predict {path} --temperature -10")
    click.echo(f"next: railvib pad fit {path} --model zener{tg}")


@pad.command()
@click.argument("data", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--model", cls=_ModelOption, default="fractional_zener", show_default=True)
@output_option(Path("pad-fit"))
@click.option(
    "--reference-temperature",
    "t_ref",
    type=float,
    default=20.0,
    show_default=True,
    help="master-curve reference temperature, degC",
)
@click.option(
    "--tg",
    type=float,
    default=None,
    help="glass transition, degC: use the universal WLF constants (17.44, 51.6 K) at Tg",
)
@click.option("--c1", type=float, default=None, help="given WLF C1 (with --c2)")
@click.option("--c2", type=float, default=None, help="given WLF C2, K (with --c1)")
@click.option(
    "--wlf-reference",
    type=float,
    default=None,
    help="temperature at which --c1/--c2 apply, degC [default: reference temperature]",
)
@vertical_shift_options
@click.option("--n-terms", type=int, default=None, help="Prony branches (generalized_maxwell)")
@click.option(
    "--temperatures",
    default="-30,-10,20",
    show_default=True,
    help="temperatures for the K(f) plot and log-linear fits, degC",
)
@click.option(
    "--band",
    default="1,1000",
    show_default=True,
    help="frequency band of the K(f) plot and log-linear fits, Hz",
)
@click.option(
    "--f0",
    type=float,
    default=5.0,
    show_default=True,
    help="reference frequency f0 of the log-linear law, Hz",
)
def fit(
    data: Path,
    model: str,
    outdir: Path,
    t_ref: float,
    tg: float | None,
    c1: float | None,
    c2: float | None,
    wlf_reference: float | None,
    no_vertical_shift: bool,
    expansion_coefficient: float,
    n_terms: int | None,
    temperatures: str,
    band: str,
    f0: float,
) -> None:
    """Fit a pad model to DATA.csv; write pad.toml and two plots to OUTPUT.

    Without --tg or --c1/--c2 the WLF constants are fitted (needs several frequencies
    per temperature). pad.toml holds a [track.pad] table usable in a case file.
    """
    from railvib.padfit import PadFitJob, fit_pad_to_folder

    job = PadFitJob(
        model=model,
        reference_temperature_c=t_ref,
        glass_transition_c=tg,
        c1=c1,
        c2_k=c2,
        wlf_reference_temperature_c=wlf_reference,
        vertical_shift=not no_vertical_shift,
        expansion_coefficient_per_k=expansion_coefficient,
        n_terms=n_terms,
        temperatures_c=tuple(_floats(temperatures, "--temperatures")),
        band_hz=tuple(_floats(band, "--band")),  # type: ignore[arg-type]
        f0_hz=f0,
    )
    report = fit_pad_to_folder(data, outdir, job)
    click.echo(report.text)
    click.echo(f"wrote {', '.join(str(p) for p in report.files)}")


@pad.command()
@click.argument("data", type=click.Path(dir_okay=False, path_type=Path))
@output_option(Path("pad-predict"))
@click.option(
    "--temperature",
    type=float,
    default=20.0,
    show_default=True,
    help="analysis temperature: the case's pad temperature and the master curve's reference, degC",
)
@click.option(
    "--tg",
    type=float,
    default=None,
    help="glass transition, degC [default: found from the loss-factor peak]",
)
@click.option(
    "--frequency",
    type=float,
    default=None,
    help="test frequency to use when DATA holds several, Hz",
)
@vertical_shift_options
@click.option(
    "--band",
    default="5,1000",
    show_default=True,
    help="frequency band of the K(f) plot and of the log-linear fit, Hz",
)
@click.option(
    "--f0",
    type=float,
    default=5.0,
    show_default=True,
    help="reference frequency f0 of the log-linear law, Hz",
)
@click.option(
    "--preset",
    default="wang2017_metro",
    show_default=True,
    help="preset the written case.toml starts from",
)
def predict(
    data: Path,
    outdir: Path,
    temperature: float,
    tg: float | None,
    frequency: float | None,
    no_vertical_shift: bool,
    expansion_coefficient: float,
    band: str,
    f0: float,
    preset: str,
) -> None:
    """Predict K*(f, T) from a one-frequency temperature sweep in DATA.csv (the paper's 3.2).

    Tg from the loss-factor peak, universal WLF constants at Tg re-referenced to
    --temperature, vertical factor, master curve. Writes to OUTPUT: pad.toml (the
    [track.pad] table and the pad temperature), case.toml (runnable: railvib run
    OUTPUT/case.toml) and three plots (cf. the paper's Figs. 6-8).
    """
    from railvib.padfit import PadPredictJob, predict_pad_to_folder

    job = PadPredictJob(
        temperature_c=temperature,
        glass_transition_c=tg,
        frequency_hz=frequency,
        vertical_shift=not no_vertical_shift,
        expansion_coefficient_per_k=expansion_coefficient,
        band_hz=tuple(_floats(band, "--band")),  # type: ignore[arg-type]
        f0_hz=f0,
        preset=preset,
    )
    report = predict_pad_to_folder(data, outdir, job)
    click.echo(report.text)
    click.echo(f"wrote {', '.join(str(p) for p in report.files)}")
    click.echo(f"next: railvib run {outdir / 'case.toml'} -o {outdir / 'run'}")
