"""FlexSim/HALE-GustAlleviation-v1: the HALE gust task flown on the geometrically nonlinear beams.

The physics is apart from this thin ``Env``: the nonlinear trim (:func:`flexsim.trimming.flexible_trim.trim_flexible`
through ``fs.trim``) and the fixed-step flight of :class:`flexsim.sim.flexible_step.FlexibleStepper` (ROS2, its
Jacobian frozen at the trim, quasi-steady strips, each strip meeting the wind where it is). The task —
gust, errors, reward — is that of ``FlexSim/HALE-GustAlleviation-v0`` (:class:`GustAlleviationTask` at the aircraft's
cruise point, :mod:`flexsim.envs.aircraft_defaults`); the limits are derived the same way, about the nonlinear trim.
"""

from __future__ import annotations

import math
from pathlib import Path

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from flexsim.aircraft.definition import Aircraft
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.atmosphere import speed_of_sound
from flexsim.kinematics import euler_321_of_quaternion
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.terms import NonlinearBeams, Terms
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim.sim.flexible_step import FlexibleStepper, body_wind
from flexsim.sim.initial_states import InitialPerturbation
from flexsim.structure.free_flexible import quaternion_matrix
from flexsim.trimming import trim
from flexsim.trimming.flexible_turn import euler_quaternion

from flexsim.envs.aircraft_defaults import limits_about, task_for_aircraft
from flexsim.envs.config import FlightLimits
from flexsim.envs.gust_alleviation import GustAlleviationTask

__all__ = ["HaleNonlinearGustEnv"]

#: (name, bound, meaning) of the observation entries, in order; bounds symmetric about 0 (the action's own 0-1 / ±1).
OBSERVATION = (("tip_deflection_increment_m", 50.0, "mean wing-tip height above the jig shape minus its trim value [m]"),
               ("root_moment_increment", 50.0, "mean wing-root flapwise moment increment / |trim value| [-]"),
               ("pitch_error_rad", math.pi, "pitch error theta - theta_trim [rad]"),
               ("roll_error_rad", math.pi, "roll error phi [rad]"),
               ("altitude_error_m", 5000.0, "altitude error [m]"),
               ("airspeed_error_m_s", 100.0, "airspeed at the body origin minus the trim's [m/s]"),
               ("alpha_rad", math.pi, "angle of attack at the body origin [rad]"),
               ("p_rad_s", 10.0, "roll rate [rad/s]"), ("q_rad_s", 10.0, "pitch rate [rad/s]"),
               ("r_rad_s", 10.0, "yaw rate [rad/s]"),
               ("thrust_action", 1.0, "applied thrust / maximum thrust"),
               ("aileron_action", 1.0, "applied aileron / its limit"), ("elevator_action", 1.0, "elevator / its limit"),
               ("rudder_action", 1.0, "rudder / its limit"))
#: Task errors (the first five observation entries), the reward's inputs.
ERRORS = tuple(e[0] for e in OBSERVATION[:5])


