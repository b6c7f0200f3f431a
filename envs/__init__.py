"""Gymnasium environments of flexsim: the flexible notional GTM in four control tasks (five ids).

Importing this package registers (idempotently) the environment ids of :data:`ENV_IDS`::

    import gymnasium as gym
    import envs  # noqa: F401  (registers the FlexSim/* ids)
    env = gym.make("FlexSim/GTM-LevelHold-v0")

or, without the import, ``gym.make("envs:FlexSim/GTM-LevelHold-v0")``. Each environment is a thin adapter
that integrates the one nonlinear model ``AircraftModel.rhs`` over each control period (:mod:`envs.dynamics`:
ETD2RK about the trim by default for the finite-state model, or ``scipy.integrate.solve_ivp``); see
``docs/environments.md``.
"""

from __future__ import annotations

import gymnasium as gym

from envs.base import FlexSimEnv
from envs.config import ActuatorRates, FlightLimits, InitialPerturbation, IntegratorSettings, RewardTerm, TrackingReward
from envs.flutter_margin import FlutterMarginEnv, FlutterMarginTask, WingFlutterMarginEnv, WingFlutterMarginTask
from envs.gust_alleviation import GustAlleviationEnv, GustAlleviationTask
from envs.level_hold import LevelHoldEnv, LevelHoldTask
from envs.turn import TurnEnv, TurnTask
from envs.wrappers import FlightLogRecorder

__all__ = [
    "ENV_IDS", "register_envs", "FlexSimEnv", "LevelHoldEnv", "TurnEnv", "GustAlleviationEnv", "FlutterMarginEnv",
    "WingFlutterMarginEnv", "LevelHoldTask", "TurnTask", "GustAlleviationTask", "FlutterMarginTask", "WingFlutterMarginTask", "ActuatorRates", "FlightLimits",
    "InitialPerturbation", "IntegratorSettings", "RewardTerm", "TrackingReward", "FlightLogRecorder",
]

#: Registered id -> (entry point, max_episode_steps; 50 steps = 1 s at the default 50 Hz).
ENV_IDS: dict[str, tuple[str, int]] = {
    "FlexSim/GTM-LevelHold-v0": ("envs.level_hold:LevelHoldEnv", 1000),
    "FlexSim/GTM-Turn-v0": ("envs.turn:TurnEnv", 1000),
    "FlexSim/GTM-GustAlleviation-v0": ("envs.gust_alleviation:GustAlleviationEnv", 500),
    "FlexSim/GTM-FlutterMargin-v0": ("envs.flutter_margin:FlutterMarginEnv", 1000),
    "FlexSim/GTM-FlutterMargin-v1": ("envs.flutter_margin:WingFlutterMarginEnv", 1000),
}


def register_envs() -> None:
    """Register the ids of :data:`ENV_IDS` with gymnasium (a no-op for ids already registered)."""
    for env_id, (entry_point, steps) in ENV_IDS.items():
        if env_id not in gym.registry:
            gym.register(id=env_id, entry_point=entry_point, max_episode_steps=steps)


register_envs()
