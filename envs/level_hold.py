"""FlexSim/GTM-LevelHold-v0: hold altitude, airspeed and heading in turbulence; v1: capture them from an offset
start under a tighter reward (v0's reward barely tells the trim controls held from a controller)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexsim.trimming import SteadyManoeuvre

from flexsim.envs.base import Episode, FlexSimEnv, shared_docs
from flexsim.envs.config import InitialPerturbation, RewardTerm, TrackingReward
from flexsim.envs.row_kernels import wrap_rows
from flexsim.sim.measurements import MeasurementBatch
from flexsim.sim.initial_states import perturbed_state, turbulence_field

__all__ = ["LevelHoldTask", "LevelHoldEnv", "LevelHoldCaptureEnv", "CAPTURE_REWARD", "CAPTURE_PERTURBATION"]


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
    <observation>

    ## Rewards
    <rewards>

    ## Starting State
    The trim of level flight at (``task.altitude_m``, ``task.mach``) plus uniform perturbations
    (``InitialPerturbation``: roll/pitch +-0.01 rad, heading +-0.01 rad, body rates +-0.005 rad/s, speed
    +-1 m/s, altitude +-5 m); a new turbulence realisation per episode. All randomness comes from
    ``self.np_random`` (seeded by ``reset(seed=...)``).

    ## Episode End
    <termination>
    <truncation>

    ## Arguments
    <arguments>
    ``aero="quasi-steady"`` is cheaper but the quasi-steady GTM flutters at this condition (wing torsion, growth
    about 0.2 1/s).

    ## Version History
    * v1: ``FlexSim/GTM-LevelHold-v1`` (:class:`LevelHoldCaptureEnv`): starts up to 30 m and 3 deg off the
      references and rewards them more tightly; v0 unchanged.
    <v0 history>
    """

    task_type = LevelHoldTask
    default_turbulence = "light"
    env_id, max_episode_steps = "FlexSim/GTM-LevelHold-v0", 1000
    task_errors_spec = (("altitude_error_m", 5000.0, "altitude error h - h_ref"),
                        ("airspeed_error_m_s", 300.0, "airspeed error V - V_ref"),
                        ("heading_error_rad", math.pi, "heading error psi - psi_ref (wrapped)"))

    def _new_episode(self, rng: np.random.Generator) -> Episode:
        manoeuvre = self.task.manoeuvre
        point = self.dynamics.trim(manoeuvre)
        x0 = perturbed_state(point.x, self.dynamics.layout, rng, self.perturbation)
        wind = turbulence_field(self.turbulence, self.task.altitude_m, x0[self.dynamics.layout.position], 0.0, rng)
        reference = {"altitude_m": self.task.altitude_m, "airspeed_m_s": manoeuvre.speed_m_s, "heading_rad": 0.0}
        return Episode(manoeuvre, x0, wind, reference)

    def _task_errors(self, meas: MeasurementBatch, ref: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        return {"altitude_error_m": meas.altitude_m - ref["altitude_m"],
                "airspeed_error_m_s": meas.airspeed_m_s - ref["airspeed_m_s"],
                "heading_error_rad": wrap_rows(meas.euler_rad[:, 2] - ref["heading_rad"])}

    def task_label(self) -> str:
        return "GTM level hold"


#: The reward of ``FlexSim/GTM-LevelHold-v1``: altitude (weight 0.4, saturating at 10 m), airspeed (0.1, 5 m/s),
#: heading (0.35, 2 deg), control rate 0.15 (the weights sum to 1 as v0's, so a flying step earns 0 to 1).
CAPTURE_REWARD = TrackingReward(
    terms=(RewardTerm("altitude_error_m", 0.4, 10.0), RewardTerm("airspeed_error_m_s", 0.1, 5.0),
           RewardTerm("heading_error_rad", 0.35, math.radians(2.0))),
    control_rate_weight=0.15)
#: The start of ``FlexSim/GTM-LevelHold-v1``: v0's perturbation with altitude +-30 m and heading +-3 deg.
CAPTURE_PERTURBATION = InitialPerturbation(altitude_m=30.0, heading_rad=math.radians(3.0))


@shared_docs
class LevelHoldCaptureEnv(LevelHoldEnv):
    """
    ## Description
    ``FlexSim/GTM-LevelHold-v0`` (:class:`LevelHoldEnv`: the flexible notional GTM in level flight at 9144 m
    and Mach 0.75, light Dryden turbulence, 20 s at 50 Hz) with two changes that make it a task on which a
    controller visibly beats the trim controls held (the reason for v1):

    * the aircraft starts up to **30 m** off the reference altitude and **3 deg** off the reference heading
      (``CAPTURE_PERTURBATION``; v0: 5 m, 0.57 deg), so it must capture them: held trim controls correct
      neither (heading is neutrally stable and the altitude wanders with the phugoid);
    * the reward saturates at **10 m**, 5 m/s and **2 deg** (``CAPTURE_REWARD``; v0: 30 m, 5 m/s, 5 deg) with
      weights **0.4** (altitude), **0.1** (airspeed), **0.35** (heading) (v0: 0.35, 0.25, 0.25); control rate
      0.15 as v0. The airspeed weight is small because the airspeed is measured against the air, which the
      gusts move: no controller removes that error (the LQR baseline's airspeed error is as large as the trim
      hold's: 0.35-0.79 against 0.40-0.64 m/s rms on seeds 0-2 of v0 in light turbulence).

    On seeds 0-9 (docs/environments.md) the trim controls held return about half of the LQR baseline's
    return (v0: 93 %), so what a learned controller adds is visible in its return.

    ## Action Space
    <action space>

    ## Observation Space
    <observation>

    ## Rewards
    <rewards>

    ## Starting State
    The trim of level flight at (``task.altitude_m``, ``task.mach``) plus uniform perturbations
    (``CAPTURE_PERTURBATION``: altitude +-30 m, heading +-3 deg, roll/pitch +-0.01 rad, body rates
    +-0.005 rad/s, speed +-1 m/s); the references are the trim's altitude and airspeed and heading 0.

    ## Episode End
    <termination>
    <truncation>

    ## Arguments
    As ``FlexSim/GTM-LevelHold-v0``; ``task`` defaults to ``LevelHoldTask(reward=CAPTURE_REWARD)`` and
    ``perturbation`` to ``CAPTURE_PERTURBATION``.

    ## Version History
    * v1: this task: offset start and tighter reward; v0 unchanged.
    * v0: see ``FlexSim/GTM-LevelHold-v0`` (:class:`LevelHoldEnv`).
    """

    env_id = "FlexSim/GTM-LevelHold-v1"
    default_task = LevelHoldTask(reward=CAPTURE_REWARD)
    default_perturbation = CAPTURE_PERTURBATION

    def task_label(self) -> str:
        return "GTM level capture and hold"
