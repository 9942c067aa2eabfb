"""The optional numba compiler of the kernels, imported only when a kernel is first loaded.

Every compiled kernel (:mod:`railvib.track.compiled`, :mod:`railvib.track.compiled_cells`,
:mod:`railvib.track.moving_kernel`, :mod:`railvib.coupled_kernel`) is compiled with the same
options, cached on disk, and falls back to NumPy where numba is not installed (the ``fast``
extra).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["numba_jit"]


def numba_jit(**options: Any) -> Callable[[Callable[..., Any]], Any] | None:
    """``numba.njit(cache=True, nogil=True, **options)``, or None where numba is not installed.

    Parameters
    ----------
    **options
        Further ``numba.njit`` options (``error_model``, ``fastmath``).

    Returns
    -------
    callable or None
        The decorator compiling a point function (at its first call, from numba's on-disk
        cache after the first process), or None without numba.
    """
    try:
        import numba
    except ImportError:
        return None
    return numba.njit(cache=True, nogil=True, **options)
