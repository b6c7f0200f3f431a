"""The generated sections of the env docstrings (gymnasium's template) state what the envs do.

For every registered id, parsed back from ``help()``'s text (``cls.__doc__``) and compared with the made env:
the Observation Space table (every row's name and bounds equal ``observation_names`` and the bounds of
``observation_space``, pi written by name; float32 equality), the Rewards line (the terms, weights and scales
of ``reward_definition`` in ``part_names`` order, scales in the unit of the error's name: deg converted to rad
to 1e-12), the Truncation line (the registered ``max_episode_steps``) and the template's section headings.
"""

import math
import re

import gymnasium as gym
import numpy as np
import pytest

from flexsim import envs
from flexsim.envs.base import TERMINATION_REASONS

SECTIONS = ("## Description", "## Action Space", "## Observation Space", "## Rewards", "## Starting State",
            "## Episode End", "### Termination", "### Truncation", "## Arguments", "## Version History")


def _number(text: str) -> float:
    sign, body = (-1.0, text[1:]) if text.startswith("-") else (1.0, text)
    return sign * {"pi": math.pi, "pi/2": math.pi / 2}.get(body, float(body) if body[:1].isdigit() else math.nan)


@pytest.fixture(scope="module", params=list(envs.ENV_IDS))
def made(request):
    env = gym.make(request.param)
    yield request.param, env.unwrapped
    env.close()


def test_the_template_sections_are_there_in_order(made):
    _, env = made
    doc = type(env).__doc__
    at = [doc.find(f"    {s}\n") for s in SECTIONS]
    assert -1 not in at and at == sorted(at), dict(zip(SECTIONS, at))
    assert "<" + "observation>" not in doc and not re.search(r"^\s*<[a-z0-9 -]+>$", doc, re.MULTILINE)


def test_observation_table_equals_the_space(made):
    _, env = made
    row = r"^\s*\| (\d+)\s+\| ``(\w+)``\s+\| (\S+)\s+\| (\S+)\s+\| (\S+)\s+\|"
    rows = re.findall(row, type(env).__doc__, re.MULTILINE)
    space = env.observation_space
    assert [int(r[0]) for r in rows] == list(range(space.shape[0]))
    assert tuple(r[1] for r in rows) == env.observation_names
    np.testing.assert_array_equal(np.array([_number(r[2]) for r in rows], np.float32), space.low)
    np.testing.assert_array_equal(np.array([_number(r[3]) for r in rows], np.float32), space.high)
    assert f"``Box({space.shape[0]},)``" in type(env).__doc__


def test_reward_line_equals_the_reward(made):
    _, env = made
    doc = " ".join(type(env).__doc__.split())
    reward = env.reward_definition
    terms = re.findall(r"``(\w+)`` -([\d.]+) min\(\(e / ([\d.]+) ?([a-z/]*)\)\^2, 1\)", doc)
    assert [t[0] for t in terms] == [t.error for t in reward.terms] == list(reward.part_names[1:-2])
    for (_, weight, scale, unit), term in zip(terms, reward.terms):
        assert float(weight) == term.weight
        assert float(scale) * (math.pi / 180 if unit == "deg" else 1.0) == pytest.approx(term.scale, rel=1e-12)
    (w_u, s_u, penalty), = re.findall(r"``control_rate`` -([\d.]+) min\(mean\(\(da / ([\d.]+)\)\^2\), 1\).*"
                                      r"``termination`` -([\d.]+) on a terminating step", doc)
    assert (float(w_u), float(s_u), float(penalty)) == (reward.control_rate_weight, reward.control_rate_scale,
                                                        reward.termination_penalty)


def test_episode_end_names_every_reason_and_the_time_limit(made):
    env_id, env = made
    doc = " ".join(type(env).__doc__.split())
    assert all(f'``"{reason}"``' in doc for reason in TERMINATION_REASONS)
    limits = envs.FlightLimits()
    assert f"|wing tip deflection| > {limits.wing_tip_deflection_m:g} m" in doc
    assert f"Mach >= {limits.max_mach:g}" in doc and f"airspeed <= {limits.min_airspeed_m_s:g} m/s" in doc
    steps = gym.registry[env_id].max_episode_steps
    assert f"``max_episode_steps`` = {steps} ({steps / 50:g} s at 50 Hz)" in doc
