"""A rich progress bar counting cases: done / total, rate and time left."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager

from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    Task,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)
from rich.text import Text

__all__ = ["case_progress"]


class _RateColumn(ProgressColumn):
    """Cases per second."""

    def render(self, task: Task) -> Text:
        speed = task.finished_speed or task.speed
        return Text("-- cases/s" if speed is None else f"{speed:,.1f} cases/s")


@contextmanager
def case_progress(total: int, done: int = 0) -> Iterator[Callable[[int], None]]:
    """Show a progress bar of cases; yields ``advance(n_cases)``.

    Parameters
    ----------
    total : int
        Number of cases in the sweep.
    done : int
        Cases already finished (resumed).
    """
    columns = (
        TextColumn("[bold]sweep"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("cases"),
        _RateColumn(),
        TimeElapsedColumn(),
        TextColumn("left"),
        TimeRemainingColumn(),
    )
    with Progress(*columns, transient=False) as bar:
        task = bar.add_task("sweep", total=total, completed=done)

        def advance(n: int) -> None:
            bar.advance(task, n)

        yield advance
