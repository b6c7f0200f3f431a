"""Classical baselines (examples/agents) against a random policy.

Fast check (default suite): on FlexSim/GTM-LevelHold-v0 (finite-state aero, light turbulence), 100
steps (2 s) from seed 0, the LQR baseline earns more than 95 and at least 10 more than uniform random
actions (measured: 99.7 against 82.9; random actions pay the control-rate and tracking costs).
Slow check (``-m slow``): for every task, mean return over 10 seeded full-length episodes; the
baseline must beat the random policy by at least 200 (the measured numbers are in docs/environments.md).
"""

import gymnasium as gym
import numpy as np
import pytest

from flexsim import envs


def _mean_return(env_id, policy_name, seeds, max_steps=None, **kwargs):
    from baselines import RandomPolicy, make_baseline, run_episode

    env = gym.make(env_id, **kwargs) if max_steps is None else gym.make(env_id, max_episode_steps=max_steps, **kwargs)
    policy = make_baseline(env_id, env) if policy_name == "baseline" else RandomPolicy(env)
    returns = [run_episode(env, policy, seed)[0] for seed in seeds]
    env.close()
    return float(np.mean(returns))


def test_level_hold_baseline_beats_random_short(agents_path):
    seeds = (0,)
    baseline = _mean_return("FlexSim/GTM-LevelHold-v0", "baseline", seeds, max_steps=100)
    random = _mean_return("FlexSim/GTM-LevelHold-v0", "random", seeds, max_steps=100)
    assert baseline > 95.0
    assert baseline > random + 10.0, (baseline, random)


@pytest.mark.slow
@pytest.mark.parametrize("env_id", list(envs.ENV_IDS))
def test_baseline_beats_random_over_10_episodes(agents_path, env_id):
    seeds = range(10)
    baseline = _mean_return(env_id, "baseline", seeds)
    random = _mean_return(env_id, "random", seeds)
    assert baseline > random + 200.0, (baseline, random)
