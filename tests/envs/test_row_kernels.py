"""The compiled per-row outputs of the environments (flexsim/envs/row_kernels.py).

Reward parts against the closed form of ``TrackingReward``; the angle wrap against ``math.remainder``; replaced
termination limits take effect (single and batched). The measurements these read are tested in
tests/sim/test_measurements.py.
"""

import math

import gymnasium as gym
import numpy as np
import pytest

from flexsim.envs.config import RewardTerm, TrackingReward
from flexsim.envs.row_kernels import wrap, wrap_rows


def _close(a, b, rtol=1e-12):
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert np.all(np.abs(a - b) <= rtol * np.maximum(np.abs(b), 1e-300) + 1e-300), (a, b)


def test_reward_parts_closed_form():
    reward = TrackingReward(terms=(RewardTerm("e1", 0.3, 2.0), RewardTerm("e2", 0.2, 1.0)), control_rate_weight=0.1,
                            control_rate_scale=0.1, termination_penalty=100.0)
    errors = {"e1": np.array([1.0, np.nan, 10.0]), "e2": np.array([0.5, 0.0, -np.inf])}
    da = np.array([[0.0, 0.1, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [1.0, 1.0, 1.0, 1.0]])
    parts = reward.parts_batch(errors, da, np.array([False, True, False]))
    assert list(parts) == ["alive", "e1", "e2", "control_rate", "termination"]
    _close(parts["e1"], [-0.3 * 0.25, -0.3, -0.3])  # min((e / s)^2, 1) w; NaN saturates
    _close(parts["e2"], [-0.2 * 0.25, 0.0, -0.2])
    _close(parts["control_rate"], [-0.1 * 0.25, 0.0, -0.1])  # mean((da / 0.1)^2) = 1/4, 0, 100 -> 1
    _close(parts["termination"], [0.0, -100.0, 0.0])
    _close(parts["alive"], [1.0, 1.0, 1.0])


def test_wrap_is_the_ieee_remainder():
    angles = np.random.default_rng(1).uniform(-50.0, 50.0, 1000)
    _close(wrap_rows(angles), [math.remainder(a, 2 * math.pi) for a in angles], rtol=1e-15)
    assert wrap(3.0 * math.pi / 2) == pytest.approx(-math.pi / 2, rel=1e-15)
    assert np.isnan(wrap_rows(np.array([np.nan, np.inf, -np.inf]))).all() and math.isnan(wrap(math.inf))


def test_replaced_limits_take_effect_and_vector_env_shares_them():
    from flexsim.envs.config import FlightLimits

    env = gym.make("FlexSim/GTM-LevelHold-v0", turbulence="none")
    _, info = env.reset(seed=0)
    assert not env.step(info["trim_action"])[2]
    env.unwrapped.limits = FlightLimits(max_mach=0.5)  # the trim flies at Mach 0.75
    _, _, terminated, _, info = env.step(info["trim_action"])
    assert terminated and info["termination_reason"] == "envelope"
    env.close()
    venv = gym.make_vec("FlexSim/GTM-LevelHold-v0", num_envs=2, vectorization_mode="vector_entry_point", turbulence="none")
    with pytest.raises(ValueError, match="steps all aircraft with one limits"):
        venv.set_attr("limits", [FlightLimits(), FlightLimits(max_mach=0.5)])
    venv.set_attr("limits", FlightLimits(max_mach=0.5))
    _, info = venv.reset(seed=0)
    _, _, terminated, _, info = venv.step(np.stack(info["trim_action"]))
    assert terminated.all() and list(info["termination_reason"]) == ["envelope"] * 2
    venv.close()
