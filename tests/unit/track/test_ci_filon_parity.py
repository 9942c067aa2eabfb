"""The Filon weights behind the load (``r < 0``) with a scipy that has no negative arguments.

scipy < 1.15 returns NaN from ``spherical_jn(n, x)`` for ``x < 0`` and ``n >= 1`` (scipy
issue 14582, fixed in 1.15); pyproject allows scipy 1.13. At that version every moving-load
receptance with an observation point behind the load (the trailing wheels of a vehicle)
was NaN, and the adaptive quadrature, whose error scale was then NaN, bisected every
panel to its last level: the CI's lower-bound step saw its workers grow past 4-10 GB and
die. Here scipy's old behaviour is imitated, whatever scipy is installed, and the weights
are checked against the closed-form integral.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.special import spherical_jn

import railvib.track.moving_kernel as kernel


def _spherical_jn_before_scipy_1_15(n, x):
    """``spherical_jn`` as scipy 1.13-1.14 computed it: NaN at ``x < 0`` for ``n >= 1``."""
    n, x = np.broadcast_arrays(n, x)
    return np.where((x < 0.0) & (n >= 1), np.nan, spherical_jn(n, np.abs(x)))


def test_the_imitation_is_nan_where_old_scipy_was():
    # the premise (measured with scipy 1.13.0: [0.4546, nan, nan, nan] at x = -2)
    values = _spherical_jn_before_scipy_1_15(np.arange(4), -2.0)
    assert np.isfinite(values[0])
    assert np.all(np.isnan(values[1:]))


@pytest.mark.parametrize("width", [1e-3, 0.5, 3.0])
@pytest.mark.parametrize("r", [-2.2, -12.6, -400.0])
def test_weights_behind_the_load_need_no_negative_argument(monkeypatch, width, r):
    """``int exp(alpha k) exp(i k r) dk`` over a panel at ``r < 0``, against its closed form."""
    monkeypatch.setattr(kernel, "spherical_jn", _spherical_jn_before_scipy_1_15)
    alpha, mid = 0.3, 1.7
    half = 0.5 * width
    weights = kernel.filon_weights(np.array([mid]), np.array([half]), np.array([r]))[0, 0]
    k = mid + half * kernel.NODES
    rule = weights @ np.exp(alpha * k)
    s = alpha + 1j * r
    exact = np.exp(s * (mid - half)) * np.expm1(s * width) / s  # no cancellation
    # as in test_filon17_quadrature: the interpolation error of exp(alpha k) (< 1e-18 here)
    # and rounding in the weights (cond(V) = 6.4, spherical Bessel functions to ~1e-15),
    # relative to the integral of |exp(alpha k)|
    scale = np.exp(alpha * (mid + half)) * width
    assert abs(rule - exact) < 1e-13 * scale
