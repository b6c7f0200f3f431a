"""Trim of the full nonlinear model in a steady manoeuvre (Tuzcu & Nguyen 2014, eqs. 33-39).

Unknowns: pitch theta, bank phi, controls [T_e, delta_a, delta_e, delta_r] (the flight-path angle gamma
replaces T_e in a glide, where T_e = 0) and the static elastic coordinates q, xi. The manoeuvre fixes the
velocities v, omega (:meth:`SteadyManoeuvre.body_rates`); the elastic rates and the inflow states are zero.
Equations: the model's own right-hand side, V_dot = 0 (6 rigid-body + all elastic equations) — a square
system solved by scipy's MINPACK hybrid method. A coordinated turn adds the heading offset psi - chi as an
unknown and zero sideslip at the centre of gravity as an equation. The residual reported is the norm of V_dot scaled by g
(translations, elastic coordinates) and g / 5 m (rotations); trim converges to ~1e-12. Every trim records its
largest local angle of attack (:class:`StripAngle`) and classifies its equilibrium from the roots of its own
linearisation (:mod:`flexsim.trimming.equilibrium`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.linalg import LinAlgWarning, lu_factor, lu_solve
from scipy.optimize import root

from flexsim._arrays import readonly
from flexsim._threads import single_blas_thread
from flexsim.atmosphere import speed_of_sound
from flexsim.errors import FlexsimError
from flexsim.model.aircraft_model import AircraftModel, Variant, check_model
from flexsim.kinematics import dcm_321
from flexsim.model.linear_range import linear_range_note
from flexsim.model.sensors import structural_sensors
from flexsim.structure.mirror import TIE_RTOL
from flexsim.trimming.equilibrium import EquilibriumStability, equilibrium_stability
from flexsim.trimming.manoeuvre import SteadyManoeuvre

__all__ = ["TrimPoint", "TrimError", "StripAngle", "trim"]

_ROT_LENGTH = 5.0  # [m] scale converting angular accelerations to g units in the residual
_TOLERANCE = 1e-8
#: A start from ``guess`` is accepted when Newton's method alone brings the scaled residual below this; otherwise
#: hybr runs from the guess as without one. From a trim at a neighbouring speed hybr's forward differences, with steps
#: relative to the tiny elastic coordinates, stall (status 5). A Newton start that converges ends at the round-off
#: floor (below); one that does not stays far above it. The threshold lies 100 times above the floor, so that where
#: the polish ends by chance just above it (1.006e-12 at M 0.65 of the GTM's level flutter scan with single-threaded
#: BLAS) the trim is not solved a second time from cold, and 100 times below the acceptance of any trim (``_TOLERANCE``).
_WARM_TOLERANCE = 1e-10
#: Round-off floor of the scaled residual of the GTM's trim (measured 3e-14 to 1.006e-12).
_ROUND_OFF = 1e-12


class TrimError(FlexsimError, RuntimeError):
    """Trim failed or is infeasible; the message names the manoeuvre, residuals and limiting quantity."""


@dataclass(frozen=True)
class StripAngle:
    """The local angle of attack of one aerodynamic strip at a trim.

    alpha = atan(w_EA / u0) of the strip's elastic-axis point: the normal velocity relative to the air (the tail
    strips in the wing's downwash) over the chordwise speed, w_EA = n^T A(q) V + u0 (alpha_el + alpha_r), which
    holds the elastic twist alpha_el and the rigging incidence alpha_r (:mod:`flexsim.model.coupling`); the
    control-surface camber is not in it.

    Attributes
    ----------
    alpha_rad : float
        [rad], positive nose up against the wind.
    strip : int
        Index of the strip among all strips of the model.
    component : str
        The component the strip belongs to.
    number : int
        The strip's number on its component, 1 at the root.
    station_m : float
        Elastic-axis station of the strip midpoint from the component root [m].
    """

    alpha_rad: float
    strip: int
    component: str
    number: int
    station_m: float

    def describe(self) -> str:
        """E.g. "-17.09 deg at right_wing strip 10 (station 17.3 m from its root)"."""
        return (f"{math.degrees(self.alpha_rad):.4g} deg at {self.component} strip {self.number} (station "
                f"{self.station_m:.3g} m from its root)")

    def as_dict(self) -> dict:
        """Plain dict for JSON (the angle in degrees)."""
        return {"alpha_deg": math.degrees(self.alpha_rad), "strip": self.strip, "component": self.component,
                "number": self.number, "station_m": self.station_m}


@dataclass(frozen=True, eq=False)
class TrimPoint:
    """A trimmed steady manoeuvre (all quantities SI, radians).

    Attributes
    ----------
    manoeuvre : SteadyManoeuvre
    x : ndarray, shape (n_states,)
        Trim state of the model (position [0, 0, -H], psi = 0, inflow zero).
    u : ndarray, shape (4,)
        Controls [T_e (N), delta_a, delta_e, delta_r (rad)].
    theta, phi, gamma : float
        Pitch, bank and flight-path angles [rad].
    alpha, beta : float
        Angle of attack atan(W/U) and sideslip asin(V/|v|) of the body axes at the body origin o [rad].
    load_factor : float
        Aerodynamic + thrust force along -z_body over the weight [-] (normal load factor n_z).
    heading_offset : float
        Heading minus track psi - chi [rad] (0 except in a coordinated turn).
    sideslip_cg : float
        Sideslip of the centre of gravity's velocity v + omega x r_cg, asin(v_cg,y / |v_cg|) [rad] (undeformed
        CG); zero in a coordinated turn. At o (``beta``) it differs in a turn by the yaw rate times the arm.
    load_factor_total : float
        |aerodynamic + thrust force| / weight [-]: in a steady level turn sqrt(1 + (V^2/gR)^2) = 1/cos(mu).
    bank_wind : float
        Bank angle mu of the wind axes (velocity of the CG, zero-sideslip lateral axis), 3-2-1 Euler roll of
        the wind frame [rad] (Stevens & Lewis sec. 2.4); in a coordinated level turn tan(mu) = V^2/(gR).
    lift_n, drag_n : float
        Aerodynamic force (strips and parasite drag, no thrust) resolved in the wind axes of the CG: lift
        along -z_w and drag along -x_w [N]. In a glide gamma = -atan(D/L).
    tip_deflection_m, tip_twist_rad : float
        Right-wing tip bending w_w(L_w) (positive down, paper's sign) [m] and torsion psi_w(L_w) (positive
        nose up) [rad], as in the paper's Tables 2-3.
    residual : float
        Scaled norm of the right-hand side at the trim state.
    max_local_alpha : StripAngle or None
        The strip with the largest local angle of attack |alpha| (None without aerodynamic strips).
    stability : EquilibriumStability or None
        The classification of the equilibrium from the roots of its linearisation
        (:mod:`flexsim.trimming.equilibrium`); None when the trim was asked not to classify (``classify=False``).
    terms : dict
        The physical terms of the model trimmed (:meth:`flexsim.model.terms.Terms.record`).
    linear_range : str or None
        One line when the trim bends or twists a beam beyond the linear structure's range
        (:func:`flexsim.model.linear_range.linear_range_note`), None within it.
    """

    manoeuvre: SteadyManoeuvre
    x: np.ndarray
    u: np.ndarray
    theta: float
    phi: float
    gamma: float
    alpha: float
    beta: float
    load_factor: float
    tip_deflection_m: float
    tip_twist_rad: float
    residual: float
    heading_offset: float = 0.0
    sideslip_cg: float = 0.0
    load_factor_total: float = 0.0
    bank_wind: float = 0.0
    lift_n: float = 0.0
    drag_n: float = 0.0
    max_local_alpha: StripAngle | None = None
    stability: EquilibriumStability | None = None
    terms: dict = field(default_factory=dict)
    linear_range: str | None = None

    def __post_init__(self) -> None:
        # a frozen result: its arrays are read-only copies (the caller's arrays are not frozen)
        object.__setattr__(self, "x", readonly(np.array(self.x, dtype=float)))
        object.__setattr__(self, "u", readonly(np.array(self.u, dtype=float)))

    @property
    def thrust_n(self) -> float:
        """Total thrust T_e [N]."""
        return float(self.u[0])

    def summary(self) -> dict[str, float]:
        """The trim quantities in display units (degrees, kN), as in the paper's tables."""
        return {
            "mach": self.manoeuvre.mach,
            "speed_m_s": self.manoeuvre.speed_m_s,
            "altitude_m": self.manoeuvre.altitude_m,
            "theta_deg": math.degrees(self.theta),
            "phi_deg": math.degrees(self.phi),
            "gamma_deg": math.degrees(self.gamma),
            "alpha_deg": math.degrees(self.alpha),
            "thrust_kN": self.thrust_n / 1e3,
            "lift_kN": self.lift_n / 1e3,
            "drag_kN": self.drag_n / 1e3,
            "lift_to_drag": self.lift_n / self.drag_n if self.drag_n else float("inf"),
            "aileron_deg": math.degrees(self.u[1]),
            "elevator_deg": math.degrees(self.u[2]),
            "rudder_deg": math.degrees(self.u[3]),
            "sideslip_deg": math.degrees(self.sideslip_cg),
            "sideslip_origin_deg": math.degrees(self.beta),
            "heading_offset_deg": math.degrees(self.heading_offset),
            "bank_wind_deg": math.degrees(self.bank_wind),
            "load_factor": self.load_factor,
            "load_factor_total": self.load_factor_total,
            "tip_deflection_m": self.tip_deflection_m,
            "tip_twist_deg": math.degrees(self.tip_twist_rad),
            "max_local_alpha_deg": math.degrees(self.max_local_alpha.alpha_rad) if self.max_local_alpha else math.nan,
            "residual": self.residual,
        }


