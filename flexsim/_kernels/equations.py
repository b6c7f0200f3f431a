"""The equations of motion, compiled: E V_dot = f assembled and solved, and the right-hand side x_dot = rhs(t, x, u).

Tuzcu & Nguyen (2014) "Flutter of Maneuvering Aircraft": eqs. (2)-(4) kinematics, (7)-(10) M(q), (12) and (33)
equations of motion, (14)-(16) stiffness, (17)-(24) generalized forces, (32) gravity; the pieces are in
:mod:`~flexsim._kernels.structure`, :mod:`~flexsim._kernels.strips`, :mod:`~flexsim._kernels.drag`,
:mod:`~flexsim._kernels.wind` and :mod:`~flexsim._kernels.solve`. Body axes xyz (x forward, y right, z down),
inertial NED; SI units, radians.
"""

from __future__ import annotations

import math

import numpy as np

from flexsim._kernels.drag import body_force, parasite_drag
from flexsim._kernels.isa import _geopotential, _sound_speed, dcm_321, isa_scalar
from flexsim._kernels.layout import (ACTIVE, ALL_ACTIVE, C_EL, EULER_FIXED, FLOATS, HAS_AERO, HAS_BODIES, HAS_DAMPING,
                                     HAS_INERTIA_OFFSET, INERTIA_DQ,
                                     HAS_DRAG, INFLOW_START, K_BENDING, K_TORSION, M0, M2, H, N_INFLOW, N_V, NQ, NXI,
                                     Q_FROZEN, Q_START, RIGID, SEMICHORD, SOLVE_PERM, SOLVE_PTR, THRUST_T0, THRUST_T1,
                                     USE_FROZEN, V_FIXED, VEL_START, XI_FROZEN, XI_START, _f1, _f2, _f3, _f4, _flag,
                                     _i1, kernel)
from flexsim._kernels.solve import block_solve
from flexsim._kernels.strips import aero_evaluate, inflow_rate
from flexsim._kernels.structure import inertia
from flexsim._kernels.wind import strip_positions, strip_wind, wind_ned


@kernel
def unpack(F, I, x):
    """Full-size (R, Theta, q, xi, V) from x, filling fixed or frozen blocks (AircraftModel.unpack)."""
    n_v, nq, nxi = _flag(I, N_V), _flag(I, NQ), _flag(I, NXI)
    vs = _flag(I, VEL_START)
    rigid = _flag(I, RIGID)
    if rigid:
        pos = x[0:3].copy()
        eul = x[3:6].copy()
    else:
        pos = np.zeros(3)
        eul = _f1(F, I, EULER_FIXED).copy()
    if _flag(I, USE_FROZEN):
        q = _f1(F, I, Q_FROZEN).copy()
        xi = _f1(F, I, XI_FROZEN).copy()
    else:
        q = x[_flag(I, Q_START):_flag(I, Q_START) + nq].copy()
        xi = x[_flag(I, XI_START):_flag(I, XI_START) + nxi].copy()
    if _flag(I, ALL_ACTIVE):
        vel = x[vs:vs + n_v].copy()
    else:
        vel = np.zeros(n_v)
        active = _i1(I, ACTIVE)
        for i in range(active.shape[0]):
            vel[active[i]] = x[vs + i]
        if not rigid:
            vel[0:3] = _f1(F, I, V_FIXED)
    return pos, eul, q, xi, vel


@kernel
def air(F, I, x):
    """(altitude [m] geometric, density of the aerodynamics [kg/m^3], speed of sound [m/s]) at state x:
    the tunnel density, else the fixed aerodynamic density, else ISA at -Z (restrained: altitude_m)."""
    fl = _f1(F, I, FLOATS)
    altitude = -x[2] if _flag(I, RIGID) else fl[1]
    hgp = _geopotential(altitude)
    if not math.isnan(fl[2]):
        rho = fl[2]
    elif not math.isnan(fl[3]):
        rho = fl[3]
    else:
        rho = isa_scalar(hgp)[0]
    return altitude, rho, _sound_speed(hgp)


