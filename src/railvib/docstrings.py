"""Shared parameter documentation: written once, substituted into the docstrings that use it.

A docstring line holding only ``{name}`` is replaced by the entry ``name`` of the
mapping given to :func:`fill_doc`, indented like the placeholder, so that a
parameter shared by many functions (a pad's ``f`` and ``temperature``, a study's
``results``) is described in one place and each function still shows it.
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Callable, Mapping
from typing import TypeVar

__all__ = ["fill_doc"]

F = TypeVar("F", bound=Callable[..., object])
_PLACEHOLDER = re.compile(r"^(?P<indent>[ \t]*)\{(?P<name>\w+)\}[ \t]*$", re.M)


def fill_doc(entries: Mapping[str, str]) -> Callable[[F], F]:
    """Decorator that fills the ``{name}`` lines of a docstring from `entries`.

    Parameters
    ----------
    entries : mapping of str to str
        Name -> numpydoc text such as ``"f : array_like"`` and its indented description,
        written without indentation.

    Returns
    -------
    callable
        The decorator; it raises KeyError for a placeholder without an entry.
    """

    def decorate(func: F) -> F:
        doc = func.__doc__ or ""

        def replace(match: re.Match[str]) -> str:
            text = textwrap.dedent(entries[match["name"]]).strip("\n")
            return textwrap.indent(text, match["indent"])

        func.__doc__ = _PLACEHOLDER.sub(replace, doc)
        return func

    return decorate
