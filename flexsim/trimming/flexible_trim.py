"""Trim of the geometrically nonlinear aircraft in steady flight (level, climb, descent, glide, pull-up, turn).

The flexible aircraft (:mod:`flexsim.model.flexible_aircraft`: rigid body + strain-based beams, strip airloads on the
deformed strips) is in a steady state when its generalized accelerations and strain rates vanish: with
``ε̇ = 0`` the equations of motion (:func:`flexsim.structure.free_flexible.steady_generalized_force`, the paper's
eq. 2 in Kane's form, plus the airloads) reduce to ``Q_total(ε, v, ω, attitude, u) = 0`` (6 + n equations).

Symmetric flight (Tuzcu & Nguyen 2014 eqs. 34-35 for level flight, 38-39 climb; the pull-up of
:meth:`flexsim.trimming.manoeuvre.SteadyManoeuvre.pull_up`, ``q = (n − 1) g / V`` at the bottom of the loop):
the speed ``V`` of the undeformed aircraft's centre of gravity makes the angle of attack ``α`` with body x,
``θ = α + γ``, ``ω = (0, q, 0)``, no sideslip. Unknowns: ``α``, the elevator ``δe``, the thrust ``T`` (or, in a
glide, ``T = 0`` and ``γ``) and all strains ``ε``; equations: the force rows x and z, the pitching moment and the
strain rows. The lateral rows vanish by the aircraft's symmetry (checked: their residual is reported). Solved by
MINPACK's ``hybrj`` (Powell's hybrid method; one forward-difference Jacobian, then Broyden's updates, carried across
the continuation and from a ``guess``) from the rigid trim's attitude with the strains continued in load
(the gravity and load factor scaled 1/4, 1/2, 3/4, 1) so that a wing bending to half its span is reached on a path
of equilibria. A steady turn (level or climbing; the paper's eqs. 36-37 or coordinated) is solved by
:mod:`flexsim.trimming.flexible_turn` for the bank, pitch, thrust, all three controls and the strains. Units SI,
radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import root

from flexsim.atmosphere import isa, isa_density
from flexsim.errors import FlexsimError
from flexsim.model.flexible_aircraft import FlexibleAircraft, flexible_aircraft
from flexsim.trimming.flexible_turn import euler_quaternion, trim_turn
from flexsim.trimming.manoeuvre import SteadyManoeuvre

__all__ = ["FlexibleTrimPoint", "FlexibleTrimError", "trim_flexible"]

_RIGID_ROWS = np.array([0, 2, 4])


class FlexibleTrimError(FlexsimError, RuntimeError):
    """The nonlinear trim did not converge (the message names the manoeuvre and the residual)."""


@dataclass(frozen=True, eq=False)
class FlexibleTrimPoint:
    """A steady symmetric state of the flexible aircraft (body axes, SI).

    Attributes
    ----------
    manoeuvre : SteadyManoeuvre
    aircraft : FlexibleAircraft
    alpha_rad, theta_rad, climb_angle_rad : float
        Angle of attack of the CG's velocity, pitch attitude and flight-path angle [rad].
    controls : ndarray, shape (4,)
        ``[T [N], δa, δe, δr [rad]]``.
    strains : ndarray, shape (n,)
    velocity_m_s, rate_rad_s : ndarray, shape (3,)
        ``v`` of o and ``ω``, body axes.
    density_kg_m3 : float
    residual : float
        Largest scaled residual of all 6 + n equations (lateral rows included) [-].
    phi_rad : float
        Bank angle [rad]; 0 in symmetric flight (a turn: :mod:`flexsim.trimming.flexible_turn`).
    heading_offset_rad : float
        Heading minus track [rad]; 0 except in a coordinated turn.
    solver_jacobian : (bool, ndarray) or None
        The solver's final Jacobian of the scaled residuals with respect to the unknowns, tagged with whether the
        unknowns were a glide's (which changes them): the first Jacobian of a trim started from this point
        (``guess``), so that a neighbouring speed of a scan costs a few residuals instead of a finite-difference
        Jacobian (one residual per unknown).
    """

    manoeuvre: SteadyManoeuvre
    aircraft: FlexibleAircraft
    alpha_rad: float
    theta_rad: float
    climb_angle_rad: float
    controls: NDArray
    strains: NDArray
    velocity_m_s: NDArray
    rate_rad_s: NDArray
    density_kg_m3: float
    residual: float
    solver_jacobian: tuple | None = field(default=None, repr=False)
    phi_rad: float = 0.0
    heading_offset_rad: float = 0.0

    def state(self) -> NDArray:
        """The free-flight state at this trim, ``[X (3), quaternion (4), ε (n), v (3), ω (3), ε̇ (n)]``
        (:func:`flexsim.structure.free_flexible.free_flight_rhs`): the body origin at the manoeuvre's altitude
        (``X = (0, 0, −h)``, NED), attitude from the 3-2-1 angles (bank φ, pitch θ, heading = the heading offset, the
        track due north), the trim's strains, velocities and rates, ``ε̇ = 0``."""
        n = self.strains.size
        return np.concatenate([[0.0, 0.0, -self.manoeuvre.altitude_m],
                               euler_quaternion(self.phi_rad, self.theta_rad, self.heading_offset_rad), self.strains,
                               self.velocity_m_s, self.rate_rad_s, np.zeros(n)])

    @property
    def sideslip_rad(self) -> float:
        """Sideslip of the body origin's velocity, ``asin(v_y / |v|)`` [rad] (the paper's turn: ``asin(sin φ sin θ)``)."""
        return float(math.asin(self.velocity_m_s[1] / np.linalg.norm(self.velocity_m_s)))

    @property
    def terms(self) -> dict:
        """The terms of the model trimmed, with the nonlinear beams used (:attr:`FlexibleAircraft.terms`)."""
        return self.aircraft.terms

    @property
    def tip_displacement_m(self) -> NDArray:
        """Tip displacement of each beam from its undeformed position [m], body axes, shape (B, 3)."""
        return self.aircraft.tip_positions(self.strains) - self.aircraft.undeformed_tips

    @property
    def max_strip_alpha_deg(self) -> float:
        """Largest local angle of attack of the strips, incidences and flaps included [deg]."""
        return self.aircraft.max_strip_alpha_deg(self.strains, self.velocity_m_s, self.rate_rad_s, self.controls)

    @property
    def tip_deflection_fraction(self) -> NDArray:
        """Vertical tip displacement (up positive) over the beam's length [-], shape (B,)."""
        return self.aircraft.tip_heights_m(self.strains) / self.aircraft.beam_lengths_m


