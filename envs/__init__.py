"""Gymnasium environments of flexsim: the flexible notional GTM in four control tasks (six ids),
and the very flexible PHC HALE aircraft in gust alleviation (two ids: the linear structure, and the geometrically
nonlinear beams in :mod:`flexsim.envs.hale_nonlinear`).

Importing this package registers (idempotently) the environment ids of :data:`ENV_IDS` and
:data:`NONLINEAR_ENV_IDS`::

    import gymnasium as gym
    import flexsim.envs  # noqa: F401  (registers the FlexSim/* ids)
    env = gym.make("FlexSim/GTM-LevelHold-v0")

or, without the import, ``gym.make("flexsim.envs:FlexSim/GTM-LevelHold-v0")``. Each environment holds the task
(episode start, errors, reward, observation, spaces) and leaves the integration of the one nonlinear model
``AircraftModel.rhs`` over each control period to :mod:`flexsim.sim.periods` (ETD2RK about the trim by default,
or ``scipy.integrate.solve_ivp``); see ``docs/environments.md``. ``gym.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")`` steps N
aircraft of a task in one call (:mod:`flexsim.envs.vector`).
"""

from __future__ import annotations

import gymnasium as gym

from flexsim.envs.base import FlexSimEnv
from flexsim.envs.config import ActuatorRates, FlightLimits, InitialPerturbation, IntegratorSettings, RewardTerm, TrackingReward
from flexsim.envs.flutter_margin import FlutterMarginEnv, FlutterMarginTask, WingFlutterMarginEnv, WingFlutterMarginTask
from flexsim.envs.gust_alleviation import GustAlleviationEnv, GustAlleviationTask, HaleGustAlleviationEnv
from flexsim.envs.hale_nonlinear import HaleNonlinearGustEnv
from flexsim.envs.level_hold import LevelHoldCaptureEnv, LevelHoldEnv, LevelHoldTask
from flexsim.envs.turn import TurnEnv, TurnTask
from flexsim.io.env_log import FlightLogRecorder

__all__ = [
    "ENV_IDS", "NONLINEAR_ENV_IDS", "VECTOR_ENTRY_POINTS", "register_envs", "FlexSimEnv", "LevelHoldEnv", "LevelHoldCaptureEnv", "TurnEnv", "GustAlleviationEnv", "HaleGustAlleviationEnv", "HaleNonlinearGustEnv", "FlutterMarginEnv",
    "WingFlutterMarginEnv", "LevelHoldTask", "TurnTask", "GustAlleviationTask", "FlutterMarginTask", "WingFlutterMarginTask", "ActuatorRates", "FlightLimits",
    "InitialPerturbation", "IntegratorSettings", "RewardTerm", "TrackingReward", "FlightLogRecorder",
]

#: The task classes, one per registered id (their ``env_id`` and ``max_episode_steps``).
_ENV_CLASSES = (LevelHoldEnv, LevelHoldCaptureEnv, TurnEnv, GustAlleviationEnv, FlutterMarginEnv, WingFlutterMarginEnv,
                HaleGustAlleviationEnv)
#: Registered id -> (entry point, max_episode_steps; 50 steps = 1 s at the default 50 Hz).
ENV_IDS: dict[str, tuple[str, int]] = {
    c.env_id: (f"{c.__module__}:{c.__name__}", c.max_episode_steps) for c in _ENV_CLASSES}
#: Registered id -> vector entry point: ``gym.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")``
#: steps N aircraft in one call (:mod:`flexsim.envs.vector`).
VECTOR_ENTRY_POINTS: dict[str, str] = {
    c.env_id: f"flexsim.envs.vector:{c.__name__.removesuffix('Env')}VectorEnv" for c in _ENV_CLASSES}

#: Registered id -> (entry point, max_episode_steps) of the environments on the geometrically nonlinear beams: a plain
#: ``gymnasium.Env`` each (:mod:`flexsim.envs.hale_nonlinear`), without the linear model's batched vector entry point.
NONLINEAR_ENV_IDS: dict[str, tuple[str, int]] = {
    c.env_id: (f"{c.__module__}:{c.__name__}", c.max_episode_steps) for c in (HaleNonlinearGustEnv,)}


def register_envs() -> None:
    """Register the ids of :data:`ENV_IDS` with gymnasium (a no-op for ids already registered), each with its
    vector entry point (:data:`VECTOR_ENTRY_POINTS`)."""
    for env_id, (entry_point, steps) in ENV_IDS.items():
        if env_id not in gym.registry:
            gym.register(id=env_id, entry_point=entry_point, vector_entry_point=VECTOR_ENTRY_POINTS[env_id], max_episode_steps=steps)
    for env_id, (entry_point, steps) in NONLINEAR_ENV_IDS.items():
        if env_id not in gym.registry:
            gym.register(id=env_id, entry_point=entry_point, max_episode_steps=steps)


register_envs()
