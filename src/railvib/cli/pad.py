"""``railvib pad``: railpad master curves and models from measurements (thin CLI layer)."""

from __future__ import annotations

from pathlib import Path

import click

__all__ = ["pad"]


def _floats(text: str, name: str) -> list[float]:
    from railvib.errors import CaseError

    try:
        return [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise CaseError(name, text, "comma-separated numbers") from None


@click.group()
def pad() -> None:
    """Railpad models: fit master curves and pad models to measurements."""


@pad.command()
@click.argument("data", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--model",
    default="fractional_zener",
    show_default=True,
    help="pad model: fractional_zener (zener), generalized_maxwell (prony), "
    "spring_damper, hysteretic, log_linear, constant_phase",
)
@click.option(
    "-o",
    "--output",
    "outdir",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("pad-fit"),
    show_default=True,
    help="output folder",
)
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
@click.option("--no-vertical-shift", is_flag=True, help="skip the rho T / (rho0 T0) factor")
@click.option(
    "--expansion-coefficient",
    type=float,
    default=4.8e-4,
    show_default=True,
    help="volume expansion coefficient a_f, 1/K",
)
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
    import numpy as np

    from railvib.errors import CaseError
    from railvib.io import atomic_path, save_figure
    from railvib.pads import WLF, fit_log_linear, fit_pad, pad_toml, read_measurements_csv
    from railvib.plot.pads import plot_master_curve, plot_stiffness_vs_frequency

    if tg is not None and (c1 is not None or c2 is not None):
        raise CaseError("--tg", tg, "give either --tg or --c1 and --c2, not both")
    if (c1 is None) != (c2 is None):
        raise CaseError("--c1/--c2", (c1, c2), "give both")
    wlf = None
    if tg is not None:
        wlf = WLF.universal(tg)
    elif c1 is not None and c2 is not None:
        wlf = WLF(c1, c2, t_ref if wlf_reference is None else wlf_reference)
    temps = _floats(temperatures, "--temperatures")
    f_band = _floats(band, "--band")
    if len(f_band) != 2:
        raise CaseError("--band", band, "two frequencies f_min,f_max (Hz)")

    measurements = read_measurements_csv(data)
    result = fit_pad(
        measurements,
        model,
        t_ref,
        wlf,
        vertical_shift=not no_vertical_shift,
        expansion_coefficient_per_k=expansion_coefficient,
        n_terms=n_terms,
        f0_hz=f0,
    )
    lines = [result.summary()]
    for t in temps:
        ll = fit_log_linear(result.model, t, (f_band[0], f_band[1]), f0_hz=f0)
        lines.append(
            f"log-linear at {t:g} degC over {f_band[0]:g}-{f_band[1]:g} Hz: "
            f"K0 = {ll.model.k0_n_per_m / 1e6:.1f} kN/mm at {f0:g} Hz, "
            f"k = {ll.model.exponent:.3f} (rms {ll.rms_log10:.3f} decades)"
        )
    report = "\n".join(lines)

    outdir.mkdir(parents=True, exist_ok=True)
    header = f"railvib pad fit {data.name} --model {model}\n" + report
    with atomic_path(outdir / "pad.toml") as tmp:
        tmp.write_text(pad_toml(result.model, header=header), encoding="utf-8")

    master = result.master
    assert master is not None
    fr = master.reduced_frequency_hz
    f_curve = np.geomspace(fr.min(), fr.max(), 400)
    axes = plot_master_curve(master, f_curve, result.model.stiffness(f_curve))
    save_figure(axes[0], outdir / "master_curve.png", tight=False)

    f_plot = np.geomspace(f_band[0], f_band[1], 200)
    ax = plot_stiffness_vs_frequency(f_plot, {t: result.model.stiffness(f_plot, t) for t in temps})
    ax.set_title(f"{data.name}: {model} with TTS")
    save_figure(ax, outdir / "stiffness_vs_frequency.png")

    click.echo(report)
    click.echo(f"wrote {outdir / 'pad.toml'}, master_curve.png, stiffness_vs_frequency.png")
