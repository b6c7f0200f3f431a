"""The compiled ETD2RK step (numba): one kernel, :func:`etd2rk_rows`, that steps N aircraft of one model (one row for a
run of ``simulate``), with the one implementation of the ETD2RK stage arithmetic (:func:`stage_a`, :func:`stage_b`),
of the actuator rate limits (:func:`rate_limit_rows`), of the checks after a step (:func:`step_end`) and of the
ground crossing (:func:`ground_crossing`).

:func:`etd2rk_rows` serves :meth:`flexsim.sim.fixed_step.ETD2RK.run` (``simulate(..., method="ETD2RK")``, one row
whose controls are linear in time) and :meth:`~flexsim.sim.fixed_step.ETD2RK.advance_rows` (control periods of N
aircraft with held controls); :func:`period_rows` is a control period of the environments in one call (rate limits,
:func:`etd2rk_rows`, measurements). A wind that the kernels cannot evaluate (a Python callable) is stepped by
:meth:`~flexsim.sim.fixed_step.ETD2RK.step`, which calls the same compiled stages around a Python right-hand side.
The right-hand side is :func:`flexsim._kernels._rhs_wind` (the kernel of :func:`flexsim._kernels.rhs`, paper eqs. 4,
33); the method, its matrix functions and its properties are documented in :mod:`flexsim.sim.fixed_step`.

Arguments are grouped in NamedTuples (:class:`StepData`, :class:`Span`, :class:`RowControls`, :class:`RowSteps`,
:class:`PeriodStart`, :class:`PeriodMode`, :class:`PeriodOut`). :func:`period_rows`, called once per control period
from Python, takes the fields of its groups flat (numba types a flat argument list in its compiled dispatcher, a
tuple of arrays in Python, about 13 us more per call); the flat list is made by :func:`period_args` and taken apart
by the kernel from the same group definitions (:data:`PERIOD_GROUPS`), so the two cannot drift.

Imports go one way: this module imports :mod:`flexsim._kernels`, never the reverse. numba's cache of these
functions embeds the compiled right-hand side, so it is keyed on the source of ``flexsim/_kernels`` too
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
from flexsim._arrays import group_bounds
from flexsim._kernels import _rhs_wind
from flexsim._numba_cache import depends_on
from flexsim.sim import measurements as _ms

__all__ = ["etd2rk_rows", "stage_a", "stage_b", "period_rows", "period_args", "period_end", "rate_limit_rows", "ground_crossing",
           "step_end",
           "StepData", "Span", "RowControls", "RowSteps", "PeriodStart", "PeriodMode", "PeriodOut", "PERIOD_GROUPS",
           "ROW_RUNNING", "ROW_GROUND", "ROW_NON_FINITE", "ROW_MODEL_ERROR"]

_jit = njit(cache=True, nogil=True)
_depends = depends_on(_k, _ms)

# x_{n+1} = a + h phi_2(hJ) [k_2 - k_1 - J d], a = x_n + d, d = h phi_1(hJ) k_1, k_1 = f(t_n, x_n), k_2 = f(t_n + h, a)
# (Cox & Matthews 2002, ETD2RK; the form derived in flexsim.sim.fixed_step). The wind fields are frozen in the air
# (independent of t), so t enters only through the controls.

#: Products with the (n, n) matrices: one pass over the matrix per product (two products with J share it), with
#: the sums reassociated so that LLVM vectorises them (``fastmath`` reassoc and contract only: no assumption of finite
#: values, so the finiteness checks stay valid). The matrices (3 x 0.5 MB at 252 states) do not fit the L2 cache, so
#: a step's products are limited by reading them; BLAS dgemv per product took ~10 us, this ~8 us.
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


@_jit
def _finite(v):
    for i in range(v.shape[0]):
        if not math.isfinite(v[i]):
            return False
    return True


#: Status codes of :func:`etd2rk_rows` (``RowSteps.status``).
ROW_RUNNING, ROW_GROUND, ROW_NON_FINITE, ROW_MODEL_ERROR = 0, 1, 2, 3


class StepData(NamedTuple):
    """The fixed ETD2RK step (:meth:`flexsim.sim.fixed_step.ETD2RK.step_data`): step ``h`` [s], ``n_steps`` steps per
    call (the steps of a control period; at most, for a :class:`Span` that does not land), the matrices ``h_phi1`` =
    h phi_1(hJ), ``h_phi2`` = h phi_2(hJ) and ``jac`` = J (n, n), the state index ``z_index`` of the down coordinate
    whose sign change is the ground contact (-1: no ground contact checked) and the model's altitude range
    [alt_lo, alt_hi] [m] (altitude -x[2])."""

    h: float
    n_steps: int
    h_phi1: np.ndarray
    h_phi2: np.ndarray
    jac: np.ndarray
    z_index: int
    alt_lo: float
    alt_hi: float


class Span(NamedTuple):
    """What one call of :func:`etd2rk_rows` steps: row i from ``t0[i]`` towards ``t_end[i]`` (N,) [s]. ``land``: step j
    ends at t0 + j h (accumulated), the last (``StepData.n_steps``) at t_end (a control period, or the short last step
    of a run); else steps of h while ``t_end - t > h (1 + 1e-9)``. ``end_derivative``: also evaluate f at the end of
    the last step (a run, whose next call and dense output start from it; a control period's controls change)."""

    t0: np.ndarray
    t_end: np.ndarray
    land: bool
    end_derivative: bool


class RowControls(NamedTuple):
    """Controls of N rows linear in time: ``u(t) = u[i] + (t - t_u[i]) du_dt[i]`` (t_u (N,) [s], u and du_dt (N, 4)
    [N, rad; per s]); held controls have du_dt = 0."""

    t_u: np.ndarray
    u: np.ndarray
    du_dt: np.ndarray


class RowSteps(NamedTuple):
    """The steps of N rows (:func:`etd2rk_rows`, written in place; K = ``StepData.n_steps``): step ends ``t`` (N, K + 1)
    [s], ``x`` and derivatives ``f`` (N, K + 1, n) (index 0: the start; f not evaluated at the end of a period: NaN),
    the mean second derivative of each step for the dense output ``mean`` (N, K, n), or (N, 0, n) for none, and per
    row the ``status`` (:data:`ROW_RUNNING` ...) and the number of steps ``taken`` (entries 0 .. taken valid).

    ROW_RUNNING: the span completed. ROW_GROUND: step ``taken`` crossed altitude 0; its end is the crossing,
    interpolated linearly (:func:`ground_crossing`). ROW_NON_FINITE: step ``taken`` gave a non-finite state (recorded),
    or, with ``Span.end_derivative``, a non-finite derivative at its end. ROW_MODEL_ERROR: the right-hand side could not
    be evaluated (an altitude outside [alt_lo, alt_hi], a singular system matrix) at the state ``x[taken]`` or at the
    stage state of the step after it."""

    t: np.ndarray
    x: np.ndarray
    f: np.ndarray
    mean: np.ndarray
    status: np.ndarray
    taken: np.ndarray


@_depends
@_jit
def stage_a(h_phi1, k1, x, live, over_rows, d, a):
    """The first ETD2RK stage of the ``live`` rows (N,) bool: ``d = h phi_1(hJ) k_1``, ``a = x + d`` (k1, x, d, a
    (N, n)); the products row by row, or with ``over_rows`` as one matrix product (BLAS dgemm) over all rows (a stopped
    row's k1 is set to 0 first)."""
    m, n = x.shape
    if over_rows:
        for i in range(m):
            if not live[i]:
                k1[i] = 0.0
        d[:] = np.dot(k1, h_phi1.T)
    else:
        for i in range(m):
            if live[i]:
                _matvec(h_phi1, k1[i], d[i])
    for i in range(m):
        if live[i]:
            for c in range(n):
                a[i, c] = x[i, c] + d[i, c]


@_depends
@_jit
def stage_b(h_phi2, jac, k1, k2, d, a, live, over_rows, mp, jm, jd, x_new):
    """The second ETD2RK stage of the ``live`` rows: ``x_new = a + h phi_2(hJ) (k_2 - k_1 - J d)`` (all (N, n)); with
    ``mp`` of N rows also ``jm = J mp`` (the dense output's mean second derivative, in the same pass over J; mp of 0
    rows: none). Products as in :func:`stage_a`; k2 is overwritten by the bracket, jd (N, n) is scratch."""
    m, n = x_new.shape
    if over_rows:
        for i in range(m):
            if not live[i]:
                d[i] = 0.0
                k1[i] = 0.0
                k2[i] = 0.0
        jd[:] = np.dot(d, jac.T)
        if mp.shape[0] > 0:
            jm[:] = np.dot(mp, jac.T)
    else:
        for i in range(m):
            if live[i]:
                if mp.shape[0] > 0:
                    _matvec2(jac, d[i], mp[i], jd[i], jm[i])
                else:
                    _matvec(jac, d[i], jd[i])
    for i in range(m):
        if live[i]:
            for c in range(n):
                k2[i, c] = k2[i, c] - k1[i, c] - jd[i, c]
    if over_rows:
        x_new[:] = np.dot(k2, h_phi2.T)
        for i in range(m):
            if live[i]:
                for c in range(n):
                    x_new[i, c] = a[i, c] + x_new[i, c]
    else:
        for i in range(m):
            if live[i]:
                inc = jd[i]  # J d is used up
                _matvec(h_phi2, k2[i], inc)
                for c in range(n):
                    x_new[i, c] = a[i, c] + inc[c]


@_depends
@_jit
def _rhs_row(F, I, wind, i, x, ctrl, t, alt_lo, alt_hi, u, out):
    """out = f(x, u(t)) of row i (its winds ``wind.rows[i]``); False where the right-hand side cannot be evaluated:
    an altitude outside [alt_lo, alt_hi] or a singular system matrix (ZeroDivisionError in the solve)."""
    if not _altitude_ok(x, alt_lo, alt_hi):
        return False
    s = t - ctrl.t_u[i]
    for c in range(4):
        u[c] = ctrl.u[i, c] + s * ctrl.du_dt[i, c]
    rows = wind.rows
    try:
        out[:] = _rhs_wind(F, I, wind.gusts[rows[i, 0]:rows[i, 1]], wind.turb[rows[i, 2]:rows[i, 3]], wind.turb_grid, x, u)
    except Exception:
        return False
    return True


@_depends
@_jit
def etd2rk_rows(model, wind, step, span, ctrl, x0, f0, over_rows, out):
    """ETD2RK steps of N aircraft of one model: the one compiled step.

    ``model`` the model's kernel data, ``wind`` its packed winds (``BatchWind``, row i in ``wind.rows[i]``), ``step``
    a :class:`StepData`, ``span`` a :class:`Span`, ``ctrl`` :class:`RowControls`, ``x0`` (N, n) the start states and
    ``f0`` their derivatives (N, n), or (0, n) to evaluate them; ``over_rows``: the products as matrix products over
    the rows (:func:`stage_a`); results into ``out``, a :class:`RowSteps`. Per step two right-hand sides: k_2 at the
    stage state, and f at the step end (the next step's k_1, or the end derivative); the stages are those of
    :func:`stage_a` and :func:`stage_b`. The step's time is t + h (k_2 at t + h), its end t + h or, for the last step
    of a landing span, t_end. Rows are independent: a row's result does not depend on the others (with
    ``over_rows``, to the rounding of the products).
    """
    F, I = model.F, model.I
    m, n = x0.shape
    h, lo, hi = step.h, step.alt_lo, step.alt_hi
    dense = out.mean.shape[1] > 0
    live = np.ones(m, np.bool_)
    work = np.empty((7, m, n))  # one allocation for the stages' rows
    x, k1, k2, d, a, x_new, jd = work[0], work[1], work[2], work[3], work[4], work[5], work[6]
    mp = np.zeros((m if dense else 0, n))  # (f_{k-1} + f_k) / 2 - (x_k - x_{k-1}) / h of the previous step
    jm = np.empty((m if dense else 0, n))
    no_mean = np.zeros((0, n))
    times = np.empty((3, m))
    t, t_next, h_prev = times[0], times[1], times[2]
    u = np.empty(4)
    for i in range(m):
        out.status[i] = ROW_RUNNING
        out.taken[i] = 0
        x[i] = x0[i]
        t[i] = span.t0[i]
        out.x[i, 0] = x0[i]
        out.t[i, 0] = t[i]
        if f0.shape[0] > 0:
            k1[i] = f0[i]
        elif not _rhs_row(F, I, wind, i, x[i], ctrl, t[i], lo, hi, u, k1[i]):
            out.status[i] = ROW_MODEL_ERROR
            live[i] = False
        out.f[i, 0] = k1[i]
    last = step.n_steps - 1
    for j in range(step.n_steps):
        stepping = False
        for i in range(m):
            if not live[i]:
                continue
            if span.land:
                t_next[i] = span.t_end[i] if j == last else t[i] + h
            elif span.t_end[i] - t[i] > h * (1.0 + 1e-9):
                t_next[i] = t[i] + h
            else:
                live[i] = False  # t_end reached (ROW_RUNNING)
                continue
            stepping = True
        if not stepping:
            break
        stage_a(step.h_phi1, k1, x, live, over_rows, d, a)
        for i in range(m):
            if live[i] and not _rhs_row(F, I, wind, i, a[i], ctrl, t[i] + h, lo, hi, u, k2[i]):
                out.status[i] = ROW_MODEL_ERROR
                live[i] = False
        stage_b(step.h_phi2, step.jac, k1, k2, d, a, live, over_rows, mp if dense and j > 0 else no_mean, jm, jd, x_new)
        for i in range(m):
            if not live[i]:
                continue
            if dense and j > 0:
                for c in range(n):
                    out.mean[i, j - 1, c] = (k1[i, c] - out.f[i, j - 1, c]) / h_prev[i] + jm[i, c]
            out.taken[i] = j + 1
            out.t[i, j + 1] = t_next[i]
            out.x[i, j + 1] = x_new[i]
            code, t_end = step_end(x[i], x_new[i], t[i], t_next[i], step.z_index, out.x[i, j + 1])
            if code != ROW_RUNNING:  # non-finite (the state recorded) or the ground (the crossing, at t_end)
                out.f[i, j + 1] = np.nan
                out.t[i, j + 1] = t_end
                out.status[i] = code
                live[i] = False
                continue
            h_prev[i] = t_next[i] - t[i]
            t[i] = t_next[i]
            if j == last and not span.end_derivative:
                out.f[i, j + 1] = np.nan  # not evaluated: the period's controls end here
                continue
            if not _rhs_row(F, I, wind, i, x_new[i], ctrl, t_next[i], lo, hi, u, k2[i]):  # the next step's k_1
                out.f[i, j + 1] = np.nan
                out.status[i] = ROW_MODEL_ERROR
                live[i] = False
                continue
            out.f[i, j + 1] = k2[i]
            if span.end_derivative and not _finite(k2[i]):  # a run stops after this step (its caller reports it)
                out.status[i] = ROW_NON_FINITE
                live[i] = False
                continue
            if dense:
                for c in range(n):
                    mp[i, c] = 0.5 * (k1[i, c] + k2[i, c]) - (x_new[i, c] - x[i, c]) / h_prev[i]
        # the live rows continue from x_new with k_1 = f there (k2): the arrays change roles, nothing is copied
        x, x_new = x_new, x
        k1, k2 = k2, k1
    if dense:
        for i in range(m):
            k = out.taken[i]
            if out.status[i] == ROW_RUNNING and k > 0 and span.end_derivative:
                _matvec(step.jac, mp[i], jm[i])
                for c in range(n):
                    out.mean[i, k - 1, c] = (out.f[i, k, c] - out.f[i, k - 1, c]) / h_prev[i] + jm[i, c]


@_jit
def period_end(out, x_end, t_end, steps):
    """The end of each row's control period from its :class:`RowSteps` ``out``: the state x_end (N, n) and time t_end
    (N,) [s] reached and the steps begun (N,): the last step end (ROW_RUNNING, ROW_GROUND: the crossing), the state
    before the non-finite step (ROW_NON_FINITE), or the state at which the model failed, with the step that needed it
    (ROW_MODEL_ERROR)."""
    for i in range(out.status.shape[0]):
        k = out.taken[i]
        s = out.status[i]
        r = k - 1 if s == ROW_NON_FINITE else k
        x_end[i] = out.x[i, r]
        t_end[i] = out.t[i, r]
        steps[i] = k + 1 if s == ROW_MODEL_ERROR else k


@_jit
def rate_limit_rows(applied, command, rate_step, out):
    """Actuator rate limits: ``out = applied + min(max(command - applied, -rate_step), rate_step)``, rows (N, 4), the
    controls after one period of rate-limited motion towards the command (rate_step (4,): rate times period)."""
    for i in range(applied.shape[0]):
        for a in range(applied.shape[1]):
            d = command[i, a] - applied[i, a]
            out[i, a] = applied[i, a] + min(max(d, -rate_step[a]), rate_step[a])


@_jit
def step_end(x, x_new, t, t_next, z_index, x_out):
    """The checks after an ETD2RK step from (t, x) to (t_next, x_new), the one implementation (:func:`etd2rk_rows`, and
    the steps around a Python right-hand side, :meth:`flexsim.sim.periods.FlightDynamics.advance`): (status, time) =
    (:data:`ROW_NON_FINITE`, t_next) when x_new has a non-finite entry; (:data:`ROW_GROUND`, the crossing time) when
    ``z_index`` >= 0 and the step crosses the ground, the crossing state in x_out (:func:`ground_crossing`); else
    (:data:`ROW_RUNNING`, t_next)."""
    if not _finite(x_new):
        return ROW_NON_FINITE, t_next
    if z_index >= 0:
        t_hit = ground_crossing(x, x_new, t, t_next, z_index, x_out)
        if t_hit != -np.inf:
            return ROW_GROUND, t_hit
    return ROW_RUNNING, t_next


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


class PeriodMode(NamedTuple):
    """How :func:`period_rows` evaluates a period: ``wind_mode`` of the measurements (:data:`flexsim.sim.measurements.WIND_STILL`
    or ``WIND_PACKED``) and ``over_rows``, the products as matrix products over the rows (:func:`stage_a`)."""

    wind_mode: int
    over_rows: bool


class PeriodOut(NamedTuple):
    """Results of :func:`period_rows` (written in place): applied controls ``u`` (N, 4), state ``x`` (N, n) and time
    ``t`` (N,) reached, ``status`` (N,) as :class:`RowSteps` and steps begun ``taken`` (N,) (:func:`period_end`),
    measurements ``meas`` (N, m) (:func:`flexsim.sim.measurements.measure_rows`)."""

    u: np.ndarray
    x: np.ndarray
    t: np.ndarray
    status: np.ndarray
    taken: np.ndarray
    meas: np.ndarray


#: The groups of :func:`period_rows`' arguments, in order: the model's kernel data, its packed winds, the step, the
#: measurement data, the period's start, its mode and its outputs.
PERIOD_GROUPS = (_k.KernelData, _k.BatchWind, StepData, _ms.MeasureData, PeriodStart, PeriodMode, PeriodOut)


(_MODEL0, _MODEL1, _WIND0, _WIND1, _STEP0, _STEP1, _MEAS0, _MEAS1, _START0, _START1, _MODE0, _MODE1, _OUT0,
 _OUT1) = group_bounds(PERIOD_GROUPS)


def period_args(model, wind, step, measure, start, mode, out) -> tuple:
    """The flat argument list of :func:`period_rows` from its groups, in the order and of the NamedTuples of
    :data:`PERIOD_GROUPS` (not checked here: it is called every control period)."""
    return (*model, *wind, *step, *measure, *start, *mode, *out)


@_depends
@_jit
def period_rows(*args):
    """One control period of N aircraft flown about one trim, in one call; ``args`` is :func:`period_args` of the
    groups model (kernel data), wind (``BatchWind``), step (:class:`StepData`), measure
    (:class:`~flexsim.sim.measurements.MeasureData`), start (:class:`PeriodStart`), mode (:class:`PeriodMode`) and out
    (:class:`PeriodOut`).

    The actuator rate limits (:func:`rate_limit_rows`: ``start.u`` towards ``start.command`` into ``out.u``, then
    held), the ETD2RK steps (:func:`etd2rk_rows`) over [k dt, (k + 1) dt], their end (:func:`period_end`) into
    ``out.x``, ``out.t``, ``out.status``, ``out.taken``, and the measurements of the states reached
    (:func:`flexsim.sim.measurements.measure_rows`) into ``out.meas``: the arithmetic of the separate calls, so the
    results are equal bit for bit."""
    model = _k.KernelData(*args[_MODEL0:_MODEL1])
    wind = _k.BatchWind(*args[_WIND0:_WIND1])
    step = StepData(*args[_STEP0:_STEP1])
    measure = _ms.MeasureData(*args[_MEAS0:_MEAS1])
    start = PeriodStart(*args[_START0:_START1])
    mode = PeriodMode(*args[_MODE0:_MODE1])
    out = PeriodOut(*args[_OUT0:_OUT1])
    m, n = start.x.shape
    times = np.empty((2, m))  # period starts and ends [s]
    t0, t1 = times[0], times[1]
    for i in range(m):
        t0[i] = start.k[i] * start.dt
        t1[i] = (start.k[i] + 1) * start.dt
    rate_limit_rows(start.u, start.command, start.rate_step, out.u)
    k = step.n_steps
    history = np.empty((2, m, k + 1, n))
    steps = RowSteps(np.empty((m, k + 1)), history[0], history[1], np.empty((m, 0, n)), out.status, np.empty(m, np.int64))
    etd2rk_rows(model, wind, step, Span(t0, t1, True, False), RowControls(t0, out.u, np.zeros((m, 4))), start.x,
                np.empty((0, n)), mode.over_rows, steps)
    period_end(steps, out.x, out.t, out.taken)
    _ms.measure_rows(out.x, mode.wind_mode, np.empty((0, 3)), wind, measure, out.meas)
