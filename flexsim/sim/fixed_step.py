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

The matrix functions are computed once per (J, h) by scaling and modified squaring on n x n matrices
(Skaflestad & Wright 2009): balance ``Z = hJ`` (``scipy.linalg.matrix_balance``, a diagonal similarity
D^-1 Z D), halve it s times until ``alpha_4 = max(||W^4||^(1/4), ||W^5||^(1/5))`` (1-norms; <= ||W||, and much
smaller for a non-normal matrix: 54 against 177 for the GTM at h = 20 ms, 6 doublings instead of 8) is <= 1, which
bounds the truncation error of the Taylor series of phi_2 there (degree 16) as ||W|| <= 1 would (Al-Mohy & Higham
2009, theorem 4.2), sum that series by the Paterson-Stockmeyer scheme (3 matrix products beyond the powers),
``phi_1 = I + W phi_2``, ``e^W = I + W phi_1``, then double s times with
``phi_2(2W) = (e^W phi_2 + phi_1 + phi_2) / 4``, ``phi_1(2W) = (e^W phi_1 + phi_1) / 2``, ``e^{2W} = (e^W)^2``.
The result is checked against ``Z phi_1(Z) = e^Z - I`` and ``Z phi_2(Z) = phi_1(Z) - I``; if either residual
exceeds 1e-8 (relative) it falls back to the exponential of the augmented matrix
(Al-Mohy & Higham 2011, section 2; Saad 1992): for ``M = [[hJ, I, 0], [0, 0, I], [0, 0, 0]]`` of size 3n,
``expm(M)[:n] = [e^{hJ}, phi_1(hJ), phi_2(hJ)]`` (``phi_functions(..., method="augmented")``, 27x the
arithmetic). On the GTM trim Jacobian (252 states) at h = 5-20 ms the two agree to 1e-12 of the largest
entry (asserted in tests/sim/test_fixed_step.py); timings are in benchmarks/, not here.

Compiled steps: every ETD2RK step is taken by the one compiled kernel :func:`flexsim.sim._step_kernels.etd2rk_rows`
(:meth:`ETD2RK.run`: a run of one aircraft for :func:`flexsim.sim.simulate`; :meth:`ETD2RK.advance_rows`: control
periods of N aircraft for :mod:`flexsim.sim.periods` and the environments), whose stage arithmetic is
:func:`flexsim.sim._step_kernels.stage_a` and :func:`~flexsim.sim._step_kernels.stage_b`. :meth:`ETD2RK.step`, for a
right-hand side the kernels cannot evaluate (a wind given as a Python callable), calls the same two compiled stages
around it, so the arithmetic exists once. The tests compare all of them with a plain numpy transcription of the
formulas above (``tests/sim/etd2rk_reference.py``).

References
----------
S. M. Cox and P. C. Matthews, "Exponential time differencing for stiff systems", J. Comput. Phys. 176
(2002) 430-455 (method ETD2RK).
M. Hochbruck and A. Ostermann, "Exponential integrators", Acta Numerica 19 (2010) 209-286.
A. H. Al-Mohy and N. J. Higham, "Computing the action of the matrix exponential, with an application to
exponential integrators", SIAM J. Sci. Comput. 33 (2011) 488-511.
A. H. Al-Mohy and N. J. Higham, "A new scaling and squaring algorithm for the matrix exponential", SIAM J. Matrix
Anal. Appl. 31 (2009) 970-989.
E. Skaflestad and W. M. Wright, "The scaling and modified squaring method for matrix functions related to
the exponential", Appl. Numer. Math. 59 (2009) 783-799.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy.integrate import DenseOutput, OdeSolver
from typing import NamedTuple

from scipy.linalg import expm, matrix_balance

from flexsim import _kernels as _k
from flexsim._arrays import kernel_arg, readonly
from flexsim.errors import positive_number
from flexsim.sim import _dense_kernels as _dk
from flexsim.sim import _step_kernels as _sk

__all__ = ["phi_functions", "PHI_METHODS", "ETD2RK", "ETD2RKSolver", "RowsAdvance", "RunSteps", "quintic_hermite",
           "step_accelerations", "quintic_weights", "interior", "off_midpoint", "NODE_TOLERANCE"]

