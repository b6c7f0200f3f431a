"""Peters finite-state inflow: its data and the inflow states' derivative, compiled.

Source: Peters, Karunamoorthy & Cao (1995), finite-state induced flow for a thin airfoil, as written in
``docs/reference/aero-kinematics.md`` section 2.1: N states lambda per unsteady strip, A lambda_dot + (u0/b) lambda =
c (w0_dot + w1_dot/2), the induced downwash lambda0 = 1/2 b^T lambda (:func:`flexsim.aero.inflow.inflow_coefficients`
gives A, b, c). The strips' kinematics use lambda0 (:mod:`~flexsim._kernels.strips`); the derivative is evaluated
with the solved accelerations (no acceleration lagged). SI units.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexsim._kernels.layout import STRIP_COL_PTR, STRIP_COLS, _f1, _f2, _flag, _i1, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class PetersData:
    """Finite-state inflow of the unsteady strips (Peters, Karunamoorthy & Cao 1995; docs/reference/aero-kinematics.md
    section 2.1): A lambda_dot + (u0/b) lambda = c (w0_dot + w1_dot/2), lambda0 = 1/2 b^T lambda."""

    a_inv: np.ndarray = packed(2, "A^-1 (N, N) [-]")
    a_inv_c: np.ndarray = packed(1, "A^-1 c (N,) [-]")
    b_vec: np.ndarray = packed(1, "b (N,) [-]")
    inflow_idx: np.ndarray = packed(1, "the unsteady strips (n_u,)", "ints")
    finite_state: int = packed(0, "1: the unsteady model (inflow states)", "flag")
    n_inflow_per_strip: int = packed(0, "N, inflow states per unsteady strip", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): the inflow coefficients and
        unsteady strips of its strip coupling (``model.aero``); none without aerodynamics."""
        a = model.aero
        if a is None:
            return dict(a_inv=np.zeros((1, 1)), a_inv_c=np.zeros(1), b_vec=np.zeros(1), n_inflow_per_strip=1)
        return dict(a_inv=a.inflow.A_inv, a_inv_c=a.inflow.A_inv_c, b_vec=a.inflow.b, inflow_idx=a.inflow_idx,
                    finite_state=a.finite_state, n_inflow_per_strip=a.options.n_inflow)


A_INV = PetersData.index["a_inv"]
A_INV_C = PetersData.index["a_inv_c"]
B_VEC = PetersData.index["b_vec"]
INFLOW_IDX = PetersData.index["inflow_idx"]
FINITE_STATE = PetersData.index["finite_state"]
N_PER_STRIP = PetersData.index["n_inflow_per_strip"]


@kernel
def inflow_lambda0(F, I, lam, n_s):
    """lambda0 = 1/2 b^T lambda of every strip (n_s,) [m/s], zero on the quasi-steady strips and models."""
    lam0 = np.zeros(n_s)
    if _flag(I, FINITE_STATE):
        nin = _flag(I, N_PER_STRIP)
        b_vec = _f1(F, I, B_VEC)
        idx = _i1(I, INFLOW_IDX)
        for c in range(idx.shape[0]):
            acc = 0.0
            for k in range(nin):
                acc += lam[c * nin + k] * b_vec[k]
            lam0[idx[c]] = 0.5 * acc
    return lam0


@kernel
def inflow_derivative(F, I, row0, w_ea_x, u0, lam, vdot, semichord, proj_p):
    """Finite-state inflow derivative (reference section 2.1, Peters et al. 1995) with the solved V_dot:
    lambda_dot = A^-1 [c (w0_dot + w1_dot/2) - (u0/b) lambda] for every unsteady strip, with
    w0_dot + w1_dot/2 = (row0 + b/2 p^T B) V_dot + w_ea_x [m/s^2]; semichord b (n_s,) [m] and proj_p p^T B
    (n_s, n_v) of the strips. Returns (n_u N,) [m/s^2]."""
    nin = _flag(I, N_PER_STRIP)
    idx = _i1(I, INFLOW_IDX)
    a_inv = _f2(F, I, A_INV)
    a_inv_c = _f1(F, I, A_INV_C)
    col_ptr = _i1(I, STRIP_COL_PTR)
    cols = _i1(I, STRIP_COLS)
    out = np.empty(idx.shape[0] * nin)
    for c in range(idx.shape[0]):
        j = idx[c]
        forcing = w_ea_x[j]
        for t in range(col_ptr[j], col_ptr[j + 1]):  # the strip's non-zero columns (strip_columns)
            i = cols[t]
            forcing += (row0[j, i] + 0.5 * semichord[j] * proj_p[j, i]) * vdot[i]
        decay = u0[j] / semichord[j]
        for r in range(nin):
            acc = 0.0
            for k in range(nin):
                acc += a_inv[r, k] * lam[c * nin + k]
            out[c * nin + r] = forcing * a_inv_c[r] - decay * acc
    return out