@kernel
def assemble(F, I, x, u, wind_c, has_wind):
    """E = M(q) + M_a and f of E V_dot = f (full size, paper eq. 33 in velocity form, docs/design.md):

    f = -M_dot V + g(V, p) + [0, 0, dT/dq, 0] - K [0, 0, q, xi] - C_el V_el + M(q)[g_b; 0] + Q_T + Q_a + Q_D
    with p = M V, g_v = -omega x p_v, g_omega = -v x p_v - omega x p_omega (quasi-coordinates, eq. 33),
    g_b = C [0, 0, g] (eq. 32: Q_g = M(q) [g_b; 0] exactly, :mod:`flexsim.structure.loads`),
    Q_T = T_e (t0 + t1 q) (eqs. 17-24), Q_a and M_a from :func:`aero_evaluate`, Q_D from :func:`parasite_drag`,
    the slender bodies' Munk moments from :func:`body_force`.

    Returns m (n_v, n_v), f (n_v,), row0 (n_s, n_v), w_ea_x (n_s,), u0 (n_s,).
    """
    nq = _flag(I, NQ)
    pos, eul, q, xi, vel = unpack(F, I, x)
    q_inertia = q
    if _flag(I, HAS_INERTIA_OFFSET):  # M(q), dT/dq, M_dot at q + dq (flexsim.model.terms.Terms.inertia_q_offset_m)
        q_inertia = q + _f1(F, I, INERTIA_DQ)
    m, dtdq, mdot_v = inertia(_f2(F, I, M0), _f3(F, I, H), _f4(F, I, M2), vel, q_inertia, vel[6:6 + nq])
    n_v = vel.shape[0]
    nxi = xi.shape[0]
    p = np.empty(n_v)  # M V
    f = np.empty(n_v)
    for i in range(n_v):
        acc = 0.0
        for k in range(n_v):
            acc += m[i, k] * vel[k]
        p[i] = acc
        f[i] = -mdot_v[i]
    v = vel[0:3]
    w = vel[3:6]
    # quasi-coordinate terms (eq. 33): -omega x p_v and -v x p_v - omega x p_omega
    f[0] -= w[1] * p[2] - w[2] * p[1]
    f[1] -= w[2] * p[0] - w[0] * p[2]
    f[2] -= w[0] * p[1] - w[1] * p[0]
    f[3] -= v[1] * p[2] - v[2] * p[1] + w[1] * p[5] - w[2] * p[4]
    f[4] -= v[2] * p[0] - v[0] * p[2] + w[2] * p[3] - w[0] * p[5]
    f[5] -= v[0] * p[1] - v[1] * p[0] + w[0] * p[4] - w[1] * p[3]
    # [0, 0, dT/dq, 0] - K [0, 0, q, xi] (eqs. 15, 33)
    k_b = _f2(F, I, K_BENDING)
    k_t = _f2(F, I, K_TORSION)
    for i in range(nq):
        acc = dtdq[i]
        for k in range(nq):
            acc -= k_b[i, k] * q[k]
        f[6 + i] += acc
    for i in range(nxi):
        acc = 0.0
        for k in range(nxi):
            acc += k_t[i, k] * xi[k]
        f[6 + nq + i] -= acc
    if _flag(I, HAS_DAMPING):
        c_el = _f2(F, I, C_EL)
        n_el = n_v - 6
        for i in range(n_el):
            acc = 0.0
            for k in range(n_el):
                acc += c_el[i, k] * vel[6 + k]
            f[6 + i] -= acc
    g = _f1(F, I, FLOATS)[0]
    if g != 0.0:
        # Q_g = M(q) [g_b; 0], g_b = C [0, 0, g] (eq. 32)
        sf, cf = math.sin(eul[0]), math.cos(eul[0])
        st, ct = math.sin(eul[1]), math.cos(eul[1])
        g0, g1, g2 = -st * g, sf * ct * g, cf * ct * g
        for i in range(n_v):
            f[i] += m[i, 0] * g0 + m[i, 1] * g1 + m[i, 2] * g2
    if u[0] != 0.0:
        # Q_T = T_e (t0 + t1 q) (eqs. 17-24)
        t0 = _f1(F, I, THRUST_T0)
        t1 = _f2(F, I, THRUST_T1)
        for i in range(n_v):
            acc = t0[i]
            for k in range(nq):
                acc += t1[i, k] * q[k]
            f[i] += u[0] * acc
    if not _flag(I, HAS_AERO):
        n_s = _f1(F, I, SEMICHORD).shape[0]
        return m, f, np.zeros((n_s, n_v)), np.zeros(n_s), np.zeros(n_s)
    _, rho, a_sound = air(F, I, x)
    mach = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) / a_sound
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
    return m, f, row0, w_ea_x, u0


@kernel
def aerodynamic_force(F, I, x, u, wind_c, has_wind):
    """Generalized aerodynamic force without the apparent-mass terms (n_v,): strip airloads (explicit part of
    :func:`aero_evaluate`) plus parasite drag and body moments; rows 0-2 force [N] (body), 3-5 moment about o [N m]."""
    pos, eul, q, xi, vel = unpack(F, I, x)
    out = np.zeros(vel.shape[0])
    if not _flag(I, HAS_AERO):
        return out
    _, rho, a_sound = air(F, I, x)
    mach = math.sqrt(vel[0:3] @ vel[0:3]) / a_sound
    lam = x[_flag(I, INFLOW_START):_flag(I, INFLOW_START) + _flag(I, N_INFLOW)]
    _, q_a, _, _, _ = aero_evaluate(F, I, q, xi, vel, lam, u, rho, mach, wind_c, has_wind)
    if _flag(I, HAS_DRAG):
        q_a = q_a + parasite_drag(F, I, q, vel, rho)
    if _flag(I, HAS_BODIES):
        q_a = q_a + body_force(F, I, q, vel, rho)
    return q_a


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


@kernel
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


@kernel
def _rhs_wind(F, I, gusts, turb, turb_grid, x, u):
    wind_c, has_wind = strip_wind_at(F, I, gusts, turb, turb_grid, x)
    return _rhs(F, I, x, u, wind_c, has_wind)


@kernel
def rhs_strip_wind(F, I, x, u, wind_c):
    """:func:`rhs` with the strip air velocity (n_s, 3), component axes [m/s], given (any wind callable)."""
    return _rhs(F, I, x, u, wind_c, True)


@kernel
def rhs_batch(F, I, rows, gusts, turb, turb_grid, xs, us):
    """x_dot of N aircraft of one model in one call: xs (N, n_states), us (N, 4) -> (N, n_states); aircraft i
    sees the gusts rows[i, 0]:rows[i, 1] and Dryden fields rows[i, 2]:rows[i, 3] (:class:`BatchWind`)."""
    out = np.empty_like(xs)
    for i in range(xs.shape[0]):
        out[i] = _rhs_wind(F, I, gusts[rows[i, 0]:rows[i, 1]], turb[rows[i, 2]:rows[i, 3]], turb_grid, xs[i], us[i])
    return out