#: Ways of computing the matrix functions (:func:`phi_functions`).
PHI_METHODS = ("scaled", "augmented")
#: Relative residual of the identities above which the scaled form falls back to the augmented matrix.
PHI_RESIDUAL_LIMIT = 1e-8
_TAYLOR_DEGREE = 16


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
    return positive_number("h", h, "s")


def phi_functions(jac: np.ndarray, h: float, method: str = "scaled") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``e^{hJ}``, ``phi_1(hJ)`` and ``phi_2(hJ)`` of a square matrix J and a step h.

    Parameters
    ----------
    jac : array_like, shape (n, n)
        The matrix J [1/s] (finite).
    h : float
        Step [s] (> 0).
    method : {"scaled", "augmented"}
        ``"scaled"`` (default): scaling and modified squaring of the balanced n x n matrix, checked, with the
        augmented form as fallback (module docstring); ``"augmented"``: one ``scipy.linalg.expm`` of the
        3n x 3n augmented matrix (the reference).

    Returns
    -------
    exp_hj, phi1, phi2 : ndarray, shape (n, n)
        ``phi_1(z) = (e^z - 1) / z``, ``phi_2(z) = (e^z - 1 - z) / z^2`` (1 and 1/2 at z = 0; J may be
        singular).
    """
    j = _check_matrix("jac", jac)
    step = _check_step(h)
    if method not in PHI_METHODS:
        raise ValueError(f"method = {method!r}: must be one of {', '.join(PHI_METHODS)}")
    if method == "scaled":
        with np.errstate(all="ignore"):
            e, phi1, phi2, residual = _phi_scaled(step * j)
        if residual <= PHI_RESIDUAL_LIMIT:
            return e, phi1, phi2
    n = j.shape[0]
    aug = np.zeros((3 * n, 3 * n))
    aug[:n, :n] = step * j
    aug[:n, n : 2 * n] = np.eye(n)
    aug[n : 2 * n, 2 * n :] = np.eye(n)
    e = expm(aug)
    return e[:n, :n].copy(), e[:n, n : 2 * n].copy(), e[:n, 2 * n :].copy()


def _phi_scaled(z: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """e^Z, phi_1(Z), phi_2(Z) by balancing, scaling, Taylor series and modified squaring (module docstring), and
    the residual of the identities (:func:`_phi_residual`, on the balanced matrix)."""
    n = z.shape[0]
    zb, (scale, _) = matrix_balance(z, permute=False, separate=True)  # zb = D^-1 z D, D = diag(scale)
    one_norm = lambda a: float(np.abs(a).sum(axis=0).max())  # noqa: E731
    powers = [np.eye(n), zb]  # Z^0 .. Z^4 (Paterson-Stockmeyer's powers, scaled below)
    alpha = one_norm(zb)
    if alpha > 1.0:  # alpha_4 = max(||Z^4||^(1/4), ||Z^5||^(1/5)) <= ||Z||: fewer doublings for a non-normal Z
        for _ in range(2, _PS_BLOCK + 1):
            powers.append(powers[-1] @ zb)
        alpha = min(alpha, max(one_norm(powers[4]) ** 0.25, one_norm(powers[4] @ zb) ** 0.2))
    s = max(0, math.ceil(math.log2(alpha))) if alpha > 0 else 0
    w = zb / 2.0**s
    powers = [powers[0], w] + [pk / 2.0 ** (s * k) for k, pk in enumerate(powers[2:], start=2)]
    diag = np.diag_indices(n)
    phi2 = _phi2_taylor(powers)
    phi1 = w @ phi2
    phi1[diag] += 1.0
    e = w @ phi1
    e[diag] += 1.0
    # the doublings, with the three products by e^W as one product e^W [phi_2, phi_1, e^W] (n x 3n)
    stack = np.empty((n, 3 * n))
    stack[:, :n], stack[:, n:2 * n], stack[:, 2 * n:] = phi2, phi1, e
    for _ in range(s):
        prod = stack[:, 2 * n:] @ stack
        prod[:, :n] += stack[:, n:2 * n] + stack[:, :n]
        prod[:, :n] *= 0.25
        prod[:, n:2 * n] += stack[:, n:2 * n]
        prod[:, n:2 * n] *= 0.5
        stack = prod
    phi2, phi1, e = stack[:, :n], stack[:, n:2 * n], stack[:, 2 * n:]
    residual = _phi_residual(zb, e, phi1, phi2)
    e, phi1, phi2 = ((scale[:, None] * m) / scale[None, :] for m in (e, phi1, phi2))  # D f(zb) D^-1
    return e, phi1, phi2, residual


#: Block size of the Paterson-Stockmeyer evaluation of the degree-16 Taylor polynomial (:func:`_phi2_taylor`).
_PS_BLOCK = 4


def _phi2_taylor(powers: list[np.ndarray]) -> np.ndarray:
    """``sum_{k=0}^{16} W^k / (k + 2)!`` (the Taylor polynomial of phi_2 of degree :data:`_TAYLOR_DEGREE`) from
    ``powers`` = [I, W] or [I, W, .., W^4], by the Paterson-Stockmeyer scheme (Higham, Functions of Matrices, SIAM
    2008, sec. 4.2): the powers W^2 .. W^4, then Horner's rule in W^4 over blocks of four terms; 6 matrix products
    (3 with the powers given) instead of Horner's 16."""
    n = powers[0].shape[0]
    c = [1.0 / math.factorial(k + 2) for k in range(_TAYLOR_DEGREE + 1)]
    powers = list(powers)
    while len(powers) <= _PS_BLOCK:
        powers.append(powers[-1] @ powers[1])
    top = _PS_BLOCK * (_TAYLOR_DEGREE // _PS_BLOCK)  # 16: the last block is c_16 I alone

    def block(j: int) -> np.ndarray:  # sum_{i < 4} c_{4j + i} W^i (the terms that exist)
        out = np.zeros((n, n))
        for i in range(_PS_BLOCK):
            if _PS_BLOCK * j + i <= _TAYLOR_DEGREE:
                out += c[_PS_BLOCK * j + i] * powers[i]
        return out

    acc = block(top // _PS_BLOCK)
    for j in range(top // _PS_BLOCK - 1, -1, -1):
        acc = powers[_PS_BLOCK] @ acc
        acc += block(j)
    return acc


def _phi_residual(z: np.ndarray, e: np.ndarray, phi1: np.ndarray, phi2: np.ndarray) -> float:
    """max of ||Z phi_1 - (e^Z - I)|| / (1 + ||e^Z||) and ||Z phi_2 - (phi_1 - I)|| / (1 + ||phi_1||) (1-norms);
    inf if anything is not finite."""
    if not (np.all(np.isfinite(e)) and np.all(np.isfinite(phi1)) and np.all(np.isfinite(phi2))):
        return math.inf
    eye = np.eye(z.shape[0])
    norm = lambda a: float(np.abs(a).sum(axis=0).max())  # noqa: E731
    r1 = norm(z @ phi1 - (e - eye)) / (1.0 + norm(e))
    r2 = norm(z @ phi2 - (phi1 - eye)) / (1.0 + norm(phi1))
    return max(r1, r2)


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

    @property
    def h_phi1(self) -> np.ndarray:
        """h phi_1(hJ) (read-only), shape (n, n) [s]."""
        return self._h_phi1

    @property
    def h_phi2(self) -> np.ndarray:
        """h phi_2(hJ) (read-only), shape (n, n) [s]."""
        return self._h_phi2

    def step_data(self, model, n_steps: int, ground: bool = True) -> _sk.StepData:
        """The step as the compiled kernel takes it (:class:`flexsim.sim._step_kernels.StepData`): ``n_steps`` steps
        of h per call for ``model`` (its altitude range), with the ground contact checked (``ground``) or not."""
        if isinstance(n_steps, bool) or not (isinstance(n_steps, (int, np.integer)) and n_steps >= 1):
            raise ValueError(f"n_steps = {n_steps!r}: must be an integer >= 1")
        lo, hi = model.altitude_range_m
        z = int(model.layout.position.start + 2) if ground else -1
        return _sk.StepData(self.h, int(n_steps), self._h_phi1, self._h_phi2, self._jac, z, float(lo), float(hi))

    def step(self, fun: Callable[..., np.ndarray], t: float, x: np.ndarray, args: tuple = (),
             k1: np.ndarray | None = None) -> np.ndarray:
        """One step from (t, x) to t + h with a right-hand side given as a Python callable: the compiled stages
        (:func:`flexsim.sim._step_kernels.stage_a`, :func:`~flexsim.sim._step_kernels.stage_b`) around ``fun``.

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
        xs = np.array(x, dtype=float, ndmin=2)
        f1 = np.array(fun(t, x, *args) if k1 is None else k1, dtype=float, ndmin=2)
        d, a, x_new = np.empty_like(xs), np.empty_like(xs), np.empty_like(xs)
        live, none = np.ones(1, np.bool_), np.zeros((0, self.n))
        _sk.stage_a(self._h_phi1, f1, xs, live, False, d, a)
        f2 = np.array(fun(t + self.h, a[0], *args), dtype=float, ndmin=2)
        _sk.stage_b(self._h_phi2, self._jac, f1, f2, d, a, live, False, none, none, np.empty_like(xs), x_new)
        return x_new[0]

    def run(self, model, t0: float, x0: np.ndarray, f0: np.ndarray, t_bound: float, max_steps: int,
            controls: tuple[float, np.ndarray, np.ndarray], wind=None, land: bool = False,
            dense: bool = False) -> RunSteps:
        """Compiled steps of one aircraft (one row of :func:`flexsim.sim._step_kernels.etd2rk_rows`): the steps of
        :class:`ETD2RKSolver` from (t0, x0) towards ``t_bound`` without a Python call per step.

        Parameters
        ----------
        model : AircraftModel
            Whose compiled right-hand side is f; J must be the Jacobian of this model (its state size n).
        t0 : float
            Start time [s].
        x0, f0 : ndarray, shape (n,)
            State at t0 and its derivative ``model.rhs(t0, x0, u(t0), wind)`` (reused: two evaluations a step).
        t_bound : float
            Steps of h are taken while ``t_bound - t > h (1 + 1e-9)`` [s] (the short last step of an interval
            is a separate call with its own ETD2RK and ``land=True``).
        max_steps : int
            At most this many steps (>= 1).
        controls : (t_u [s], u_u (4,), du_dt (4,))
            Controls linear in time, u(t) = u_u + (t - t_u) du_dt [N, rad; per s].
        wind : WindData or BatchWind, optional
            The arrays of a field of :mod:`flexsim.sim.disturbances` (``wind.wind_data``), or the same packed for one
            row once (``flexsim._kernels.pack_winds([wind_data])``: the Dryden grids are copied per pack); None: still
            air.
        land : bool
            Take exactly one step, ending at ``t_bound``.
        dense : bool
            Also the mean second derivative of each step for the dense output (``RunSteps.mean``, the ``mean`` of
            :func:`step_accelerations`, its product with J in the pass over J of the next step).

        Returns
        -------
        RunSteps
            The step ends (row 0: the start). The run stops after a step whose state or derivative is not finite
            or whose altitude leaves the model's range (:attr:`AircraftModel.altitude_range_m`); that step is the
            last row, and ``model.rhs`` at it reports the reason.
        """
        x0 = kernel_arg(x0)  # writable: a read-only trim state would compile the step kernel a second time
        if x0.shape != (self.n,):
            raise ValueError(f"x0: expected shape ({self.n},) to match jac, got shape {x0.shape}")
        k, n = int(max_steps), self.n
        t_u, u_u, du_dt = controls
        packed = wind if isinstance(wind, _k.BatchWind) else _k.pack_winds([wind])
        span = _sk.Span(np.array([float(t0)]), np.array([float(t_bound)]), bool(land), True)
        ctrl = _sk.RowControls(np.array([float(t_u)]), kernel_arg(np.reshape(u_u, (1, 4))), kernel_arg(np.reshape(du_dt, (1, 4))))
        out = _sk.RowSteps(np.empty((1, k + 1)), np.empty((1, k + 1, n)), np.empty((1, k + 1, n)),
                           np.empty((1, k if dense else 0, n)), np.empty(1, np.int64), np.empty(1, np.int64))
        with np.errstate(all="ignore"):
            _sk.etd2rk_rows(model.kernel_data, packed, self.step_data(model, k, ground=False), span, ctrl, x0[None, :],
                            kernel_arg(f0)[None, :], False, out)
        done = int(out.taken[0])
        if out.status[0] != _sk.ROW_RUNNING:
            out.f[0, done] = np.nan  # the step the run stops after (its caller asks model.rhs there for the reason)
        return RunSteps(out.t[0, :done + 1], out.x[0, :done + 1], out.f[0, :done + 1], out.mean[0, :done] if dense else None)

    def advance_rows(self, model, x: np.ndarray, u: np.ndarray, t0: np.ndarray, t1: np.ndarray, n_steps: int,
                     wind=None, over_rows: bool = False) -> RowsAdvance:
        """``n_steps`` compiled steps of N aircraft over their control periods [t0, t1] with held controls
        (:func:`flexsim.sim._step_kernels.etd2rk_rows`, its :func:`~flexsim.sim._step_kernels.period_end`).

        Parameters
        ----------
        model : AircraftModel
            Whose compiled right-hand side is f (J: its Jacobian).
        x : ndarray, shape (N, n) or (n,)
            States at t0.
        u : ndarray, shape (N, 4) or (4,)
            Held controls [T_e (N), delta_a, delta_e, delta_r (rad)].
        t0, t1 : array_like, shape (N,) or scalars
            Period ends [s]; step j ends at t0 + j h, the last at t1 (normally t1 = t0 + n_steps h).
        n_steps : int
            Steps per period (>= 1).
        wind : None or BatchWind
            Still air, or the winds of the rows packed once by :meth:`AircraftModel.pack_winds`.
        over_rows : bool
            Take the products as matrix products over the rows (:func:`flexsim.sim._step_kernels.stage_a`, faster for
            many rows) instead of row by row.

        Returns
        -------
        RowsAdvance
            Per row: the state and time reached, the status (:data:`flexsim.sim._step_kernels.ROW_RUNNING` ...) and the
            number of steps begun (each two right-hand sides; :func:`flexsim.sim._step_kernels.period_end`).
        """
        xs = np.array(x, dtype=float, ndmin=2, order="C")
        m = xs.shape[0]
        if xs.ndim != 2 or xs.shape[1] != self.n:
            raise ValueError(f"x: expected shape (N, {self.n}) to match jac, got shape {np.shape(x)}")
        # kernel_arg: writable (a read-only broadcast view is another numba type: a second compile of the kernel)
        us = kernel_arg(np.broadcast_to(np.asarray(u, dtype=float), (m, 4)))
        t0s = kernel_arg(np.broadcast_to(np.asarray(t0, dtype=float), (m,)))
        t1s = kernel_arg(np.broadcast_to(np.asarray(t1, dtype=float), (m,)))
        step = self.step_data(model, n_steps)
        if wind is None:
            wind = model.pack_winds([None] * m)
        elif not isinstance(wind, _k.BatchWind) or wind.rows.shape[0] != m:
            raise ValueError(f"wind: expected None or a BatchWind of {m} rows (AircraftModel.pack_winds)")
        k, n = step.n_steps, self.n
        out = _sk.RowSteps(np.empty((m, k + 1)), np.empty((m, k + 1, n)), np.empty((m, k + 1, n)), np.empty((m, 0, n)),
                           np.empty(m, np.int64), np.empty(m, np.int64))
        with np.errstate(all="ignore"):
            _sk.etd2rk_rows(model.kernel_data, wind, step, _sk.Span(t0s, t1s, True, False), _sk.RowControls(t0s, us, np.zeros((m, 4))),
                            xs, np.empty((0, n)), bool(over_rows), out)
        x_out, t_out, steps = np.empty_like(xs), np.empty(m), np.empty(m, np.int64)
        _sk.period_end(out, x_out, t_out, steps)
        return RowsAdvance(x_out, t_out, out.status, steps)


class RunSteps(NamedTuple):
    """Step ends of :meth:`ETD2RK.run`: t (k + 1,) [s], x and the derivatives f (k + 1, n); row 0 is the start; with
    ``dense=True`` the steps' mean second derivatives (k, n) (:func:`step_accelerations`; else None)."""

    t: np.ndarray
    x: np.ndarray
    f: np.ndarray
    mean: np.ndarray | None = None


class RowsAdvance(NamedTuple):
    """Result of :meth:`ETD2RK.advance_rows`: x (N, n), t (N,) [s], status (N,) (0 period completed, 1 ground
    reached within the step (interpolated), 2 non-finite state, 3 model error at the state reached) and the
    steps taken (N,)."""

    x: np.ndarray
    t: np.ndarray
    status: np.ndarray
    steps: np.ndarray


class ETD2RKSolver(OdeSolver):
    """ETD2RK with fixed steps behind scipy's ``OdeSolver`` interface (for :func:`flexsim.sim.simulate`).

    Steps of exactly ``step`` [s] from ``t0`` (the last one of an interval shortened to land on
    ``t_bound``; one :class:`ETD2RK` per distinct step, kept in ``cache`` across solvers). The state
    derivative at the end of a step is the first evaluation of the next, so a step costs two evaluations
    of ``fun``. Dense output: the quintic Hermite interpolant of the states, derivatives and second derivatives
    at both ends (:func:`quintic_hermite`, :func:`step_accelerations`; exact where the method is exact).

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
        if abs(h - self.h_step) <= 1e-9 * self.h_step:  # a last step shortened by rounding only: the same matrices
            h = self.h_step
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
        return _Hermite(self.t_old, self.t, self._y_old, self.y, self._f_old, self.f, self._jac)


class _Hermite(DenseOutput):
    """Quintic Hermite interpolant between (t_old, y_old, f_old) and (t, y, f) with the second derivatives of
    :func:`step_accelerations` (linear part ``jac``); see :func:`quintic_hermite`."""

    def __init__(self, t_old, t, y_old, y, f_old, f, jac):
        super().__init__(t_old, t)
        self.h = t - t_old
        self.y_old, self.y, self.f_old, self.f, self.jac = y_old, y, f_old, f, jac

    def _call_impl(self, t):
        s = np.atleast_1d((np.asarray(t, dtype=float) - self.t_old) / self.h)
        mean = half_diff = None
        if np.any(interior(s)):
            mean, half_diff = step_accelerations(self.h, self.y - self.y_old, self.f_old, self.f, self.jac,
                                                 difference=bool(np.any(off_midpoint(s))))
        rows = quintic_hermite(s, self.h, self.y_old, self.y, self.f_old, self.f, mean, half_diff)
        return rows[0] if np.ndim(t) == 0 else rows.T


#: Fraction of a step within which a sample counts as the step's end or its midpoint (see the kernel module).
NODE_TOLERANCE = _dk.NODE_TOLERANCE


def interior(s: np.ndarray) -> np.ndarray:
    """Whether the step fractions s lie inside the step (not at an end, :data:`NODE_TOLERANCE`)."""
    return (s > NODE_TOLERANCE) & (s < 1.0 - NODE_TOLERANCE)


def off_midpoint(s: np.ndarray) -> np.ndarray:
    """Whether the step fractions s lie inside the step and away from its midpoint (:data:`NODE_TOLERANCE`)."""
    return interior(s) & (np.abs(s - 0.5) > NODE_TOLERANCE)


def step_accelerations(h, dy, f0, f1, jac: np.ndarray, difference: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
    """Second derivatives x'' at the two ends of ETD2RK steps for :func:`quintic_hermite`, as their mean and half
    difference ``((x''_0 + x''_1) / 2, (x''_1 - x''_0) / 2)``.

    Splitting f = J x + N as the method does (module docstring), x'' = J f + dN/dt; dN/dt is taken constant over a
    step and equal to the secant of the remainder, ``(N_1 - N_0) / h = (f_1 - f_0 - J dy) / h``, dy = y_1 - y_0.
    Then the mean is ``(f_1 - f_0) / h + J ((f_0 + f_1) / 2 - dy / h)`` and the half difference ``J (f_1 - f_0) / 2``:
    exact for ``f = J x + g(t)`` with g linear in t (problems on which ETD2RK itself is exact). One product with J
    per step for the mean, one more for the difference, which a sample at the midpoint does not need
    (``difference=False``: None).

    Parameters
    ----------
    h : float or ndarray (m, 1)
        Step lengths [s].
    dy, f0, f1 : ndarray (n,) or (m, n)
        y_1 - y_0 and the derivatives x' at both ends (rows: steps).
    jac : ndarray (n, n)
        The linear part J [1/s].
    """
    mean = (f1 - f0) / h + (0.5 * (f0 + f1) - dy / h) @ jac.T
    return mean, ((0.5 * (f1 - f0)) @ jac.T if difference else None)


def quintic_hermite(s, h, y0, y1, f0, f1, mean=None, half_diff=None) -> np.ndarray:
    """The quintic Hermite interpolant of a step from its end values, first and second derivatives.

    ``y(s) = H0 y0 + H5 y1 + h (H1 f0 + H4 f1) + h^2 (H2 a0 + H3 a1)`` at ``t = t0 + s h``, s in [0, 1], with
    H0 = 1 - 10 s^3 + 15 s^4 - 6 s^5 = 1 - H5, H1 = s - 6 s^3 + 8 s^4 - 3 s^5, H4 = -4 s^3 + 7 s^4 - 3 s^5,
    H2 = (s^2 - 3 s^3 + 3 s^4 - s^5) / 2, H3 = (s^3 - 2 s^4 + s^5) / 2 (the basis matching value, first and
    second derivative at each end: Hermite interpolation, e.g. Burden & Faires, Numerical Analysis, sec. 3.4),
    written as ``h^2 ((H2 + H3) mean + (H3 - H2) half_diff)`` with mean = (a0 + a1) / 2 and half_diff = (a1 - a0) / 2
    (H3 - H2 vanishes at s = 1/2). Exact for polynomials of degree 5; for an oscillation of angular frequency
    omega its error at mid-step is about (omega h)^6 / 46080 of the amplitude (the cubic's: (omega h)^4 / 384).

    Parameters
    ----------
    s : ndarray (m,)
        Fractions of the step.
    h : float or ndarray (m,)
        Step lengths [s].
    y0, y1, f0, f1 : ndarray (n,) or (m, n)
        Values and first derivatives at the two ends.
    mean, half_diff : ndarray (n,) or (m, n), or None
        (a0 + a1) / 2 and (a1 - a0) / 2 of the second derivatives a0, a1 at the ends (:func:`step_accelerations`);
        None where its weight is below rounding: ``mean`` when every s is at an end (:func:`interior`),
        ``half_diff`` when every s is at an end or the midpoint (:func:`off_midpoint`).

    Returns
    -------
    ndarray (m, n)
    """
    w = quintic_weights(s, h)
    y = w[0][:, None] * y0 + w[1][:, None] * y1 + w[2][:, None] * f0 + w[3][:, None] * f1
    if mean is not None:
        y = y + w[4][:, None] * mean
        if half_diff is not None:
            y = y + w[5][:, None] * half_diff
    return y


def quintic_weights(s, h) -> np.ndarray:
    """Weights of :func:`quintic_hermite` at step fractions s (m,) of steps h [s] (scalar or (m,)): rows for y0, y1,
    f0, f1, mean and half_diff, shape (6, m): ``1 - H5, H5, h H1, h H4, h^2 (H2 + H3), h^2 (H3 - H2)`` (the compiled
    :func:`flexsim.sim._dense_kernels.quintic_weights`, which the chunks' dense output uses too)."""
    s = np.ascontiguousarray(s, dtype=float).reshape(-1)
    hh = np.ascontiguousarray(np.broadcast_to(np.asarray(h, dtype=float), s.shape))
    out = np.empty((6, s.size))
    _dk.quintic_weights(s, hh, out)
    return out