"""Compiled per-aircraft outputs of the environments (numba): termination, reward parts, observation.

One implementation over rows of aircraft, used by the single environment (as one row) and by the batched
:class:`~flexsim.envs.vector.FlexSimVectorEnv` (N rows): :meth:`FlexSimEnv._step_rows` calls, per control period,
:func:`finish_rows` (termination, reward parts, reward and observation) on the measurement rows of
:mod:`flexsim.sim.measurements`; only the task errors (a few lines of array code per task) stay in Python. Its
arguments are grouped in NamedTuples (:class:`RowsEnd`, :class:`EndData`, :class:`ObserveData`, :class:`FinishOut`);
called once per control period from Python, it takes their fields flat, made by :func:`finish_args` and taken apart by
the kernel from the same group definitions (:data:`FINISH_GROUPS`, as :func:`flexsim.sim._step_kernels.period_rows`
does). Reward:
:class:`flexsim.envs.config.TrackingReward` (parts in the order of ``part_names``, summed left to right);
observation: the layout of :meth:`FlexSimEnv._observation_layout` (NaN replaced by 0, clipped to the bounds,
float32). Compiled with ``cache=True``; plain Python under ``NUMBA_DISABLE_JIT=1``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from flexsim._arrays import group_bounds
from flexsim.sim.measurements import SENSORS_AT

__all__ = ["termination_rows", "finish_rows", "finish_args", "observe_rows", "reward_rows", "wrap", "wrap_rows", "RowsEnd",
           "EndData", "ObserveData", "FinishOut", "FINISH_GROUPS"]

_jit = njit(cache=True, nogil=True)

#: Columns of a measurement row (:data:`flexsim.sim.measurements.MEAS_COLUMNS`) read here.
_EUL, _OM, _V, _ALPHA, _BETA, _MACH, _ALT = 3, 6, 9, 10, 11, 12, 13
_TWO_PI = 2.0 * math.pi


@_jit
def wrap(angle):
    """``angle`` [rad] wrapped to [-pi, pi]: the exact ``fmod`` by 2 pi plus one exact (Sterbenz) correction by 2 pi
    (the IEEE remainder; NaN stays NaN, an infinity gives NaN)."""
    if not math.isfinite(angle):
        return math.nan
    r = np.fmod(angle, _TWO_PI)
    if r > math.pi:
        return r - _TWO_PI
    if r < -math.pi:
        return r + _TWO_PI
    return r


@_jit
def wrap_rows(angles):
    """:func:`wrap` of every entry of ``angles`` (k,) [rad], a new array (k,)."""
    out = np.empty(angles.shape[0])
    for i in range(angles.shape[0]):
        out[i] = wrap(angles[i])
    return out


@_jit
def termination_rows(meas, failed, crashed, limits, n_comp, codes):
    """Termination code of N aircraft into ``codes`` (N,) int (index into ``TERMINATION_CODES``, 0: flying): the
    first that holds of 1 non-finite state or solver failure (``failed``), 2 crash (``crashed`` or altitude
    <= 0), 3 structural limit (|tip deflection| of component 0 or 1 > limits[0] m, or |tip twist| of
    component 2 > limits[1] rad), 4 gimbal lock (|theta| >= limits[2]), 5 envelope (Mach >= limits[3],
    |alpha| >= limits[4] or airspeed <= limits[5]); a NaN output fails its test. meas: the measurement rows
    (:func:`flexsim.sim.measurements.measure_rows`) with ``n_comp`` components."""
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
def observe_rows(meas, errors, u, ob, obs):
    """Observations of N aircraft into ``obs`` (N, n_obs) float32: Euler angles (psi wrapped), body rates,
    airspeed, alpha, beta, altitude, the task errors (N, k), per component the tip deflection, its rate, the tip
    twist and its rate, and the applied controls u (N, 4) normalised by ``ob.u_scale`` (0 where the scale is 0),
    clipped to [ob.act_low, ob.act_high] and rounded to float32; NaN -> 0, then clipped to [ob.obs_low, ob.obs_high];
    ``ob`` the environment's :class:`ObserveData`."""
    u_scale, act_low, act_high, n_comp, obs_low, obs_high = ob.u_scale, ob.act_low, ob.act_high, ob.n_comp, ob.obs_low, ob.obs_high
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