def _state(z: NDArray, man: SteadyManoeuvre, cg: NDArray, g: float, glide: bool):
    alpha, de = z[0], z[1]
    thrust, gamma = (0.0, z[2]) if glide else (z[2], man.climb_angle_rad)
    speed = man.speed_m_s
    q = (man.load_factor - 1.0) * g / speed
    omega = np.array([0.0, q, 0.0])
    v = speed * np.array([math.cos(alpha), 0.0, math.sin(alpha)]) - np.cross(omega, cg)
    theta = alpha + gamma
    quat = np.array([math.cos(theta / 2), 0.0, math.sin(theta / 2), 0.0])
    return v, omega, quat, np.array([thrust, 0.0, de, 0.0]), theta, gamma


def _forward_jacobian(fun, x: NDArray, *args) -> NDArray:
    """Forward-difference Jacobian of ``fun(x, *args)`` with MINPACK's steps ``√ε |x_j|`` (``√ε`` at 0)."""
    f0 = fun(x, *args)
    out = np.empty((f0.size, x.size))
    h0 = math.sqrt(np.finfo(float).eps)
    for j in range(x.size):
        h = h0 * abs(x[j]) or h0
        xp = x.copy()
        xp[j] += h
        out[:, j] = (fun(xp, *args) - f0) / h
    return out


