"""Assumed-mode shape functions of paper eq. (1).

Bending: eigenfunctions of a uniform clamped-free Euler-Bernoulli beam; torsion: eigenfunctions of a
uniform fixed-free shaft (Tuzcu & Nguyen 2014, text below eq. 1). Normalisation as in
``docs/reference/aero-kinematics.md`` sections 6.2-6.3::

    phi_n(x) = cosh(b x) - cos(b x) - sigma_n (sinh(b x) - sin(b x)),  b = beta_n L / L
    int_0^L phi_n^2 dx = L,   phi_n(L) = 2 (-1)^(n+1)
    psi_n(x) = sin((2n - 1) pi x / (2 L)),  int_0^L psi_n^2 dx = L / 2

The bending functions are evaluated in an overflow- and cancellation-free form (the growing exponential
is multiplied by 1 - sigma_n, computed without subtraction), so they are accurate for every supported
mode number.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from flexsim.aircraft.definition import MAX_MODES

__all__ = [
    "MAX_MODES",
    "cantilever_beta_l",
    "bending_shapes",
    "torsion_shapes",
]



@lru_cache(maxsize=None)
def _beta_sigma(n_modes: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Roots beta_n L of cos(bL) cosh(bL) = -1, sigma_n and 1 - sigma_n for n = 1..n_modes."""
    beta = np.empty(n_modes)
    for k in range(n_modes):
        guess = (2 * k + 1) * np.pi / 2
        # cos y + 1/cosh y has one root in each interval around (2k+1) pi/2; well conditioned.
        beta[k] = brentq(lambda y: np.cos(y) + 1.0 / np.cosh(y), guess - 1.0, guess + 1.0, xtol=1e-15)
    sh, ch = np.sinh(beta), np.cosh(beta)
    s, c = np.sin(beta), np.cos(beta)
    one_minus_sigma = (s - c - np.exp(-beta)) / (sh + s)
    sigma = 1.0 - one_minus_sigma
    beta.setflags(write=False)
    sigma.setflags(write=False)
    one_minus_sigma.setflags(write=False)
    return beta, sigma, one_minus_sigma


def cantilever_beta_l(n_modes: int) -> np.ndarray:
    """Dimensionless clamped-free beam eigenvalues beta_n L, n = 1..n_modes (reference table 6.2).

    Parameters
    ----------
    n_modes : int
        Number of roots, 1..MAX_MODES.

    Returns
    -------
    ndarray, shape (n_modes,)
    """
    return _beta_sigma(n_modes)[0].copy()


def bending_shapes(x: np.ndarray, length: float, n_modes: int, derivative: int = 0) -> np.ndarray:
    """Clamped-free beam eigenfunctions U_i(x) of paper eq. (1) and their x-derivatives.

    Parameters
    ----------
    x : array_like, shape (k,)
        Stations along the beam axis, 0 <= x <= length [m].
    length : float
        Beam length L [m].
    n_modes : int
        Number m of shape functions (0..MAX_MODES).
    derivative : {0, 1, 2}
        Order of the x-derivative returned (units 1, 1/m, 1/m^2).

    Returns
    -------
    ndarray, shape (k, n_modes)
        Entry [j, n] is d^derivative phi_{n+1} / dx^derivative at x[j]; phi dimensionless.
    """
    x = np.atleast_1d(np.asarray(x, dtype=float))
    if n_modes == 0:
        return np.zeros((x.size, 0))
    beta_l, sigma, oms = _beta_sigma(n_modes)
    b = beta_l / length
    bx = np.outer(x, b)
    ep = 0.5 * oms * np.exp(bx)  # (1 - sigma) e^{bx} <= (1 - sigma) e^{beta L} = O(1): no cancellation
    em = 0.5 * (1.0 + sigma) * np.exp(-bx)
    s, c = np.sin(bx), np.cos(bx)
    if derivative == 0:
        out = ep + em - c + sigma * s
    elif derivative == 1:
        out = b * (ep - em + s + sigma * c)
    elif derivative == 2:
        out = b**2 * (ep + em + c - sigma * s)
    else:
        raise ValueError(f"derivative = {derivative!r}: must be 0, 1 or 2")
    return out


def torsion_shapes(x: np.ndarray, length: float, n_modes: int, derivative: int = 0) -> np.ndarray:
    """Fixed-free shaft eigenfunctions Psi_i(x) of paper eq. (1) and their x-derivatives.

    Parameters
    ----------
    x : array_like, shape (k,)
        Stations along the beam axis [m].
    length : float
        Shaft length L [m].
    n_modes : int
        Number n of shape functions (0..MAX_MODES).
    derivative : {0, 1}
        Order of the x-derivative (units 1 or 1/m).

    Returns
    -------
    ndarray, shape (k, n_modes)
    """
    x = np.atleast_1d(np.asarray(x, dtype=float))
    k = (2.0 * np.arange(1, n_modes + 1) - 1.0) * np.pi / (2.0 * length)
    kx = np.outer(x, k)
    if derivative == 0:
        return np.sin(kx)
    if derivative == 1:
        return k * np.cos(kx)
    raise ValueError(f"derivative = {derivative!r}: must be 0 or 1")
