"""Compiled outputs of many samples at once: the aerodynamic force and wing lift behind the load factor and wing
lift signals (:meth:`flexsim.sim.outputs.OutputMaps.load_factor_and_lift`) of N states in one call, the cost of a
flight log's signals (``docs/performance.md``).

The kernels of one state are those the Python path calls (:func:`flexsim._kernels.aerodynamic_force`,
``strip_wind_at``, ``strip_kinematics``, ``downwash_shift``, ``circulatory``: paper eqs. 24-31 and the tail downwash
of :func:`flexsim.model.coupling.AeroCoupling.strip_loads`), with the same arguments, so the results are the same.
Arguments are grouped in NamedTuples (:class:`LoadSamples`, :class:`LoadsData`, :class:`LoadsOut`), passed as
they are (one call per series: the dispatcher's cost of a tuple does not matter). Units SI, angles in radians; body axes.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from flexsim import _kernels as _k
from flexsim._numba_cache import depends_on

__all__ = ["loads_rows", "LoadSamples", "LoadsData", "LoadsOut"]

_jit = njit(cache=True, nogil=True)


class LoadSamples(NamedTuple):
    """N samples: states ``x`` (N, n), controls ``u`` (N, 4) [N, rad] and the speed of sound ``sound`` (N,) [m/s] at
    each sample's altitude."""

    x: np.ndarray
    u: np.ndarray
    sound: np.ndarray


class LoadsData(NamedTuple):
    """What :func:`loads_rows` needs of the model beyond its kernel data: the thrust map T (t0 + t1 q), ``thrust_t0``
    (n_v,) and ``thrust_t1`` (n_v, nq); the ``wing`` strip indices (k,) int (none: no wing lift) and the strip widths
    ``width`` (n_strips,) [m]; ``downwash``, the tail in the wing's downwash; ``inflow`` (2,) int, the first and end
    state index of the inflow states."""

    thrust_t0: np.ndarray
    thrust_t1: np.ndarray
    wing: np.ndarray
    width: np.ndarray
    downwash: bool
    inflow: np.ndarray


class LoadsOut(NamedTuple):
    """Results of :func:`loads_rows` (written in place): ``force`` (N, 3) [N] and ``lift`` (N,) [N]."""

    force: np.ndarray
    lift: np.ndarray


@depends_on(_k)
@_jit
def loads_rows(model, wind, samples, data, out):
    """For each sample i of ``samples`` (:class:`LoadSamples`: state x[i], controls u[i]) in the winds ``wind.rows[i]``
    of the packed ``wind`` (``BatchWind``), with the model's kernel data ``model`` and ``data`` (:class:`LoadsData`):
    the resultant of the thrust and aerodynamic forces out.force[i] (N, 3) [N] (body axes; the thrust
    T (t0 + t1 q), T = u[i, 0]; the strip airloads without apparent mass, parasite drag and body forces of
    :func:`flexsim._kernels.aerodynamic_force`) and, for ``data.wing`` strip indices (none: lift untouched), the wing
    lift out.lift[i] = sum of the circulatory strip lifts times ``data.width`` [N] at the model's air density and the
    Mach number |v| / sound[i], with the tail in the wing's downwash when ``data.downwash``."""
    F, I = model.F, model.I
    rows = wind.rows
    xs, us, sound = samples
    t0, t1, wing, width, downwash, inflow = data
    force, lift = out
    for i in range(xs.shape[0]):
        x, u = xs[i], us[i]
        _, _, q, xi, vel = _k.unpack(F, I, x)
        wind_c, has_wind = _k.strip_wind_at(F, I, wind.gusts[rows[i, 0]:rows[i, 1]], wind.turb[rows[i, 2]:rows[i, 3]],
                                            wind.turb_grid, x)
        q_a = _k.aerodynamic_force(F, I, x, u, wind_c, has_wind)
        q_t = u[0] * (t0 + np.dot(t1, q))
        for c in range(3):
            force[i, c] = q_t[c] + q_a[c]
        if wing.shape[0] == 0:
            continue
        v3 = vel[0:3].copy()
        mach = np.sqrt(np.dot(v3, v3)) / sound[i]
        rho = _k.air(F, I, x)[1]
        kin = _k.strip_kinematics(F, I, q, xi, vel, x[inflow[0]:inflow[1]].copy(), u, wind_c, has_wind)
        u0, wc, w_moment, alpha_chord = kin[3], kin[6], kin[7], kin[8]
        if downwash:
            shift = _k.downwash_shift(F, I, vel, u0, wc, mach)
            wc = wc + shift
            w_moment = w_moment + shift
        strip_lift = _k.circulatory(F, I, u0, wc, w_moment, alpha_chord, rho, mach)[0]
        s = np.empty(wing.shape[0])
        w = np.empty(wing.shape[0])
        for j in range(wing.shape[0]):
            s[j] = strip_lift[wing[j]]
            w[j] = width[wing[j]]
        lift[i] = np.dot(s, w)
