"""Jacobians of the one nonlinear model, d rhs / dx and d rhs / du, by central differences.

The same right-hand side as trim, simulation and the envs (:meth:`AircraftModel.rhs`), differentiated with
steps scaled to each state's magnitude (relative step 1e-6, floor 1e-7). A property of the model, used by
linear analysis (:mod:`flexsim.linear`), the implicit integrator of :mod:`flexsim.sim` and the envs.

Structured columns over the inflow states (``method="structured"``, the default). The finite-state inflow
``lambda_j`` of strip j (N states, Peters, Karunamoorthy & Cao 1995; :mod:`flexsim.aero.inflow`) enters
the right-hand side in two ways only (:mod:`flexsim.model.coupling`):

* through ``lambda0_j = 1/2 b^T lambda_j`` in the strip's circulatory loads (and from there in every
  acceleration and every inflow forcing);
* linearly in its own rate, ``lambda_dot_j = A^-1 c (w0_dot + w1_dot/2)_j - (u0_j / b_j) A^-1 lambda_j``.

So ``d rhs / d lambda_j = g_j (1/2 b^T) + E_j`` with ``g_j = d rhs / d lambda0_j`` (one central difference
along a direction v with 1/2 b^T v = 1, from which E_j v is removed) and ``E_j`` the exact block
``-(u0_j / b_j) A^-1`` on the rows of lambda_j. That is 2 right-hand sides per unsteady strip instead of
2 N: 2 (60 + 32) + 8 = 192 instead of 512 for the GTM with N = 6. The result equals the dense central
difference (``method="dense"``) within the differences' truncation and round-off errors (both about 5e-9
of the largest inflow column against the exact derivative; tests/model/test_jacobian.py).
"""

from __future__ import annotations

import numpy as np

from flexsim._threads import single_blas_thread
from flexsim.model.aircraft_model import AircraftModel

__all__ = ["JACOBIAN_METHODS", "jacobian"]

#: Ways of differentiating over the inflow states.
JACOBIAN_METHODS = ("structured", "dense")

_REL_STEP = 1e-6
_ABS_STEP = 1e-7
#: Step in lambda0 [m/s] (relative above 1 m/s). The truncation error of the central difference is
#: h^2 f'''/6 and the round-off about eps |f| / h: 1e-4 balances them (measured against a fourth-order
#: Richardson extrapolation: 2.8e-9 of the largest inflow column, 2.8e-7 at 1e-3, 3e-9 to 8e-9 at 1e-5;
#: the dense difference with its 1e-7 steps: 6e-9).
_INFLOW_STEP = 1e-4


def _column(model: AircraftModel, t: float, x: np.ndarray, u: np.ndarray, direction: np.ndarray, h: float, wind=None) -> np.ndarray:
    return (model.rhs(t, x + h * direction, u, wind) - model.rhs(t, x - h * direction, u, wind)) / (2 * h)


@single_blas_thread
def jacobian(model: AircraftModel, x: np.ndarray, u: np.ndarray, t: float = 0.0, *,
             method: str = "structured", controls: bool = True, wind=None) -> tuple[np.ndarray, np.ndarray | None]:
    """Central-difference Jacobians of ``model.rhs`` at (t, x, u) (module docstring).

    Parameters
    ----------
    model : AircraftModel
    x : ndarray, shape (n,)
        State (the model's layout).
    u : ndarray, shape (4,)
        Controls [T_e (N), delta_a, delta_e, delta_r (rad)].
    t : float
        Time [s] (for the wind field).
    method : {"structured", "dense"}
        ``structured``: two right-hand sides per unsteady strip for its inflow states; ``dense``: two per
        state (the reference).
    controls : bool
        Also return B = d rhs / du (8 more right-hand sides); None otherwise.
    wind : callable, optional
        Disturbance passed to every ``model.rhs`` call (:meth:`AircraftModel.rhs`); None: still air.

    Returns
    -------
    a : ndarray, shape (n, n)
        d rhs / dx [1/s and mixed units of the layout].
    b : ndarray, shape (n, 4) or None
        d rhs / du.
    """
    if method not in JACOBIAN_METHODS:
        raise ValueError(f"method = {method!r}: must be one of {', '.join(JACOBIAN_METHODS)}")
    x = np.asarray(x, dtype=float)
    u = np.asarray(u, dtype=float)
    n = x.size
    lay = model.layout
    structured = method == "structured" and lay.n_inflow > 0
    n_direct = lay.inflow.start if structured else n
    a = np.empty((n, n))
    for j in range(n_direct):
        h = max(_ABS_STEP, _REL_STEP * abs(x[j]))
        e = np.zeros(n)
        e[j] = 1.0
        a[:, j] = _column(model, t, x, u, e, h, wind)
    if structured:
        _inflow_columns(model, t, x, u, a, wind)
    b = None
    if controls:
        b = np.empty((n, 4))
        for j in range(4):
            h = max(1e-3 if j == 0 else 1e-7, _REL_STEP * abs(u[j]))
            up, um = u.copy(), u.copy()
            up[j] += h
            um[j] -= h
            b[:, j] = (model.rhs(t, x, up, wind) - model.rhs(t, x, um, wind)) / (2 * h)
    return a, b


def _inflow_columns(model: AircraftModel, t: float, x: np.ndarray, u: np.ndarray, a: np.ndarray, wind=None) -> None:
    """Fill the inflow columns of ``a`` (module docstring: g_j (1/2 b^T) + E_j per unsteady strip)."""
    lay = model.layout
    coupling = model.aero
    n_in = coupling.options.n_inflow
    coef = coupling.inflow
    idx = np.flatnonzero(coupling.strips.unsteady)
    _, _, q, xi, vel = model.unpack(x)
    kin = coupling.kinematics(q, xi, vel, x[lay.inflow], u, model.strip_wind(t, x, wind))
    decay = kin.u0[idx] / coupling.strips.semichord_m[idx]  # u0_j / b_j [1/s]
    half_b = 0.5 * coef.b
    v = coef.b / (half_b @ coef.b)  # 1/2 b^T v = 1
    lam = x[lay.inflow].reshape(-1, n_in)
    for c in range(idx.size):
        rows = slice(lay.inflow.start + c * n_in, lay.inflow.start + (c + 1) * n_in)
        lam0 = float(half_b @ lam[c])
        h = _INFLOW_STEP * max(1.0, abs(lam0))
        direction = np.zeros(x.size)
        direction[rows] = v
        g = _column(model, t, x, u, direction, h, wind)
        e_block = -decay[c] * coef.A_inv
        g[rows] -= e_block @ v
        a[:, rows] = np.outer(g, half_b)
        a[rows, rows] += e_block