class HaleNonlinearGustEnv(gym.Env[np.ndarray, np.ndarray]):
    """
    ## Description
    The very flexible PHC HALE aircraft (bundled ``phc_hale``) flies trimmed at its cruise point (20 km, 25 m/s)
    with its wings bent up by half their length, and meets a vertical "1 - cos" gust: hold the attitude and altitude
    while keeping the wing loads — tip deflection and root bending moment above their trim values — small. The task
    is ``FlexSim/HALE-GustAlleviation-v0``'s; the structure is the geometrically nonlinear strain-based beam
    (``Terms(nonlinear_beams=NonlinearBeams(elements_per_beam))``, docs/nonlinear-beams.md), so the large
    deflections are within the model's range. Neglected: unsteady aerodynamics (the strips are quasi-steady), the
    density's change with altitude.

    ## Action Space
    ``Box([0, -1, -1, -1], [1, 1, 1, 1], float32)``: thrust / maximum thrust, aileron, elevator and rudder / their
    deflection limits (the aircraft's ``control_limits()``), held over the control period.

    ## Observation Space
    ``Box(float32)`` of 14 entries (:data:`OBSERVATION`): the five task errors (tip deflection increment [m], root
    moment increment [-], pitch and roll errors [rad], altitude error [m]), the airspeed error [m/s] and angle of
    attack [rad] at the body origin, the body rates p, q, r [rad/s] and the applied action (4), each clipped to
    its bound.

    ## Rewards
    ``task.reward`` (:class:`flexsim.envs.config.TrackingReward`): alive bonus, the tracking costs of the five
    errors, the control-rate cost and the termination penalty; ``info["reward_parts"]`` holds the parts.

    ## Starting State
    The nonlinear trim plus ``perturbation`` (``InitialPerturbation``: roll and pitch, heading, body rates, forward
    speed, altitude, drawn in that order from ``self.np_random``); gust amplitude, sign, gradient distance and
    encounter time drawn from ``self.np_random`` (``info["reference"]``).

    ## Episode End
    Terminated when a wing tip is further than ``limits.wing_tip_deflection_m`` from its jig position (vertically),
    the pitch beyond ``max_abs_pitch_rad``, the angle of attack beyond ``max_abs_alpha_rad``, the airspeed below
    ``min_airspeed_m_s``, the Mach number above ``max_mach``, the altitude at 0 or the state not finite
    (``info["termination_reason"]``). The aircraft's fin is rigid, so ``fin_tip_twist_rad`` bounds a flexible
    ``vtail``'s total twist only. Truncated after ``max_episode_steps`` (500: 10 s at 50 Hz).

    ## Arguments
    ``aircraft`` (bundled name, TOML path or Aircraft with ``ei_chord_nm2`` on its flexible components; default
    ``"phc_hale"``), ``elements_per_beam`` (1-64, default 4), ``control_rate_hz`` (5-200, default 50), ``step_s``
    (the ROS2 step [s], a whole fraction of the control period, default 0.01), ``task``
    (:class:`GustAlleviationTask`; default the GTM task at this aircraft's cruise point), ``limits``
    (:class:`FlightLimits`; default derived from the aircraft about the nonlinear trim), ``perturbation``
    (:class:`InitialPerturbation`).

    ## Version History
    * v1: the geometrically nonlinear beams (v0 flies the linear structure beyond its range).
    """

    metadata = {"render_modes": []}
    env_id, max_episode_steps = "FlexSim/HALE-GustAlleviation-v1", 500

    def __init__(self, *, aircraft: str | Path | Aircraft = "phc_hale", elements_per_beam: int = 4,
                 control_rate_hz: float = 50.0, step_s: float = 0.01, task: GustAlleviationTask | None = None,
                 limits: FlightLimits | None = None, perturbation: InitialPerturbation | None = None) -> None:
        ac = aircraft if isinstance(aircraft, Aircraft) else load_aircraft(aircraft)
        if isinstance(control_rate_hz, bool) or not isinstance(control_rate_hz, (int, float)) \
                or not 5.0 <= control_rate_hz <= 200.0:
            raise ValueError(f"control_rate_hz = {control_rate_hz!r}: must be a rate in [5, 200] Hz")
        period = 1.0 / float(control_rate_hz)
        if isinstance(step_s, bool) or not isinstance(step_s, (int, float)) or not 0.0 < step_s <= period:
            raise ValueError(f"step_s = {step_s!r}: must be a step in (0, {period:g}] s (the control period)")
        steps = round(period / step_s)
        if abs(steps * step_s - period) > 1e-9 * period:
            raise ValueError(f"step_s = {step_s!r}: must divide the control period {period:g} s into whole steps")
        if task is not None and not isinstance(task, GustAlleviationTask):
            raise ValueError(f"task = {task!r}: must be a GustAlleviationTask")
        if limits is not None and not isinstance(limits, FlightLimits):
            raise ValueError(f"limits = {limits!r}: must be a FlightLimits")
        if perturbation is not None and not isinstance(perturbation, InitialPerturbation):
            raise ValueError(f"perturbation = {perturbation!r}: must be an InitialPerturbation")
        self.aircraft_source = ac.source
        self.model = AircraftModel(ac, terms=Terms(nonlinear_beams=NonlinearBeams(elements_per_beam)))
        self.task = task if task is not None else task_for_aircraft(GustAlleviationTask(), ac)
        self.point = trim(self.model, self.task.manoeuvre)
        flex = self.point.aircraft
        if "right_wing" not in flex.beam_components or "left_wing" not in flex.beam_components:
            raise ValueError(f"aircraft = {ac.name!r}: needs flexible right_wing and left_wing components")
        self._wings = [flex.beam_index(c) for c in ("right_wing", "left_wing")]
        self._fin = flex.beam_index("vtail") if "vtail" in flex.beam_components else None
        self._structure = flex.free_structure(self.model.terms.gravity_m_s2)
        self._lengths = flex.beam_lengths_m
        self._y_trim = self.point.state()
        self.stepper = FlexibleStepper.about(flex, self._structure, self._y_trim, self.point.controls,
                                             self.point.density_kg_m3, float(step_s))
        self._steps, self.control_period_s = int(steps), period
        trim_tips = self._tip_heights(self._y_trim)
        self.limits = limits if limits is not None else limits_about(ac, self.model.replace(nonlinear_beams=None),
                                                                      self.task, float(np.abs(trim_tips).max()))
        self.perturbation = perturbation if perturbation is not None else InitialPerturbation()
        lo, hi = ac.control_limits()
        self._u_scale = hi.copy()
        self.action_space = spaces.Box(np.array([0.0, -1.0, -1.0, -1.0], np.float32), np.ones(4, np.float32),
                                       dtype=np.float32)
        bounds = np.array([b for _, b, _ in OBSERVATION], np.float32)
        self.observation_space = spaces.Box(-bounds, bounds, dtype=np.float32)
        self._trim_ref = {"tip_m": float(trim_tips.mean()), "root_moment_n_m": float(self._root_moments(self._y_trim).mean()),
                          "theta_rad": self.point.theta_rad, "altitude_m": self.task.altitude_m,
                          "airspeed_m_s": float(np.linalg.norm(self.point.velocity_m_s))}
        self._y, self._episode_wind = None, None
        self._t = 0.0
        self._ended = False

    # ------------------------------------------------------------------ measurements of the state
    def _strains(self, y: np.ndarray) -> np.ndarray:
        return y[7:7 + self._structure.n_strains]

    def _tip_heights(self, y: np.ndarray) -> np.ndarray:
        """Each wing tip's height above its jig position, body axes (up +) [m], shape (2,)."""
        return self.point.aircraft.tip_heights_m(self._strains(y))[self._wings]

    def _root_moments(self, y: np.ndarray) -> np.ndarray:
        """Each wing's flapwise root bending moment EI_flap κ2 of its root element [N m], shape (2,)."""
        return self.point.aircraft.root_bending_moments_n_m(self._strains(y))[self._wings]

    def _measure(self, y: np.ndarray) -> tuple[dict, np.ndarray, str]:
        """Task errors, the observation (unclipped) and the termination reason ("" when flying) of state ``y``."""
        if not np.all(np.isfinite(y)):
            return {k: math.nan for k in ERRORS}, np.zeros(len(OBSERVATION)), "state not finite"
        ref, n = self._trim_ref, self._structure.n_strains
        phi, theta, _ = euler_321_of_quaternion(y[3:7])
        tips = self._tip_heights(y)
        altitude = -float(y[2])
        air = y[7 + n:10 + n] - body_wind(self._episode_wind, self._t, y)
        airspeed = float(np.linalg.norm(air))
        alpha = math.atan2(air[2], air[0])
        root = self._root_moments(y)
        errors = {"tip_deflection_increment_m": float(tips.mean()) - ref["tip_m"],
                  "root_moment_increment": (float(root.mean()) - ref["root_moment_n_m"])
                  / max(abs(ref["root_moment_n_m"]), 1.0),
                  "pitch_error_rad": theta - ref["theta_rad"], "roll_error_rad": phi,
                  "altitude_error_m": altitude - ref["altitude_m"]}
        obs = np.array([*errors.values(), airspeed - ref["airspeed_m_s"], alpha, *y[10 + n:13 + n], *self._action])
        lim = self.limits
        reason = ""
        if np.abs(tips).max() > lim.wing_tip_deflection_m:
            reason = "wing-tip deflection limit"
        elif self._fin is not None and abs(self._fin_twist(y)) > lim.fin_tip_twist_rad:
            reason = "fin tip twist limit"
        elif abs(theta) > lim.max_abs_pitch_rad:
            reason = "pitch limit"
        elif abs(alpha) > lim.max_abs_alpha_rad:
            reason = "angle-of-attack limit"
        elif airspeed < lim.min_airspeed_m_s:
            reason = "airspeed below the envelope"
        elif airspeed / speed_of_sound(max(altitude, 0.0)) > lim.max_mach:
            reason = "Mach limit"
        elif altitude <= 0.0:
            reason = "ground"
        return errors, obs, reason

    def _fin_twist(self, y: np.ndarray) -> float:
        return float(self.point.aircraft.tip_twists_rad(self._strains(y))[self._fin])

    def _observe(self, obs: np.ndarray) -> np.ndarray:
        return np.clip(obs, self.observation_space.low, self.observation_space.high).astype(np.float32)

    # ------------------------------------------------------------------ gymnasium API
    def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple[np.ndarray, dict]:
        if options:
            raise ValueError(f"options = {options!r}: {self.env_id} takes no reset options")
        super().reset(seed=seed)
        rng, pert, task = self.np_random, self.perturbation, self.task
        y = self._y_trim.copy()
        n = self._structure.n_strains
        d_phi, d_theta = rng.uniform(-pert.attitude_rad, pert.attitude_rad, 2)
        d_psi = rng.uniform(-pert.heading_rad, pert.heading_rad)
        y[3:7] = euler_quaternion(self.point.phi_rad + d_phi, self.point.theta_rad + d_theta,
                                  self.point.heading_offset_rad + d_psi)
        y[10 + n:13 + n] += rng.uniform(-pert.body_rate_rad_s, pert.body_rate_rad_s, 3)
        y[7 + n] += rng.uniform(-pert.airspeed_m_s, pert.airspeed_m_s)
        y[2] -= rng.uniform(-pert.altitude_m, pert.altitude_m)
        amplitude = float(rng.uniform(*task.gust_amplitude_range_m_s)) * (1.0 if rng.random() < 0.5 else -1.0)
        length = float(rng.uniform(*task.gust_length_range_m))
        start = float(rng.uniform(*task.gust_start_range_s))
        velocity_ned = quaternion_matrix(y[3:7]) @ y[7 + n:10 + n]
        self._episode_wind = OneMinusCosineGust.encounter(amplitude, length, position_ned_m=y[:3],
                                                          velocity_ned_m_s=velocity_ned, start_time_s=start)
        self._y, self._t, self._ended = y, 0.0, False
        self._u = self.point.controls.copy()
        self._action = np.divide(self._u, self._u_scale, out=np.zeros(4), where=self._u_scale > 0)
        _, obs, _ = self._measure(y)
        info = {"time_s": 0.0, "trim_action": self._action.astype(np.float32),
                "reference": {"gust_amplitude_m_s": amplitude, "gust_length_m": length, "gust_start_s": start,
                              "tip_deflection_fraction": float(self.point.tip_deflection_fraction[self._wings].mean())}}
        return self._observe(obs), info

    def step(self, action) -> tuple[np.ndarray, float, bool, bool, dict]:
        if self._y is None:
            raise RuntimeError("step() called before reset()")
        if self._ended:
            raise RuntimeError("step() called after the episode terminated; call reset()")
        a = np.asarray(action, dtype=np.float64)
        if a.shape != (4,) or not np.all(np.isfinite(a)):
            raise ValueError(f"action = {action!r}: must be 4 finite numbers [thrust, aileron, elevator, rudder]")
        clipped = np.clip(a, self.action_space.low, self.action_space.high)
        change = clipped - self._action
        self._action, self._u = clipped, clipped * self._u_scale
        with np.errstate(all="ignore"):
            self._y = self.stepper.advance(self._t, self._y, self._u, self._episode_wind, self._steps)
        self._t += self.control_period_s
        errors, obs, reason = self._measure(self._y)
        terminated = bool(reason)
        self._ended = terminated
        parts = self.task.reward.parts(errors, change, terminated)
        reward = self.task.reward.total(parts)
        info = {"time_s": self._t, "reward_parts": parts, "termination_reason": reason or None,
                "action_clipped": bool((clipped != a).any())}
        return self._observe(obs), float(reward), terminated, False, info

    def task_label(self) -> str:
        return "HALE gust (nonlinear beams)"
