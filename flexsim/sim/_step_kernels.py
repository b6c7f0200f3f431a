"""Compiled ETD2RK steps (numba) over the one compiled right-hand side: a run of one aircraft and control periods
of N aircraft, with the one implementation of the actuator rate limits and of the ground crossing.

:func:`etd2rk_run` serves :meth:`flexsim.sim.fixed_step.ETD2RK.run` (``simulate(..., method="ETD2RK")``),
:func:`etd2rk_rows` and :func:`etd2rk_rows_gemm` serve :meth:`~flexsim.sim.fixed_step.ETD2RK.advance_rows` and
:func:`period_rows` (control periods, :mod:`flexsim.sim.periods`): one implementation of the step for all.
:func:`rate_limit_rows` and :func:`ground_crossing` are called by the compiled periods and by the Python periods
of :class:`flexsim.sim.periods.FlightDynamics` alike. The right-hand side is :func:`flexsim._kernels._rhs_wind`
(the kernel of :func:`flexsim._kernels.rhs`, paper eqs. 4, 33); the method, its matrix functions and its
properties are documented in :mod:`flexsim.sim.fixed_step`.

Imports go one way: this module imports :mod:`flexsim._kernels`, never the reverse. numba's cache of these
functions embeds the compiled right-hand side, so it is keyed on the source of ``flexsim/_kernels.py`` too
(:func:`flexsim._numba_cache.depends_on`): a change of the right-hand side recompiles them on first use.

Units SI, angles in radians; states and their layout as in :class:`flexsim.model.AircraftModel`.

References
----------
S. M. Cox and P. C. Matthews, "Exponential time differencing for stiff systems", J. Comput. Phys. 176 (2002)
430-455 (method ETD2RK).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from flexsim import _kernels as _k
from flexsim._kernels import _rhs_wind
from flexsim._numba_cache import depends_on
from flexsim.sim import measurements as _ms

__all__ = ["etd2rk_run", "etd2rk_run_dense", "etd2rk_rows", "etd2rk_rows_gemm", "period_rows", "rate_limit_rows", "ground_crossing",
           "StepData", "PeriodStart", "PeriodOut", "ROW_RUNNING", "ROW_GROUND", "ROW_NON_FINITE", "ROW_MODEL_ERROR"]

_jit = njit(cache=True, nogil=True)
_depends = depends_on(_k, _ms)

# x_{n+1} = a + h phi_2(hJ) [k_2 - k_1 - J (a - x_n)], a = x_n + h phi_1(hJ) k_1, k_1 = f(t_n, x_n), k_2 = f(t_n + h, a)
# (Cox & Matthews 2002, ETD2RK; the form of flexsim.sim.fixed_step.ETD2RK.step). The wind fields are frozen in
# the air (independent of t), so t enters only through the controls.

#: Products with the (n, n) matrices: one pass over the matrix per product (two products with J share it), with
#: the sums reassociated so that LLVM vectorises them (``fastmath`` reassoc and contract only: no assumption of finite
#: values, so the finiteness checks stay valid). The matrices (3 x 0.5 MB at 252 states) do not fit the L2 cache, so
#: a step's products are limited by reading them; BLAS dgemv per product (before) took ~10 us, this ~8 us.
_fm_jit = njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})


@_depends
@_fm_jit
def _matvec(a, v, out):
    """out = a @ v for a (n, m) C-contiguous, v (m,)."""
    for i in range(a.shape[0]):
        s = 0.0
        for j in range(a.shape[1]):
            s += a[i, j] * v[j]
        out[i] = s


@_depends
@_fm_jit
def _matvec2(a, v, w, out_v, out_w):
    """out_v = a @ v and out_w = a @ w in one pass over a (n, m) C-contiguous."""
    for i in range(a.shape[0]):
        s = 0.0
        r = 0.0
        for j in range(a.shape[1]):
            s += a[i, j] * v[j]
            r += a[i, j] * w[j]
        out_v[i] = s
        out_w[i] = r


@_depends
@_jit
def _altitude_ok(x, alt_lo, alt_hi):
    """-x[2] in [alt_lo, alt_hi], or no range given (both infinite: any value, NaN included, as AircraftModel.rhs)."""
    if alt_lo == -np.inf and alt_hi == np.inf:
        return True
    return alt_lo <= -x[2] <= alt_hi


@_depends
@_jit
def _state_ok(x, alt_lo, alt_hi):
    for i in range(x.shape[0]):
        if not math.isfinite(x[i]):
            return False
    return _altitude_ok(x, alt_lo, alt_hi)


@_depends
@_jit
def etd2rk_run(F, I, gusts, turb, turb_grid, x0, f0, t0, t_bound, h, max_steps, land, t_u, u_u, du_dt, h_phi1, h_phi2,
               jac, alt_lo, alt_hi, ts, xs, fs):
    """ETD2RK steps of one aircraft from (t0, x0), f0 = x_dot there, with the step end derivatives reused (FSAL).

    Steps of h while ``t_bound - t > h (1 + 1e-9)``, at most ``max_steps`` (``land``: exactly one step, ending at
    t_bound: the short last step of an interval, with its own matrix functions). Controls linear in time:
    u(t) = u_u + (t - t_u) du_dt (a piecewise-linear schedule between two breakpoints, or held). Writes the step
    ends into ts[k], xs[k], fs[k] (row 0: the start) and returns the number k of steps taken; it stops after the
    first step whose state or derivative is not finite or whose altitude -x[2] leaves [alt_lo, alt_hi] (that
    step is included: the caller reports it). ts (max_steps + 1,), xs and fs (max_steps + 1, n).
    """
    return _run(F, I, gusts, turb, turb_grid, x0, f0, t0, t_bound, h, max_steps, land, t_u, u_u, du_dt, h_phi1, h_phi2,
                jac, alt_lo, alt_hi, ts, xs, fs, np.empty((0, x0.shape[0])))


@_depends
@_jit
def etd2rk_run_dense(F, I, gusts, turb, turb_grid, x0, f0, t0, t_bound, h, max_steps, land, t_u, u_u, du_dt, h_phi1,
                     h_phi2, jac, alt_lo, alt_hi, ts, xs, fs, ms):
    """:func:`etd2rk_run` that also writes the mean second derivative of each step for the quintic Hermite dense
    output into ms[k - 1] (k = 1 .. the steps taken; ms (max_steps, n)):
    ``(f_k - f_{k-1}) / h_k + J ((f_{k-1} + f_k) / 2 - (x_k - x_{k-1}) / h_k)``
    (:func:`flexsim.sim.fixed_step.step_accelerations`, its ``mean``). The product with J shares the pass over J
    with the step's own product J (a - x), so it costs a fraction of a separate product. A step whose state or
    derivative is not finite gets no mean (its row is left as it is).
    """
    return _run(F, I, gusts, turb, turb_grid, x0, f0, t0, t_bound, h, max_steps, land, t_u, u_u, du_dt, h_phi1, h_phi2,
                jac, alt_lo, alt_hi, ts, xs, fs, ms)


@_depends
@_jit
def _run(F, I, gusts, turb, turb_grid, x0, f0, t0, t_bound, h, max_steps, land, t_u, u_u, du_dt, h_phi1, h_phi2, jac,
         alt_lo, alt_hi, ts, xs, fs, ms):
    """The steps of :func:`etd2rk_run` and :func:`etd2rk_run_dense` (means only if ms has rows)."""
    n = x0.shape[0]
    dense = ms.shape[0] > 0
    ts[0] = t0
    xs[0] = x0
    fs[0] = f0
    d = np.empty(n)  # a - x = h phi_1 k_1
    a = np.empty(n)
    jd = np.empty(n)  # J (a - x)
    r = np.empty(n)
    inc = np.empty(n)
    m = np.zeros(n)  # (f_{k-1} + f_k) / 2 - (x_k - x_{k-1}) / h of the previous step
    jm = np.empty(n)
    t = t0
    h_prev = h
    k = 0
    while k < max_steps:
        if land:
            if k == 1:
                break
        elif not t_bound - t > h * (1.0 + 1e-9):
            break
        x = xs[k]
        k1 = fs[k]
        t_new = t_bound if land else t + h
        u2 = u_u + (t + h - t_u) * du_dt
        _matvec(h_phi1, k1, d)
        for i in range(n):
            a[i] = x[i] + d[i]
        k2 = _rhs_wind(F, I, gusts, turb, turb_grid, a, u2)
        if dense and k > 0:
            _matvec2(jac, d, m, jd, jm)
            for i in range(n):
                ms[k - 1, i] = (k1[i] - fs[k - 1, i]) / h_prev + jm[i]
        else:
            _matvec(jac, d, jd)
        for i in range(n):
            r[i] = k2[i] - k1[i] - jd[i]
        _matvec(h_phi2, r, inc)
        x_new = xs[k + 1]
        for i in range(n):
            x_new[i] = a[i] + inc[i]
        h_prev = t_new - t
        t = t_new
        k += 1
        ts[k] = t
        if not _state_ok(x_new, alt_lo, alt_hi):
            fs[k] = np.nan
            return k
        f_new = _rhs_wind(F, I, gusts, turb, turb_grid, x_new, u_u + (t - t_u) * du_dt)
        fs[k] = f_new
        if not _state_ok(f_new, -np.inf, np.inf):
            return k
        for i in range(n):
            m[i] = 0.5 * (k1[i] + f_new[i]) - (x_new[i] - x[i]) / h_prev
    if dense and k > 0:
        _matvec(jac, m, jm)
        for i in range(n):
            ms[k - 1, i] = (fs[k, i] - fs[k - 1, i]) / h_prev + jm[i]
    return k


#: Status codes of :func:`etd2rk_rows`.
ROW_RUNNING, ROW_GROUND, ROW_NON_FINITE, ROW_MODEL_ERROR = 0, 1, 2, 3


class StepData(NamedTuple):
    """The fixed ETD2RK step of a control period (:meth:`flexsim.sim.fixed_step.ETD2RK.step_data`): step ``h`` [s],
    ``n_steps`` steps per period, the matrices ``h_phi1`` = h phi_1(hJ), ``h_phi2`` = h phi_2(hJ) and ``jac`` = J
    (n, n), the state index ``z_index`` of the down coordinate (altitude -x[z_index]) and the model's altitude range
    [alt_lo, alt_hi] [m]."""

    h: float
    n_steps: int
    h_phi1: np.ndarray
    h_phi2: np.ndarray
    jac: np.ndarray
    z_index: int
    alt_lo: float
    alt_hi: float


class PeriodStart(NamedTuple):
    """The start of a control period of N aircraft: states ``x`` (N, n), the controls applied so far ``u`` (N, 4)
    and commanded ``command`` (N, 4) [N, rad], the actuator rates times the period ``rate_step`` (4,), the index
    ``k`` (N,) int of each row's period, which spans [k dt, (k + 1) dt] [s], and the period ``dt`` [s]."""

    x: np.ndarray
    u: np.ndarray
    command: np.ndarray
    rate_step: np.ndarray
    k: np.ndarray
    dt: float


