"""Command-line interface: thin click commands over the public API.

Importing this package installs the command line's handler of an uncaught Ctrl-C
(``sys.excepthook``: "aborted", exit code 130); the library itself (``import railvib``)
changes no interpreter state.
"""

from __future__ import annotations

import os
import sys
from types import TracebackType
from typing import Any


def _quiet_interrupt(hook: Any) -> Any:
    """`hook` (a ``sys.excepthook``) ending an uncaught Ctrl-C with "aborted", exit code 130.

    Ctrl-C while the command line is still importing (before ``main`` runs) or outside
    click's handling would otherwise print a KeyboardInterrupt traceback. Nothing has been
    written then, so the process ends at once. Installed here, first of the command
    line's modules and before any of their imports, so that the window left to Python's
    own traceback is the interpreter's start and ``import railvib`` (~20 ms).
    """

    def _hook(kind: type[BaseException], exc: BaseException, tb: TracebackType | None) -> None:
        if not issubclass(kind, KeyboardInterrupt):
            hook(kind, exc, tb)
            return
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os.write(2, b"\naborted\n")
        os._exit(130)

    return _hook


sys.excepthook = _quiet_interrupt(sys.excepthook)
