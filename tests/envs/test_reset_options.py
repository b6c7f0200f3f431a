"""``reset(options=...)`` is honoured or refused: a single environment understands no option, the vector environment
``reset_mask`` alone; a non-dict or an unknown key is a ValueError naming it, never ignored."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from flexsim.envs.base import check_reset_options


@pytest.mark.parametrize(("options", "message"), [
    ({"seed": 3}, r"options\['seed'\]: not an option of reset\(\); allowed: none"),
    (["reset_mask"], r"options = \['reset_mask'\]: must be None or a dict \(got list\)"),
    ("altitude", r"options = 'altitude': must be None or a dict \(got str\)"),
])
def test_single_env_refuses_options_it_does_not_have(options, message):
    env = gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady")
    with pytest.raises(ValueError, match=message):
        env.reset(seed=0, options=options)
    obs, _ = env.reset(seed=0, options={})  # an empty dict asks for nothing
    assert np.all(np.isfinite(obs))
    env.close()


def test_vector_env_accepts_its_mask_and_refuses_other_keys():
    """A new case of the class: the vector environment's options."""
    venv = gym.make_vec("FlexSim/GTM-LevelHold-v0", num_envs=2, vectorization_mode="vector_entry_point",
                        aero="quasi-steady")
    with pytest.raises(ValueError, match=r"options\['mask'\]: not an option of reset\(\); allowed: 'reset_mask'"):
        venv.reset(seed=0, options={"mask": np.array([True, False])})
    venv.reset(seed=0, options={"reset_mask": np.array([True, True])})
    venv.close()


def test_the_check_itself():
    check_reset_options(None, ())
    check_reset_options({"a": 1}, ("a",))
    with pytest.raises(ValueError, match=r"options\[1\]"):
        check_reset_options({1: 2}, ("a",))
