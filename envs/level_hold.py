"""FlexSim/GTM-LevelHold-v0: hold altitude, airspeed and heading in turbulence."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexsim.trim import SteadyManoeuvre

from flexsim.envs.base import Episode, FlexSimEnv, shared_docs
from flexsim.envs.config import RewardTerm, TrackingReward
from flexsim.envs.dynamics import Measurements
from flexsim.envs.episodes import perturbed_state, turbulence_field, wrap_angle

__all__ = ["LevelHoldTask", "LevelHoldEnv"]


@dataclass(frozen=True)
class LevelHoldTask:
    """Parameters of the level-hold task.

    Attributes
    ----------
    altitude_m : float
        Trim (and target) altitude [m] (default 9144 m, 30 000 ft, the paper's cruise).
    mach : float
        Trim (and target) Mach number [-] (default 0.75).
    reward : TrackingReward
        Costs on ``altitude_error_m`` (weight 0.35, saturating at 30 m), ``airspeed_error_m_s`` (0.25, 5 m/s),
        ``heading_error_rad`` (0.25, 5 deg); control rate 0.15; alive bonus 1; termination penalty 100.
    """

    altitude_m: float = 9144.0
    mach: float = 0.75
    reward: TrackingReward = TrackingReward(
        terms=(RewardTerm("altitude_error_m", 0.35, 30.0), RewardTerm("airspeed_error_m_s", 0.25, 5.0),
               RewardTerm("heading_error_rad", 0.25, math.radians(5.0))),
        control_rate_weight=0.15)

    def __post_init__(self) -> None:
        SteadyManoeuvre.level(self.altitude_m, mach=self.mach)  # validates altitude (ISA range) and Mach in (0, 1)
        if not self.altitude_m > 0.0:
            raise ValueError(f"altitude_m = {self.altitude_m!r}: must be > 0 m (altitude <= 0 is a crash)")

    @property
    def manoeuvre(self) -> SteadyManoeuvre:
        """The trimmed level flight."""
        return SteadyManoeuvre.level(self.altitude_m, mach=self.mach)


@shared_docs
class LevelHoldEnv(FlexSimEnv):
    """
    ## Description
    The flexible notional GTM (Tuzcu & Nguyen, *Flutter of Maneuvering Aircraft*: six beams in bending
    and torsion, six rigid-body DOFs, finite-state unsteady strip aerodynamics) starts near its trim in
    level flight at 9144 m and Mach 0.75 and must hold that altitude, airspeed and its initial heading
    through Dryden turbulence (MIL-F-8785C, light by default). Every step integrates the one nonlinear
    model ``AircraftModel.rhs`` over the control period with the controls held (zero-order hold) after
    actuator rate limits.

    ## Action Space
    <action space>

    ## Observation Space
    ``Box(29,)`` float32 with finite bounds; values are clipped to them (and NaN replaced by 0), so
    observations stay finite even at termination. ``env.observation_structure`` maps block names to
    slices, ``env.observation_names`` names every entry.

    <observation rows 0-9>
    | 10    | altitude error h - h_ref                           | -5000  | 5000  | m      |
    | 11    | airspeed error V - V_ref                           | -300   | 300   | m/s    |
    | 12    | heading error psi - psi_ref (wrapped)              | -pi    | pi    | rad    |
    | 13-24 | right wing, left wing, fin tips: deflection [m], deflection rate [m/s], twist [rad], twist rate [rad/s] | +-50, +-500, +-pi, +-1000 | | |
    | 25-28 | applied controls, normalised like the action       | 0/-1   | 1     | -      |

    ## Rewards
    Per step (``TrackingReward``; the parts are in ``info["reward_parts"]`` and sum exactly to the reward):
    ``alive`` +1; ``altitude_error_m`` -0.35 min((e/30 m)^2, 1); ``airspeed_error_m_s`` -0.25 min((e/5 m/s)^2, 1);
    ``heading_error_rad`` -0.25 min((e/5 deg)^2, 1); ``control_rate`` -0.15 min(mean((da/0.1)^2), 1) with da the
    change of the normalised action; ``termination`` -100 on a terminating step. Per-step reward in [-100.15, 1].

    ## Starting State
    The trim of level flight at (``task.altitude_m``, ``task.mach``) plus uniform perturbations
    (``InitialPerturbation``: roll/pitch +-0.01 rad, heading +-0.01 rad, body rates +-0.005 rad/s, speed
    +-1 m/s, altitude +-5 m); a new turbulence realisation per episode. All randomness comes from
    ``self.np_random`` (seeded by ``reset(seed=...)``).

    ## Episode End
    ### Termination
    ``info["termination_reason"]``: ``"crash"`` (altitude <= 0), ``"structural_limit"`` (|wing tip
    deflection| > 5.5 m or |fin tip twist| > 0.1 rad), ``"non_finite"`` (non-finite state or solver
    failure, e.g. a flutter blow-up), ``"gimbal_lock"`` (|theta| >= 85 deg), ``"envelope"`` (Mach >= 0.95,
    |alpha| >= 25 deg or airspeed <= 60 m/s). Bounds: ``FlightLimits``.
    ### Truncation
    ``TimeLimit`` at ``max_episode_steps`` = 1000 (20 s at 50 Hz).

    ## Arguments
    ``gymnasium.make("FlexSim/GTM-LevelHold-v0", aircraft="gtm", aero="unsteady", control_rate_hz=50.0,
    turbulence="light", render_mode=None, task=LevelHoldTask(), integrator=IntegratorSettings(),
    actuator_rates=ActuatorRates(), limits=FlightLimits(), perturbation=InitialPerturbation())``.
    ``turbulence`` is one of "none", "light", "moderate", "severe"; ``aero="quasi-steady"`` is cheaper but
    the quasi-steady GTM flutters at this condition (wing torsion, growth about 0.2 1/s); ``render_mode``
    "rgb_array" (matplotlib image) or "human" (Rerun viewer, spawned on the first frame).

    ## Version History
    <v0 history>
    """

    task_type = LevelHoldTask
    default_turbulence = "light"
    task_errors_spec = (("altitude_error_m", 5000.0), ("airspeed_error_m_s", 300.0), ("heading_error_rad", math.pi))

    def _new_episode(self, rng: np.random.Generator) -> Episode:
        manoeuvre = self.task.manoeuvre
        point = self.dynamics.trim(manoeuvre)
        x0 = perturbed_state(point.x, self.dynamics.layout, rng, self.perturbation)
        wind = turbulence_field(self.turbulence, self.task.altitude_m, x0[self.dynamics.layout.position], 0.0, rng)
        reference = {"altitude_m": self.task.altitude_m, "airspeed_m_s": manoeuvre.speed_m_s, "heading_rad": 0.0}
        return Episode(manoeuvre, x0, wind, reference)

    def _task_errors(self, meas: Measurements) -> dict[str, float]:
        ref = self._reference
        return {"altitude_error_m": meas.altitude_m - ref["altitude_m"],
                "airspeed_error_m_s": meas.airspeed_m_s - ref["airspeed_m_s"],
                "heading_error_rad": wrap_angle(float(meas.euler_rad[2]) - ref["heading_rad"])}

    def task_label(self) -> str:
        return "GTM level hold"
