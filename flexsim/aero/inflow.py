"""Peters finite-state induced-flow (inflow) model for 2-D airfoils.

Source: Peters, Karunamoorthy & Cao (1995), "Finite-State Induced Flow Models, Part I", J. Aircraft 32(2);
Hodges & Pierce (2011) §5.5.2 (as cited in reference §2.1); coefficients as in
``docs/reference/aero-kinematics.md`` §2.1 ("reference §2.1"). This is the wake model behind ``λ0``
in the paper's eqs. 25 and 27.

Equations (reference §2.1), per airfoil section:

* ``[A]{λ̇} + (u0/b){λ} = {c}(ẇ0 + ẇ1/2)``; ``λ0 = ½ {b}ᵀ{λ}``;
* ``[A] = [D] + {d}{b}ᵀ + {c}{d}ᵀ + ½{c}{b}ᵀ`` with ``D_nm = ±1/(2n)`` for ``n = m ± 1``;
* ``b_n = (-1)^(n-1) (N+n-1)! / ((N-n-1)! (n!)²)`` for ``n < N``, ``b_N = (-1)^(N+1)``;
  ``c_n = 2/n``; ``d_1 = ½``, other ``d_n = 0``.

Units: ``λ_n`` and ``λ0`` in m/s (positive down, reducing the effective downwash); ``u0`` in m/s; ``b`` (the
semichord) in m; time in s. The binomial ``b_n`` series stops converging beyond ``N ≈ 10`` (reference
§2.2), so ``n_states`` is restricted to 1–10; 6–8 is recommended.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from math import factorial

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flexsim._arrays import readonly

MIN_STATES = 1
MAX_STATES = 10


@dataclass(frozen=True, eq=False)
class InflowCoefficients:
    """Read-only coefficients of the ``N``-state Peters inflow model (reference §2.1).

    Attributes
    ----------
    n_states : int
        ``N``.
    A : ndarray, shape (N, N)
        Inflow matrix [A].
    A_inv : ndarray, shape (N, N)
        Its inverse.
    A_inv_c : ndarray, shape (N,)
        ``[A]⁻¹{c}``: the response of ``{λ̇}`` to ``ẇ0 + ẇ1/2`` (acceleration coupling).
    b, c, d : ndarray, shape (N,)
        Coefficient vectors.
    """

    n_states: int
    A: NDArray[np.float64]
    A_inv: NDArray[np.float64]
    A_inv_c: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    d: NDArray[np.float64]


def _check_n_states(n_states: object) -> int:
    if (
        isinstance(n_states, bool)
        or not isinstance(n_states, (int, np.integer))
        or not MIN_STATES <= n_states <= MAX_STATES
    ):
        raise ValueError(
            f"n_states must be an integer in the range {MIN_STATES}..{MAX_STATES} "
            f"(the Peters b_n series diverges beyond about 10); got {n_states!r}"
        )
    return int(n_states)


@lru_cache(maxsize=MAX_STATES)
def _build(n: int) -> InflowCoefficients:
    order = np.arange(1, n + 1)
    binomial = [
        (-1) ** (k - 1) * factorial(n + k - 1) // (factorial(n - k - 1) * factorial(k) ** 2)
        for k in range(1, n)
    ]
    b_vec = np.array(binomial + [(-1) ** (n + 1)], dtype=float)
    c_vec = 2.0 / order
    d_vec = np.zeros(n)
    d_vec[0] = 0.5
    half_inverse = 1.0 / (2.0 * order[1:])
    d_mat = np.diag(half_inverse, -1) - np.diag(1.0 / (2.0 * order[:-1]), 1)
    a_mat = d_mat + np.outer(d_vec, b_vec) + np.outer(c_vec, d_vec) + 0.5 * np.outer(c_vec, b_vec)
    a_inv = np.linalg.inv(a_mat)
    return InflowCoefficients(
        n_states=n,
        A=readonly(a_mat),
        A_inv=readonly(a_inv),
        A_inv_c=readonly(a_inv @ c_vec),
        b=readonly(b_vec),
        c=readonly(c_vec),
        d=readonly(d_vec),
    )


def inflow_coefficients(n_states: int) -> InflowCoefficients:
    """Coefficients of the ``N``-state Peters inflow model (reference §2.1; Peters et al. 1995).

    Parameters
    ----------
    n_states : int
        Number of inflow states ``N``, an integer in 1–10.

    Returns
    -------
    InflowCoefficients
        Cached, read-only.

    Raises
    ------
    ValueError
        If ``n_states`` is not an integer in 1–10.
    """
    return _build(_check_n_states(n_states))


def induced_inflow(coefficients: InflowCoefficients, lam: ArrayLike) -> NDArray:
    """Effective uniform inflow ``λ0 = ½ {b}ᵀ{λ}`` (reference §2.1).

    Parameters
    ----------
    coefficients : InflowCoefficients
    lam : array_like, shape (..., N)
        Inflow states [m/s].

    Returns
    -------
    ndarray, shape (...)
        ``λ0`` [m/s], positive down.
    """
    return 0.5 * (np.asarray(lam) @ coefficients.b)


def inflow_state_derivative(
    coefficients: InflowCoefficients,
    lam: ArrayLike,
    forcing_rate: ArrayLike,
    u0: ArrayLike,
    b: ArrayLike,
) -> NDArray:
    """State derivative ``{λ̇} = [A]⁻¹({c}(ẇ0 + ẇ1/2) - (u0/b){λ})`` (reference §2.1).

    ``forcing_rate`` contains accelerations (for a rigid section
    ``ẇ0 + ẇ1/2 = ḧ + u0 θ̇ + u̇0 θ + b(½ - a)θ̈``), so in a coupled model use
    :attr:`InflowCoefficients.A_inv_c` to assemble the implicit system ``E ẋ = f``.

    Parameters
    ----------
    coefficients : InflowCoefficients
    lam : array_like, shape (..., N)
        Inflow states [m/s].
    forcing_rate : array_like, shape (...)
        ``ẇ0 + ẇ1/2`` [m/s²].
    u0 : array_like, shape (...)
        Free-stream speed [m/s] (may vary in time).
    b : array_like, shape (...)
        Semichord [m].

    Returns
    -------
    ndarray, shape (..., N)
        ``λ̇`` [m/s²].
    """
    decay = (np.asarray(u0) / np.asarray(b))[..., None] * np.asarray(lam)
    return np.asarray(forcing_rate)[..., None] * coefficients.A_inv_c - decay @ coefficients.A_inv.T


def inflow_transfer_function(coefficients: InflowCoefficients, k: ArrayLike) -> NDArray[np.complex128]:
    """Harmonic transfer ``λ0/(w0 + w1/2) = ½{b}ᵀ(ik[A] + [I])⁻¹{c} ik ≈ 1 - C(k)``.

    Source: reference §2.1 (accuracy: §2.2).

    Parameters
    ----------
    coefficients : InflowCoefficients
    k : array_like, shape (...)
        Reduced frequency ``ω b / u0`` (``e^{iωt}`` convention), dimensionless.

    Returns
    -------
    ndarray, shape (...)
        Complex, dimensionless; compare with ``1 - C(k)``.
    """
    k = np.asarray(k, dtype=float)
    ik = 1j * k[..., None, None]
    system = ik * coefficients.A + np.eye(coefficients.n_states)
    rhs = np.broadcast_to(coefficients.c, system.shape[:-1])[..., None].astype(complex)
    solution = np.linalg.solve(system, rhs)[..., 0]
    return 0.5 * (solution @ coefficients.b) * (1j * k)
