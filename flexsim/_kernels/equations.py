"""The equations of motion, compiled: E V_dot = f assembled from the terms and solved; x_dot = rhs(t, x, u).

Tuzcu & Nguyen (2014) "Flutter of Maneuvering Aircraft": eqs. (2)-(4) kinematics, (12) and (33) equations of
motion. Each term of eq. 33 is a module of this package with its data class and kernel:
:mod:`~flexsim._kernels.structure` (inertia, eqs. 8-10), :mod:`~flexsim._kernels.elasticity` (eqs. 14-16),
:mod:`~flexsim._kernels.gravity` (eq. 32), :mod:`~flexsim._kernels.thrust` (eqs. 17-24),
:mod:`~flexsim._kernels.gyroscopic` (the engines' rotors, Etkin & Reid 1996),
:mod:`~flexsim._kernels.strips` (strip airloads, eqs. 17-31), :mod:`~flexsim._kernels.peters` (inflow), :mod:`~flexsim._kernels.downwash`
(the wing's downwash at the tail), :mod:`~flexsim._kernels.drag` (parasite drag), :mod:`~flexsim._kernels.bodies`
(slender bodies), :mod:`~flexsim._kernels.wind` (gusts, turbulence);
:mod:`~flexsim._kernels.solve` eliminates E V_dot = f. Body axes xyz (x forward, y right, z down), inertial NED;
SI units, radians.
"""

from __future__ import annotations

import math

import numpy as np

from flexsim._kernels.bodies import HAS_BODIES, body_force
from flexsim._kernels.downwash_lag import downwash_lag_mass
from flexsim._kernels.drag import HAS_DRAG, parasite_drag
from flexsim._kernels.elasticity import elastic_force
from flexsim._kernels.gravity import gravity_force
from flexsim._kernels.gyroscopic import gyroscopic_force
from flexsim._kernels.isa import dcm_321
from flexsim._kernels.layout import SOLVE_PERM, SOLVE_PTR, _f1, _flag, _i1, inline, kernel
from flexsim._kernels.solve import block_solve
from flexsim._kernels.state import (ACTIVE, HAS_AERO, INFLOW_START, N_INFLOW, NQ, NXI, Q_START, RIGID, USE_FROZEN,
                                    VEL_START, air_state, unpack)
from flexsim._kernels.strips import SEMICHORD, aero_evaluate, inflow_rate
from flexsim._kernels.structure import inertia_term
from flexsim._kernels.thrust import thrust_force
from flexsim._kernels.wind import strip_positions, strip_wind, wind_ned


@kernel
def assemble(F, I, x, u, wind_c, has_wind):
    """E = M(q) + M_a and f of E V_dot = f (full size; paper eq. 33 in velocity form, docs/design.md):

        E = M(q) + M_a,   f = Q_inertia + Q_elastic + Q_g + Q_T + Q_gyro + Q_a + Q_D + Q_B

    Q_inertia = -M_dot V + g(V, p) + [0, 0, dT/dq, 0] (:func:`inertia_term`), Q_elastic = -K [0, 0, q, xi] -
    C_el V_el (:func:`elastic_force`), Q_g = M(q) [g_b; 0] (:func:`gravity_force`), Q_T = T_e (t0 + t1 q)
    (:func:`thrust_force`), the engines' gyroscopic moment Q_gyro = [0; -omega x h_e; 0] (:func:`gyroscopic_force`),
    the strips' airloads Q_a with their apparent mass M_a (:func:`aero_evaluate`), the
    parasite drag Q_D (:func:`parasite_drag`) and the slender bodies' Munk moments Q_B (:func:`body_force`).

    Returns m (n_v, n_v), f (n_v,), row0 (n_s, n_v), w_ea_x (n_s,), u0 (n_s,) (the inflow's terms).
    """
    pos, eul, q, xi, vel = unpack(F, I, x)
    m, f = inertia_term(F, I, q, vel)
    elastic_force(F, I, q, xi, vel, f)
    gravity_force(F, I, m, eul, f)
    thrust_force(F, I, q, u, f)
    gyroscopic_force(F, I, vel, f)
    row0, w_ea_x, u0 = aerodynamic_terms(F, I, x, q, xi, vel, u, wind_c, has_wind, m, f)
    return m, f, row0, w_ea_x, u0


