"""Measurements of many aircraft in one compiled call: air data, attitude, rates and structural sensors.

One implementation of the air data (:func:`air_data`: airspeed, angle of attack, sideslip) used by
:func:`measure_rows` (the control periods of :mod:`flexsim.sim.periods`, single and batched) and by
:func:`flexsim.sim.outputs.air_angles` (results and flight logs). A measurement row (:data:`MEAS_COLUMNS`, SI
units, radians):

* position R (NED) [m], Euler angles Theta = (phi, theta, psi) [rad] and body rates omega = (p, q, r) [rad/s],
  copied from the state (layout :class:`flexsim.model.layout.StateLayout`);
* the velocity of the body origin relative to the air, body axes, ``v_a = v - C(Theta) w(R)`` (paper eq. 4 for
  C; the wind w NED of the packed wind fields, frozen in the air), and from it the airspeed ``V = |v_a|``, the
  angle of attack ``alpha = atan2(w_a, u_a)`` and the sideslip ``beta = asin(v_a / V)`` (0 at V = 0);
* Mach ``V / a(H)`` with the ISA 1976 speed of sound at the geopotential altitude H of ``-R_z`` (1976 standard
  eqs. 18, 50); NaN outside the ISA range, where :func:`flexsim.atmosphere.speed_of_sound` raises;
* the heading rate ``psi_dot = (q sin phi + r cos phi) / cos theta`` [rad/s] (NaN at cos theta = 0);
* the structural outputs of :class:`flexsim.model.sensors.SensorBank` (tip deflection, its rate, tip twist, its
  rate, root bending moment per component): each a fixed row times the state (:class:`MeasureData`).

The kernels are compiled with ``cache=True`` (plain Python under ``NUMBA_DISABLE_JIT=1``); :func:`measure_rows`
embeds compiled code of the model kernels (wind, direction cosines, ISA), so its cache is keyed on their source.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from flexsim import _kernels as _k
from flexsim._numba_cache import depends_on
from flexsim.atmosphere import H_MAX, H_MIN
from flexsim.model.sensors import SENSOR_QUANTITIES

__all__ = ["MEAS_COLUMNS", "SENSORS_AT", "WIND_STILL", "WIND_PACKED", "WIND_GIVEN", "MeasureData", "Measurements",
           "MeasurementBatch", "air_data", "air_angles_rows", "heading_rate_rows", "measure_rows", "measure_data"]

_jit = njit(cache=True, nogil=True)

#: Columns of a measurement row (:func:`measure_rows`); the structural outputs follow from :data:`SENSORS_AT`.
MEAS_COLUMNS = ("north_m", "east_m", "down_m", "roll_rad", "pitch_rad", "heading_rad", "p_rad_s", "q_rad_s", "r_rad_s",
                "airspeed_m_s", "alpha_rad", "beta_rad", "mach", "altitude_m", "heading_rate_rad_s")
#: First column of the structural outputs: column ``SENSORS_AT + C k + c`` is output k
#: (:data:`flexsim.model.sensors.SENSOR_QUANTITIES`) of component c (C components).
SENSORS_AT = len(MEAS_COLUMNS)
_POS, _EUL, _OM, _V, _ALPHA, _BETA, _MACH, _ALT, _HDOT = 0, 3, 6, 9, 10, 11, 12, 13, 14
#: Wind modes of :func:`measure_rows`: still air, packed winds (``AircraftModel.pack_winds``), air velocities given.
WIND_STILL, WIND_PACKED, WIND_GIVEN = 0, 1, 2


class MeasureData(NamedTuple):
    """What :func:`measure_rows` needs of a model (:func:`measure_data`): ``index`` (4,) int, the first state index of
    R, Theta, v, omega; the structural outputs, output o = ``sum_j s_w[j] x[s_idx[j]]`` over
    ``s_ptr[o] <= j < s_ptr[o + 1]``; ``h_range`` (2,), the ISA geopotential range [m]."""

    index: np.ndarray
    s_ptr: np.ndarray
    s_idx: np.ndarray
    s_w: np.ndarray
    h_range: np.ndarray


def measure_data(layout, bank: np.ndarray, n_comp: int) -> MeasureData:
    """:class:`MeasureData` of a state layout and a :class:`~flexsim.model.sensors.SensorBank` matrix (n, 5 C) of
    ``n_comp`` components: the structural outputs in the kernel's column order (output k of component c at
    C k + c) as the nonzero entries of the bank's columns, in state order."""
    index = np.array([layout.position.start, layout.euler.start, layout.v.start, layout.omega.start], dtype=np.int64)
    ptr, idx, w = [0], [], []
    for o in range(bank.shape[1]):
        k, comp = divmod(o, n_comp)
        column = bank[:, len(SENSOR_QUANTITIES) * comp + k]
        nz = np.flatnonzero(column)
        idx.extend(nz.tolist())
        w.extend(column[nz].tolist())
        ptr.append(len(idx))
    return MeasureData(index, np.array(ptr, np.int64), np.array(idx, np.int64), np.array(w, float), np.array([H_MIN, H_MAX]))


