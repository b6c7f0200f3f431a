"""Compiled per-aircraft outputs of the environments (numba): measurements, termination, reward parts, observation.

One implementation over rows of aircraft, used by the single environment (as one row) and by the batched
:class:`~flexsim.envs.vector.FlexSimVectorEnv` (N rows): :meth:`FlexSimEnv._step_rows` calls, per control period,
:func:`measure_rows` (the outputs of the states the integration reached), :func:`termination_rows` and
:func:`finish_rows` (reward parts, reward and observation); only the task errors (a few lines of array code per
task) stay in Python. The kernels are compiled with ``cache=True`` and are plain Python under
``NUMBA_DISABLE_JIT=1``.

Measurements (:data:`MEAS_COLUMNS`, one row per aircraft, SI units, radians):

* position R (NED) [m], Euler angles Theta = (phi, theta, psi) [rad] and body rates omega = (p, q, r) [rad/s],
  copied from the state (layout :class:`flexsim.model.layout.StateLayout`);
* the velocity of the body origin relative to the air, body axes, ``v_a = v - C(Theta) w(R)`` (paper eq. 4 for
  C; the wind w NED of :func:`flexsim._kernels.wind_ned`, frozen in the air), and from it the airspeed
  ``V = |v_a|``, the angle of attack ``alpha = atan2(w_a, u_a)`` and the sideslip ``beta = asin(v_a / V)``
  (0 at V = 0): :func:`flexsim.sim.outputs.air_angles`, the same formulas (tests/envs/test_row_kernels.py
  compares them);
* Mach ``V / a(H)`` with the ISA 1976 speed of sound at the geopotential altitude H of ``-R_z`` (1976 standard
  eqs. 18, 50: :func:`flexsim._kernels._geopotential`, :func:`flexsim._kernels._sound_speed`); NaN outside the
  ISA range, as :func:`flexsim.atmosphere.speed_of_sound` raises there;
* the heading rate ``psi_dot = (q sin phi + r cos phi) / cos theta`` [rad/s] (NaN at cos theta = 0;
  :func:`flexsim.sim.outputs.heading_rate`);
* the structural outputs of :class:`flexsim.model.sensors.SensorBank` (tip deflection, its rate, tip twist, its
  rate, root bending moment per component): each a fixed row times the state, summed over the nonzero entries
  of the bank's matrix in state order.

Reward and observation: :class:`flexsim.envs.config.TrackingReward` (parts in the order of ``part_names``,
summed left to right) and the observation layout of :meth:`FlexSimEnv._observation_layout` (NaN replaced by 0,
clipped to the bounds, float32).

:func:`measure_rows` embeds compiled code of :mod:`flexsim._kernels` (wind, direction cosines, ISA), so its numba
cache is keyed on that file's source too (:func:`flexsim._numba_cache.depends_on`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from flexsim import _kernels as _k
from flexsim._numba_cache import depends_on
from flexsim.sim import _step_kernels as _sk

__all__ = ["MEAS_COLUMNS", "SENSORS_AT", "WIND_STILL", "WIND_PACKED", "WIND_GIVEN", "measure_rows", "period_rows",
           "termination_rows", "finish_rows", "observe_rows", "reward_rows", "wrap", "wrap_rows"]

_jit = njit(cache=True, nogil=True)

#: Columns of a measurement row (:func:`measure_rows`); the structural outputs follow from :data:`SENSORS_AT`.
MEAS_COLUMNS = ("north_m", "east_m", "down_m", "roll_rad", "pitch_rad", "heading_rad", "p_rad_s", "q_rad_s", "r_rad_s",
                "airspeed_m_s", "alpha_rad", "beta_rad", "mach", "altitude_m", "heading_rate_rad_s")
#: First column of the structural outputs: column ``SENSORS_AT + C k + c`` is output k
#: (:data:`flexsim.model.sensors.SENSOR_QUANTITIES`) of component c (C components).
SENSORS_AT = len(MEAS_COLUMNS)
_POS, _EUL, _OM, _V, _ALPHA, _BETA, _MACH, _ALT, _HDOT = 0, 3, 6, 9, 10, 11, 12, 13, 14
#: Wind modes of :func:`measure_rows`: still air, winds packed (:class:`flexsim._kernels.BatchWind`), air
#: velocities given.
WIND_STILL, WIND_PACKED, WIND_GIVEN = 0, 1, 2
_TWO_PI = 2.0 * math.pi


@_jit
def wrap(angle):
    """``angle`` [rad] wrapped to [-pi, pi] as :func:`flexsim.envs.episodes.wrap_angle` (fmod by 2 pi plus one
    exact correction; NaN stays NaN, an infinity gives NaN)."""
    if not math.isfinite(angle):
        return math.nan
    r = np.fmod(angle, _TWO_PI)
    if r > math.pi:
        return r - _TWO_PI
    if r < -math.pi:
        return r + _TWO_PI
    return r


@_jit
def wrap_rows(angles, out):
    """:func:`wrap` of every entry of ``angles`` (k,) into ``out`` (k,)."""
    for i in range(angles.shape[0]):
        out[i] = wrap(angles[i])


@depends_on(_k)
@_jit
def measure_rows(x, wind_mode, v_given, rows, gusts, turb, turb_grid, index, s_ptr, s_idx, s_w, h_range, out):
    """Measurements of N aircraft (module docstring) into ``out`` (N, SENSORS_AT + n_outputs).

    x (N, n) states (the wind fields are frozen in the air: the time does not enter); wind_mode :data:`WIND_STILL`, :data:`WIND_PACKED` (aircraft i in the winds ``rows[i]`` of the packed
    ``gusts``, ``turb``, ``turb_grid``; a row whose position or attitude is not finite gets still-air data) or
    :data:`WIND_GIVEN` (v_given (N, 3): the air-relative velocities [m/s], body axes); index (4,) int: first
    state index of R, Theta, v, omega; the structural outputs: output o is ``sum_j s_w[j] x[s_idx[j]]`` over
    ``s_ptr[o] <= j < s_ptr[o + 1]``; h_range (2,): the ISA geopotential range [m].
    """
    p0, e0, v0, w0 = index[0], index[1], index[2], index[3]
    n_out = s_ptr.shape[0] - 1
    for i in range(x.shape[0]):
        for a in range(3):
            out[i, _POS + a] = x[i, p0 + a]
            out[i, _EUL + a] = x[i, e0 + a]
            out[i, _OM + a] = x[i, w0 + a]
        phi, theta, psi = x[i, e0], x[i, e0 + 1], x[i, e0 + 2]
        ua, va, wa = x[i, v0], x[i, v0 + 1], x[i, v0 + 2]
        if wind_mode == WIND_GIVEN:
            ua, va, wa = v_given[i, 0], v_given[i, 1], v_given[i, 2]
        elif wind_mode == WIND_PACKED:
            finite = True
            for a in range(3):
                if not (math.isfinite(x[i, p0 + a]) and math.isfinite(x[i, e0 + a])):
                    finite = False
            if finite:
                w = _k.wind_ned(gusts[rows[i, 0]:rows[i, 1]], turb[rows[i, 2]:rows[i, 3]], turb_grid, x[i:i + 1, p0:p0 + 3])
                c = _k.dcm_321(phi, theta, psi)
                ua = ua - (c[0, 0] * w[0, 0] + c[0, 1] * w[0, 1] + c[0, 2] * w[0, 2])
                va = va - (c[1, 0] * w[0, 0] + c[1, 1] * w[0, 1] + c[1, 2] * w[0, 2])
                wa = wa - (c[2, 0] * w[0, 0] + c[2, 1] * w[0, 1] + c[2, 2] * w[0, 2])
        speed = math.sqrt(ua * ua + va * va + wa * wa)
        ratio = va / (speed if speed > 0.0 else 1.0)
        if ratio > 1.0:
            ratio = 1.0
        elif ratio < -1.0:
            ratio = -1.0
        out[i, _V] = speed
        out[i, _ALPHA] = math.atan2(wa, ua)
        out[i, _BETA] = math.asin(ratio)
        altitude = -x[i, p0 + 2]
        out[i, _ALT] = altitude
        h = _k._geopotential(altitude)
        if h_range[0] <= h <= h_range[1]:
            out[i, _MACH] = speed / _k._sound_speed(h)
        else:
            out[i, _MACH] = math.nan
        cos_theta = math.cos(theta)
        if cos_theta == 0.0:
            out[i, _HDOT] = math.nan
        else:
            out[i, _HDOT] = (x[i, w0 + 1] * math.sin(phi) + x[i, w0 + 2] * math.cos(phi)) / cos_theta
        for o in range(n_out):
            acc = 0.0
            for j in range(s_ptr[o], s_ptr[o + 1]):
                acc += s_w[j] * x[i, s_idx[j]]
            out[i, SENSORS_AT + o] = acc


@_jit
def termination_rows(meas, failed, crashed, limits, n_comp, codes):
    """Termination code of N aircraft into ``codes`` (N,) int (index into ``TERMINATION_CODES``, 0: flying): the
    first that holds of 1 non-finite state or solver failure (``failed``), 2 crash (``crashed`` or altitude
    <= 0), 3 structural limit (|tip deflection| of component 0 or 1 > limits[0] m, or |tip twist| of
    component 2 > limits[1] rad), 4 gimbal lock (|theta| >= limits[2]), 5 envelope (Mach >= limits[3],
    |alpha| >= limits[4] or airspeed <= limits[5]); a NaN output fails its test. meas: :func:`measure_rows`
    rows with ``n_comp`` components."""
    defl, twist = SENSORS_AT, SENSORS_AT + 2 * n_comp
    for i in range(meas.shape[0]):
        if failed[i]:
            code = 1
        elif crashed[i] or meas[i, _ALT] <= 0.0:
            code = 2
        elif not (abs(meas[i, defl]) <= limits[0] and abs(meas[i, defl + 1]) <= limits[0]
                  and abs(meas[i, twist + 2]) <= limits[1]):
            code = 3
        elif not abs(meas[i, _EUL + 1]) < limits[2]:
            code = 4
        elif not (meas[i, _MACH] < limits[3] and abs(meas[i, _ALPHA]) < limits[4] and meas[i, _V] > limits[5]):
            code = 5
        else:
            code = 0
        codes[i] = code


@_jit
def observe_rows(meas, errors, u, u_scale, act_low, act_high, n_comp, obs_low, obs_high, obs):
    """Observations of N aircraft into ``obs`` (N, n_obs) float32: Euler angles (psi wrapped), body rates,
    airspeed, alpha, beta, altitude, the task errors (N, k), per component the tip deflection, its rate, the tip
    twist and its rate, and the applied controls u (N, 4) normalised by ``u_scale`` (0 where the scale is 0),
    clipped to [act_low, act_high] and rounded to float32; NaN -> 0, then clipped to [obs_low, obs_high]."""
    k = errors.shape[1]
    for i in range(meas.shape[0]):
        row = np.empty(obs.shape[1])
        row[0] = meas[i, _EUL]
        row[1] = meas[i, _EUL + 1]
        row[2] = wrap(meas[i, _EUL + 2])
        for a in range(3):
            row[3 + a] = meas[i, _OM + a]
        row[6], row[7], row[8], row[9] = meas[i, _V], meas[i, _ALPHA], meas[i, _BETA], meas[i, _ALT]
        for j in range(k):
            row[10 + j] = errors[i, j]
        s = 10 + k
        for c in range(n_comp):
            for q in range(4):
                row[s + 4 * c + q] = meas[i, SENSORS_AT + n_comp * q + c]
        s += 4 * n_comp
        for a in range(4):
            v = u[i, a] / u_scale[a] if u_scale[a] > 0.0 else 0.0
            v = min(max(v, act_low[a]), act_high[a])
            row[s + a] = np.float32(v)
        for j in range(row.shape[0]):
            v = row[j]
            if math.isnan(v):
                v = 0.0
            obs[i, j] = np.float32(min(max(v, obs_low[j]), obs_high[j]))


@_jit
def reward_rows(errors, terms, terminated, da, reward_data, parts, reward):
    """:class:`~flexsim.envs.config.TrackingReward` of N aircraft: task errors (N, k), ``terms`` (T,) int: the error
    column of each reward term, end flags (N,), action changes (N, 4); reward_data = [alive, -w_u, s_u, penalty,
    s_1..s_T, -w_1..-w_T]. Into parts (N, T + 3) (alive, the T terms, control rate, termination) and reward (N,)
    (their sum, left to right). A non-finite ratio counts as saturated."""
    k = terms.shape[0]
    alive, w_u, s_u, penalty = reward_data[0], reward_data[1], reward_data[2], reward_data[3]
    for i in range(errors.shape[0]):
        parts[i, 0] = alive
        for j in range(k):
            r = errors[i, terms[j]] / reward_data[4 + j]
            r = r * r
            parts[i, 1 + j] = (min(r, 1.0) if math.isfinite(r) else 1.0) * reward_data[4 + k + j]
        acc = 0.0
        for a in range(da.shape[1]):
            d = da[i, a] / s_u
            acc += d * d
        r = acc / da.shape[1]
        parts[i, 1 + k] = (min(r, 1.0) if math.isfinite(r) else 1.0) * w_u
        parts[i, 2 + k] = -penalty if terminated[i] else 0.0
        total = 0.0
        for j in range(k + 3):
            total += parts[i, j]
        reward[i] = total


@_jit
def finish_rows(meas, errors, terms, terminated, da, reward_data, u, u_scale, act_low, act_high, n_comp, obs_low, obs_high,
                parts, reward, obs):
    """:func:`reward_rows` and :func:`observe_rows` in one call (the end of a control period)."""
    reward_rows(errors, terms, terminated, da, reward_data, parts, reward)
    observe_rows(meas, errors, u, u_scale, act_low, act_high, n_comp, obs_low, obs_high, obs)


@depends_on(_k, _sk)
@_jit
def period_rows(F, I, rows, gusts, turb, turb_grid, x, u_applied, action, u_scale, rate_step, steps, dt, h, n_steps, h_phi1,
                h_phi2, jac, z_index, alt_lo, alt_hi, over_rows, wind_mode, index, s_ptr, s_idx, s_w, h_range, limits,
                n_comp, u_out, x_out, t_out, status, taken, meas, codes):
    """One control period of N aircraft flown about one trim, in one call: actuator rate limits, the ETD2RK steps
    (:func:`flexsim.sim._step_kernels.etd2rk_rows`, or with ``over_rows``
    :func:`~flexsim.sim._step_kernels.etd2rk_rows_gemm`: the products as matrix products over the rows),
    :func:`measure_rows` and :func:`termination_rows`.

    Row i: commanded controls ``action[i] * u_scale`` (N, 4), reached from the applied ``u_applied[i]`` at most
    ``rate_step`` per period (``FlightDynamics.rate_limit``: ``u + min(max(c - u, -rate_step), rate_step)``) into
    ``u_out`` (N, 4) and held; the period [steps[i] dt, (steps[i] + 1) dt] [s] in ``n_steps`` steps of h, into
    ``x_out``, ``t_out``, ``status``, ``taken`` (as etd2rk_rows); the measurements of the states reached into
    ``meas`` (wind_mode :data:`WIND_STILL` or :data:`WIND_PACKED`, the packed winds ``rows``, ``gusts``, ``turb``,
    ``turb_grid``) and the termination codes into ``codes`` (a non-finite state or a model error fails, the
    ground reached within a step is a crash). The same arithmetic as the separate calls
    (``FlexSimEnv._step_rows``' general path), so the results are equal bit for bit.
    """
    m = x.shape[0]
    t0s, t1s = np.empty(m), np.empty(m)
    for i in range(m):
        for a in range(4):
            d = action[i, a] * u_scale[a] - u_applied[i, a]
            u_out[i, a] = u_applied[i, a] + min(max(d, -rate_step[a]), rate_step[a])
        t0s[i] = steps[i] * dt
        t1s[i] = (steps[i] + 1) * dt
    if over_rows:
        _sk.etd2rk_rows_gemm(F, I, rows, gusts, turb, turb_grid, x, u_out, t0s, t1s, h, n_steps, h_phi1, h_phi2, jac, z_index,
                             alt_lo, alt_hi, x_out, t_out, status, taken)
    else:
        _sk.etd2rk_rows(F, I, rows, gusts, turb, turb_grid, x, u_out, t0s, t1s, h, n_steps, h_phi1, h_phi2, jac, z_index, alt_lo,
                        alt_hi, x_out, t_out, status, taken)
    measure_rows(x_out, wind_mode, np.empty((0, 3)), rows, gusts, turb, turb_grid, index, s_ptr, s_idx, s_w, h_range, meas)
    failed = np.empty(m, np.bool_)
    crashed = np.empty(m, np.bool_)
    for i in range(m):
        failed[i] = status[i] == _sk.ROW_NON_FINITE or status[i] == _sk.ROW_MODEL_ERROR
        crashed[i] = status[i] == _sk.ROW_GROUND
    termination_rows(meas, failed, crashed, limits, n_comp, codes)
