"""Options shared by the commands, defined once so every command spells them alike."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import click

__all__ = ["output_option", "vertical_shift_options"]


def output_option(default: Path | None, help: str = "output folder") -> Callable[[Any], Any]:
    """The ``-o/--output`` folder option (parameter ``outdir``) of a command.

    Parameters
    ----------
    default : pathlib.Path or None
        Default folder (None: the command picks one, said in `help`).
    help : str
        Help text.
    """
    return click.option(
        "-o",
        "--output",
        "outdir",
        type=click.Path(file_okay=False, path_type=Path),
        default=default,
        show_default=default is not None,
        help=help,
    )


def vertical_shift_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """The TTS vertical-factor options of a pad command.

    ``--no-vertical-shift`` (parameter ``no_vertical_shift``) and
    ``--expansion-coefficient`` (``expansion_coefficient``, 1/K, the paper's 4.8e-4).

    Parameters
    ----------
    command : callable
        The click command (or the function below its other options).

    Returns
    -------
    callable
        `command` with both options added.
    """
    command = click.option(
        "--expansion-coefficient",
        type=float,
        default=4.8e-4,
        show_default=True,
        help="volume expansion coefficient a_f, 1/K",
    )(command)
    return click.option(
        "--no-vertical-shift", is_flag=True, help="skip the rho T / (rho0 T0) factor"
    )(command)