class PeriodOut(NamedTuple):
    """Results of :func:`period_rows` (written in place): applied controls ``u`` (N, 4), state ``x`` (N, n) and time
    ``t`` (N,) reached, ``status`` and steps ``taken`` (N,) as :func:`etd2rk_rows`, measurements ``meas`` (N, m)
    (:func:`flexsim.sim.measurements.measure_rows`)."""

    u: np.ndarray
    x: np.ndarray
    t: np.ndarray
    status: np.ndarray
    taken: np.ndarray
    meas: np.ndarray


@_jit
def rate_limit_rows(applied, command, rate_step, out):
    """Actuator rate limits: ``out = applied + min(max(command - applied, -rate_step), rate_step)``, rows (N, 4), the
    controls after one period of rate-limited motion towards the command (rate_step (4,): rate times period)."""
    for i in range(applied.shape[0]):
        for a in range(applied.shape[1]):
            d = command[i, a] - applied[i, a]
            out[i, a] = applied[i, a] + min(max(d, -rate_step[a]), rate_step[a])


@_jit
def ground_crossing(x, x_new, t, t_next, z_index, x_out):
    """The ground contact within a step from (t, x) to (t_next, x_new): if the altitude -x[z_index] goes from above 0
    to 0 or below, the state interpolated linearly at the crossing, fraction ``s = x_z / (x_z - x_new_z)``, into
    x_out (which may be x itself), and its time t + s (t_next - t) [s] is returned; else -inf (x_out untouched)."""
    if not x_new[z_index] >= 0.0 > x[z_index]:
        return -np.inf
    s = x[z_index] / (x[z_index] - x_new[z_index])
    for c in range(x.shape[0]):
        x_out[c] = x[c] + s * (x_new[c] - x[c])
    return t + s * (t_next - t)


