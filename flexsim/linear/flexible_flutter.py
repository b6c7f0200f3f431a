"""Flutter of a very flexible aircraft's wing about the aircraft's nonlinear trim.

For each speed of a scan, the geometrically nonlinear aircraft is trimmed in the manoeuvre
(:func:`flexsim.trimming.flexible_trim.trim_flexible`: level flight, climb, pull-up at load factor n), and one wing —
a strain-based beam clamped at its root, at its trimmed strains ``ε0`` — is linearised about that deformed
equilibrium (:func:`flexsim.model.beam_aero.aeroelastic_system`: Peters finite-state strips, the preload's geometric
stiffness and the steady airloads' stiffness of the deformed strips, :func:`flexsim.model.beam_aero.static_stiffness`).
The preload is the trim's: gravity and the manoeuvre's inertial load on the sections' mass centres,
``f = m (g_b − ω × v − ω × (ω × r))`` per unit length (steady flight in body axes, Shearer & Cesnik 2007 eq. 9 at
``V̇ = 0``), and the flow is the trim's air velocity at the wing root, ``−(v + ω × r_root)``. The flutter speed is the
first crossing of the most unstable oscillatory root's damping ratio, refined by Brent's method on re-trimmed states.

What is neglected, and said in every result: the coupling of the wing's motion with the rigid-body motion and with
the other wing (the wing is clamped at the trim's root; Patil, Hodges & Cesnik 2001 find the complete HALE's flutter
close to its clamped wing's at the same deformed state), and the spanwise variation of the pull-up's rotational
air velocity in the perturbation equations. SI units, radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from flexsim.atmosphere import isa
from flexsim.model.aircraft_model import check_model
from flexsim.model.beam_aero import AeroelasticSystem, TunnelFlow, aeroelastic_system, static_stiffness
from flexsim.linear.flexible_unsteady import free_aircraft_unsteady
from flexsim.model.terms import STABILITY_STRUCTURES, NonlinearBeams
from flexsim.structure.free_flexible import _cross
from flexsim.structure.strain_beam import BeamKinematics, BeamProperties, mass_points
from flexsim.trimming.flexible_trim import FlexibleTrimError, FlexibleTrimPoint, trim_flexible
from flexsim.trimming.manoeuvre import SteadyManoeuvre

__all__ = ["SteadyInertialLoad", "FlexibleFlutterPoint", "wing_system", "wing_stability", "flexible_flutter", "NEGLECTED",
           "MAX_FREQUENCY_RAD_S", "FREE_AIRCRAFT", "STRUCTURES"]

#: The approximation every result of this module carries.
NEGLECTED = ("wing clamped at the trimmed root: coupling with the rigid-body motion and the other wing neglected "
             "in the stability (not in the trim)")

_NEUTRAL = 1e-6
#: Roots above this frequency are the beams' unconverged band, left out of stability verdicts [rad/s] (the HALE
#: wing's highest roots: 6002 rad/s with 8 elements, 16937 rad/s with 16; its flutter and first modes below 40 rad/s
#: converge to 1 %).
MAX_FREQUENCY_RAD_S = 200.0


@dataclass(frozen=True)
class SteadyInertialLoad:
    """Gravity and the inertial load of steady flight on a beam's mass centres (a ``LoadModel``).

    Parameters
    ----------
    gravity_body_m_s2, velocity_m_s, rate_rad_s : ndarray, shape (3,)
        ``g_b`` [m/s²], ``v`` of o [m/s] and ``ω`` [rad/s] in body axes (the beam's global frame).
    """

    gravity_body_m_s2: NDArray
    velocity_m_s: NDArray
    rate_rad_s: NDArray

    def generalized_force(self, beam: BeamProperties, kin: BeamKinematics) -> NDArray[np.float64]:
        """``Q = Σ w J_cᵀ m (g_b − ω × v − ω × (ω × r_c))``, shape (n,)."""
        pts = mass_points(beam, kin)  # the sections' mass centres and the point masses
        om = np.asarray(self.rate_rad_s, float)
        acc = _cross(om, self.velocity_m_s) + _cross(om, _cross(om, pts.r))
        return np.einsum("pik,pi->k", pts.jac_c, pts.mass[:, None] * (np.asarray(self.gravity_body_m_s2, float) - acc))


def wing_system(model, point: FlexibleTrimPoint, component: str = "right_wing",
                inflow_states: int = 6) -> AeroelasticSystem:
    """The linear aeroelastic system of ``component``'s wing, clamped at its trimmed root, about the trim ``point``
    (module docstring): ``x = [δε, δε̇, λ]`` of the wing's strains and its strips' Peters inflow states
    (:func:`flexsim.model.beam_aero.aeroelastic_system`), with the preload's and the steady airloads' stiffness."""
    flex = point.aircraft
    i = flex.beam_index(component)
    beam = flex.structure.beams[i]
    eps = point.strains[flex.structure.strain_slices()[i]]
    aero = flex.beam_strips[i].aero
    if inflow_states != aero.inflow_states or flex.compressibility_beta != aero.compressibility_beta:
        aero = replace(aero, inflow_states=inflow_states, compressibility_beta=flex.compressibility_beta)
    air = -(point.velocity_m_s + np.cross(point.rate_rad_s, beam.root_position_m))
    speed = float(np.linalg.norm(air))
    flow = TunnelFlow(speed, point.density_kg_m3, air / speed)
    theta, phi = point.theta_rad, point.phi_rad
    g = float(model.terms.gravity_m_s2)
    # gravity in body axes, g (-sin θ, sin φ cos θ, cos φ cos θ) (the bank φ is 0 in symmetric flight)
    g_body = g * np.array([-np.sin(theta), np.sin(phi) * np.cos(theta), np.cos(phi) * np.cos(theta)])
    preload = SteadyInertialLoad(g_body, point.velocity_m_s,
                                 point.rate_rad_s)
    stiffness = static_stiffness(beam, eps, preload, aero, flow)
    # the beam's block of the structure's modal damping (blocks of the clamped-body modes are the beams' own)
    sl = flex.structure.strain_slices()[i]
    return aeroelastic_system(beam, aero, flow, eps, stiffness, flex.structure.damping()[sl, sl])


def wing_stability(model, point: FlexibleTrimPoint, component: str = "right_wing", inflow_states: int = 6,
                   max_frequency_rad_s: float = MAX_FREQUENCY_RAD_S) -> tuple[float, float, NDArray]:
    """Stability of ``component``'s wing about the trim ``point`` (module docstring).

    Roots above ``max_frequency_rad_s`` are left out of the growth: they are the discretisation's unconverged band
    (the HALE wing's highest roots: 6002 rad/s with 8 elements, 16937 rad/s with 16; its flutter and first
    modes below 40 rad/s converge to 1 %).

    Returns
    -------
    growth : float
        Largest damping ratio ``Re λ / |λ|`` of the oscillatory roots [-] (> 0: unstable).
    frequency_rad_s : float
        ``|Im λ|`` of that root.
    roots : ndarray of complex
    """
    roots = np.linalg.eigvals(wing_system(model, point, component, inflow_states).state_matrix)
    ratio = roots.real / np.maximum(np.abs(roots), 1e-300)
    oscillatory = ((np.abs(roots.imag) > 1e-6 * np.abs(roots)) & (np.abs(ratio) > _NEUTRAL)
                   & (np.abs(roots.imag) <= max_frequency_rad_s))
    if not np.any(oscillatory):
        return -1.0, 0.0, roots
    k = int(np.argmax(np.where(oscillatory, ratio, -np.inf)))
    return float(ratio[k]), float(abs(roots[k].imag)), roots


@dataclass(frozen=True, eq=False)
class FlexibleFlutterPoint:
    """Flutter of a very flexible aircraft's wing about its nonlinear trim.

    Attributes
    ----------
    speed_m_s, mach, frequency_rad_s : float
        Flutter speed [m/s] (true airspeed), Mach number, frequency [rad/s]; NaN when no crossing in the range.
    trim : FlexibleTrimPoint or None
        The trim at the flutter speed.
    speeds_m_s, growth : ndarray
        The scan (trimmed speeds) and the damping ratio of the most unstable oscillatory root.
    skipped_m_s : ndarray
        Speeds of the scan that could not be trimmed (e.g. beyond the strips' lift range).
    warnings : tuple of str
        What the result neglects (:data:`NEGLECTED`) and any skipped speeds.
    terms : dict
        The terms of the model analysed, with the nonlinear beams used (:attr:`FlexibleAircraft.terms`).
    component : str
        The wing that flutters ("" when none does); in a turn the less stable of both wings.
    """

    speed_m_s: float
    mach: float
    frequency_rad_s: float
    trim: FlexibleTrimPoint | None
    speeds_m_s: NDArray
    growth: NDArray
    skipped_m_s: NDArray
    warnings: tuple
    terms: dict = field(default_factory=dict)
    component: str = ""

    @property
    def tip_deflection_fraction(self) -> float:
        """Vertical tip deflection of the analysed wing at the flutter speed over its length [-] (NaN: none)."""
        if self.trim is None:
            return float("nan")
        i = self.trim.aircraft.beam_index(self.component) if self.component else 0
        return float(self.trim.tip_deflection_fraction[i])


#: The approximation of a result of the free aircraft (``structure="free-aircraft"``).
FREE_AIRCRAFT = ("free aircraft with Peters' strips on every lifting strip about the nonlinear trim "
                 "(flexsim.linear.flexible_unsteady); elastic roots only (over half their kinetic energy in the strains)")

#: The structures a flutter search can linearise.
STRUCTURES = STABILITY_STRUCTURES


def flexible_flutter(model, manoeuvre: SteadyManoeuvre, speed_range_m_s: tuple[float, float], *,
                     speed_step_m_s: float = 1.0, component: str = "right_wing", elements_per_beam: int | None = None,
                     inflow_states: int | None = None, tol_m_s: float = 1e-3,
                     structure: str | None = None) -> FlexibleFlutterPoint:
    """Lowest flutter speed of a very flexible aircraft's wing about its nonlinear trim in ``manoeuvre``.

    Parameters
    ----------
    model : AircraftModel
        Aircraft (its flexible components need ``ei_chord_nm2``), gravity and density.
    manoeuvre : SteadyManoeuvre
        Level, climb, pull-up or a turn (its load factor, radius and altitude are kept; its speed is searched). In a
        turn both wings are analysed (``component`` is not used) and the bank follows the speed at fixed radius.
    speed_range_m_s : (float, float)
        Scanned true airspeeds [m/s], 0 < lo < hi.
    speed_step_m_s : float
        Scan step [m/s], > 0.
    component : str
        The wing analysed in symmetric flight.
    elements_per_beam : int, optional
        Beam elements per component; default the model's ``terms.nonlinear_beams`` (8 for a model of the linear
        structure).
    inflow_states : int, optional
        Peters inflow states per strip; default the model's ``terms.aero.n_inflow``.
    tol_m_s : float
        Brent tolerance [m/s].
    structure : {"clamped-wing", "free-aircraft"}, optional
        What is linearised about each trim: the wing clamped at its trimmed root (:func:`wing_stability`) or the whole
        free aircraft with its six rigid-body degrees of freedom and Peters' strips on every lifting strip
        (:meth:`flexsim.linear.flexible_unsteady.UnsteadyFreeAircraft.elastic_stability`: its elastic roots); default
        the model's ``terms.nonlinear_beams.stability`` ("clamped-wing" for a model of the linear structure).

    Returns
    -------
    FlexibleFlutterPoint
    """
    if structure is not None and structure not in STRUCTURES:
        raise ValueError(f"structure = {structure!r}: must be one of {', '.join(STRUCTURES)}")
    check_model(model, nonlinear=True)
    beams = model.terms.nonlinear_beams or NonlinearBeams()
    if elements_per_beam is not None:
        beams = replace(beams, elements_per_beam=elements_per_beam)
    if structure is not None:
        beams = replace(beams, stability=structure)
    free = beams.stability == "free-aircraft"
    if model.aero is None:
        raise ValueError("the model has no aerodynamics (Terms(aero=None)): a flutter search needs its strips")
    if inflow_states is None:
        inflow_states = model.terms.aero.n_inflow
    terms = replace(model.terms, nonlinear_beams=beams).record()
    lo, hi = (float(v) for v in speed_range_m_s)
    if not (0.0 < lo < hi and np.isfinite(hi)):
        raise ValueError(f"speed_range_m_s = {speed_range_m_s!r}: must be 0 < lo < hi, finite [m/s]")
    if not (np.isfinite(speed_step_m_s) and speed_step_m_s > 0):
        raise ValueError(f"speed_step_m_s = {speed_step_m_s!r}: must be > 0 [m/s]")

    evaluated = {}  # speed -> (trim, growth, frequency): brentq's last evaluation is its root
    converged = []  # the last converged trim, within the strips' lift range or not: the start of the next scan speed
    limit = math.degrees(model.aircraft.aero_settings.max_alpha_rad)
    turn = manoeuvre.turn_radius_m != math.inf
    wings = ("right_wing", "left_wing") if turn else (component,)
    critical = {}  # speed -> the wing whose root is the least stable

    def at(speed, guess):
        if speed not in evaluated:
            man = SteadyManoeuvre(speed, manoeuvre.altitude_m, climb_angle_rad=manoeuvre.climb_angle_rad,
                                  load_factor=manoeuvre.load_factor, turn_radius_m=manoeuvre.turn_radius_m,
                                  coordinated=manoeuvre.coordinated)
            point = trim_flexible(model, man, elements_per_beam=beams.elements_per_beam, guess=guess, check_limits=False)
            converged[:] = [point]
            if point.max_strip_alpha_deg > limit:  # refused with trim_flexible's own error (from the converged trim)
                trim_flexible(model, man, elements_per_beam=beams.elements_per_beam, guess=point)
            if free:
                growth, freq = free_aircraft_unsteady(model, point, inflow_states).elastic_stability()[:2]
                wing = ""
            else:  # in a turn both wings (inner and outer) are analysed and the less stable one kept
                growth, freq, wing = max((*wing_stability(model, point, w, inflow_states)[:2], w) for w in wings)
            evaluated[speed] = (point, growth, freq)
            critical[speed] = wing
        return evaluated[speed]

    def nearest(speed):
        """The trim of the evaluated speed closest to ``speed`` (the start of its trim)."""
        return evaluated[min(evaluated, key=lambda s: abs(s - speed))][0]

    speeds, growth, skipped = [], [], []
    previous = None
    found = None
    for speed in np.append(np.arange(lo, hi, speed_step_m_s), hi):
        try:
            point, g, f = at(speed, previous[0] if previous is not None else (converged[0] if converged else None))
        except FlexibleTrimError:
            skipped.append(speed)
            if previous is not None:
                break  # the trimmable range ended
            continue
        speeds.append(speed), growth.append(g)
        if previous is not None and previous[1] < 0.0 < g:
            speed_f = brentq(lambda s: at(s, nearest(s))[1], previous[2], speed, xtol=tol_m_s)
            point_f = at(speed_f, nearest(speed_f))[0]
            # the critical root just past the crossing (at the crossing it is neutral and not counted)
            past = min(speed_f + 2.0 * tol_m_s, speed)
            freq_f = at(past, nearest(past))[2]
            found = (speed_f, freq_f, point_f)
            break
        previous = (point, g, speed)
    notes = [FREE_AIRCRAFT if free else NEGLECTED]
    if turn and not free:
        notes.append(f"turn of fixed radius {manoeuvre.turn_radius_m:g} m: the bank changes with the scanned speed "
                     "(tan phi ~ V^2/(g R)); both wings analysed, the result is the less stable wing's")
    if skipped:
        notes.append(f"speeds not trimmable (skipped): {', '.join(f'{s:g}' for s in skipped)} m/s")
    unmodelled = next(iter(evaluated.values()))[0].aircraft.unmodelled if evaluated else ()
    if unmodelled:
        notes.append(f"not in the nonlinear strips: {', '.join(unmodelled)}")
    sound = float(isa(manoeuvre.altitude_m).speed_of_sound)
    if found is None:
        return FlexibleFlutterPoint(float("nan"), float("nan"), float("nan"), None, np.array(speeds),
                                    np.array(growth), np.array(skipped), tuple(notes), terms, "")
    speed_f, freq_f, point_f = found
    return FlexibleFlutterPoint(float(speed_f), float(speed_f / sound), float(freq_f), point_f, np.array(speeds),
                                np.array(growth), np.array(skipped), tuple(notes), terms, critical[speed_f])
