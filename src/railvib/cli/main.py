"""The ``railvib`` command line: a thin layer over the public API."""

from __future__ import annotations

import os
import signal
import sys
import threading
import traceback
import warnings
from pathlib import Path
from typing import Any

import click

from railvib.cli.options import output_option
from railvib.errors import DamagedOutputWarning, PlausibilityWarning, RailvibError

__all__ = ["cli", "main"]


def _print_version(ctx: click.Context, _param: click.Parameter, value: bool) -> None:
    """``--version``: the installed version (``unknown`` when run from a source tree)."""
    if value and not ctx.resilient_parsing:
        from railvib.io import railvib_version

        click.echo(f"railvib, version {railvib_version()}")
        ctx.exit()


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.option(
    "--version",
    is_flag=True,
    expose_value=False,
    is_eager=True,
    callback=_print_version,
    help="Show the version (from the git tag of the installed build) and exit.",
)
def cli() -> None:
    """railvib: random vibration of a vehicle on an infinite periodic track.

    Start with `railvib reproduce` (the paper's study: figures, table, HTML report) or
    `railvib template > case.toml` then `railvib run case.toml -o out/`; many cases with
    `railvib sweep SWEEP.toml` (then `railvib sweep plot SWEEP_OUT`); every model and
    its keys with `railvib models`. Units are SI
    unless a key names its unit; PSDs are one-sided per Hz. Each command has --help.
    """


@cli.command()
@click.argument("case_file", type=click.Path(dir_okay=False, path_type=Path))
@output_option(Path("railvib-out"))
@click.option("--no-plots", is_flag=True, help="skip the PNG figures")
@click.option(
    "--strict",
    is_flag=True,
    help="exit with code 3 when the case is beyond the linear model (loss of contact above "
    "output.loss_of_contact_threshold); the results are written all the same",
)
@click.option("--force", is_flag=True, help="run a grid of more than 2,000,000 frequencies")
def run(case_file: Path, outdir: Path, no_plots: bool, strict: bool, force: bool) -> None:
    """Run CASE_FILE and write the dataset, summary and PSD plots to OUTPUT."""
    from railvib.cli.run import run_case_command

    run_case_command(case_file, outdir, plots=not no_plots, strict=strict, force=force)


@cli.command()
@click.option("--preset", default=None, help="preset supplying the values")
def template(preset: str | None) -> None:
    """Print a fully commented default case file."""
    from railvib.case.template import render_template
    from railvib.presets import DEFAULT_PRESET

    click.echo(render_template(preset or DEFAULT_PRESET), nl=False)


@cli.command()
def presets() -> None:
    """List the shipped presets."""
    from railvib.presets import list_presets, load_preset

    for name in list_presets():
        click.echo(f"{name}: {load_preset(name).get('title', '')}")


@cli.command()
@click.argument("family", required=False)
def models(family: str | None) -> None:
    """List the models of FAMILY (pad, spectrum, track, vehicle, output), or of all.

    Each model with its case-file keys, units, defaults and allowed values, as
    Markdown (docs/models.md is this output).
    """
    from railvib.models import models_markdown

    click.echo(models_markdown(family), nl=False)


def _register_optional() -> None:
    """Add sub-commands that live in their own modules."""
    import importlib

    for module, name in (
        ("railvib.cli.pad", "pad"),
        ("railvib.cli.validate", "validate"),
        ("railvib.cli.reproduce", "reproduce"),
        ("railvib.cli.sweep", "sweep"),
        ("railvib.cli.track", "track"),
        ("railvib.cli.explore", "explore"),
    ):
        try:
            mod = importlib.import_module(module)
        except ModuleNotFoundError as exc:
            if exc.name != module:
                raise
            continue
        cli.add_command(getattr(mod, name))
    if "sweep" in cli.commands:
        cli.add_command(_plot_alias())


def _plot_alias() -> click.Command:
    """``railvib plot`` = ``railvib sweep plot`` (kept for existing scripts; not listed)."""
    from railvib.cli.sweep import plot

    alias = click.Command(
        "plot",
        params=plot.params,
        callback=plot.callback,
        help=f"Alias of `railvib sweep plot`. {plot.help or ''}",
        hidden=True,
    )
    return alias


