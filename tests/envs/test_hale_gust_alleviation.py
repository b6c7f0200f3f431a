"""FlexSim/HALE-GustAlleviation-v0: the gust task on the very flexible PHC HALE aircraft (bundled ``phc_hale``).

Checks (gymnasium's ``check_env`` for this id: tests/envs/test_checker.py; 20-step determinism with noisy actions:
tests/envs/test_determinism.py; its docstring: tests/envs/test_env_docs.py):

* the task and the limits are the aircraft's, through ``flexsim.envs.aircraft_defaults``: its cruise point 20 km and
  25 m/s (the file's ``[envelope]``); the gust amplitudes the GTM task's 6-12 m/s scaled by 25 m/s over the GTM task's
  speed (M 0.7 at 6000 m); the tip bound the trim's deflection plus 0.3 x the 16 m wing; the lowest airspeed the
  envelope's 5 m/s EAS as true airspeed at 20 km: 5 / sqrt(0.08891 / 1.225) = 18.56 m/s (US Standard Atmosphere 1976
  density at 20 km, 0.08891 kg/m^3; 0.01 m/s for its 4 digits);
* reset says the trim is beyond the linear structure's range (tips 7.49 m, 47 % of the wing: the structure flown is
  the linear one, tests/cli/test_linear_range_said.py);
* a whole 500-step episode is the same for the same seed (exact: all randomness comes from ``np_random``) and
  differs for another seed;
* the baseline's return recorded in docs/environments.md: the trim's controls held (``TrimHold`` of
  examples/agents/baselines.py; the GTM task's LQR gains end 2 of 3 HALE episodes at the structural limit),
  mean over seeds 0-9 of full episodes, 406.30; tolerance 0.01: the recorded figure's rounding (0.005) and more; the
  per-episode returns with ``NUMBA_CPU_NAME=generic`` kernels differed from this machine's target by less than 1e-11.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import data_equivalence

from flexsim import envs  # noqa: F401 (registers the environments)
from flexsim.atmosphere import speed_of_sound

ENV_ID = "FlexSim/HALE-GustAlleviation-v0"
#: Mean return of the trim-hold baseline over seeds 0-9 (docs/environments.md, "Baselines").
TRIM_HOLD_MEAN_RETURN = 406.30
RETURN_TOLERANCE = 0.01


@pytest.fixture(scope="module")
def env():
    e = gym.make(ENV_ID)
    yield e
    e.close()


def test_task_and_limits_come_from_the_hale(env):
    u = env.unwrapped
    assert Path(str(u.aircraft_source)).name == "phc_hale.toml"
    task = u.task
    assert task.altitude_m == 20000.0
    assert task.mach * speed_of_sound(20000.0) == pytest.approx(25.0, rel=1e-12)
    ratio = 25.0 / (0.7 * speed_of_sound(6000.0))
    assert task.gust_amplitude_range_m_s == pytest.approx((6.0 * ratio, 12.0 * ratio), rel=1e-12)
    trim_tip = abs(float(u.dynamics.trim(task.manoeuvre).tip_deflection_m))
    assert u.limits.wing_tip_deflection_m == pytest.approx(trim_tip + 0.3 * 16.0, rel=1e-12)
    assert u.limits.min_airspeed_m_s == pytest.approx(5.0 / math.sqrt(0.08891 / 1.225), abs=0.01)


def test_reset_says_the_linear_structure_is_beyond_its_range(env):
    _, info = env.reset(seed=0)
    assert re.search(r"right_wing tip deflection -7\.49\d* m = 47% of its 16 m length", info["linear_range"])
    assert info["linear_range"].endswith("docs/nonlinear-beams.md")


def _episode(env, seed):
    obs, info = env.reset(seed=seed)
    record = [(obs, info)]
    action = info["trim_action"]
    while True:
        obs, reward, terminated, truncated, info = env.step(action)
        record.append((obs, reward, terminated, truncated, info))
        if terminated or truncated:
            return record


def test_same_seed_same_episode(env):
    a, b = _episode(env, 5), _episode(env, 5)
    assert len(a) == len(b) == 501
    assert all(data_equivalence(ra, rb, exact=True) for ra, rb in zip(a, b))
    c = _episode(env, 6)
    assert not np.array_equal(a[-1][0], c[-1][0])


def test_trim_hold_baseline_return_as_recorded(agents_path):
    from baselines import TrimHold, make_baseline, run_episode

    e = gym.make(ENV_ID)
    policy = make_baseline(ENV_ID, e)
    assert isinstance(policy, TrimHold)
    rows = [run_episode(e, policy, seed) for seed in range(10)]
    e.close()
    assert all(length == 500 and reason == "" for _, length, reason in rows)
    mean = float(np.mean([r for r, _, _ in rows]))
    print(f"{ENV_ID} trim-hold baseline, seeds 0-9: mean return {mean:.2f}")
    assert mean == pytest.approx(TRIM_HOLD_MEAN_RETURN, abs=RETURN_TOLERANCE)
