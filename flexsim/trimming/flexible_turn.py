"""Trim of the geometrically nonlinear aircraft in a steady turn (level or climbing; the paper's or coordinated).

The turn of Tuzcu & Nguyen 2014, eqs. (36)-(37): the track turns at ``Ω = V cos γ / R`` about the vertical
(``R < 0`` turns left), the heading stays on the track (``ψ = Ω t``), the velocity of the body origin o is
constant in body axes, ``v = C(φ, θ, Δψ) V (cos γ, 0, −sin γ)`` and ``ω = Ω (−sin θ, sin φ cos θ, cos φ cos θ)``
(:meth:`flexsim.trimming.manoeuvre.SteadyManoeuvre.body_rates`, the linear trim's kinematics). The steady
equations of the flexible aircraft (:meth:`flexsim.model.flexible_aircraft.FlexibleAircraft.steady_residual`,
6 + n rows: rigid-body forces and moments, strain rows) are solved for the pitch ``θ``, bank ``φ``, thrust ``T``,
aileron, elevator and rudder and all strains ``ε``; the sideslip follows from the kinematics (the paper's turn is
a slipping turn, ``β = asin(sin φ sin θ)`` at o). A coordinated turn (``manoeuvre.coordinated``, as the linear
trim defines it: Stevens & Lewis 2003 sec. 3.6) frees the heading offset ``Δψ = ψ − χ`` and adds the row
``v_CG,y = 0`` (zero sideslip at the centre of gravity). A climbing turn keeps ``γ`` given; a gliding turn is
refused. Solved by the symmetric trim's ``hybrj`` with the load continued (gravity and turn rate scaled together,
so the bank of a point mass ``tan φ = V Ω / g`` stays that of the full turn). Units SI, radians.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = ["euler_quaternion", "trim_turn"]


def euler_quaternion(phi: float, theta: float, psi: float) -> NDArray:
    """Body→inertial quaternion ``[q0, q1, q2, q3]`` (scalar first) of the 3-2-1 Euler angles [rad]
    (Stevens & Lewis 2003 eq. 1.8-17); its matrix is the transpose of :func:`flexsim.kinematics.dcm_321`."""
    cf, sf = math.cos(phi / 2), math.sin(phi / 2)
    ct, st = math.cos(theta / 2), math.sin(theta / 2)
    cp, sp = math.cos(psi / 2), math.sin(psi / 2)
    return np.array([cf * ct * cp + sf * st * sp, sf * ct * cp - cf * st * sp,
                     cf * st * cp + sf * ct * sp, cf * ct * sp - sf * st * cp])


def _state(z: NDArray, man, weight: float, n: int, scale: float):
    """Velocity of o, rates, attitude quaternion and controls of the unknowns ``z`` (turn rate scaled by ``scale``)."""
    theta, phi = z[0], z[1]
    gamma = man.climb_angle_rad
    dpsi = z[6 + n] if man.coordinated else 0.0
    v, omega = man.body_rates(phi, theta, gamma, dpsi)  # a turn has no pull-up rate (load factor 1)
    omega = omega * scale
    u = np.array([z[2] * weight, z[3], z[4], z[5]])
    return v, omega, euler_quaternion(phi, theta, dpsi), u, theta, phi, gamma


def trim_turn(flex, manoeuvre, *, cg: NDArray, weight: float, span: float, k_diag: NDArray, rho: float, g: float,
              guess=None, solve=None):
    """Solve the steady turn (module docstring) of the flexible aircraft ``flex``.

    Parameters
    ----------
    flex : FlexibleAircraft
    manoeuvre : SteadyManoeuvre
        A turn (finite ``turn_radius_m``) with a given flight-path angle.
    cg : ndarray, shape (3,)
        Centre of gravity of the undeformed aircraft [m], body axes.
    weight, span : float
        Residual scales [N], [m]; ``k_diag``: the strain rows' scales (√ of the stiffness diagonal), shape (n,).
    rho, g : float
        Air density [kg/m^3] and gravity [m/s^2].
    guess : FlexibleTrimPoint, optional
        A nearby turn (or straight trim) to start from; else the load is continued from 1/4.
    solve : callable
        The symmetric trim's solver ``_solve(residual, z0, loads, jacobian, maxfev)``.

    Returns
    -------
    dict
        ``z`` (unknowns: θ, φ, T/W, δa, δe, δr, ε[, Δψ]), the state (v, ω, quaternion, u, θ, φ, γ), the largest
        scaled residual of every row and the solver's last Jacobian.
    """
    n = flex.structure.n_strains
    coordinated = manoeuvre.coordinated

    def residual(z: NDArray, g_now: float) -> NDArray:
        scale = g_now / g if g > 0 else 1.0
        v, omega, quat, u, *_ = _state(z, manoeuvre, weight, n, scale)
        full = flex.steady_residual(z[6:6 + n], quat, v, omega, u, rho, g_now)
        r = np.concatenate([full[:3] / weight, full[3:6] / (weight * span), full[6:] / k_diag])
        if not coordinated:
            return r
        v_cg = v + np.cross(omega, cg)
        return np.append(r, v_cg[1] / manoeuvre.speed_m_s)

    tag = ("turn", coordinated)
    if guess is not None:
        u0 = guess.controls
        z0 = np.concatenate([[guess.theta_rad, guess.phi_rad, u0[0] / weight, u0[1], u0[2], u0[3]], guess.strains,
                             [guess.heading_offset_rad] if coordinated else []])
        steps = (1.0,)
        known = guess.solver_jacobian
        start = known[1] if known is not None and known[0] == tag else None
    else:
        phi0 = math.atan(manoeuvre.speed_m_s * manoeuvre.turn_rate(manoeuvre.climb_angle_rad) / max(g, 1e-3))
        z0 = np.concatenate([[math.radians(2.0) + manoeuvre.climb_angle_rad, phi0, 0.1, 0.0, 0.0, 0.0], np.zeros(n),
                             [0.0] if coordinated else []])
        steps = (0.25, 0.5, 0.75, 1.0)
        start = None
    z, jacobian = solve(residual, z0, [g * f for f in steps], start, 200 * (n + 8))
    final = residual(z, g)
    v, omega, quat, u, theta, phi, gamma = _state(z, manoeuvre, weight, n, 1.0)
    return dict(z=z, strains=z[6:6 + n].copy(), v=v, omega=omega, u=u, theta=float(theta), phi=float(phi),
                gamma=float(gamma), residual=float(np.abs(final).max()), jacobian=(tag, jacobian),
                heading_offset=float(z[6 + n]) if coordinated else 0.0)