_register_optional()


def _one_line(show: Any) -> Any:
    """`show` (a ``warnings.showwarning``) printing a PlausibilityWarning as one line."""

    def _show(message: Warning | str, category: type[Warning], *args: Any, **kw: Any) -> None:
        if issubclass(category, PlausibilityWarning | DamagedOutputWarning):
            click.echo(f"warning: {message}", err=True)  # no file name, no source line
        else:
            show(message, category, *args, **kw)

    return _show


def main(argv: list[str] | None = None) -> int:
    """Entry point: run the CLI; a RailvibError becomes one line on stderr and its exit code.

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments without the program name; None reads ``sys.argv``.

    Returns
    -------
    int
        Exit code: 0 on success, 2 for a RailvibError (bad input) or a usage error (both
        one line ``error: ...`` on stderr), 3 when ``--strict`` finds a result beyond the
        linear model (:class:`~railvib.errors.LinearModelInvalid`), 130 when aborted, 2
        for a system error no command names (standard output on a full disk), 141 when
        standard output is a closed pipe, else click's code.

    Notes
    -----
    Called as the program (`argv` None), Ctrl-C is ignored once the command has ended:
    the interpreter only shuts down then, and a signal would kill it mid-way (exit
    status -2 instead of the command's code).
    """
    try:
        return _main(argv)
    finally:
        if argv is None and threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, signal.SIG_IGN)


def _main(argv: list[str] | None) -> int:
    """:func:`main` without the handling of the process's end."""
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _one_line(warnings.showwarning)
            cli.main(args=argv, standalone_mode=False)
    except RailvibError as exc:
        click.echo(f"error: {exc}", err=True)
        return exc.exit_code
    except (PlausibilityWarning, DamagedOutputWarning) as exc:  # escalated by -W error
        click.echo(f"error: {exc}", err=True)
        return 2
    except click.exceptions.Abort as exc:  # Ctrl-C; a command may say what was kept
        click.echo(f"aborted: {exc}" if str(exc) else "aborted", err=True)
        _forget_interrupt()
        return 130
    except click.UsageError as exc:
        click.echo(f"error: {_usage_line(exc)}", err=True)
        return exc.exit_code
    except click.ClickException as exc:
        exc.show()
        return exc.exit_code
    except BrokenPipeError:  # `railvib models | head`: the reader has what it wanted
        _stdout_to_devnull()
        return 141  # 128 + SIGPIPE, as a killed shell tool
    except OSError as exc:  # the summary printed to a full disk (`> /dev/full`), ...
        click.echo(f"error: {_os_error_line(exc)}", err=True)
        return 2
    return 0


def _os_error_line(exc: OSError) -> str:
    """One line for an OSError no command turned into a RailvibError (files name themselves)."""
    reason = os.strerror(exc.errno) if exc.errno else str(exc)
    if exc.filename is not None:
        return f"{exc.filename}: {reason}"
    if any(frame.name == "echo" for frame in traceback.extract_tb(exc.__traceback__)):
        _stdout_to_devnull()
        return f"cannot write standard output: {reason}"
    return reason


def _stdout_to_devnull() -> None:
    """Point stdout at the null device, so that the exit's flush of unwritten text cannot fail."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # stdout replaced (tests) or closed
        pass


def _forget_interrupt() -> None:
    """Let a handled Ctrl-C end with exit code 130, not with death by SIGINT.

    CPython remembers a KeyboardInterrupt that left code run by ``exec`` of a string
    (scipy's imports do that) and, once the interpreter has finished, kills itself with
    SIGINT instead of exiting with the code given (exit status -2 instead of 130, one
    Ctrl-C in six during start-up); running any string of code clears that memory.
    """
    import ctypes

    api = getattr(ctypes, "pythonapi", None)  # CPython only
    if api is not None:
        api.PyRun_SimpleString(b"pass")


def _usage_line(exc: click.UsageError) -> str:
    """A usage error on one line: click's message and where the help is."""
    message = " ".join(exc.format_message().split())
    command = exc.ctx.command_path if exc.ctx is not None else "railvib"
    return f"{message} (see `{command} --help`)"


if __name__ == "__main__":
    sys.exit(main())