def _solve(residual, z0: NDArray, loads: list, jacobian: NDArray | None, maxfev: int) -> tuple[NDArray, NDArray]:
    """Solve ``residual(z, g) = 0`` for each gravity ``g`` of the continuation in turn by MINPACK's ``hybrj``
    (Powell's hybrid method with Broyden updates of the Jacobian). The first Jacobian of each solve is the last
    one of the previous solve (or ``jacobian``; else forward differences); ``hybrj`` asks for a fresh
    finite-difference one when its steps stop making progress. Returns the solution and its final Jacobian."""
    z = z0
    for g_now in loads:
        start = jacobian if jacobian is not None and jacobian.shape == (z.size, z.size) else None

        known = [(z.copy(), start)]  # (x, Jacobian at x): scipy calls jac once more at the start to check its shape

        def jac(x, g_arg, known=known):
            if known[0][1] is None or not np.array_equal(x, known[0][0]):
                known[0] = (x.copy(), _forward_jacobian(residual, x, g_arg))
            return known[0][1]

        sol = root(residual, z, args=(g_now,), method="hybr", jac=jac, options={"xtol": 1e-10, "maxfev": maxfev})
        z = sol.x
        r = np.zeros((z.size, z.size))
        r[np.triu_indices(z.size)] = sol.r
        jacobian = sol.fjac.T @ r
    return z, jacobian


def trim_flexible(model, manoeuvre: SteadyManoeuvre, *, elements_per_beam: int | None = None,
                  guess: FlexibleTrimPoint | None = None, check_limits: bool = True) -> FlexibleTrimPoint:
    """Trim the geometrically nonlinear aircraft of ``model`` in a steady symmetric manoeuvre (module docstring).

    Parameters
    ----------
    model : AircraftModel
        Its aircraft, strips, gravity (``terms.gravity_m_s2``) and air density (ISA at the manoeuvre's altitude, or
        the variant's ``air_density_kg_m3``).
    manoeuvre : SteadyManoeuvre
        Level, climb/descent, glide or pull-up; or a turn (level or climbing, the paper's eqs. 36-37 or coordinated:
        :mod:`flexsim.trimming.flexible_turn`); a gliding turn is refused.
    elements_per_beam : int, optional
        Elements of each flexible component's beam (:func:`flexible_aircraft`), 1-64; default the model's
        ``terms.nonlinear_beams`` (8 for a model of the linear structure).
    guess : FlexibleTrimPoint, optional
        A nearby trim to start from (e.g. the previous speed of a scan); else the load is continued from 1/4.
    check_limits : bool
        Refuse a trim whose strips' angle of attack exceeds the aircraft's linear-lift range
        (``[aero] max_alpha_deg``; the strips have no stall), as the linear trim does.

    Returns
    -------
    FlexibleTrimPoint

    Raises
    ------
    ValueError
        A gliding turn, or a model without aerodynamics.
    FlexibleTrimError
        No convergence, or (``check_limits``) strips beyond the linear-lift range.
    """
    if not isinstance(manoeuvre, SteadyManoeuvre):
        raise ValueError(f"manoeuvre = {manoeuvre!r}: must be a SteadyManoeuvre")
    if manoeuvre.turn_radius_m != math.inf and manoeuvre.climb_angle_rad is None:
        raise ValueError(f"manoeuvre.turn_radius_m = {manoeuvre.turn_radius_m!r} with climb_angle_rad = None: a "
                         "gliding turn is not available with the nonlinear structure (give the flight-path angle)")
    flex = guess.aircraft if guess is not None else flexible_aircraft(model, elements_per_beam)
    # the strips' compressibility factor held at this trim's Mach number, as the density at its altitude
    flex = flex.held_at_mach(manoeuvre.speed_m_s / float(isa(manoeuvre.altitude_m).speed_of_sound))
    variant_rho = model.variant.air_density_kg_m3
    rho = float(variant_rho) if variant_rho is not None else float(isa_density(manoeuvre.altitude_m))
    g = float(model.terms.gravity_m_s2)
    glide = manoeuvre.climb_angle_rad is None
    struct = flex.structure
    mp = model.structure.mass_properties
    cg, weight = np.asarray(mp.cg_m), mp.mass_kg * max(g, 1e-3)
    span = max(max(b.length_m for b in struct.beams) if struct.beams else 1.0, 1.0)
    k_diag = np.sqrt(np.clip(np.diag(struct.stiffness()), 1e-12, None))
    n = struct.n_strains

    def residual(z: NDArray, g_now: float) -> NDArray:
        v, omega, quat, u, _, _ = _state(z, manoeuvre, cg, g, glide)
        eps = z[3:]
        # a step of the load continuation scales gravity and the pull-up's rate together
        full = flex.steady_residual(eps, quat, v, omega * (g_now / g if g > 0 else 1.0), u, rho, g_now)
        return np.concatenate([full[_RIGID_ROWS] / np.array([weight, weight, weight * span]), full[6:] / k_diag])

    if manoeuvre.turn_radius_m != math.inf:
        return _turn_point(model, manoeuvre, flex, cg, weight, span, k_diag, rho, g, guess, check_limits)
    if guess is not None:
        z0 = np.concatenate([[guess.alpha_rad, guess.controls[2],
                              guess.climb_angle_rad if glide else guess.controls[0]], guess.strains])
        steps = (1.0,)
    else:
        z0 = np.concatenate([[math.radians(2.0), 0.0, -0.05 if glide else 0.1 * weight], np.zeros(n)])
        steps = (0.25, 0.5, 0.75, 1.0)
    known = guess.solver_jacobian if guess is not None else None
    start = known[1] if known is not None and known[0] == glide else None  # the same unknowns
    z, jacobian = _solve(residual, z0, [g * frac for frac in steps], start, 200 * (n + 4))
    final = residual(z, g)
    v, omega, quat, u, theta, gamma = _state(z, manoeuvre, cg, g, glide)
    full = flex.steady_residual(z[3:], quat, v, omega, u, rho, g)
    lateral = np.abs(full[[1, 3, 5]]).max() / weight
    worst = float(max(np.abs(final).max(), lateral))
    if not np.isfinite(worst) or worst > 1e-8:
        raise FlexibleTrimError(f"the nonlinear trim of {flex.name!r} at {manoeuvre.speed_m_s:g} m/s, "
                                f"{manoeuvre.altitude_m:g} m, load factor {manoeuvre.load_factor:g} did not converge "
                                f"(largest scaled residual {worst:.2e}; allowed 1e-8)")
    point = FlexibleTrimPoint(manoeuvre=manoeuvre, aircraft=flex, alpha_rad=float(z[0]), theta_rad=float(theta),
                              climb_angle_rad=float(gamma), controls=u, strains=z[3:].copy(), velocity_m_s=v,
                              rate_rad_s=omega, density_kg_m3=rho, residual=worst,
                              solver_jacobian=(glide, jacobian))
    return _checked(model, point, check_limits)