@inline
def aerodynamic_terms(F, I, x, q, xi, vel, u, wind_c, has_wind, m, f):
    """The aerodynamic terms, the one list of them: m += M_a and f += Q_a + Q_D + Q_B (strip airloads with their
    apparent mass, parasite drag, slender bodies), m += the tail's downwash lag (:func:`downwash_lag_mass`, off by
    default) at the air state of state x (:func:`air_state`: density, Mach
    number, speed of sound), which each term's kernel takes; returns the inflow's terms row0 (n_s, n_v), w_ea_x
    (n_s,), u0 (n_s,). :func:`assemble` and :func:`aerodynamic_force` both evaluate this list."""
    n_v = vel.shape[0]
    if not _flag(I, HAS_AERO):
        n_s = _f1(F, I, SEMICHORD).shape[0]
        return np.zeros((n_s, n_v)), np.zeros(n_s), np.zeros(n_s)
    air = air_state(F, I, x, vel)
    rho, mach = air[0], air[1]
    lam = x[_flag(I, INFLOW_START):_flag(I, INFLOW_START) + _flag(I, N_INFLOW)]
    m_a, q_a, row0, w_ea_x, u0 = aero_evaluate(F, I, q, xi, vel, lam, u, rho, mach, wind_c, has_wind)
    for i in range(n_v):
        f[i] += q_a[i]
        for k in range(n_v):
            m[i, k] += m_a[i, k]
    if _flag(I, HAS_DRAG):
        q_d = parasite_drag(F, I, q, vel, rho)
        for i in range(n_v):
            f[i] += q_d[i]
    if _flag(I, HAS_BODIES):
        q_b = body_force(F, I, q, vel, rho)
        for i in range(n_v):
            f[i] += q_b[i]
    downwash_lag_mass(F, I, air, m)
    return row0, w_ea_x, u0


@kernel
def aerodynamic_force(F, I, x, u, wind_c, has_wind):
    """Generalized aerodynamic force without the apparent-mass terms (n_v,): the f part of :func:`aerodynamic_terms`
    (strip airloads, the explicit part of :func:`aero_evaluate`, plus parasite drag and body moments, and any other
    aerodynamic term of that list; what a term adds to E is left out); rows 0-2 force [N] (body), 3-5 moment about o
    [N m]."""
    pos, eul, q, xi, vel = unpack(F, I, x)
    n_v = vel.shape[0]
    out = np.zeros(n_v)
    aerodynamic_terms(F, I, x, q, xi, vel, u, wind_c, has_wind, np.zeros((n_v, n_v)), out)
    return out


@kernel
def strip_wind_at(F, I, gusts, turb, turb_grid, x):
    """Strip air velocity (component axes, (n_s, 3) [m/s]) of a wind (:class:`WindData` arrays) at state x,
    and whether there is any."""
    n_s = _f1(F, I, SEMICHORD).shape[0]
    if not _flag(I, HAS_AERO) or (gusts.shape[0] == 0 and turb.shape[0] == 0):
        return np.zeros((n_s, 3)), False
    pos, eul, _, _, _ = unpack(F, I, x)
    c = dcm_321(eul[0], eul[1], eul[2])
    w_ned = wind_ned(gusts, turb, turb_grid, strip_positions(F, I, pos, c))
    return strip_wind(F, I, w_ned, c), True


