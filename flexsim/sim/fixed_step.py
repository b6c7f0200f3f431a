"""Fixed-step exponential integrator for stiff systems near a known linearisation (ETD2RK).

The gymnasium environments integrate the nonlinear model ``x_dot = f(t, x)`` (``AircraftModel.rhs``)
over short control periods near a trim whose Jacobian J = df/dx is known. Splitting
``f(t, x) = J x + N(t, x)`` with the remainder ``N = f - J x``, the second-order exponential Runge-Kutta
method ETD2RK of Cox & Matthews (2002) treats the linear part exactly and the remainder explicitly:

    a       = e^{hJ} x_n + h phi_1(hJ) N(t_n, x_n)
    x_{n+1} = a + h phi_2(hJ) [N(t_n + h, a) - N(t_n, x_n)]

with ``phi_1(z) = (e^z - 1) / z`` and ``phi_2(z) = (e^z - 1 - z) / z^2``. Because ``h phi_1(hJ) J =
e^{hJ} - I`` this is, in terms of f alone (the form evaluated here, which never forms ``J x`` of the
large absolute states such as the altitude),

    k_1     = f(t_n, x_n)
    a       = x_n + h phi_1(hJ) k_1
    k_2     = f(t_n + h, a)
    x_{n+1} = a + h phi_2(hJ) [k_2 - k_1 - J (a - x_n)]

Two evaluations of f and three dense matrix-vector products per step; no linear solves. Properties
(Hochbruck & Ostermann 2010, section 2.3, where this is the method with c_2 = 1):

* exact for linear problems ``f = J x + g`` with constant g, for every h (the linear stiff modes, e.g.
  finite-state inflow eigenvalues near -650 1/s, are neither step-size limited nor damped, and
  oscillatory modes keep their growth rate: no numerical damping of a flutter mode);
* order 2 for any fixed J when N is smooth; the error constant scales with the part of the dynamics
  that J does not describe (distance from the linearisation point, time-varying forcing);
* explicit in N: stable as long as ``h * ||df/dx - J||`` stays moderate, i.e. near the linearisation.

The matrix functions are computed once per (J, h) from the exponential of an augmented matrix
(Al-Mohy & Higham 2011, section 2; Saad 1992): for ``M = [[hJ, I, 0], [0, 0, I], [0, 0, 0]]`` of size 3n,
``expm(M)[:n] = [e^{hJ}, phi_1(hJ), phi_2(hJ)]``.

References
----------
S. M. Cox and P. C. Matthews, "Exponential time differencing for stiff systems", J. Comput. Phys. 176
(2002) 430-455 (method ETD2RK).
M. Hochbruck and A. Ostermann, "Exponential integrators", Acta Numerica 19 (2010) 209-286.
A. H. Al-Mohy and N. J. Higham, "Computing the action of the matrix exponential, with an application to
exponential integrators", SIAM J. Sci. Comput. 33 (2011) 488-511.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy.integrate import DenseOutput, OdeSolver
from scipy.linalg import expm

from flexsim._arrays import readonly

__all__ = ["phi_functions", "ETD2RK", "ETD2RKSolver"]


def _check_matrix(name: str, a: np.ndarray) -> np.ndarray:
    try:
        m = np.array(a, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: must be a square array of finite numbers, got {type(a).__name__}") from None
    if m.ndim != 2 or m.shape[0] != m.shape[1] or m.shape[0] == 0:
        raise ValueError(f"{name}: must be a non-empty square matrix (n, n), got shape {m.shape}")
    bad = np.argwhere(~np.isfinite(m))
    if bad.size:
        i, j = bad[0]
        raise ValueError(f"{name}: must be finite, got {name}[{i}, {j}] = {m[i, j]} ({len(bad)} non-finite entries)")
    return m


def _check_step(h: float) -> float:
    try:
        step = float(h)
    except (TypeError, ValueError):
        raise ValueError(f"h = {h!r}: must be a finite number > 0 [s]") from None
    if not (math.isfinite(step) and step > 0.0):
        raise ValueError(f"h = {h!r}: must be a finite number > 0 [s]")
    return step


def phi_functions(jac: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``e^{hJ}``, ``phi_1(hJ)`` and ``phi_2(hJ)`` of a square matrix J and a step h.

    Parameters
    ----------
    jac : array_like, shape (n, n)
        The matrix J [1/s] (finite).
    h : float
        Step [s] (> 0).

    Returns
    -------
    exp_hj, phi1, phi2 : ndarray, shape (n, n)
        ``phi_1(z) = (e^z - 1) / z``, ``phi_2(z) = (e^z - 1 - z) / z^2`` (1 and 1/2 at z = 0; J may be
        singular), from one ``scipy.linalg.expm`` of the 3n x 3n augmented matrix (module docstring).
    """
    j = _check_matrix("jac", jac)
    step = _check_step(h)
    n = j.shape[0]
    aug = np.zeros((3 * n, 3 * n))
    aug[:n, :n] = step * j
    aug[:n, n : 2 * n] = np.eye(n)
    aug[n : 2 * n, 2 * n :] = np.eye(n)
    e = expm(aug)
    return e[:n, :n].copy(), e[:n, n : 2 * n].copy(), e[:n, 2 * n :].copy()


