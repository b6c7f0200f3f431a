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


def _central_differences(model: AircraftModel, t: float, x: np.ndarray, u: np.ndarray, dx: np.ndarray, du: np.ndarray,
                         h: np.ndarray, wind=None) -> np.ndarray:
    """Columns (rhs(x + dx_k, u + du_k) - rhs(x - dx_k, u - du_k)) / (2 h_k), shape (n, k): all 2k right-hand
    sides in one compiled call (:meth:`AircraftModel.rhs_batch`; each row equals ``model.rhs`` bit for bit), or
    one by one for a wind that is a plain Python callable."""
    xs = np.concatenate([x + dx, x - dx])
    us = np.concatenate([u + du, u - du])
    k = dx.shape[0]
    batched = type(model).rhs is AircraftModel.rhs  # a subclass's own rhs is differentiated call by call
    if batched and (wind is None or getattr(wind, "wind_data", None) is not None):
        r = model.rhs_batch(t, xs, us, wind)
    else:
        r = np.stack([model.rhs(t, xi, ui, wind) for xi, ui in zip(xs, us)])
    return ((r[:k] - r[k:]) / (2 * h)[:, None]).T


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
    h = np.maximum(_ABS_STEP, _REL_STEP * np.abs(x[:n_direct]))
    dx = np.zeros((n_direct, n))
    dx[np.arange(n_direct), np.arange(n_direct)] = h
    a[:, :n_direct] = _central_differences(model, t, x, u, dx, np.zeros((n_direct, 4)), h, wind)
    if structured:
        _inflow_columns(model, t, x, u, a, wind)
    b = None
    if controls:
        hu = np.maximum([1e-3, 1e-7, 1e-7, 1e-7], _REL_STEP * np.abs(u))
        b = _central_differences(model, t, x, u, np.zeros((4, n)), np.diag(hu), hu, wind)
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
    hs = _INFLOW_STEP * np.maximum(1.0, np.abs(lam @ half_b))
    dirs = np.zeros((idx.size, x.size))
    for c in range(idx.size):
        dirs[c, lay.inflow.start + c * n_in: lay.inflow.start + (c + 1) * n_in] = v * hs[c]
    g_all = _central_differences(model, t, x, u, dirs, np.zeros((idx.size, 4)), hs, wind)
    for c in range(idx.size):
        rows = slice(lay.inflow.start + c * n_in, lay.inflow.start + (c + 1) * n_in)
        g = g_all[:, c].copy()
        e_block = -decay[c] * coef.A_inv
        g[rows] -= e_block @ v
        a[:, rows] = np.outer(g, half_b)
        a[rows, rows] += e_block