class _Problem:
    """Maps the unknown vector to a model state and evaluates the scaled residual."""

    def __init__(self, model: AircraftModel, manoeuvre: SteadyManoeuvre) -> None:
        if model.variant.kind is Variant.RESTRAINED:
            raise ValueError("trim needs a free or quasi-rigid model (a restrained aircraft has no flight path)")
        self.model, self.man = model, manoeuvre
        # without a rudder (a flying wing) the yaw balance is met by sideslip: the heading offset psi - chi takes the
        # rudder's place among the unknowns (the rudder stays 0); a coordinated manoeuvre, zero sideslip, cannot be flown
        self.sideslip = bool(model.aircraft.control_limits()[1][3] == 0.0)
        if self.sideslip and manoeuvre.coordinated:
            raise TrimError(f"trim infeasible for {manoeuvre.describe()}: {model.aircraft.name} has no rudder, so it "
                            "balances yaw by sideslip; a coordinated (zero-sideslip) manoeuvre needs a rudder")
        lay = model.layout
        self.n_el = lay.nq + lay.nxi
        mass = model.structure.mass_properties.mass_kg
        g = max(model.terms.gravity_m_s2, 1.0)
        # the thrust unknown's scale: the weight (with gravity below 1 m/s^2, mass x 1 m/s^2: a thrust scaled by a
        # vanishing weight would have no effect on the scaled equations and be reported as undetermined)
        self.weight = mass * g
        n_vel = lay.velocity.stop - lay.velocity.start
        self.scale = np.full(n_vel, 1.0 / g)
        self.scale[3:6] = _ROT_LENGTH / g
        self.coordinated = manoeuvre.coordinated
        self.r_cg = model.structure.mass_properties.cg_m
        # the residual through the batched kernel (one row; equal to ``rhs`` bit for bit), which the Jacobian needs
        # anyway: a process that only trims and linearises then loads one compiled right-hand side from numba's
        # cache instead of two (about 0.1 s per process); a model class with its own rhs: its rhs
        batched = type(model).rhs is AircraftModel.rhs and type(model).rhs_batch is AircraftModel.rhs_batch
        self._still_air = model.pack_winds([None]) if batched else None

    def state(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        theta, phi = z[0], z[1]
        if self.man.is_glide:
            gamma, thrust = z[2], 0.0
        else:
            gamma, thrust = self.man.climb_angle_rad, z[2] * self.weight
        u = np.array([thrust, z[3], z[4], 0.0 if self.sideslip else z[5]])
        lay = self.model.layout
        dpsi = z[-1] if self.coordinated else z[5] if self.sideslip else 0.0
        v, omega = self.man.body_rates(phi, theta, gamma, dpsi)
        x = lay.zeros()
        x[lay.position] = [0.0, 0.0, -self.man.altitude_m]
        x[lay.euler] = [phi, theta, dpsi]
        x[lay.q.start : lay.xi.stop] = z[6 : 6 + self.n_el]
        x[lay.v] = v
        x[lay.omega] = omega
        return x, u, gamma

    def residual(self, z: np.ndarray) -> np.ndarray:
        x, u, _ = self.state(z)
        lay = self.model.layout
        if self._still_air is None:
            x_dot = self.model.rhs(0.0, x, u)
        else:
            x_dot = self.model.rhs_batch(0.0, x[None, :], u[None, :], self._still_air)[0]
        r = x_dot[lay.velocity] * self.scale
        if not self.coordinated:
            return r
        v_cg = x[lay.v] + np.cross(x[lay.omega], self.r_cg)
        return np.append(r, v_cg[1] / self.man.speed_m_s)  # zero sideslip at the CG

    def jacobian(self, z: np.ndarray) -> np.ndarray:
        """Central-difference Jacobian d residual / dz, steps 1e-7 max(1, |z_j|): the 2 n residuals in one
        compiled call (:meth:`AircraftModel.rhs_batch`, rows equal to ``rhs`` bit for bit), so equal to the
        column-by-column differences of :meth:`residual` (a model class with its own ``rhs``: column by column)."""
        n = z.size
        if type(self.model).rhs is not AircraftModel.rhs:
            return _fd_jacobian(self.residual, z, n)
        lay = self.model.layout
        h = 1e-7 * np.maximum(1.0, np.abs(z))
        zs = np.concatenate([z + np.diag(h), z - np.diag(h)])
        x0, u0, _ = self.state(z)
        xs = np.tile(x0, (2 * n, 1))
        us = np.tile(u0, (2 * n, 1))
        # unknowns 0-2 (and the heading offset) enter the velocities and attitude: the full state map;
        # the controls and elastic coordinates are copied into place as state() does
        moving = [0, 1, 2] + ([n - 1] if self.coordinated else []) + ([5] if self.sideslip else [])
        rows = [j for j in moving] + [n + j for j in moving]
        for r in rows:
            xs[r], us[r], _ = self.state(zs[r])
        copy = np.setdiff1d(np.arange(2 * n), rows)
        if not self.man.is_glide:
            us[copy, 0] = zs[copy, 2] * self.weight
        us[copy, 1:] = zs[copy, 3:6]
        if self.sideslip:
            us[copy, 3] = 0.0
        xs[copy, lay.q.start : lay.xi.stop] = zs[copy, 6 : 6 + self.n_el]
        r = self.model.rhs_batch(0.0, xs, us)[:, lay.velocity] * self.scale
        if self.coordinated:
            v_cg = xs[:, lay.v] + np.cross(xs[:, lay.omega], self.r_cg)
            r = np.concatenate([r, (v_cg[:, 1] / self.man.speed_m_s)[:, None]], axis=1)
        return ((r[:n] - r[n:]) / (2 * h)[:, None]).T


@single_blas_thread
def trim(model: AircraftModel, manoeuvre: SteadyManoeuvre, *, guess: TrimPoint | None = None, check_limits: bool = True,
         classify: bool | None = None) -> TrimPoint:
    """Trim ``model`` in ``manoeuvre`` (eqs. 33-39) with its own right-hand side.

    Parameters
    ----------
    model : AircraftModel
        Free or quasi-rigid; any aerodynamic model (the inflow is zero in a steady state, so the
        quasi-steady and finite-state models have the same trim).
    manoeuvre : SteadyManoeuvre
    guess : TrimPoint, optional
        Starting point (e.g. the trim at a neighbouring speed).
    check_limits : bool
        Raise when the angle of attack of the CG or the local angle of attack of a strip is beyond the linear
        aerodynamics' range (the aircraft's ``[aero] max_alpha_deg``) or the thrust or a surface is beyond its
        limit (default True; False returns the solution of the equations as asked).
    classify : bool, optional
        Classify the equilibrium from the roots of the model linearised about it (``TrimPoint.stability``,
        :func:`flexsim.trimming.equilibrium.equilibrium_stability`; default: yes for the linear structure). False
        leaves it None, for a caller that classifies from an eigen-analysis of its own (the flutter search). A model
        with the geometrically nonlinear beams is not classified here (True is refused): its roots are
        :func:`flexsim.linear.flexible_stability.free_aircraft_spectrum`.

    Returns
    -------
    TrimPoint or FlexibleTrimPoint
        The latter for a model with ``terms.nonlinear_beams`` (:func:`flexsim.trimming.flexible_trim.trim_flexible`:
        symmetric flight and the pull-up; its ``guess`` a FlexibleTrimPoint).

    Raises
    ------
    TrimError
        Naming the manoeuvre and either the residuals that did not vanish or the limiting quantity.
    """
    check_model(model, nonlinear=True)
    if model.terms.nonlinear_beams is not None:
        return _trim_nonlinear(model, manoeuvre, guess, check_limits, classify)
    prob = _Problem(model, manoeuvre)
    lay = model.layout
    z0 = np.zeros(6 + prob.n_el + (1 if manoeuvre.coordinated else 0))
    if guess is not None:
        z0[0], z0[1] = guess.theta, guess.phi
        z0[2] = guess.gamma if manoeuvre.is_glide else guess.u[0] / prob.weight
        z0[3:6] = guess.u[1:]
        if prob.sideslip:
            z0[5] = guess.heading_offset
        z0[6 : 6 + prob.n_el] = guess.x[lay.q.start : lay.xi.stop]
        if manoeuvre.coordinated:
            z0[-1] = guess.heading_offset
    else:
        omega = manoeuvre.turn_rate(0.0)
        z0[0] = 0.08
        z0[1] = math.atan(manoeuvre.speed_m_s * omega / max(model.terms.gravity_m_s2, 1e-9)) if omega else 0.0
        z0[2] = -0.03 if manoeuvre.is_glide else 0.03
    z = r = None
    if guess is not None:  # Newton from a neighbouring trim; hybr only if that does not converge
        z, jac = _newton_polish(prob.residual, z0, jac_of=prob.jacobian)
        r = prob.residual(z)
        if not float(np.linalg.norm(r)) <= _WARM_TOLERANCE:
            z = None
    if z is None:
        sol = root(prob.residual, z0, method="hybr", options={"xtol": 1e-13, "maxfev": 200 * (z0.size + 1)})
        z, jac = _newton_polish(prob.residual, sol.x, jac_of=prob.jacobian)
        r = prob.residual(z)
    norm = float(np.linalg.norm(r))
    if not np.isfinite(norm) or norm > _TOLERANCE:
        labels = _residual_labels(model)
        worst = np.argsort(-np.abs(r))[:4]
        detail = ", ".join(f"{labels[i]} = {r[i]:.3g}" for i in worst)
        raise TrimError(f"trim failed for {manoeuvre.describe()}: scaled residual {norm:.3g} > {_TOLERANCE:g}; largest: {detail}"
                        f"{_demand(model, manoeuvre)}")
    x, u, gamma = prob.state(z)
    point = _trim_point(model, manoeuvre, x, u, gamma, norm, float(z[-1]) if manoeuvre.coordinated else float(z[5]) if prob.sideslip else 0.0)
    if not check_limits:
        _check_singular(prob, z, jac)  # without limits a singular direction would be returned as a trim
    else:
        try:
            _check_limits(model, manoeuvre, point)
        except TrimError:
            _check_singular(prob, z, jac)  # an absurd control from a singular system: say so instead
            raise
    if classify is None or classify:
        point = replace(point, stability=equilibrium_stability(model, x, u))
    return point


def _unknown_labels(prob: "_Problem") -> list[str]:
    """Names of the trim unknowns z (pitch, bank, thrust or flight path, surfaces, elastic coordinates)."""
    labels = prob.model.structure.dofs.labels
    el = [labels[i] for i in prob.model.active_dofs][6:]
    third = "flight-path angle gamma" if prob.man.is_glide else "thrust T_e"
    yaw = "heading offset psi - chi (sideslip, no rudder)" if prob.sideslip else "rudder delta_r"
    return ["pitch theta", "bank phi", third, "aileron delta_a", "elevator delta_e", yaw, *el][: 6 + prob.n_el]


def _check_singular(prob: "_Problem", z: np.ndarray, jac: np.ndarray | None = None) -> None:
    """Raise TrimError when the trim equations do not determine an unknown at the solution.

    The Jacobian d(residual)/dz (central differences) is column-scaled; an unknown whose column
    vanishes has no effect on the equations (e.g. an aileron inboard of every aerodynamic strip), and a
    condition number above 1e12 means a combination of unknowns is undetermined: the "solution" along
    that direction is arbitrary, so it is not reported as a trim. ``jac``: the Jacobian the Newton polish
    last built (at z, or at an earlier iterate from which its steps converged to z), reused instead of a new one
    at z: a dead column or a condition number of 1e12 is a property of the equations, not of the last Newton step
    (default None, or not finite: built at z).
    """
    if jac is None or not np.all(np.isfinite(jac)):
        jac = prob.jacobian(z)
    labels = _unknown_labels(prob)
    col = np.linalg.norm(jac, axis=0)
    if not np.all(np.isfinite(col)):
        return
    dead = np.flatnonzero(col <= 1e-9 * col.max())
    describe = prob.man.describe()
    if dead.size:
        names = ", ".join(labels[i] for i in dead)
        raise TrimError(f"trim singular for {describe}: the equations do not depend on {names}; the trim is "
                        f"undetermined — {_why_dead([labels[i] for i in dead], prob.model)}")
    sv, vt = np.linalg.svd(jac / col, compute_uv=True)[1:]
    cond = sv[0] / sv[-1] if sv[-1] > 0 else np.inf
    if cond > 1e12:
        null = np.abs(vt[-1])
        names = ", ".join(labels[i] for i in np.argsort(-null)[:3])
        raise TrimError(f"trim singular for {describe}: the trim equations are (nearly) singular, condition number "
                        f"{cond:.3g} > 1e12, along a direction mostly in {names}; the trim is undetermined")


def _why_dead(names: list[str], model: AircraftModel) -> str:
    """What makes each trim unknown of ``names`` drop out of the equations, in the user's terms."""
    reasons = []
    attitude = [n for n in names if n.startswith(("pitch", "bank", "heading"))]
    if attitude:
        if model.terms.gravity_m_s2 == 0.0:
            reasons.append(f"{', '.join(attitude)}: the model has no gravity (gravity_m_s2 = 0), and the attitude "
                           "enters the steady equations only through the weight; trim a model with gravity, or "
                           "start a simulation from a state you choose")
        else:
            reasons.append(f"{', '.join(attitude)}: no force or moment changes with it")
    surfaces = [n for n in names if n.startswith(("aileron", "elevator", "rudder"))]
    if surfaces:
        reasons.append(f"{', '.join(surfaces)}: no aerodynamic strip carries the surface (check the aircraft's "
                       "strips and control surfaces)" + (" — the model has no aerodynamics (aero=None)"
                                                         if model.aero is None else ""))
    thrust = [n for n in names if n.startswith(("thrust", "flight-path"))]
    if thrust:
        reasons.append(f"{', '.join(thrust)}: no force changes with it (check the aircraft's engines)")
    other = [n for n in names if n not in attitude + surfaces + thrust]
    if other:
        reasons.append(f"{', '.join(other)}: no force or moment changes with it")
    return "; ".join(reasons)


def _demand(model: AircraftModel, man: SteadyManoeuvre) -> str:
    """What the manoeuvre asks of the aircraft, to explain a trim that does not converge.

    A coordinated steady turn needs the bank tan(phi) = V^2 cos(gamma) / (g R) and the load factor
    n = 1 / cos(phi) (point-mass relations; the flexible trim differs little).
    """
    if man.turn_radius_m == math.inf or model.terms.gravity_m_s2 <= 0.0:
        return ""
    gamma = 0.0 if man.climb_angle_rad is None else man.climb_angle_rad
    phi = math.atan(man.speed_m_s**2 * math.cos(gamma) / (model.terms.gravity_m_s2 * abs(man.turn_radius_m)))
    return (f" (this turn needs a bank of about {math.degrees(phi):.0f} deg and a load factor of {1 / math.cos(phi):.2g}"
            f"; a larger radius or a lower speed asks less)")


def _newton_polish(fun, z: np.ndarray, iterations: int = 12, jac_of=None) -> tuple[np.ndarray, np.ndarray | None]:
    """Newton steps polishing hybr's root (it stops at ~1e-8 at high dynamic pressure, or earlier when it
    makes no progress from a distant guess).

    A central-difference Jacobian and its LU serve as long as each step reduces the residual at least tenfold
    (the chord method, Kelley, *Iterative Methods for Linear and Nonlinear Equations*, SIAM 1995, §5.4: it
    converges linearly at a rate proportional to the distance from the root); after a slower step, or a step
    that fails to reduce the residual, the Jacobian is rebuilt at the current point (Newton's method, §5.1),
    so that a start far from the root still converges quadratically. Stops below 1e-13, when a step with a
    fresh Jacobian no longer reduces the residual, or after a slow step that ends below ``_ROUND_OFF`` (the
    residual's round-off floor, where a fresh Jacobian cannot do better).

    Returns the polished z and the last Jacobian built (None when z needed no step).
    """
    r = fun(z)
    lu = jac = None
    fresh = False
    for _ in range(iterations):
        if not np.all(np.isfinite(r)) or np.linalg.norm(r) < 1e-13:
            break
        if lu is None:
            jac, lu, fresh = *_jacobian_lu(fun, z, r.size, jac_of), True
            if lu is None:
                break
        z_new = z - lu_solve(lu, r, check_finite=False)
        r_new = fun(z_new)
        if not np.linalg.norm(r_new) < np.linalg.norm(r):
            if fresh:
                break
            lu = None  # the chord went stale: a fresh Jacobian at z
            continue
        slow = np.linalg.norm(r_new) > 0.1 * np.linalg.norm(r)
        z, r, fresh = z_new, r_new, False
        if slow and np.linalg.norm(r) < _ROUND_OFF:  # at the round-off floor: a new Jacobian would not help
            break
        if slow:
            lu = None
    return z, jac


def _fd_jacobian(fun, z: np.ndarray, m: int) -> np.ndarray:
    """Central-difference Jacobian of ``fun`` at z, shape (m, z.size), steps 1e-7 max(1, |z_j|)."""
    jac = np.empty((m, z.size))
    for j in range(z.size):
        h = 1e-7 * max(1.0, abs(z[j]))
        zp, zm = z.copy(), z.copy()
        zp[j] += h
        zm[j] -= h
        jac[:, j] = (fun(zp) - fun(zm)) / (2 * h)
    return jac


def _jacobian_lu(fun, z: np.ndarray, m: int, jac_of=None):
    """The central-difference Jacobian of ``fun`` at z (steps 1e-7 max(1, |z_j|), or ``jac_of(z)``) and its LU
    factors (None if singular or not finite)."""
    jac = _fd_jacobian(fun, z, m) if jac_of is None else jac_of(z)
    if not np.all(np.isfinite(jac)):
        return jac, None
    with warnings.catch_warnings():
        warnings.simplefilter("error", LinAlgWarning)
        try:
            return jac, lu_factor(jac, check_finite=False)
        except (LinAlgWarning, np.linalg.LinAlgError, ValueError):
            return jac, None


def _residual_labels(model: AircraftModel) -> list[str]:
    labels = model.structure.dofs.labels
    return [f"d/dt {labels[i]}" for i in model.active_dofs]


def _alpha_cg(model: AircraftModel, x: np.ndarray) -> float:
    """Angle of attack of the centre of gravity atan(w_cg / u_cg) [rad], v_cg = v + omega x r_cg (undeformed CG,
    body axes), as ``sideslip_cg``."""
    lay = model.layout
    v_cg = x[lay.v] + np.cross(x[lay.omega], model.structure.mass_properties.cg_m)
    return math.atan2(v_cg[2], v_cg[0])


def _check_limits(model: AircraftModel, manoeuvre: SteadyManoeuvre, point: TrimPoint) -> None:
    """Raise TrimError naming every limit a solved trim exceeds: the angle of attack, then the controls.

    Angle of attack: the strip aerodynamics are linear (no stall), so a trim is accepted only while the angle of
    attack of the centre of gravity is within +-``aero_settings.max_alpha_rad`` (the file's ``[aero]
    max_alpha_deg``), the aircraft's linear lift range. The limit stands for the end of the aircraft's linear lift
    curve, and its public measurement (for the GTM, NASA's T2 wind-tunnel database,
    :func:`flexsim.aircraft.t2_data.t2_linear_alpha_limit_deg`) is a whole-aircraft lift curve against the angle of
    attack of the body axes, with the fuselage's upwash, the wing's twist, sweep and span loading and the tail's
    downwash inside it. The CG's angle is the flight-mechanics alpha of a steady manoeuvre: equal to
    ``TrimPoint.alpha`` (taken at o) in straight flight; in a turn they differ by the pitch rate times the arm.

    Local angles: the same limit applies to every strip's local angle of attack (:class:`StripAngle`: the rigging,
    the elastic twist and the rotation rates included), and the strip with the largest |alpha| is named. Each
    section's own stall angle is not in the public GTM data, and strip theory has no spanwise flow (which makes a
    swept wing's tips stall first), so the whole aircraft's range is the only limit there is to apply; it refuses
    what the linear aerodynamics cannot represent at all, e.g. a wing twisted -18 deg past a static divergence, or
    a fin at -12 deg in a sideslipping turn.

    Controls: thrust in [0, the engines' maximum], each surface within +-its ``max_deflection``; the thrust is
    not checked in a glide (it is 0 there).
    """
    problems = []
    alpha, limit = _alpha_cg(model, point.x), model.aircraft.aero_settings.max_alpha_rad
    if not abs(alpha) <= limit + 1e-12:
        problems.append(f"angle of attack alpha = {math.degrees(alpha):.4g} deg at the CG beyond the range of the linear "
                        f"(no-stall) aerodynamics, +-{math.degrees(limit):.4g} deg = [aero] max_alpha_deg of "
                        f"{model.aircraft.name}")
    local = point.max_local_alpha
    if local is not None and not abs(local.alpha_rad) <= limit + 1e-12:
        problems.append(f"local angle of attack {local.describe()} beyond the range of the linear (no-stall) "
                        f"aerodynamics, +-{math.degrees(limit):.4g} deg = [aero] max_alpha_deg of {model.aircraft.name}")
    lo, hi = model.aircraft.control_limits()
    names = ("thrust T_e [N]", "aileron delta_a [rad]", "elevator delta_e [rad]", "rudder delta_r [rad]")
    for k in range(4):
        if manoeuvre.is_glide and k == 0:
            continue
        if not lo[k] - 1e-9 <= point.u[k] <= hi[k] + 1e-9:
            problems.append(f"{names[k]} = {point.u[k]:.5g} outside its limits [{lo[k]:.5g}, {hi[k]:.5g}]")
    if problems:
        raise TrimError(f"trim infeasible for {manoeuvre.describe()}: {'; '.join(problems)} (the equations were "
                        f"solved, scaled residual {point.residual:.2g})")


def _wind_axes(v_cg: np.ndarray) -> np.ndarray:
    """Rows x_w, y_w, z_w of the wind axes in body components: x_w along the CG velocity, y_w the body y
    axis made normal to it, z_w = x_w x y_w (Stevens & Lewis 2003, sec. 2.4)."""
    x_w = v_cg / np.linalg.norm(v_cg)
    y_w = np.array([0.0, 1.0, 0.0]) - x_w[1] * x_w
    y_w /= np.linalg.norm(y_w)
    return np.stack([x_w, y_w, np.cross(x_w, y_w)])


def _lift_drag(force_b: np.ndarray, v_cg: np.ndarray) -> tuple[float, float]:
    """Lift -F . z_w and drag -F . x_w [N] of the aerodynamic force F (body axes) in the wind axes of the CG."""
    w = _wind_axes(v_cg)
    return float(-force_b @ w[2]), float(-force_b @ w[0])


def _wind_bank(euler: np.ndarray, v_cg: np.ndarray) -> float:
    """Bank angle mu of the wind axes [rad] (Stevens & Lewis, 2nd ed., sec. 2.4).

    Wind axes: x_w along the CG velocity, y_w the body y axis made normal to it, z_w = x_w x y_w; mu is the
    3-2-1 roll angle of that frame relative to north-east-down.
    """
    c_w = _wind_axes(v_cg) @ dcm_321(*euler)  # wind <- body <- NED
    return float(math.atan2(c_w[1, 2], c_w[2, 2]))


def _trim_point(model: AircraftModel, man: SteadyManoeuvre, x: np.ndarray, u: np.ndarray, gamma: float, residual: float,
                heading_offset: float = 0.0) -> TrimPoint:
    st = model.structure
    _, eul, q, _, vel = model.unpack(x)
    v = vel[0:3]
    speed = float(np.linalg.norm(v))
    alpha = math.atan2(v[2], v[0])
    beta = math.asin(v[1] / speed)
    # aerodynamic + thrust force along -z_body over the weight
    aero_force = model.aerodynamic_force(x, u)[0:3]
    force = st.thrust.force(u[0], q)[0:3] + aero_force
    v_cg = v + np.cross(vel[3:6], st.mass_properties.cg_m)
    lift, drag = _lift_drag(aero_force, v_cg)
    weight = st.mass_properties.mass_kg * max(model.terms.gravity_m_s2, 1e-9)
    tip_w = tip_t = 0.0
    sensors = structural_sensors(model)  # the one implementation of the structural outputs
    wing = sensors.get("right_wing")
    if wing is not None:
        tip_w, tip_t = float(wing.tip_deflection_m(x)), float(wing.tip_twist_rad(x))
    return TrimPoint(
        manoeuvre=man,
        x=x,
        u=u,
        theta=float(eul[1]),
        phi=float(eul[0]),
        gamma=float(gamma),
        alpha=alpha,
        beta=beta,
        load_factor=float(-force[2] / weight),
        tip_deflection_m=tip_w,
        tip_twist_rad=tip_t,
        residual=residual,
        heading_offset=heading_offset,
        sideslip_cg=math.asin(v_cg[1] / float(np.linalg.norm(v_cg))),
        load_factor_total=float(np.linalg.norm(force) / weight),
        bank_wind=_wind_bank(eul, v_cg),
        lift_n=lift,
        drag_n=drag,
        max_local_alpha=_max_local_alpha(model, x, u),
        terms=model.terms.record(),
        linear_range=linear_range_note(model, x, sensors=sensors),
    )


def _max_local_alpha(model: AircraftModel, x: np.ndarray, u: np.ndarray) -> StripAngle | None:
    """The strip with the largest local angle of attack |atan(w_EA / u0)| at the state x (:class:`StripAngle`; the
    strips' kinematics of :meth:`flexsim.model.coupling.AeroCoupling.strip_loads`, downwash included); None without
    strips."""
    if model.aero is None or model.aero.strips.n_strips == 0:
        return None
    _, _, q, xi, vel = model.unpack(x)
    mach = float(np.linalg.norm(vel[0:3])) / speed_of_sound(float(-x[model.layout.position][2]))
    loads = model.aero.strip_loads(q, xi, vel, x[model.layout.inflow], u, model.air_density(x), mach)
    alpha = np.arctan2(loads.w_ea_m_s, loads.u0_m_s)
    size = np.abs(alpha)
    j = int(np.argmax(size))
    strips = model.aero.strips
    # A round-off tie between mirror strips (same station, in symmetric flight) goes to the one listed first, the
    # right half, as the mode labels' ties do (TIE_RTOL), so the strip named does not change between machines.
    station = np.asarray(strips.station_m)
    tie = (np.abs(station - station[j]) <= 1e-9) & (size >= size[j] * (1.0 - TIE_RTOL))
    j = int(np.flatnonzero(tie)[0])
    name = strips.component[j]
    number = sum(1 for c in strips.component[:j] if c == name) + 1
    return StripAngle(float(alpha[j]), j, name, number, float(strips.station_m[j]))


def _trim_nonlinear(model: AircraftModel, manoeuvre: SteadyManoeuvre, guess, check_limits: bool, classify: bool | None):
    """:func:`trim` of a model with the geometrically nonlinear beams, its options checked where they enter."""
    from flexsim.trimming.flexible_trim import FlexibleTrimPoint, trim_flexible

    if classify:
        raise ValueError(f"classify = {classify!r}: the trim of the geometrically nonlinear beams (nonlinear_beams = "
                         f"{model.terms.nonlinear_beams!r}) is not classified by trim; its roots are "
                         "flexsim.linear.flexible_stability.free_aircraft_spectrum(model, point)")
    if guess is not None and not isinstance(guess, FlexibleTrimPoint):
        raise ValueError(f"guess = {type(guess).__name__}: a model with the geometrically nonlinear beams starts from a "
                         "FlexibleTrimPoint (a trim of the same model)")
    return trim_flexible(model, manoeuvre, guess=guess, check_limits=check_limits)