class RowsEnd(NamedTuple):
    """What a control period of N aircraft ended with: the measurement rows ``meas`` (N, m)
    (:func:`flexsim.sim.measurements.measure_rows`), the integration's ``failed`` and ``crashed`` flags (N,) bool, the
    task's own termination codes ``task_codes`` (N,) int (0: none), the task errors ``errors`` (N, k), the action
    changes ``da`` (N, 4) and the applied controls ``u`` (N, 4) [N, rad]."""

    meas: np.ndarray
    failed: np.ndarray
    crashed: np.ndarray
    task_codes: np.ndarray
    errors: np.ndarray
    da: np.ndarray
    u: np.ndarray


class EndData(NamedTuple):
    """The environment's constants of termination and reward: ``limits`` (6,) of :func:`termination_rows`, ``terms``
    (T,) int and ``reward_data`` of :func:`reward_rows`."""

    limits: np.ndarray
    terms: np.ndarray
    reward_data: np.ndarray


class ObserveData(NamedTuple):
    """The environment's constants of :func:`observe_rows`: the control scales ``u_scale`` (4,) [N, rad], the action
    bounds ``act_low``, ``act_high`` (4,), the number of sensor components ``n_comp`` and the observation bounds
    ``obs_low``, ``obs_high`` (n_obs,)."""

    u_scale: np.ndarray
    act_low: np.ndarray
    act_high: np.ndarray
    n_comp: int
    obs_low: np.ndarray
    obs_high: np.ndarray


class FinishOut(NamedTuple):
    """Results of :func:`finish_rows` (written in place): termination ``codes`` (N,) int, reward ``parts`` (N, T + 3),
    ``reward`` (N,) and observations ``obs`` (N, n_obs) float32."""

    codes: np.ndarray
    parts: np.ndarray
    reward: np.ndarray
    obs: np.ndarray


#: The groups of :func:`finish_rows`' arguments, in order.
FINISH_GROUPS = (RowsEnd, EndData, ObserveData, FinishOut)
_END0, _END1, _DATA0, _DATA1, _OBS0, _OBS1, _OUT0, _OUT1 = group_bounds(FINISH_GROUPS)


def finish_args(end: RowsEnd, data: EndData, observe: ObserveData, out: FinishOut) -> tuple:
    """The flat argument list of :func:`finish_rows` from its groups, in the order and of the NamedTuples of
    :data:`FINISH_GROUPS` (not checked here: it is called every control period)."""
    return (*end, *data, *observe, *out)


@_jit
def finish_rows(*args):
    """The end of a control period in one call; ``args`` is :func:`finish_args` of the groups end (:class:`RowsEnd`),
    data (:class:`EndData`), observe (:class:`ObserveData`) and out (:class:`FinishOut`): :func:`termination_rows`
    into ``out.codes``, where it gives 0 the task's own code ``end.task_codes[i]`` (0: none), then :func:`reward_rows`
    (terminated: code > 0) and :func:`observe_rows`."""
    end = RowsEnd(*args[_END0:_END1])
    data = EndData(*args[_DATA0:_DATA1])
    ob = ObserveData(*args[_OBS0:_OBS1])
    out = FinishOut(*args[_OUT0:_OUT1])
    codes = out.codes
    termination_rows(end.meas, end.failed, end.crashed, data.limits, ob.n_comp, codes)
    terminated = np.empty(codes.shape[0], np.bool_)
    for i in range(codes.shape[0]):
        if codes[i] == 0:
            codes[i] = end.task_codes[i]
        terminated[i] = codes[i] > 0
    reward_rows(end.errors, data.terms, terminated, end.da, data.reward_data, out.parts, out.reward)
    observe_rows(end.meas, end.errors, end.u, ob, out.obs)
