"""The learner's side of ``examples/agents/train_sb3.py`` without Stable-Baselines3: its training rewards,
its deterministic actor and its checkpoint choice on validation seeds.

* Potential-based shaping (Ng, Harada & Russell 1999, eq. 2: F = gamma Phi(s') - Phi(s)) telescopes: over an
  episode's first T steps the discounted sum of F is gamma^T Phi(s_T) - Phi(s_0), exactly, whatever the policy.
* The unsaturated tracking cost subtracts ``penalty * (|altitude error| / 30 m + |heading error| / 3 deg)`` of the
  state after the step.
Tolerances: the rewards are float32 (relative 6e-8 each), summed over 40 steps of magnitude <= 12.
"""

import math

import numpy as np
import pytest

ENV = "FlexSim/GTM-LevelHold-v1"


def _batches(agents_path, **kwargs):
    from train_sb3 import ResidualBatch

    plain = ResidualBatch(ENV, 2, "unsteady", 0.1, seed=7)
    other = ResidualBatch(ENV, 2, "unsteady", 0.1, seed=7, **kwargs)
    return plain, other


def _fly(plain, other, steps, rng):
    """Same seeds, same actions: the two batches fly the same trajectories; returns both rewards and observations."""
    obs0, obs1 = plain.reset(), other.reset()
    np.testing.assert_array_equal(obs0, obs1)
    rewards0, rewards1, observations = [], [], [obs0]
    for _ in range(steps):
        a = rng.uniform(-1.0, 1.0, (2, 4))
        o0, r0, d0, _ = plain.step(a)
        o1, r1, d1, _ = other.step(a)
        np.testing.assert_array_equal(o0, o1)
        assert not d0.any()
        rewards0.append(r0.astype(np.float64))
        rewards1.append(r1.astype(np.float64))
        observations.append(o0)
    return np.array(rewards0), np.array(rewards1), observations


def test_potential_shaping_telescopes(agents_path):
    gamma, steps = 0.99, 40
    plain, shaped = _batches(agents_path, shaping=10.0, gamma=gamma)
    r0, r1, observations = _fly(plain, shaped, steps, np.random.default_rng(0))
    discount = gamma ** np.arange(steps)
    phi = shaped.potential
    expected = gamma**steps * phi(observations[-1]) - phi(observations[0])
    np.testing.assert_allclose(discount @ (r1 - r0), expected, rtol=0, atol=2e-5)
    assert np.all(np.abs(expected) > 0.1)  # the start offsets make the potential visible


def test_tracking_penalty_is_the_error_after_the_step(agents_path):
    plain, penalised = _batches(agents_path, penalty=0.2)
    r0, r1, observations = _fly(plain, penalised, 10, np.random.default_rng(1))
    names = list(plain.venv.envs[0].observation_names)
    after = np.array(observations[1:], dtype=np.float64)
    error = np.abs(after[..., names.index("altitude_error_m")]) / 30.0 + np.abs(after[..., names.index("heading_error_rad")]) / math.radians(3.0)
    np.testing.assert_allclose(r1 - r0, -0.2 * error, rtol=0, atol=1e-6)


class _ConstantModel:
    """A stand-in for an SB3 model: the deterministic action is ``value`` for every aircraft; ``save`` records paths."""

    def __init__(self, value):
        self.value, self.saved = np.asarray(value, dtype=np.float32), []

    def predict(self, z, deterministic=True):
        assert deterministic and z.dtype == np.float32
        return np.broadcast_to(self.value, (len(z), 4)).copy(), None

    def save(self, path):
        self.saved.append(path)


def test_actor_adds_the_scaled_residual_to_the_trim(agents_path):
    from train_sb3 import agent_actor

    obs = np.zeros((2, 29))
    stats = {"mean": np.zeros(29), "var": np.ones(29), "eps": 1e-8, "clip": 10.0}
    trim = np.array([[0.5, 0.0, -0.1, 0.0], [0.98, 0.95, 0.0, -0.2]])
    low, high = np.array([0.0, -1, -1, -1]), np.ones(4)
    np.testing.assert_array_equal(agent_actor(_ConstantModel(np.zeros(4)), stats, trim, 0.1, low, high)(obs), trim)
    act = agent_actor(_ConstantModel([1.0, 2.0, -1.0, 0.5]), stats, trim, 0.1, low, high)(obs)
    # residual clipped to [-1, 1], then the sum clipped to the action box; the model acts in float32 (6e-8 relative)
    np.testing.assert_allclose(act, np.clip(trim + 0.1 * np.array([1.0, 1.0, -1.0, 0.5]), low, high), rtol=0, atol=1e-8)


def test_validation_keeps_the_best_checkpoint(agents_path, tmp_path):
    import argparse

    from train_sb3 import VALIDATION_SEED, Validation

    args = argparse.Namespace(env=ENV, aero="unsteady", val_episodes=2, val_every=1000, residual_scale=0.1)
    validation = Validation(args, tmp_path / "best")
    assert validation.seeds == [VALIDATION_SEED, VALIDATION_SEED + 1] and validation.next_steps == 1000
    stats = {"mean": np.zeros(29), "var": np.ones(29), "eps": 1e-8, "clip": 10.0}
    trim_hold, pitch_down = _ConstantModel(np.zeros(4)), _ConstantModel([0.0, 0.0, 1.0, 0.0])
    held = validation(trim_hold, 1000, stats)
    dived = validation(pitch_down, 2100, stats)
    assert dived < held  # full residual elevator for 20 s leaves the reference altitude (or the envelope)
    assert validation.history == [(1000, held), (2100, dived)] and validation.next_steps == 3100
    assert validation.best["steps"] == 1000 and validation.best["stats"] is stats
    assert trim_hold.saved == [tmp_path / "best"] and pitch_down.saved == []


def test_flown_reward_parts_sum_to_the_returns(agents_path):
    """Per-episode sums of ``info["reward_parts"]`` (the final step's from ``final_info``) add up to the returns: the
    parts sum exactly to each step's reward (envs/level_hold.py)."""
    import gymnasium as gym

    from train_sb3 import fly

    venv = gym.make_vec(ENV, num_envs=2, vectorization_mode="vector_entry_point", autoreset_mode="SameStep", max_episode_steps=30)
    obs, info = venv.reset(seed=[3, 4])
    flown = fly(venv, obs, lambda o: np.asarray(info["trim_action"]))
    for total, steps, reason, parts in flown:
        assert steps == 30 and reason == "" and parts["alive"] == 30.0
        assert math.isclose(sum(parts.values()), total, rel_tol=0, abs_tol=1e-9)


def test_penalty_on_a_task_without_tracking_errors_is_refused(agents_path):
    from train_sb3 import ResidualBatch

    with pytest.raises(ValueError, match=r"penalty = 0.2: both must be 0 for FlexSim/GTM-GustAlleviation-v0"):
        ResidualBatch("FlexSim/GTM-GustAlleviation-v0", 1, "unsteady", 0.1, seed=0, penalty=0.2)
