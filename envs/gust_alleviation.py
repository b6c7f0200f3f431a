"""FlexSim/GTM-GustAlleviation-v0: hold attitude through a discrete gust with small wing loads."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexsim.sim.disturbances import OneMinusCosineGust, combine
from flexsim.kinematics import dcm_321
from flexsim.trimming import SteadyManoeuvre

from flexsim.envs.base import Episode, FlexSimEnv, shared_docs
from flexsim.envs.config import GUST_MAX_STEP_S, RewardTerm, TrackingReward
from flexsim.sim.measurements import MeasurementBatch
from flexsim.sim.initial_states import perturbed_state, turbulence_field

__all__ = ["GustAlleviationTask", "GustAlleviationEnv", "HaleGustAlleviationEnv"]


def _range(name: str, value: tuple[float, float], low: float, high: float) -> tuple[float, float]:
    lo, hi = (float(v) for v in value)
    if not low <= lo <= hi <= high:
        raise ValueError(f"{name} = {value!r}: must be (lo, hi) with {low:g} <= lo <= hi <= {high:g}")
    return lo, hi


@dataclass(frozen=True)
class GustAlleviationTask:
    """Parameters of the gust-load-alleviation task.

    Attributes
    ----------
    altitude_m : float
        Trim altitude [m] (default 6000 m).
    mach : float
        Trim Mach number [-] (default 0.7).
    gust_amplitude_range_m_s : tuple of float
        |U_ds| of the 1-cos gust (CS-25.341(a) shape) ~ U(range) [m/s] (default 6-12 m/s true airspeed);
        up or down with probability 1/2 each.
    gust_length_range_m : tuple of float
        Gust gradient distance H ~ U(range) [m] (default 30-107 m; CS-25: 9 to 107 m).
    gust_start_range_s : tuple of float
        Time at which the body origin reaches the front ~ U(range) [s] (default 1-2 s).
    reward : TrackingReward
        Costs on ``tip_deflection_increment_m`` (weight 0.25, saturating at 0.3 m), ``root_moment_increment``
        (0.2, 0.3 of the 1-g root bending moment), ``pitch_error_rad`` (0.2, 2 deg), ``roll_error_rad`` (0.1,
        2 deg), ``altitude_error_m`` (0.1, 20 m); control rate 0.15.
    """

    altitude_m: float = 6000.0
    mach: float = 0.7
    gust_amplitude_range_m_s: tuple[float, float] = (6.0, 12.0)
    gust_length_range_m: tuple[float, float] = (30.0, 107.0)
    gust_start_range_s: tuple[float, float] = (1.0, 2.0)
    reward: TrackingReward = TrackingReward(
        terms=(RewardTerm("tip_deflection_increment_m", 0.25, 0.3), RewardTerm("root_moment_increment", 0.2, 0.3),
               RewardTerm("pitch_error_rad", 0.2, math.radians(2.0)), RewardTerm("roll_error_rad", 0.1, math.radians(2.0)),
               RewardTerm("altitude_error_m", 0.1, 20.0)),
        control_rate_weight=0.15)

    def __post_init__(self) -> None:
        SteadyManoeuvre.level(self.altitude_m, mach=self.mach)
        if not self.altitude_m > 0.0:
            raise ValueError(f"altitude_m = {self.altitude_m!r}: must be > 0 m (altitude <= 0 is a crash)")
        object.__setattr__(self, "gust_amplitude_range_m_s", _range("gust_amplitude_range_m_s", self.gust_amplitude_range_m_s, 0.0, 50.0))
        object.__setattr__(self, "gust_length_range_m", _range("gust_length_range_m", self.gust_length_range_m, 1.0, 1000.0))
        object.__setattr__(self, "gust_start_range_s", _range("gust_start_range_s", self.gust_start_range_s, 0.0, 3600.0))

    @property
    def manoeuvre(self) -> SteadyManoeuvre:
        """The trimmed level flight."""
        return SteadyManoeuvre.level(self.altitude_m, mach=self.mach)


@shared_docs
class GustAlleviationEnv(FlexSimEnv):
    """
    ## Description
    The flexible notional GTM (see ``FlexSim/GTM-LevelHold-v0``) flies trimmed at 6000 m and Mach 0.7 and
    meets a vertical "1 - cos" gust (CS-25.341(a) shape, frozen in the air, reaching the nose before the
    tail): hold the attitude (pitch, roll) and altitude while keeping the wing loads — tip deflection and
    root bending moment above their 1-g values — small. The GTM's ailerons deflect antisymmetrically only,
    so the symmetric loads are shaped with the elevator and thrust. The gust is a
    :class:`flexsim.sim.disturbances.OneMinusCosineGust`; Dryden turbulence can be added.

    ## Action Space
    <action space>

    ## Observation Space
    <observation>

    The root bending moment is the modal-curvature estimate EI(0) w''(0) of the beam model.

    ## Rewards
    <rewards>

    ## Starting State
    Perturbed level trim (``InitialPerturbation``); gust amplitude, sign, gradient distance and encounter
    time drawn from ``self.np_random`` (``info["reference"]`` at reset reports them).

    ## Episode End
    <termination>
    <truncation>

    ## Arguments
    <arguments>

    ## Version History
    <v0 history>
    """

    task_type = GustAlleviationTask
    default_max_step_s = GUST_MAX_STEP_S  # the structural response is the task's subject
    default_turbulence = "none"
    env_id, max_episode_steps = "FlexSim/GTM-GustAlleviation-v0", 500
    task_errors_spec = (("tip_deflection_increment_m", 50.0, "mean wing-tip deflection minus its trim value"),
                        ("root_moment_increment", 50.0, "mean wing-root bending moment increment / |1-g value|"),
                        ("pitch_error_rad", math.pi, "pitch error theta - theta_trim"),
                        ("roll_error_rad", math.pi, "roll error phi"),
                        ("altitude_error_m", 5000.0, "altitude error"))

    def _new_episode(self, rng: np.random.Generator) -> Episode:
        task = self.task
        manoeuvre = task.manoeuvre
        point = self.dynamics.trim(manoeuvre)
        lay = self.dynamics.layout
        x0 = perturbed_state(point.x, lay, rng, self.perturbation)
        amplitude = float(rng.uniform(*task.gust_amplitude_range_m_s)) * (1.0 if rng.random() < 0.5 else -1.0)
        length = float(rng.uniform(*task.gust_length_range_m))
        start = float(rng.uniform(*task.gust_start_range_s))
        velocity_ned = dcm_321(*point.x[lay.euler]).T @ point.x[lay.v]
        gust = OneMinusCosineGust.encounter(amplitude, length, position_ned_m=x0[lay.position], velocity_ned_m_s=velocity_ned,
                                            start_time_s=start)
        turbulence = turbulence_field(self.turbulence, task.altitude_m, x0[lay.position], 0.0, rng)
        trim_meas = self.dynamics.measure(point.x, 0.0)
        reference = {"altitude_m": task.altitude_m, "pitch_rad": point.theta, "gust_amplitude_m_s": amplitude,
                     "gust_length_m": length, "gust_start_s": start,
                     "tip_deflection_m": 0.5 * (trim_meas.tip_deflection_m["right_wing"] + trim_meas.tip_deflection_m["left_wing"]),
                     "root_moment_n_m": 0.5 * (trim_meas.root_bending_moment_n_m["right_wing"] + trim_meas.root_bending_moment_n_m["left_wing"])}
        wind = gust if turbulence is None else combine(gust, turbulence)
        return Episode(manoeuvre, x0, wind, reference)

    def _task_errors(self, meas: MeasurementBatch, ref: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        tip = 0.5 * (meas.tip_deflection_m["right_wing"] + meas.tip_deflection_m["left_wing"])
        root = 0.5 * (meas.root_bending_moment_n_m["right_wing"] + meas.root_bending_moment_n_m["left_wing"])
        return {"tip_deflection_increment_m": tip - ref["tip_deflection_m"],
                "root_moment_increment": (root - ref["root_moment_n_m"]) / np.maximum(np.abs(ref["root_moment_n_m"]), 1.0),
                "pitch_error_rad": meas.euler_rad[:, 1] - ref["pitch_rad"],
                "roll_error_rad": meas.euler_rad[:, 0].copy(),
                "altitude_error_m": meas.altitude_m - ref["altitude_m"]}

    def task_label(self) -> str:
        return f"GTM gust {self._reference.get('gust_amplitude_m_s', math.nan):+.1f} m/s"


@shared_docs
class HaleGustAlleviationEnv(GustAlleviationEnv):
    """
    ## Description
    The very flexible PHC HALE aircraft (bundled ``phc_hale``: Patil, Hodges & Cesnik 2001; 16 m wing halves,
    see ``flexsim/aircraft/data/phc_hale.md``) flies trimmed at its cruise point (20 km, the file's
    ``[envelope]``) and meets a vertical "1 - cos" gust: hold the attitude (pitch, roll) and altitude while
    keeping the wing loads — tip deflection and root bending moment above their 1-g values — small. The task
    is ``FlexSim/GTM-GustAlleviation-v0``'s with its defaults derived from this aircraft
    (``flexsim.envs.aircraft_defaults``): the cruise altitude and Mach number, gust amplitudes scaled with the
    airspeed (the same gust angles of attack), the wing-tip deflection bound 0.3 x the wing's length beyond the
    trim's own deflection, and the speed bounds from the aircraft's envelope.

    The structure flown is the paper's linear (small-deflection) beam: the trim alone bends the wing tips by
    several metres, beyond the linear structure's range (14 % of the wing's length), and ``reset`` says so in one
    line (``info["linear_range"]``, a warning once per env). ``FlexSim/HALE-GustAlleviation-v1``
    (:class:`flexsim.envs.hale_nonlinear.HaleNonlinearGustEnv`) flies the same task on the geometrically nonlinear
    beams, within their range.

    ## Action Space
    <action space>

    ## Observation Space
    <observation>

    The root bending moment is the modal-curvature estimate EI(0) w''(0) of the beam model.

    ## Rewards
    <rewards>

    ## Starting State
    Perturbed level trim (``InitialPerturbation``); gust amplitude, sign, gradient distance and encounter
    time drawn from ``self.np_random`` (``info["reference"]`` at reset reports them).

    ## Episode End
    <termination>
    <truncation>

    ## Arguments
    <arguments>

    ## Version History
    * v0: initial version (linear structure, with the linear-range note).
    """

    env_id, max_episode_steps = "FlexSim/HALE-GustAlleviation-v0", 500

    def __init__(self, *, aircraft="phc_hale", **kwargs) -> None:
        super().__init__(aircraft=aircraft, **kwargs)

    def task_label(self) -> str:
        return f"HALE gust {self._reference.get('gust_amplitude_m_s', math.nan):+.1f} m/s"