@inline
def _rhs(F, I, x, u, wind_c, has_wind):
    m, f, row0, w_ea_x, u0 = assemble(F, I, x, u, wind_c, has_wind)
    act = _i1(I, ACTIVE)
    full = block_solve(m, f, _i1(I, SOLVE_PERM), _i1(I, SOLVE_PTR))
    dx = np.empty_like(x)
    vs = _flag(I, VEL_START)
    na = act.shape[0]
    for i in range(na):
        dx[vs + i] = full[act[i]]
    n_in = _flag(I, N_INFLOW)
    if n_in:
        i0 = _flag(I, INFLOW_START)
        dx[i0:i0 + n_in] = inflow_rate(F, I, row0, w_ea_x, u0, x[i0:i0 + n_in], full)
    vel = x[vs:vs + na]
    if _flag(I, RIGID):
        phi, theta, psi = x[3], x[4], x[5]
        c = dcm_321(phi, theta, psi)
        for a in range(3):  # R_dot = C^T v (eq. 4)
            dx[a] = c[0, a] * vel[0] + c[1, a] * vel[1] + c[2, a] * vel[2]
        # Euler rates Theta_dot = E^-1 omega (paper eq. 4; kinematics.euler_rate_matrix_inverse)
        sf, cf = math.sin(phi), math.cos(phi)
        tt, sec = math.tan(theta), 1.0 / math.cos(theta)
        p_, q_, r_ = vel[3], vel[4], vel[5]
        dx[3] = p_ + sf * tt * q_ + cf * tt * r_
        dx[4] = cf * q_ - sf * r_
        dx[5] = sf * sec * q_ + cf * sec * r_
    n_el = 0 if _flag(I, USE_FROZEN) else _flag(I, NQ) + _flag(I, NXI)
    if n_el:
        off = 6 if _flag(I, RIGID) else 0
        q0 = _flag(I, Q_START)
        dx[q0:q0 + n_el] = vel[off:off + n_el]
    return dx


@kernel
def rhs(F, I, gusts, turb, turb_grid, x, u):
    """State derivative x_dot of the nonlinear model (paper eqs. 4, 33) with a wind (:class:`WindData`
    arrays; :data:`NO_WIND`: still air).

    Solves E V_dot = f (:func:`solve`), then lambda_dot with the solved accelerations (no acceleration
    lagged), R_dot = C^T v, Theta_dot = E^-1 omega, [q, xi]_dot = [s, eta]. x (n_states,), u (4,)
    [T_e (N), delta_a, delta_e, delta_r (rad)].
    """
    return _rhs_wind(F, I, gusts, turb, turb_grid, x, u)


@inline
def _rhs_wind(F, I, gusts, turb, turb_grid, x, u):
    wind_c, has_wind = strip_wind_at(F, I, gusts, turb, turb_grid, x)
    return _rhs(F, I, x, u, wind_c, has_wind)


@kernel
def rhs_strip_wind(F, I, x, u, wind_c):
    """:func:`rhs` with the strip air velocity (n_s, 3), component axes [m/s], given (any wind callable)."""
    # a run-time bool (always true), not the literal True: numba compiles a callee once more, and with it the whole
    # right-hand side, for a literal argument (flexsim._kernels.layout.inline)
    has_wind = wind_c.shape[0] >= 0
    return _rhs(F, I, x, u, wind_c, has_wind)


@kernel
def rhs_batch(F, I, rows, gusts, turb, turb_grid, xs, us):
    """x_dot of N aircraft of one model in one call: xs (N, n_states), us (N, 4) -> (N, n_states); aircraft i
    sees the gusts rows[i, 0]:rows[i, 1] and Dryden fields rows[i, 2]:rows[i, 3] (:class:`BatchWind`)."""
    out = np.empty_like(xs)
    for i in range(xs.shape[0]):
        out[i] = _rhs_wind(F, I, gusts[rows[i, 0]:rows[i, 1]], turb[rows[i, 2]:rows[i, 3]], turb_grid, xs[i], us[i])
    return out

