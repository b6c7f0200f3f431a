"""Compiled parts of the p-k state matrix (:func:`flexsim.linear.stability.pk_state_matrix`).

:func:`w34_jacobian` is the central-difference output matrix C_w = d (w0 + w1/2)_j / dx of paper eq. 27 (the
downwash at the three-quarter chord of every unsteady strip, eqs. 25-31): the same steps, perturbations and
kernels (:func:`flexsim._kernels.unpack`, :func:`flexsim._kernels.strip_kinematics`) as one call of the model's
``unpack`` and the coupling's ``kinematics`` per perturbed state in Python, in one compiled call (equal bit for
bit; ``tests/linear/test_pk.py``).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from flexsim import _kernels
from flexsim._numba_cache import depends_on

__all__ = ["w34_jacobian"]


@depends_on(_kernels)
@njit(cache=True, nogil=True)
def w34_jacobian(f_model: np.ndarray, i_model: np.ndarray, f_aero: np.ndarray, i_aero: np.ndarray, x: np.ndarray,
                 u: np.ndarray, inflow_start: int, inflow_stop: int, n_strips: int, strips: np.ndarray, first: int,
                 stop: int) -> np.ndarray:
    """d (w0 + w1/2) / dx at the strips ``strips`` [m/s per state unit], shape (strips.size, stop): columns
    ``first`` to ``stop - 1`` by central differences with the step ``max(1e-7, 1e-6 |x_j|)``, the others zero.

    ``(f_model, i_model)``: the model's packed data (``AircraftModel.kernel_data``); ``(f_aero, i_aero)``: its
    coupling's (``AeroCoupling.kernel_data``); ``x`` (n,) the state with the inflow states at
    ``inflow_start:inflow_stop``; ``u`` (4,) the controls; ``n_strips`` the coupling's number of strips. No wind
    (the p-k analysis is of still air).
    """
    wind = np.zeros((n_strips, 3))
    has_wind = n_strips < 0  # false; a run-time bool, as the right-hand side passes (not a literal: one compile fewer)
    out = np.zeros((strips.shape[0], stop))
    for j in range(first, stop):
        h = max(1e-7, 1e-6 * abs(x[j]))
        xp = x.copy()
        xm = x.copy()
        xp[j] += h
        xm[j] -= h
        _, _, q, xi, v = _kernels.unpack(f_model, i_model, xp)
        wp = _kernels.strip_kinematics(f_aero, i_aero, q, xi, v, xp[inflow_start:inflow_stop].copy(), u, wind, has_wind)[5]
        _, _, q, xi, v = _kernels.unpack(f_model, i_model, xm)
        wm = _kernels.strip_kinematics(f_aero, i_aero, q, xi, v, xm[inflow_start:inflow_stop].copy(), u, wind, has_wind)[5]
        for r in range(strips.shape[0]):
            out[r, j] = (wp[strips[r]] - wm[strips[r]]) / (2 * h)
    return out
