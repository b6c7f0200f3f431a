"""Frozen parameter sets shared by every flexsim environment (actuators, integrator, limits, rewards).

All quantities SI and radians. Each dataclass validates itself and raises ``ValueError`` naming the
field, the value and the allowed range.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

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
#: Integration methods accepted by :class:`IntegratorSettings` (``"auto"`` picks by aerodynamic model).
INTEGRATOR_METHODS = ("auto", "ETD2RK", "DOP853", "Radau")
#: The fixed-step methods among them (:mod:`flexsim.sim.fixed_step`); the others are ``solve_ivp`` methods.
FIXED_STEP_METHODS = ("ETD2RK",)
#: Default ETD2RK step [s] (:attr:`IntegratorSettings.max_step_s`): 1 step per 50 Hz control period.
DEFAULT_MAX_STEP_S = 0.02
#: Default ETD2RK step of the GustAlleviation task [s], whose subject is the structural response: its fin and wing
#: tip deflection rates within 0.8 % of their range of DOP853's over 2 s of gusts (2 % at 20 ms; docs/environments.md).
GUST_MAX_STEP_S = 0.01
#: Default ETD2RK step of the FlutterMargin tasks [s]: the flutter amplitude within about 1 % after 5 s.
FLUTTER_MAX_STEP_S = 0.005
#: Allowed range of :attr:`IntegratorSettings.max_step_s` [s].
MAX_STEP_RANGE_S = (1e-4, 0.05)
#: Aerodynamic models of the time-domain model.
AERO_MODELS = ("unsteady", "quasi-steady")


def _positive(name: str, value: float, *, allow_zero: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be a finite number {'>= 0' if allow_zero else '> 0'}") from None
    if not math.isfinite(v) or v < 0.0 or (v == 0.0 and not allow_zero):
        raise ValueError(f"{name} = {value!r}: must be a finite number {'>= 0' if allow_zero else '> 0'}")
    return v


@dataclass(frozen=True)
class ActuatorRates:
    """Rate limits of the actuators (applied to the commanded controls every control period).

    The notional GTM file has no actuator data; the defaults are typical of a 757-class transport
    (hydraulic surfaces 40-60 deg/s, engine spool-up from idle to full thrust in about 4 s).

    Attributes
    ----------
    thrust_fraction_per_s : float
        Largest thrust change per second as a fraction of the maximum thrust [1/s] (default 0.25).
    aileron_rad_s, elevator_rad_s, rudder_rad_s : float
        Largest surface rates [rad/s] (defaults 60, 40 and 60 deg/s).
    """

    thrust_fraction_per_s: float = 0.25
    aileron_rad_s: float = math.radians(60.0)
    elevator_rad_s: float = math.radians(40.0)
    rudder_rad_s: float = math.radians(60.0)

    def __post_init__(self) -> None:
        for name in ("thrust_fraction_per_s", "aileron_rad_s", "elevator_rad_s", "rudder_rad_s"):
            object.__setattr__(self, name, _positive(name, getattr(self, name)))

    def limits(self, max_thrust_n: float) -> np.ndarray:
        """Rates of u = [T_e, delta_a, delta_e, delta_r]: [N/s, rad/s, rad/s, rad/s], shape (4,)."""
        return np.array([self.thrust_fraction_per_s * max_thrust_n, self.aileron_rad_s, self.elevator_rad_s, self.rudder_rad_s])


@dataclass(frozen=True)
class IntegratorSettings:
    """How each control period is integrated.

    Attributes
    ----------
    method : {"auto", "ETD2RK", "DOP853", "Radau"}
        ``"auto"`` (default) uses ETD2RK for the finite-state (``"unsteady"``) model and DOP853 for the
        quasi-steady model. ETD2RK (:class:`flexsim.sim.fixed_step.ETD2RK`) is a fixed-step second-order
        exponential integrator whose linear part is the Jacobian of the trim the episode starts from
        (computed once per trim): it integrates ``rhs`` itself, treats the stiff finite-state inflow
        states (eigenvalues down to about -650 1/s, |lambda| up to 1500 1/s on the GTM) and the
        structural modes exactly to first order about the trim, and does not damp them numerically
        (the 179 rad/s fin flutter mode keeps its growth rate), with 2 right-hand sides per step. DOP853
        and Radau are ``scipy.integrate.solve_ivp`` methods with error control (``rtol``, :meth:`atol`);
        Radau gets the constant trim Jacobian and damps lightly damped high-frequency modes (the fin
        flutter amplitude after 5 s is 22 % low at the default tolerances). ETD2RK has no error
        control: near the trim it is as accurate as Radau, far from it (random actions, wing tips at
        5 m) its errors are centimetres where Radau's are tenths of millimetres. Measured in
        ``benchmarks/bench_envs.py``; see ``docs/environments.md``.
    rtol : float
        Relative tolerance of DOP853 and Radau (default 1e-3; the error is dominated by ``atol`` on the
        small states). Not used by ETD2RK.
    atol_scale : float
        Multiplies the per-state absolute tolerances of :meth:`atol` (default 10). Not used by ETD2RK.
    max_step_s : float
        Largest step of ETD2RK [s], in [1e-4, 0.05] (default 0.02, :data:`DEFAULT_MAX_STEP_S`): each control
        period is split into ``ceil(period / max_step_s)`` equal steps (1 per period at 50 Hz). An env made with
        ``integrator=None`` uses its task's ``default_max_step_s``: 20 ms for LevelHold and Turn, 10 ms for
        GustAlleviation (:data:`GUST_MAX_STEP_S`), 5 ms for FlutterMargin (:data:`FLUTTER_MAX_STEP_S`). Not used
        by DOP853 and Radau. Measured against DOP853 at rtol 1e-10 over 25 periods in still air (LevelHold,
        small random actions): altitude 2.0e-6 m, pitch 2.5e-7 rad, wing tip 2.0e-6 m at 20 ms (10 ms: 2.1e-7 m,
        1.9e-8 rad, 1.7e-7 m; 5 ms: 5.7e-8 m, 5.2e-9 rad, 4.5e-8 m); over 2 s of actions trim + N(0, 0.05) in
        light turbulence against DOP853 at rtol 1e-9: LevelHold rewards within 2.6e-5 at 20 ms (7.8e-7 at 10 ms),
        tip deflection and twist rates within 1.6e-2 m/s or rad/s (4.4e-3), GustAlleviation's fin tip deflection
        rate 4.2e-2 m/s at 20 ms, 1.7e-2 at 10 ms (its range 2 m/s); open-loop fin flutter amplitude after 5 s
        -2.9 % at 10 ms, -1.1 % at 5 ms, -4.9 % at 20 ms (``benchmarks/bench_envs.py``).
    """

    method: str = "auto"
    rtol: float = 1e-3
    atol_scale: float = 10.0
    max_step_s: float = DEFAULT_MAX_STEP_S

    def __post_init__(self) -> None:
        if self.method not in INTEGRATOR_METHODS:
            raise ValueError(f"method = {self.method!r}: must be one of {', '.join(INTEGRATOR_METHODS)}")
        rtol = _positive("rtol", self.rtol)
        if not 1e-12 <= rtol <= 1e-2:
            raise ValueError(f"rtol = {self.rtol!r}: must be in [1e-12, 1e-2]")
        object.__setattr__(self, "rtol", rtol)
        object.__setattr__(self, "atol_scale", _positive("atol_scale", self.atol_scale))
        lo, hi = MAX_STEP_RANGE_S
        step = _positive("max_step_s", self.max_step_s)
        if not lo <= step <= hi:
            raise ValueError(f"max_step_s = {self.max_step_s!r}: must be in [{lo:g}, {hi:g}] s")
        object.__setattr__(self, "max_step_s", step)

    def resolve(self, aero: str) -> str:
        """The method used for aerodynamic model ``aero``: ETD2RK for ``"unsteady"``, DOP853 otherwise.

        Both automatic choices leave lightly damped high-frequency structural modes (the flutter-margin
        tasks' subject) free of numerical damping, so no task needs another choice.
        """
        if self.method != "auto":
            return self.method
        return "ETD2RK" if aero == "unsteady" else "DOP853"

    def substeps(self, period_s: float) -> int:
        """Number of equal ETD2RK steps per control period of ``period_s`` [s]: ceil(period / max_step_s)."""
        return max(1, math.ceil(period_s / self.max_step_s * (1.0 - 1e-12)))

    def atol(self, layout) -> np.ndarray:
        """Per-state absolute tolerances for a :class:`~flexsim.model.layout.StateLayout`.

        Base values (times ``atol_scale``): position 1e-3 m, Euler angles 1e-6 rad, bending 1e-5 m,
        torsion 1e-6 rad, body velocity 1e-4 m/s, body rates 1e-6 rad/s, bending rates 1e-4 m/s,
        torsion rates 1e-5 rad/s, inflow 1e-3 m/s.
        """
        a = np.empty(layout.n_states)
        for name, value in (("position", 1e-3), ("euler", 1e-6), ("q", 1e-5), ("xi", 1e-6), ("v", 1e-4),
                            ("omega", 1e-6), ("s", 1e-4), ("eta", 1e-5), ("inflow", 1e-3)):
            a[getattr(layout, name)] = value
        return a * self.atol_scale


@dataclass(frozen=True)
class FlightLimits:
    """Termination bounds (an episode ends with ``terminated = True`` when one is crossed).

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
            object.__setattr__(self, name, _positive(name, getattr(self, name)))
        if not self.max_abs_pitch_rad < math.pi / 2:
            raise ValueError(f"max_abs_pitch_rad = {self.max_abs_pitch_rad!r}: must be in (0, pi/2)")


@dataclass(frozen=True)
class InitialPerturbation:
    """Half-widths of the uniform random perturbation added to the trim state at reset.

    Attributes
    ----------
    attitude_rad : float
        Roll and pitch [rad] (default 0.01).
    heading_rad : float
        Yaw [rad] (default 0.01).
    body_rate_rad_s : float
        Each body rate p, q, r [rad/s] (default 0.005).
    airspeed_m_s : float
        Forward body velocity u [m/s] (default 1).
    altitude_m : float
        Altitude [m] (default 5).
    """

    attitude_rad: float = 0.01
    heading_rad: float = 0.01
    body_rate_rad_s: float = 0.005
    airspeed_m_s: float = 1.0
    altitude_m: float = 5.0

    def __post_init__(self) -> None:
        for name in ("attitude_rad", "heading_rad", "body_rate_rad_s", "airspeed_m_s", "altitude_m"):
            object.__setattr__(self, name, _positive(name, getattr(self, name), allow_zero=True))


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
        object.__setattr__(self, "weight", _positive(f"RewardTerm({self.error}).weight", self.weight, allow_zero=True))
        object.__setattr__(self, "scale", _positive(f"RewardTerm({self.error}).scale", self.scale))


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
            object.__setattr__(self, name, _positive(name, getattr(self, name), allow_zero=True))
        object.__setattr__(self, "control_rate_scale", _positive("control_rate_scale", self.control_rate_scale))
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