@_jit
def air_data(ua, va, wa):
    """Airspeed V = |v_a| [m/s], angle of attack atan2(w_a, u_a) [rad] and sideslip asin(v_a / V) [rad] (0 at V = 0)
    of the velocity relative to the air in body axes (u_a, v_a, w_a) [m/s]."""
    speed = math.sqrt(ua * ua + va * va + wa * wa)
    ratio = va / (speed if speed > 0.0 else 1.0)
    if ratio > 1.0:
        ratio = 1.0
    elif ratio < -1.0:
        ratio = -1.0
    return speed, math.atan2(wa, ua), math.asin(ratio)


@_jit
def air_angles_rows(v, out):
    """:func:`air_data` of the rows of v (N, 3) [m/s] into out (N, 3): airspeed, alpha, beta."""
    for i in range(v.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = air_data(v[i, 0], v[i, 1], v[i, 2])


@_jit
def _heading_rate(phi, theta, q, r):
    cos_theta = math.cos(theta)
    if cos_theta == 0.0:
        return math.nan
    return (q * math.sin(phi) + r * math.cos(phi)) / cos_theta


@_jit
def heading_rate_rows(euler, rates, out):
    """psi_dot = (q sin phi + r cos phi) / cos theta [rad/s] of Euler angles (N, 3) [rad] and body rates (N, 3)
    [rad/s] into out (N,) (NaN at cos theta = 0)."""
    for i in range(euler.shape[0]):
        out[i] = _heading_rate(euler[i, 0], euler[i, 1], rates[i, 1], rates[i, 2])


@depends_on(_k)
@_jit
def measure_rows(x, wind_mode, v_given, wind, data, out):
    """Measurements of N aircraft (module docstring) into ``out`` (N, SENSORS_AT + n_outputs).

    x (N, n) states (the wind fields are frozen in the air: the time does not enter); ``wind_mode``
    :data:`WIND_STILL`, :data:`WIND_PACKED` (aircraft i in the winds ``wind.rows[i]`` of the packed ``wind``, a
    ``BatchWind``; a row whose position or attitude is not finite gets still-air data) or :data:`WIND_GIVEN`
    (``v_given`` (N, 3): the air-relative velocities [m/s], body axes); ``data`` a :class:`MeasureData`.
    """
    p0, e0, v0, w0 = data.index[0], data.index[1], data.index[2], data.index[3]
    s_ptr, s_idx, s_w, h_range = data.s_ptr, data.s_idx, data.s_w, data.h_range
    rows = wind.rows
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
                w = _k.wind_ned(wind.gusts[rows[i, 0]:rows[i, 1]], wind.turb[rows[i, 2]:rows[i, 3]], wind.turb_grid,
                                x[i:i + 1, p0:p0 + 3])
                c = _k.dcm_321(phi, theta, psi)
                ua = ua - (c[0, 0] * w[0, 0] + c[0, 1] * w[0, 1] + c[0, 2] * w[0, 2])
                va = va - (c[1, 0] * w[0, 0] + c[1, 1] * w[0, 1] + c[1, 2] * w[0, 2])
                wa = wa - (c[2, 0] * w[0, 0] + c[2, 1] * w[0, 1] + c[2, 2] * w[0, 2])
        speed, alpha, beta = air_data(ua, va, wa)
        out[i, _V] = speed
        out[i, _ALPHA] = alpha
        out[i, _BETA] = beta
        altitude = -x[i, p0 + 2]
        out[i, _ALT] = altitude
        h = _k._geopotential(altitude)
        if h_range[0] <= h <= h_range[1]:
            out[i, _MACH] = speed / _k._sound_speed(h)
        else:
            out[i, _MACH] = math.nan
        out[i, _HDOT] = _heading_rate(phi, theta, x[i, w0 + 1], x[i, w0 + 2])
        for o in range(n_out):
            acc = 0.0
            for j in range(s_ptr[o], s_ptr[o + 1]):
                acc += s_w[j] * x[i, s_idx[j]]
            out[i, SENSORS_AT + o] = acc


@dataclass(frozen=True)
class Measurements:
    """Outputs of one state (SI, radians; structural signs as in ``docs/conventions.md``).

    Attributes
    ----------
    time_s : float
    position_ned_m, euler_rad, body_rates_rad_s : ndarray, shape (3,)
    airspeed_m_s, alpha_rad, beta_rad, mach : float
        Air data relative to the air at the body origin (wind included).
    altitude_m : float
    heading_rate_rad_s : float
        psi_dot = (q sin(phi) + r cos(phi)) / cos(theta) [rad/s] (the turn rate of a level turn).
    tip_deflection_m, tip_deflection_rate_m_s, tip_twist_rad, tip_twist_rate_rad_s : dict
        Per sensor component: bending deflection w(L) (positive along z_i, i.e. down on a wing half), its rate,
        torsion psi(L) and its rate at the tip.
    root_bending_moment_n_m : dict
        Per wing half: EI(0) w''(0), the modal-curvature root bending moment [N m].
    """

    time_s: float
    position_ned_m: np.ndarray
    euler_rad: np.ndarray
    body_rates_rad_s: np.ndarray
    airspeed_m_s: float
    alpha_rad: float
    beta_rad: float
    mach: float
    altitude_m: float
    heading_rate_rad_s: float
    tip_deflection_m: dict
    tip_deflection_rate_m_s: dict
    tip_twist_rad: dict
    tip_twist_rate_rad_s: dict
    root_bending_moment_n_m: dict


class MeasurementBatch:
    """:class:`Measurements` of N states at once: the same fields with a leading axis N (scalars become arrays (N,),
    vectors (N, 3); the structural dicts map a component to an array (N,)), views of one matrix, the rows of
    :func:`measure_rows`.

    Attributes
    ----------
    time_s : ndarray, shape (N,)
    matrix : ndarray, shape (N, SENSORS_AT + 5 C)
        The measurement rows (columns :data:`MEAS_COLUMNS`, then the structural outputs of the C ``components``).
    components : tuple of str
        The sensor components, in column order; root bending moments are read for those in ``wing_halves``.
    """

    __slots__ = ("time_s", "matrix", "components", "wing_halves")

    def __init__(self, time_s: np.ndarray, matrix: np.ndarray, components: tuple[str, ...],
                 wing_halves: tuple[str, ...] = ("right_wing", "left_wing")) -> None:
        self.time_s, self.matrix, self.components, self.wing_halves = time_s, matrix, components, wing_halves

    position_ned_m = property(lambda self: self.matrix[:, 0:3])
    euler_rad = property(lambda self: self.matrix[:, 3:6])
    body_rates_rad_s = property(lambda self: self.matrix[:, 6:9])
    airspeed_m_s = property(lambda self: self.matrix[:, 9])
    alpha_rad = property(lambda self: self.matrix[:, 10])
    beta_rad = property(lambda self: self.matrix[:, 11])
    mach = property(lambda self: self.matrix[:, 12])
    altitude_m = property(lambda self: self.matrix[:, 13])
    heading_rate_rad_s = property(lambda self: self.matrix[:, 14])

    @property
    def sensors(self) -> np.ndarray:
        """All structural outputs, (N, 5, C) (:meth:`flexsim.model.sensors.SensorBank.evaluate`)."""
        return self.matrix[:, SENSORS_AT:].reshape(-1, 5, len(self.components))

    def _structural(self, k: int, names=None) -> dict:
        s = SENSORS_AT + k * len(self.components)
        return {name: self.matrix[:, s + j] for j, name in enumerate(self.components) if names is None or name in names}

    tip_deflection_m = property(lambda self: self._structural(0))
    tip_deflection_rate_m_s = property(lambda self: self._structural(1))
    tip_twist_rad = property(lambda self: self._structural(2))
    tip_twist_rate_rad_s = property(lambda self: self._structural(3))
    root_bending_moment_n_m = property(lambda self: self._structural(4, self.wing_halves))

    def row(self, i: int) -> Measurements:
        """The :class:`Measurements` of state i (floats and copies)."""
        def f(a):
            return float(a[i])

        return Measurements(f(self.time_s), self.position_ned_m[i].copy(), self.euler_rad[i].copy(), self.body_rates_rad_s[i].copy(),
                            f(self.airspeed_m_s), f(self.alpha_rad), f(self.beta_rad), f(self.mach), f(self.altitude_m),
                            f(self.heading_rate_rad_s), *({k: f(v) for k, v in d.items()} for d in (
                                self.tip_deflection_m, self.tip_deflection_rate_m_s, self.tip_twist_rad, self.tip_twist_rate_rad_s,
                                self.root_bending_moment_n_m)))
