"""Frozen parameter sets shared by every flexsim environment (limits, rewards; the initial perturbation re-exported).

All quantities SI and radians. Each dataclass validates itself and raises ``ValueError`` naming the field, the
value and the allowed range. The integration's settings, :class:`flexsim.sim.IntegratorSettings` (the one class of
``simulate`` and of the control periods) and :class:`~flexsim.sim.periods.ActuatorRates`, live with the integration.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from flexsim.errors import positive_number
from flexsim.sim import IntegratorSettings
from flexsim.sim.initial_states import InitialPerturbation
from flexsim.sim.periods import DEFAULT_MAX_STEP_S, FIXED_STEP_METHODS, INTEGRATOR_METHODS, ActuatorRates

from flexsim.envs.row_kernels import reward_rows

__all__ = [
    "ActuatorRates",
    "IntegratorSettings",
    "FlightLimits",
    "InitialPerturbation",
    "RewardTerm",
    "TrackingReward",
    "TURBULENCE_LEVELS",
    "INTEGRATOR_METHODS",
    "FIXED_STEP_METHODS",
    "AERO_MODELS",
    "DEFAULT_MAX_STEP_S",
    "GUST_MAX_STEP_S",
    "FLUTTER_MAX_STEP_S",
]

#: Turbulence levels accepted by the ``turbulence`` argument (MIL-F-8785C severities, or none).
TURBULENCE_LEVELS = ("none", "light", "moderate", "severe")
#: Default ETD2RK step of the GustAlleviation task [s], whose subject is the structural response: its fin and wing
#: tip deflection rates within 0.8 % of their range of DOP853's over 2 s of gusts (2 % at 20 ms; docs/environments.md).
GUST_MAX_STEP_S = 0.01
#: Default ETD2RK step of the FlutterMargin tasks [s]: the flutter amplitude within about 1 % after 5 s.
FLUTTER_MAX_STEP_S = 0.005
#: Aerodynamic models of the time-domain model.
AERO_MODELS = ("unsteady", "quasi-steady")


@dataclass(frozen=True)
class FlightLimits:
    """Termination bounds (an episode ends with ``terminated = True`` when one is crossed).

    The defaults are the notional GTM's; an environment flown with another aircraft and ``limits=None`` derives its
    bounds from that aircraft (:func:`flexsim.envs.aircraft_defaults.limits_for_aircraft`).

    Attributes
    ----------
    wing_tip_deflection_m : float
        Structural limit on |tip bending deflection| of either wing half [m] (default 5.5 m, 30 % of the
        GTM's 18.25 m semispan).
    fin_tip_twist_rad : float
        Structural limit on |tip twist| of the vertical stabilizer [rad] (default 0.1 rad, 5.7 deg).
    max_abs_pitch_rad : float
        Gimbal-lock guard of the 3-2-1 Euler angles: |theta| limit [rad] (default 85 deg).
    max_mach : float
        Envelope: Mach limit (default 0.95, where the model's Prandtl-Glauert correction is capped).
    max_abs_alpha_rad : float
        Envelope: |angle of attack| limit (default 25 deg; strip theory has no stall).
    min_airspeed_m_s : float
        Envelope: lowest airspeed [m/s] (default 60 m/s).
    """

    wing_tip_deflection_m: float = 5.5
    fin_tip_twist_rad: float = 0.1
    max_abs_pitch_rad: float = math.radians(85.0)
    max_mach: float = 0.95
    max_abs_alpha_rad: float = math.radians(25.0)
    min_airspeed_m_s: float = 60.0

    def __post_init__(self) -> None:
        for name in ("wing_tip_deflection_m", "fin_tip_twist_rad", "max_abs_pitch_rad", "max_mach",
                     "max_abs_alpha_rad", "min_airspeed_m_s"):
            object.__setattr__(self, name, positive_number(name, getattr(self, name)))
        if not self.max_abs_pitch_rad < math.pi / 2:
            raise ValueError(f"max_abs_pitch_rad = {self.max_abs_pitch_rad!r}: must be in (0, pi/2)")


@dataclass(frozen=True)
class RewardTerm:
    """One tracking cost: ``-weight * min((error / scale)**2, 1)``, bounded in [-weight, 0].

    Attributes
    ----------
    error : str
        Name of the task error it penalises (a key of the env's task errors).
    weight : float
        Weight [-] (>= 0).
    scale : float
        Error at which the cost saturates, in the error's unit (> 0).
    """

    error: str
    weight: float
    scale: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "weight", positive_number(f"RewardTerm({self.error}).weight", self.weight,
                                                           allow_zero=True))
        object.__setattr__(self, "scale", positive_number(f"RewardTerm({self.error}).scale", self.scale))


@dataclass(frozen=True)
class TrackingReward:
    """Per-step reward of every flexsim task (its parts go to ``info["reward_parts"]``)::

        reward = alive + sum_i -w_i min((e_i / s_i)^2, 1) - w_u min(mean((da / s_u)^2), 1) - penalty [terminated]

    with ``da`` the change of the normalised action from the previous step. The parts are, in order,
    ``"alive"``, one entry per :class:`RewardTerm` named after its error, ``"control_rate"`` and
    ``"termination"``; ``reward`` is their sum, in that order, so the parts add up to it exactly.

    Attributes
    ----------
    terms : tuple of RewardTerm
    alive : float
        Bonus per step while flying [-] (default 1).
    control_rate_weight : float
        w_u [-] (default 0.1).
    control_rate_scale : float
        s_u: normalised action change at which the control-rate cost saturates (default 0.1 per step).
    termination_penalty : float
        Subtracted once on the terminating step [-] (default 100).
    """

    terms: tuple[RewardTerm, ...]
    alive: float = 1.0
    control_rate_weight: float = 0.1
    control_rate_scale: float = 0.1
    termination_penalty: float = 100.0
    _names: tuple[str, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "terms", tuple(self.terms))
        names = [t.error for t in self.terms]
        reserved = {"alive", "control_rate", "termination"}
        if len(set(names)) != len(names) or reserved & set(names):
            raise ValueError(f"terms: error names must be unique and not one of {sorted(reserved)}, got {names}")
        for name in ("alive", "control_rate_weight", "termination_penalty"):
            object.__setattr__(self, name, positive_number(name, getattr(self, name), allow_zero=True))
        object.__setattr__(self, "control_rate_scale", positive_number("control_rate_scale", self.control_rate_scale))
        object.__setattr__(self, "_names", ("alive", *names, "control_rate", "termination"))

    @property
    def part_names(self) -> tuple[str, ...]:
        """Keys of ``info["reward_parts"]``, in summation order."""
        return self._names

    def parts(self, errors: Mapping[str, float], action_change: np.ndarray, terminated: bool) -> dict[str, float]:
        """The reward parts for task ``errors`` (name -> value), the action change and the end flag
        (:meth:`parts_batch` of one aircraft). Non-finite errors count as saturated (cost -weight)."""
        batch = self.parts_batch({k: np.array([float(v)]) for k, v in errors.items()}, np.asarray(action_change, float)[None, :],
                                 np.array([bool(terminated)]))
        return {k: float(v[0]) for k, v in batch.items()}

    def parts_batch(self, errors: Mapping[str, np.ndarray], action_change: np.ndarray, terminated: np.ndarray) -> dict[str, np.ndarray]:
        """The reward parts of m aircraft: task ``errors`` name -> (m,), action changes (m, 4), end flags (m,);
        name -> (m,) in :attr:`part_names` order. Non-finite errors count as saturated (cost -weight)."""
        terminated = np.ascontiguousarray(terminated, dtype=np.bool_)
        m, k = len(terminated), len(self.terms)
        table = np.empty((m, k))
        for j, term in enumerate(self.terms):
            table[:, j] = errors[term.error]
        parts, reward = np.empty((m, k + 3)), np.empty(m)
        reward_rows(table, np.arange(k, dtype=np.int64), terminated, np.ascontiguousarray(action_change, dtype=float).reshape(m, -1),
                    self.kernel_data, parts, reward)
        return dict(zip(self._names, parts.T))

    @property
    def kernel_data(self) -> np.ndarray:
        """The reward's constants as :func:`flexsim.envs.row_kernels.reward_rows` takes them: [alive, -w_u, s_u,
        penalty, s_1..s_T, -w_1..-w_T]."""
        return np.array([self.alive, -self.control_rate_weight, self.control_rate_scale, self.termination_penalty,
                         *(t.scale for t in self.terms), *(-t.weight for t in self.terms)])

    @staticmethod
    def total(parts: Mapping[str, float]) -> float:
        """The reward: the sum of the parts in their order (exactly what :meth:`parts` returns)."""
        reward = 0.0
        for value in parts.values():
            reward += value
        return reward