class ETD2RK:
    """Second-order exponential Runge-Kutta step with a fixed linear part (module docstring).

    Parameters
    ----------
    jac : array_like, shape (n, n)
        The fixed linear part J [1/s], normally the Jacobian df/dx at a reference point (finite).
    h : float
        Step [s] (> 0).

    Attributes
    ----------
    h : float
        Step [s].
    n : int
        State dimension.
    nfev_per_step : int
        Right-hand-side evaluations per :meth:`step` (2).
    """

    nfev_per_step = 2

    def __init__(self, jac: np.ndarray, h: float) -> None:
        self._jac = readonly(_check_matrix("jac", jac))
        self.h = _check_step(h)
        self.n = self._jac.shape[0]
        _, phi1, phi2 = phi_functions(self._jac, self.h)
        self._h_phi1 = readonly(self.h * phi1)
        self._h_phi2 = readonly(self.h * phi2)

    @property
    def jac(self) -> np.ndarray:
        """The linear part J (read-only), shape (n, n) [1/s]."""
        return self._jac

    def step(self, fun: Callable[..., np.ndarray], t: float, x: np.ndarray, args: tuple = (),
             k1: np.ndarray | None = None) -> np.ndarray:
        """One step from (t, x) to t + h.

        Parameters
        ----------
        fun : callable
            ``fun(t, x, *args) -> x_dot``, shape (n,).
        t : float
            Time [s].
        x : ndarray, shape (n,)
            State at t.
        args : tuple
            Extra arguments of ``fun`` (e.g. held controls).
        k1 : ndarray, shape (n,), optional
            ``fun(t, x, *args)`` if already known (saves one evaluation).

        Returns
        -------
        ndarray, shape (n,)
            State at t + h (non-finite entries propagate; the caller checks).
        """
        if np.shape(x) != (self.n,):
            raise ValueError(f"x: expected shape ({self.n},) to match jac, got shape {np.shape(x)}")
        if k1 is None:
            k1 = fun(t, x, *args)
        a = x + self._h_phi1 @ k1
        k2 = fun(t + self.h, a, *args)
        return a + self._h_phi2 @ (k2 - k1 - self._jac @ (a - x))

    def step_rows(self, fun: Callable[[np.ndarray, np.ndarray], np.ndarray], t: np.ndarray, x: np.ndarray) -> np.ndarray:
        """One step of many independent systems sharing this J and h (the rows of ``x``), as matrix products.

        Parameters
        ----------
        fun : callable
            ``fun(t, x) -> x_dot`` for all rows at once: ``t`` shape (m,) [s], ``x`` and the result shape (m, n).
        t : ndarray, shape (m,)
            Time of each row [s].
        x : ndarray, shape (m, n)
            States at t.

        Returns
        -------
        ndarray, shape (m, n)
            States at t + h: row i equals ``step`` of row i to rounding (the products are evaluated as
            GEMMs instead of GEMVs); non-finite entries propagate.
        """
        if np.ndim(x) != 2 or np.shape(x)[1] != self.n:
            raise ValueError(f"x: expected shape (m, {self.n}) to match jac, got shape {np.shape(x)}")
        k1 = fun(t, x)
        a = x + k1 @ self._h_phi1.T
        k2 = fun(t + self.h, a)
        return a + (k2 - k1 - (a - x) @ self._jac.T) @ self._h_phi2.T


