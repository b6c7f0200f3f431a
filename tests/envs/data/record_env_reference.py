"""Record the observations and rewards of a few steps of every registered FlexSim env (the recorded reference).

Run from a checkout whose environments are the reference (``PYTHONPATH=. python3 tests/envs/data/record_env_reference.py``);
it writes ``env_reference.npz`` next to this file. tests/envs/test_env_reference.py replays the same episodes
(:func:`episodes`, the same seeds and actions) and compares.

Each case: single env (``gym.make``) or batched (``gym.make_vec`` with ``vectorization_mode="vector_entry_point"``),
``reset(seed=SEED)``, then STEPS actions ``clip(trim_action + N(0, 0.05))`` from ``np.random.default_rng(ACTION_SEED)``.
Arrays per case: ``obs`` (STEPS + 1, [num_envs,] n_obs) float32 (the reset observation first), ``reward``
(STEPS, [num_envs]) float64.
"""

from __future__ import annotations

import sys
from pathlib import Path

import gymnasium as gym
import numpy as np

SEED = 11
ACTION_SEED = 2024
STEPS = 6
#: (case name, env id, num_envs (0: single env), env kwargs; ``"method"`` becomes ``integrator=IntegratorSettings(method=...)``).
#: 40 rows take the products over the rows as matrix products (many rows); 3 rows take them row by row; the
#: quasi-steady cases integrate with solve_ivp's DOP853.
CASES = [
    *((f"single:{env_id}", env_id, 0, {}) for env_id in (
        "FlexSim/GTM-LevelHold-v0", "FlexSim/GTM-LevelHold-v1", "FlexSim/GTM-Turn-v0", "FlexSim/GTM-GustAlleviation-v0",
        "FlexSim/GTM-FlutterMargin-v0", "FlexSim/GTM-FlutterMargin-v1")),
    *((f"vector3:{env_id}", env_id, 3, {}) for env_id in (
        "FlexSim/GTM-LevelHold-v0", "FlexSim/GTM-LevelHold-v1", "FlexSim/GTM-Turn-v0", "FlexSim/GTM-GustAlleviation-v0",
        "FlexSim/GTM-FlutterMargin-v0", "FlexSim/GTM-FlutterMargin-v1")),
    ("vector40:FlexSim/GTM-LevelHold-v0", "FlexSim/GTM-LevelHold-v0", 40, {"turbulence": "light"}),
    ("single-quasi-steady-dop853:FlexSim/GTM-LevelHold-v0", "FlexSim/GTM-LevelHold-v0", 0, {"aero": "quasi-steady", "method": "DOP853"}),
    ("vector3-quasi-steady-dop853:FlexSim/GTM-Turn-v0", "FlexSim/GTM-Turn-v0", 3, {"aero": "quasi-steady", "method": "DOP853"}),
]


def run_case(env_id: str, num_envs: int, kwargs: dict) -> tuple[np.ndarray, np.ndarray]:
    """(observations, rewards) of one case (module docstring)."""
    import flexsim.envs as envs  # registers the ids

    kwargs = dict(kwargs)
    if "method" in kwargs:
        kwargs["integrator"] = envs.IntegratorSettings(method=kwargs.pop("method"))
    rng = np.random.default_rng(ACTION_SEED)
    if num_envs:
        env = gym.make_vec(env_id, num_envs=num_envs, vectorization_mode="vector_entry_point", **kwargs)
        obs, info = env.reset(seed=SEED)
        trim = np.asarray(info["trim_action"], dtype=np.float64)
        low, high = env.single_action_space.low, env.single_action_space.high
    else:
        env = gym.make(env_id, **kwargs)
        obs, info = env.reset(seed=SEED)
        trim = np.asarray(info["trim_action"], dtype=np.float64)
        low, high = env.action_space.low, env.action_space.high
    observations, rewards = [np.array(obs)], []
    for _ in range(STEPS):
        action = np.clip(trim + rng.normal(0.0, 0.05, trim.shape), low, high).astype(np.float32)
        obs, reward, _, _, _ = env.step(action)
        observations.append(np.array(obs))
        rewards.append(np.array(reward, dtype=np.float64))
    env.close()
    return np.array(observations, dtype=np.float32), np.array(rewards, dtype=np.float64)


def main(out: Path) -> None:
    arrays = {}
    for name, env_id, num_envs, kwargs in CASES:
        obs, reward = run_case(env_id, num_envs, kwargs)
        arrays[f"{name}/obs"], arrays[f"{name}/reward"] = obs, reward
        print(f"{name}: obs {obs.shape}, reward {reward.shape}", flush=True)
    np.savez_compressed(out, **arrays)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).with_name("env_reference.npz"))