@_depends
@_jit
def etd2rk_rows(model, wind, step, xs, us, t0s, t1s, x_out, t_out, status, steps):
    """``step.n_steps`` ETD2RK steps of ``step.h`` over [t0, t1] for N aircraft of one model (``model``: its kernel
    data) with held controls (a control period), two right-hand sides per step.

    The step is :func:`etd2rk_run`'s, product for product (``d = h phi_1 k_1``, ``a = x + d``, ``x_new = a + h phi_2
    (k_2 - k_1 - J d)``), so a period of the environments and a run of ``simulate`` take the same arithmetic.
    Row i starts at xs[i] (N, n) with controls us[i] (N, 4) and the winds ``wind.rows[i]`` of the packed ``wind``.
    Step j ends at t0 + j h (the last at t1). Per row, into x_out (N, n), t_out (N,), status (N,) and steps (N,)
    (steps taken): ROW_RUNNING (0): the period completed, x_out = state at t1; ROW_GROUND (1): the altitude reached
    0 within step ``steps``, x_out and t_out at the crossing (:func:`ground_crossing`); ROW_NON_FINITE (2): step
    ``steps`` gave a non-finite state, x_out = the state before it; ROW_MODEL_ERROR (3): the right-hand side could
    not be evaluated at the state before step ``steps`` (singular system matrix, or an altitude outside
    [alt_lo, alt_hi]), x_out = that state. Rows are independent: a row's result does not depend on the others.
    """
    F, I = model.F, model.I
    h, n_steps, h_phi1, h_phi2, jac, z_index = step.h, step.n_steps, step.h_phi1, step.h_phi2, step.jac, step.z_index
    alt_lo, alt_hi = step.alt_lo, step.alt_hi
    rows, turb_grid = wind.rows, wind.turb_grid
    n = xs.shape[1]
    x, x_new = np.empty(n), np.empty(n)
    d, a, jd, r, inc = np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)  # as in _run
    for i in range(xs.shape[0]):
        g = wind.gusts[rows[i, 0]:rows[i, 1]]
        tb = wind.turb[rows[i, 2]:rows[i, 3]]
        u = us[i]
        x[:] = xs[i]
        t = t0s[i]
        st = ROW_RUNNING
        j = 0
        while j < n_steps:
            t_next = t1s[i] if j == n_steps - 1 else t0s[i] + (j + 1) * h
            j += 1
            if not _altitude_ok(x, alt_lo, alt_hi):
                st = ROW_MODEL_ERROR
                break
            try:
                k1 = _rhs_wind(F, I, g, tb, turb_grid, x, u)
                _matvec(h_phi1, k1, d)
                for c in range(n):
                    a[c] = x[c] + d[c]
                if not _altitude_ok(a, alt_lo, alt_hi):
                    st = ROW_MODEL_ERROR
                    break
                k2 = _rhs_wind(F, I, g, tb, turb_grid, a, u)
            except Exception:  # singular system matrix (ZeroDivisionError in solve)
                st = ROW_MODEL_ERROR
                break
            _matvec(jac, d, jd)
            for c in range(n):
                r[c] = k2[c] - k1[c] - jd[c]
            _matvec(h_phi2, r, inc)
            finite = True
            for c in range(n):
                x_new[c] = a[c] + inc[c]
                if not math.isfinite(x_new[c]):
                    finite = False
            if not finite:
                st = ROW_NON_FINITE
                break
            t_hit = ground_crossing(x, x_new, t, t_next, z_index, x)
            if t_hit != -np.inf:
                t = t_hit
                st = ROW_GROUND
                break
            x[:] = x_new
            t = t_next
        x_out[i] = x
        t_out[i] = t
        status[i] = st
        steps[i] = j