class ETD2RKSolver(OdeSolver):
    """ETD2RK with fixed steps behind scipy's ``OdeSolver`` interface (for :func:`flexsim.sim.simulate`).

    Steps of exactly ``step`` [s] from ``t0`` (the last one of an interval shortened to land on
    ``t_bound``; one :class:`ETD2RK` per distinct step, kept in ``cache`` across solvers). The state
    derivative at the end of a step is the first evaluation of the next, so a step costs two evaluations
    of ``fun``. Dense output: the cubic Hermite interpolant of the states and derivatives at both ends
    (third order, below the method's own error at the step end).

    Parameters
    ----------
    fun, t0, y0, t_bound
        As for every scipy ``OdeSolver``.
    jac : ndarray, shape (n, n)
        The fixed linear part J [1/s] (normally the Jacobian at the initial state).
    step : float
        The fixed step h [s] > 0.
    cache : dict, optional
        ``{h: ETD2RK}`` shared between the solvers of one run (the matrix functions cost one ``expm`` of a
        3n x 3n matrix per h).
    """

    def __init__(self, fun, t0, y0, t_bound, jac, step, cache=None, vectorized=False, **extraneous):
        super().__init__(fun, t0, y0, t_bound, vectorized)
        self._jac = _check_matrix("jac", jac)
        self.h_step = _check_step(step)
        self._cache = {} if cache is None else cache
        self.f = self.fun(self.t, self.y)
        self._f_old = None
        self.njev, self.nlu = 0, 0

    def _method(self, h: float) -> ETD2RK:
        key = round(h, 12)
        if key not in self._cache:
            self._cache[key] = ETD2RK(self._jac, h)
        return self._cache[key]

    def _step_impl(self):
        remaining = self.t_bound - self.t
        h = self.h_step if remaining > self.h_step * (1.0 + 1e-9) else remaining
        y_new = self._method(h).step(self.fun, self.t, self.y, k1=self.f)
        t_new = self.t_bound if h == remaining else self.t + h
        self._y_old, self._f_old = self.y, self.f
        self.t, self.y = t_new, y_new
        self.f = self.fun(t_new, y_new)
        return True, None

    def _dense_output_impl(self):
        return _Hermite(self.t_old, self.t, self._y_old, self.y, self._f_old, self.f)


class _Hermite(DenseOutput):
    """Cubic Hermite interpolant between (t_old, y_old, f_old) and (t, y, f)."""

    def __init__(self, t_old, t, y_old, y, f_old, f):
        super().__init__(t_old, t)
        self.h = t - t_old
        self.y_old, self.dy = y_old, y - y_old
        self.f_old, self.f = f_old, f

    def _call_impl(self, t):
        s = (np.asarray(t, dtype=float) - self.t_old) / self.h
        h01, h10, h11 = s * s * (3 - 2 * s), s * (1 - s) ** 2, s * s * (s - 1)  # h00 = 1 - h01
        y = np.multiply.outer(self.y_old, np.ones_like(s)) + np.multiply.outer(self.dy, h01)
        return y + self.h * (np.multiply.outer(self.f_old, h10) + np.multiply.outer(self.f, h11))
