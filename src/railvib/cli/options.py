"""Options shared by the commands, defined once so every command spells them alike."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import click

__all__ = ["output_option"]


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