@_depends
@_jit
def etd2rk_rows_gemm(model, wind, step, xs, us, t0s, t1s, x_out, t_out, status, steps):
    """:func:`etd2rk_rows` (same arguments, results and status codes) with each stage of all rows at once: the
    right-hand sides row by row, then the products with the (n, n) matrices as matrix products over the rows
    (BLAS dgemm), ``a = x + k_1 h phi_1^T``, ``x_new = a + (k_2 - k_1 - (a - x) J^T) h phi_2^T`` (the arithmetic
    of :meth:`flexsim.sim.fixed_step.ETD2RK.step_rows`). Many rows: each matrix is read once per stage instead of
    once per row. A row that stopped (status not ROW_RUNNING) takes zero derivatives in the products that follow
    and keeps its state; rows are independent (a row's result does not depend on the others, to rounding of the
    products)."""
    F, I = model.F, model.I
    h, n_steps, h_phi1, h_phi2, jac, z_index = step.h, step.n_steps, step.h_phi1, step.h_phi2, step.jac, step.z_index
    alt_lo, alt_hi = step.alt_lo, step.alt_hi
    rows, gusts, turb, turb_grid = wind.rows, wind.gusts, wind.turb, wind.turb_grid
    m, n = xs.shape
    x = xs.copy()
    t = t0s.copy()
    st = np.zeros(m, np.int64)
    taken = np.zeros(m, np.int64)
    k1 = np.empty((m, n))
    k2 = np.empty((m, n))
    for j in range(n_steps):
        for i in range(m):
            if st[i] != ROW_RUNNING:
                k1[i] = 0.0
                continue
            taken[i] = j + 1
            ok = _altitude_ok(x[i], alt_lo, alt_hi)
            if ok:
                try:
                    k1[i] = _rhs_wind(F, I, gusts[rows[i, 0]:rows[i, 1]], turb[rows[i, 2]:rows[i, 3]], turb_grid, x[i], us[i])
                except Exception:  # singular system matrix (ZeroDivisionError in solve)
                    ok = False
            if not ok:
                st[i] = ROW_MODEL_ERROR
                k1[i] = 0.0
        a = x + np.dot(k1, h_phi1.T)
        for i in range(m):
            if st[i] != ROW_RUNNING:
                k2[i] = 0.0
                continue
            ok = _altitude_ok(a[i], alt_lo, alt_hi)
            if ok:
                try:
                    k2[i] = _rhs_wind(F, I, gusts[rows[i, 0]:rows[i, 1]], turb[rows[i, 2]:rows[i, 3]], turb_grid, a[i], us[i])
                except Exception:
                    ok = False
            if not ok:
                st[i] = ROW_MODEL_ERROR
                k2[i] = 0.0
        x_new = a + np.dot(k2 - k1 - np.dot(a - x, jac.T), h_phi2.T)
        for i in range(m):
            if st[i] != ROW_RUNNING:
                continue
            t_next = t1s[i] if j == n_steps - 1 else t0s[i] + (j + 1) * h
            finite = True
            for c in range(n):
                if not math.isfinite(x_new[i, c]):
                    finite = False
                    break
            if not finite:
                st[i] = ROW_NON_FINITE
                continue
            t_hit = ground_crossing(x[i], x_new[i], t[i], t_next, z_index, x[i])
            if t_hit != -np.inf:
                t[i] = t_hit
                st[i] = ROW_GROUND
            else:
                x[i] = x_new[i]
                t[i] = t_next
    x_out[:] = x
    t_out[:] = t
    status[:] = st
    steps[:] = taken