def _turn_point(model, manoeuvre, flex, cg, weight, span, k_diag, rho, g, guess, check_limits):
    """The turn of :mod:`flexsim.trimming.flexible_turn` as a checked :class:`FlexibleTrimPoint`."""
    sol = trim_turn(flex, manoeuvre, cg=cg, weight=weight, span=span, k_diag=k_diag, rho=rho, g=g, guess=guess,
                    solve=_solve)
    worst = sol["residual"]
    if not np.isfinite(worst) or worst > 1e-8:
        raise FlexibleTrimError(f"the nonlinear trim of {flex.name!r} in the {manoeuvre.describe()} did not converge "
                                f"(largest scaled residual {worst:.2e}; allowed 1e-8)")
    v_cg = sol["v"] + np.cross(sol["omega"], cg)
    point = FlexibleTrimPoint(manoeuvre=manoeuvre, aircraft=flex, alpha_rad=float(math.atan2(v_cg[2], v_cg[0])),
                              theta_rad=sol["theta"], climb_angle_rad=sol["gamma"], controls=sol["u"],
                              strains=sol["strains"], velocity_m_s=sol["v"], rate_rad_s=sol["omega"],
                              density_kg_m3=rho, residual=float(worst), solver_jacobian=sol["jacobian"],
                              phi_rad=sol["phi"], heading_offset_rad=sol["heading_offset"])
    return _checked(model, point, check_limits)


def _checked(model, point: FlexibleTrimPoint, check_limits: bool) -> FlexibleTrimPoint:
    """Refuse (``check_limits``) a trim whose strips exceed the aircraft's linear-lift range."""
    flex, manoeuvre = point.aircraft, point.manoeuvre
    limit = math.degrees(model.aircraft.aero_settings.max_alpha_rad)
    if check_limits and point.max_strip_alpha_deg > limit:
        raise FlexibleTrimError(f"the nonlinear trim of {flex.name!r} at {manoeuvre.speed_m_s:g} m/s, "
                                f"{manoeuvre.altitude_m:g} m, load factor {manoeuvre.load_factor:g} has strips at "
                                f"{point.max_strip_alpha_deg:.1f} deg angle of attack, beyond the linear (no-stall) "
                                f"lift range +-{limit:g} deg ([aero] max_alpha_deg)")
    return point
