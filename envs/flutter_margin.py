"""FlexSim/GTM-FlutterMargin-v0 and -v1: fly just beyond the open-loop flutter speed and keep the structure stable.

v0 (:class:`FlutterMarginEnv`): fin flutter of ``gtm_uncalibrated``; v1 (:class:`WingFlutterMarginEnv`):
antisymmetric wing flutter of the calibrated ``gtm``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flexsim.aircraft.definition import Aircraft
from flexsim.linear.flutter import FlutterCondition, flutter_condition
from flexsim.trimming import SteadyManoeuvre

from flexsim.envs.base import TERMINATION_CODES, Episode, FlexSimEnv, shared_docs
from flexsim.envs.config import FLUTTER_MAX_STEP_S, RewardTerm, TrackingReward
from flexsim.sim.measurements import MeasurementBatch
from flexsim.sim.initial_states import perturbed_state, turbulence_field

__all__ = ["FlutterMarginTask", "WingFlutterMarginTask", "FlutterMarginEnv", "WingFlutterMarginEnv", "FlutterCondition",
           "flutter_condition", "SUBJECTS"]

#: Structural subjects of the task: the rewarded tip twist rate and the seeded first-torsion rate.
SUBJECTS = ("fin", "wing_antisymmetric")


def _flutter_reward(rate_error: str, rate_scale: float) -> TrackingReward:
    """The flutter-margin reward: ``rate_error`` (weight 0.3, saturating at ``rate_scale``), flutter-speed
    deficit (0.2, 1 m/s), airspeed error (0.15, 3 m/s), altitude error (0.15, 15 m); control rate 0.1."""
    return TrackingReward(
        terms=(RewardTerm(rate_error, 0.3, rate_scale), RewardTerm("flutter_speed_deficit_m_s", 0.2, 1.0),
               RewardTerm("airspeed_error_m_s", 0.15, 3.0), RewardTerm("altitude_error_m", 0.15, 15.0)),
        control_rate_weight=0.1)


@dataclass(frozen=True)
class FlutterMarginTask:
    """Parameters of the flutter-margin task.

    Attributes
    ----------
    altitude_m : float
        Flight altitude [m] (default 300 m: sea-level conditions with room above the ground, where
        altitude <= 0 ends the episode).
    mach_margin : float
        The target Mach number is the open-loop flutter Mach plus this margin [-] (default 0.01).
    flutter_mach_range : tuple of float
        Mach range searched for the flutter point (default 0.8-0.95).
    fin_twist_rate_range_rad_s : tuple of float
        |initial fin-torsion rate| ~ U(range) [rad/s], random sign (default 0.3-0.6 rad/s): seeds the
        flutter mode (``subject="fin"``).
    subject : str
        ``"fin"`` (default, v0): the rewarded error ``fin_twist_rate_rad_s`` is the fin tip twist rate and
        the episode is seeded with a fin first-torsion rate. ``"wing_antisymmetric"`` (v1): the rewarded
        error ``wing_twist_rate_rad_s`` is the antisymmetric wing tip twist rate 0.5 (psi_R' + psi_L') of
        the torsion coordinates (a positive coordinate is nose-up on the right wing and nose-down on the
        left one, ``docs/conventions.md``, so equal coordinates are the antisymmetric twist) and both wing
        halves get the same first-torsion rate.
    wing_twist_rate_range_rad_s : tuple of float
        |initial antisymmetric wing first-torsion rate| ~ U(range) [rad/s], random sign
        (``subject="wing_antisymmetric"``; default 0.05-0.1 rad/s).
    wing_tip_twist_limit_rad : float
        Structural limit on |tip twist| of either wing half [rad] (default inf: none; v1 0.1 rad), on top
        of ``FlightLimits``.
    reward : TrackingReward
        Costs on ``fin_twist_rate_rad_s`` (weight 0.3, saturating at 0.5 rad/s), ``flutter_speed_deficit_m_s``
        (0.2, 1 m/s below the flutter speed), ``airspeed_error_m_s`` (0.15, 3 m/s), ``altitude_error_m`` (0.15,
        15 m); control rate 0.1.
    """

    altitude_m: float = 300.0
    mach_margin: float = 0.01
    flutter_mach_range: tuple[float, float] = (0.8, 0.95)
    fin_twist_rate_range_rad_s: tuple[float, float] = (0.3, 0.6)
    reward: TrackingReward = _flutter_reward("fin_twist_rate_rad_s", 0.5)
    subject: str = "fin"
    wing_twist_rate_range_rad_s: tuple[float, float] = (0.05, 0.1)
    wing_tip_twist_limit_rad: float = math.inf

    def __post_init__(self) -> None:
        if self.subject not in SUBJECTS:
            raise ValueError(f"subject = {self.subject!r}: must be one of {', '.join(SUBJECTS)}")
        if not self.wing_tip_twist_limit_rad > 0.0:
            raise ValueError(f"wing_tip_twist_limit_rad = {self.wing_tip_twist_limit_rad!r}: must be > 0 rad")
        SteadyManoeuvre.level(self.altitude_m, mach=0.5)
        if not self.altitude_m > 0.0:
            raise ValueError(f"altitude_m = {self.altitude_m!r}: must be > 0 m (altitude <= 0 is a crash)")
        if not 0.0 <= self.mach_margin <= 0.05:
            raise ValueError(f"mach_margin = {self.mach_margin!r}: must be in [0, 0.05]")
        lo, hi = (float(v) for v in self.flutter_mach_range)
        if not 0.0 < lo < hi < 1.0:
            raise ValueError(f"flutter_mach_range = {self.flutter_mach_range!r}: must satisfy 0 < lo < hi < 1")
        object.__setattr__(self, "flutter_mach_range", (lo, hi))
        for name in ("fin_twist_rate_range_rad_s", "wing_twist_rate_range_rad_s"):
            value = getattr(self, name)
            a, b = (float(v) for v in value)
            if not 0.0 <= a <= b <= 10.0:
                raise ValueError(f"{name} = {value!r}: must be (lo, hi), 0 <= lo <= hi <= 10 rad/s")
            object.__setattr__(self, name, (a, b))

    @property
    def rate_error(self) -> str:
        """Name of the rewarded structural error (the first task error)."""
        return "fin_twist_rate_rad_s" if self.subject == "fin" else "wing_twist_rate_rad_s"


@dataclass(frozen=True)
class WingFlutterMarginTask(FlutterMarginTask):
    """The v1 flutter-margin task: antisymmetric wing flutter of the calibrated GTM.

    As :class:`FlutterMarginTask` with ``subject="wing_antisymmetric"``, ``flutter_mach_range`` 0.5-0.95,
    ``wing_tip_twist_limit_rad`` 0.1 rad and the reward's first term on ``wing_twist_rate_rad_s``
    (weight 0.3, saturating at 0.2 rad/s).
    """

    flutter_mach_range: tuple[float, float] = (0.5, 0.95)
    reward: TrackingReward = _flutter_reward("wing_twist_rate_rad_s", 0.2)
    subject: str = "wing_antisymmetric"
    wing_tip_twist_limit_rad: float = 0.1


@shared_docs
class FlutterMarginEnv(FlexSimEnv):
    """
    ## Description
    The flexible notional GTM flies level at 300 m (sea-level conditions) slightly beyond its open-loop
    flutter speed: at the flutter Mach number found by ``flexsim.linear.flutter.FlutterAnalysis`` with the
    env's aerodynamic model, plus ``task.mach_margin`` (0.01). v0 flies the **uncalibrated** notional GTM
    (``aircraft="gtm_uncalibrated"``, the default of this env only): the task was designed for its fin
    flutter. (The calibrated default GTM, ``docs/calibration.md``, flutters first in an antisymmetric
    37 rad/s wing-torsion mode at M 0.69 at 300 m: ``FlexSim/GTM-FlutterMargin-v1``.)
    With the finite-state model the flutter point is M 0.887 (179 rad/s = 28.5 Hz) at 300 m
    (M 0.885 at sea level): a **fin bending-torsion mode**, dominated by the
    vertical stabilizer's first torsion mode coupled with its first bending mode and the horizontal
    stabilizers' symmetric bending; at M_f + 0.01 it grows at about 0.2 1/s. Hold the speed above the
    flutter speed, altitude, and keep the fin from diverging (the rudder is the fin's control surface).
    The flutter mode is above the Nyquist frequency of the default 50 Hz control rate (25 Hz); a
    sampled rudder feedback can still damp it (see ``FlutterPidDamper`` in ``examples/agents/baselines.py``).

    ## Action Space
    <action space>

    ## Observation Space
    <observation>

    ## Rewards
    <rewards>
    A fin tip twist beyond 0.1 rad is a structural failure.

    ## Starting State
    Trim at the target Mach number, perturbed (``InitialPerturbation``) and with a fin first-torsion rate
    of random sign and magnitude ``task.fin_twist_rate_range_rad_s`` (``self.np_random``).
    ``info["reference"]`` at reset reports the flutter point and the target.

    ## Episode End
    <termination>
    The structural limit reached here is mostly the fin twist.
    <truncation>

    ## Arguments
    <arguments>
    The flutter search (about 2 s) runs once per process and aircraft file. With ``aero="quasi-steady"``
    the GTM is already unstable at M 0.8 at 300 m, and construction raises ``ValueError``. The default
    integrator, ETD2RK with 5 ms steps (``IntegratorSettings(max_step_s=FLUTTER_MAX_STEP_S)``, where LevelHold and
    Turn step 20 ms and GustAlleviation 10 ms), keeps the flutter mode's growth: the fin tip twist amplitude after 5 s open loop is
    within 1 % of a DOP853 rtol 1e-10 reference (10 ms: 2.9 % low); Radau at the default tolerances damps
    the mode numerically (amplitude 22 % low).

    ## Version History
    * v0: initial version; default aircraft pinned to ``gtm_uncalibrated`` when the bundled ``gtm`` became the
      calibrated aircraft, so that the task keeps its fin-flutter mode;
      default integrator ETD2RK (5 ms steps) instead of DOP853, same trajectories to within the
      integration error, about 10 times faster (622 against 64 steps/s open loop, docs/environments.md).
    """

    task_type = FlutterMarginTask
    default_turbulence = "none"
    env_id, max_episode_steps = "FlexSim/GTM-FlutterMargin-v0", 1000
    task_errors_spec = (("fin_twist_rate_rad_s", 1000.0, "fin tip twist rate (the rewarded structural error)"),
                        ("flutter_speed_deficit_m_s", 600.0, "flutter-speed deficit max(0, V_f - V)"),
                        ("airspeed_error_m_s", 300.0, "airspeed error V - V_target"),
                        ("altitude_error_m", 5000.0, "altitude error"),
                        ("flutter_margin_m_s", 600.0, "flutter margin V - V_f"))

    default_max_step_s = FLUTTER_MAX_STEP_S  # the flutter mode's growth within about 1 % after 5 s

    def __init__(self, *, aircraft: str | Path | Aircraft = "gtm_uncalibrated", **kwargs) -> None:
        super().__init__(aircraft=aircraft, **kwargs)
        task = self.task
        if task.rate_error != self.task_errors_spec[0][0]:
            raise ValueError(f"task.subject = {task.subject!r}: {type(self).__name__} observes {self.task_errors_spec[0][0]}, "
                             f"not {task.rate_error} (use {'FlutterMarginEnv' if task.subject == 'fin' else 'WingFlutterMarginEnv'})")
        self.flutter = flutter_condition(self.dynamics.model, self.dynamics.aero, task.altitude_m, task.flutter_mach_range)
        self.target = SteadyManoeuvre.level(task.altitude_m, mach=self.flutter.mach + task.mach_margin)
        names = ("vtail",) if task.subject == "fin" else ("right_wing", "left_wing")
        dofs, lay = self.dynamics.model.structure.dofs, self.dynamics.layout
        for name in names:
            if dofs.torsion[name].stop == dofs.torsion[name].start:
                raise ValueError(f"aircraft {self.aircraft.name!r}: {name} needs at least one torsion mode for this task")
        self._seed_eta = [lay.eta.start + dofs.torsion[name].start for name in names]
        self._rate_range = task.fin_twist_rate_range_rad_s if task.subject == "fin" else task.wing_twist_rate_range_rad_s

    def _new_episode(self, rng: np.random.Generator) -> Episode:
        point = self.dynamics.trim(self.target)
        x0 = perturbed_state(point.x, self.dynamics.layout, rng, self.perturbation)
        lo, hi = self._rate_range
        rate = float(rng.uniform(lo, hi)) * (1.0 if rng.random() < 0.5 else -1.0)
        for i in self._seed_eta:
            x0[i] += rate
        wind = turbulence_field(self.turbulence, self.task.altitude_m, x0[self.dynamics.layout.position], 0.0, rng)
        reference = {"altitude_m": self.task.altitude_m, "airspeed_m_s": self.target.speed_m_s, "target_mach": self.target.mach,
                     "flutter_mach": self.flutter.mach, "flutter_speed_m_s": self.flutter.speed_m_s,
                     "flutter_frequency_rad_s": self.flutter.frequency_rad_s}
        return Episode(self.target, x0, wind, reference)

    def _task_errors(self, meas: MeasurementBatch, ref: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        margin = meas.airspeed_m_s - ref["flutter_speed_m_s"]
        rates = meas.tip_twist_rate_rad_s
        rate = rates["vtail"] if self.task.subject == "fin" else 0.5 * (rates["right_wing"] + rates["left_wing"])
        return {self.task.rate_error: rate,
                "flutter_speed_deficit_m_s": np.where(np.isfinite(margin), np.maximum(0.0, -margin), np.nan),
                "airspeed_error_m_s": meas.airspeed_m_s - ref["airspeed_m_s"],
                "altitude_error_m": meas.altitude_m - ref["altitude_m"],
                "flutter_margin_m_s": margin}

    def _task_termination(self, meas: MeasurementBatch) -> np.ndarray | None:
        limit = self.task.wing_tip_twist_limit_rad
        if not math.isfinite(limit):
            return None
        twist = meas.tip_twist_rad
        with np.errstate(invalid="ignore"):
            over = ~(np.maximum(np.abs(twist["right_wing"]), np.abs(twist["left_wing"])) <= limit)
        return np.where(over, TERMINATION_CODES.index("structural_limit"), 0).astype(np.int64)

    def task_label(self) -> str:
        return f"GTM flutter margin M {self.target.mach:.3f} (M_f {self.flutter.mach:.3f})"


@shared_docs
class WingFlutterMarginEnv(FlutterMarginEnv):
    """
    ## Description
    Active flutter suppression on the **calibrated** default GTM (``aircraft="gtm"``, ``docs/calibration.md``,
    1 % modal structural damping). The aircraft flies level at 300 m at its open-loop flutter Mach number
    (``flexsim.linear.flutter.FlutterAnalysis`` with the env's aerodynamic model, searched over M 0.5-0.95)
    plus ``task.mach_margin`` (0.01). With the finite-state model the flutter point is M 0.6904 (234.1 m/s,
    36.93 rad/s = 5.88 Hz) at 300 m: an **antisymmetric wing mode**, first torsion and first bending of
    the two wing halves out of phase (right wing nose-up while the left is nose-down) with sideslip, roll
    and yaw. At M_f + 0.01 it grows at +0.42 1/s (sampled linear model at the trim; open loop the
    antisymmetric tip twist-rate amplitude grows about 1.5 times per second and the wing tip twist limit
    ends every episode after 6-14 s). Hold the speed above the flutter speed and the altitude, and damp the
    antisymmetric wing torsion; the ailerons (antisymmetric) are its natural control. The flutter mode is
    well below the Nyquist frequency of the default 50 Hz control rate (see
    ``examples/agents/baselines.py``, ``WingFlutterAileronDamper``).

    ## Action Space
    <action space>

    ## Observation Space
    <observation>

    Twists are torsion coordinates (``docs/conventions.md``): positive is nose-up on the right wing and
    nose-down on the left one, so equal right and left values are an antisymmetric twist.

    ## Rewards
    <rewards>

    ## Starting State
    Trim at the target Mach number (M 0.7004), perturbed (``InitialPerturbation``) and with the same
    first-torsion rate on both wing halves (an antisymmetric twist rate) of random sign and magnitude
    ``task.wing_twist_rate_range_rad_s`` (0.05-0.1 rad/s, ``self.np_random``). ``info["reference"]`` at
    reset reports the flutter point and the target.

    ## Episode End
    <termination>
    Also a wing structural limit: |tip twist| of either wing half beyond ``task.wing_tip_twist_limit_rad``
    (0.1 rad, 5.7 deg; the trim twist is 0.023 rad) is ``"structural_limit"`` — the limit that ends the
    open-loop episodes (the 5.5 m wing tip deflection and 0.1 rad fin twist limits are not reached).
    <truncation>

    ## Arguments
    <arguments>
    ``task`` is a ``FlutterMarginTask`` with ``subject="wing_antisymmetric"``. The flutter search (about 3 s)
    runs once per process and aircraft file.

    ## Version History
    * v1: the flutter task on the calibrated default ``gtm`` (antisymmetric wing flutter, ailerons); v0
      unchanged (fin flutter of ``gtm_uncalibrated``).
    * v0: see ``FlexSim/GTM-FlutterMargin-v0`` (``FlutterMarginEnv``).
    """

    task_type = WingFlutterMarginTask
    env_id = "FlexSim/GTM-FlutterMargin-v1"
    task_errors_spec = ((("wing_twist_rate_rad_s", 1000.0, "antisymmetric wing tip twist rate 0.5 (psi_R' + psi_L') "
                          "(the rewarded structural error)"),) + FlutterMarginEnv.task_errors_spec[1:])

    def __init__(self, *, aircraft: str | Path | Aircraft = "gtm", **kwargs) -> None:
        super().__init__(aircraft=aircraft, **kwargs)