@_depends
@_jit
def period_rows(F, I, rows, gusts, turb, turb_grid, h, n_steps, h_phi1, h_phi2, jac, z_index, alt_lo, alt_hi, index, s_ptr, s_idx,
                s_w, h_range, x, u, command, rate_step, k, dt, wind_mode, over_rows, u_out, x_out, t_out, status, taken, meas):
    """One control period of N aircraft flown about one trim, in one call; the arguments are the fields of the named
    data, called as ``period_rows(*model, *wind, *step, *measure, *start, wind_mode, over_rows, *out)`` with
    ``model`` the model's kernel data, ``wind`` its packed winds (``BatchWind``), ``step`` a :class:`StepData`,
    ``measure`` a :class:`~flexsim.sim.measurements.MeasureData`, ``start`` a :class:`PeriodStart` and ``out`` a
    :class:`PeriodOut` (flat, because numba's dispatcher types a flat argument list in compiled code and a tuple
    argument in Python, which took 13 us more per call).

    The actuator rate limits (:func:`rate_limit_rows`: ``start.u`` towards ``start.command`` into ``out.u``, then
    held), the ETD2RK steps (:func:`etd2rk_rows`, or with ``over_rows`` :func:`etd2rk_rows_gemm`) over
    [k dt, (k + 1) dt] into ``out.x``, ``out.t``, ``out.status``, ``out.taken``, and the measurements of the
    states reached (:func:`flexsim.sim.measurements.measure_rows`, ``wind_mode`` still air or packed ``wind``) into
    ``out.meas``: the arithmetic of the separate calls, so the results are equal bit for bit."""
    model = _k.KernelData(F, I)
    wind = _k.BatchWind(rows, gusts, turb, turb_grid)
    step = StepData(h, n_steps, h_phi1, h_phi2, jac, z_index, alt_lo, alt_hi)
    t0, t1 = np.empty(k.shape[0]), np.empty(k.shape[0])
    for i in range(k.shape[0]):
        t0[i] = k[i] * dt
        t1[i] = (k[i] + 1) * dt
    rate_limit_rows(u, command, rate_step, u_out)
    if over_rows:
        etd2rk_rows_gemm(model, wind, step, x, u_out, t0, t1, x_out, t_out, status, taken)
    else:
        etd2rk_rows(model, wind, step, x, u_out, t0, t1, x_out, t_out, status, taken)
    _ms.measure_rows(x_out, wind_mode, np.empty((0, 3)), wind, _ms.MeasureData(index, s_ptr, s_idx, s_w, h_range), meas)
