"""FlexSim/GTM-Turn-v0: enter and hold a level turn of commanded radius."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexsim.model.aircraft_model import STANDARD_GRAVITY
from flexsim.trimming import SteadyManoeuvre

from flexsim.envs.base import Episode, FlexSimEnv, shared_docs
from flexsim.envs.config import RewardTerm, TrackingReward
from flexsim.sim.measurements import MeasurementBatch
from flexsim.sim.initial_states import perturbed_state, turbulence_field

__all__ = ["TurnTask", "TurnEnv"]


#: Steepest bank of a commanded turn [rad]: 60 deg, load factor 2 (transport category manoeuvring load factors are
#: 2.5 and above, 14 CFR 25.337, so a level turn of the task stays inside them).
MAX_BANK_RAD = math.radians(60.0)


@dataclass(frozen=True)
class TurnTask:
    """Parameters of the turn task.

    Attributes
    ----------
    altitude_m : float
        Altitude of the initial level flight and of the turn [m] (default 9144 m).
    mach : float
        Mach number of both [-] (default 0.75).
    radius_range_m : tuple of float
        The commanded radius |R| is drawn uniformly from this range [m] (default 7000-12000 m: bank 26 to
        41 deg on the GTM at M 0.75), the direction (right R > 0, left R < 0) with probability 1/2 each.
    reward : TrackingReward
        Costs on ``turn_rate_error_rad_s`` (weight 0.4, saturating at 0.005 rad/s), ``altitude_error_m`` (0.2,
        30 m), ``airspeed_error_m_s`` (0.15, 5 m/s), ``sideslip_error_rad`` (0.1, 0.02 rad); control rate 0.15.
    """

    altitude_m: float = 9144.0
    mach: float = 0.75
    radius_range_m: tuple[float, float] = (7000.0, 12000.0)
    reward: TrackingReward = TrackingReward(
        terms=(RewardTerm("turn_rate_error_rad_s", 0.4, 0.005), RewardTerm("altitude_error_m", 0.2, 30.0),
               RewardTerm("airspeed_error_m_s", 0.15, 5.0), RewardTerm("sideslip_error_rad", 0.1, 0.02)),
        control_rate_weight=0.15)

    def __post_init__(self) -> None:
        SteadyManoeuvre.level(self.altitude_m, mach=self.mach)
        if not self.altitude_m > 0.0:
            raise ValueError(f"altitude_m = {self.altitude_m!r}: must be > 0 m (altitude <= 0 is a crash)")
        lo, hi = (float(v) for v in self.radius_range_m)
        speed = self.manoeuvre.speed_m_s
        r_min = speed**2 / (STANDARD_GRAVITY * math.tan(MAX_BANK_RAD))  # tan(mu) = V^2 / (g R)
        if not r_min <= lo <= hi < math.inf:
            raise ValueError(f"radius_range_m = {self.radius_range_m!r}: must be (lo, hi) with {r_min:.4g} m <= lo <= hi < inf "
                             f"(a level turn at V = {speed:.4g} m/s banks at most {math.degrees(MAX_BANK_RAD):g} deg)")
        object.__setattr__(self, "radius_range_m", (lo, hi))

    @property
    def manoeuvre(self) -> SteadyManoeuvre:
        """The level flight the episode starts from."""
        return SteadyManoeuvre.level(self.altitude_m, mach=self.mach)

    def turn(self, radius_m: float) -> SteadyManoeuvre:
        """The commanded steady level turn of radius ``radius_m`` [m] (> 0 right)."""
        return SteadyManoeuvre.turn(self.altitude_m, radius_m, mach=self.mach)


@shared_docs
class TurnEnv(FlexSimEnv):
    """
    ## Description
    The flexible notional GTM (see ``FlexSim/GTM-LevelHold-v0``) starts near its trim in level flight at
    9144 m and Mach 0.75 and must enter and hold a steady level turn of a commanded radius R (drawn per
    episode): heading rate psi_dot = V / R at constant altitude and airspeed, with the sideslip of the steady turn.
    The steady turn is a trim of the same model (paper eqs. 36-37): bank about 37 deg for R = 8000 m.
    That trim puts the velocity along the heading (psi = track), so its body-axis sideslip is
    asin(sin(phi) sin(theta)) (about +5.3 deg at R = +8000 m, -5.3 deg at R = -8000 m), held with about 6.4 deg
    of rudder; the rewarded sideslip error is measured from this trimmed sideslip.
    Still air by default (Dryden turbulence is frozen along a straight line, so it is not a natural
    companion of a turn; it can still be switched on).

    ## Action Space
    <action space>

    ## Observation Space
    <observation>

    ## Rewards
    <rewards>

    ## Starting State
    Perturbed level trim (``InitialPerturbation``); the commanded radius |R| ~ U(``task.radius_range_m``)
    and its sign ~ U{-1, +1} from ``self.np_random``. ``info["reference"]`` at reset holds R, the commanded
    turn rate and the trim of the steady turn (bank, pitch, sideslip, normalised controls).

    ## Episode End
    <termination>
    <truncation>

    ## Arguments
    <arguments>

    ## Version History
    <v0 history>
    """

    task_type = TurnTask
    default_turbulence = "none"
    env_id, max_episode_steps = "FlexSim/GTM-Turn-v0", 1000
    task_errors_spec = (("turn_rate_error_rad_s", 1.0, "turn-rate error psi_dot - V_ref / R"),
                        ("turn_rate_command_rad_s", 1.0, "commanded turn rate V_ref / R (> 0 right)"),
                        ("altitude_error_m", 5000.0, "altitude error"), ("airspeed_error_m_s", 300.0, "airspeed error"),
                        ("sideslip_error_rad", math.pi / 2, "sideslip error beta - beta_turn_trim"))

    def _new_episode(self, rng: np.random.Generator) -> Episode:
        manoeuvre = self.task.manoeuvre
        point = self.dynamics.trim(manoeuvre)
        x0 = perturbed_state(point.x, self.dynamics.layout, rng, self.perturbation)
        lo, hi = self.task.radius_range_m
        radius = float(rng.uniform(lo, hi)) * (1.0 if rng.random() < 0.5 else -1.0)
        turn = self.task.turn(radius)
        turn_trim = self.dynamics.trim(turn)
        wind = turbulence_field(self.turbulence, self.task.altitude_m, x0[self.dynamics.layout.position], 0.0, rng)
        action = self.controls_to_action(turn_trim.u)
        reference = {"altitude_m": self.task.altitude_m, "airspeed_m_s": manoeuvre.speed_m_s, "radius_m": radius,
                     "turn_rate_rad_s": turn.turn_rate(0.0), "turn_bank_rad": turn_trim.phi, "turn_pitch_rad": turn_trim.theta,
                     "turn_sideslip_rad": turn_trim.beta,
                     "turn_thrust_fraction": float(action[0]), "turn_aileron_fraction": float(action[1]),
                     "turn_elevator_fraction": float(action[2]), "turn_rudder_fraction": float(action[3])}
        return Episode(manoeuvre, x0, wind, reference)

    def _task_errors(self, meas: MeasurementBatch, ref: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        return {"turn_rate_error_rad_s": meas.heading_rate_rad_s - ref["turn_rate_rad_s"],
                "turn_rate_command_rad_s": ref["turn_rate_rad_s"].copy(),
                "altitude_error_m": meas.altitude_m - ref["altitude_m"],
                "airspeed_error_m_s": meas.airspeed_m_s - ref["airspeed_m_s"],
                "sideslip_error_rad": meas.beta_rad - ref["turn_sideslip_rad"]}

    def task_label(self) -> str:
        return f"GTM turn R = {self._reference.get('radius_m', math.nan):.0f} m"
