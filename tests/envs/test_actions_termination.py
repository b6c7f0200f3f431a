"""Action validation and termination.

Checks: an out-of-range action is clipped to the Box (same result as the clipped action, exactly;
``info["action_clipped"]``); NaN/inf or a wrong shape raise ValueError naming the problem; the actuator
rate limits bound the change of the applied controls per step (to 1e-12); a forced crash (full
nose-down elevator at 150 m) terminates with reason "crash" and finite, in-bounds observations; a
structural limit below the trim deflection terminates at once (DOP853, and ETD2RK's one compiled call per period,
also FlutterMargin-v1's own wing twist limit, single and batched); a failing model (non-finite wind)
terminates with "non_finite" and finite observations; stepping after termination raises.
"""

import math

import gymnasium as gym
import numpy as np
import pytest

from flexsim import envs
from flexsim.envs import vector


@pytest.fixture(scope="module")
def env():
    e = gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady", turbulence="none")
    yield e
    e.close()


def test_out_of_range_actions_are_clipped(env):
    _, info = env.reset(seed=0)
    wild = np.array([2.0, -3.0, 0.5, 7.0], np.float32)
    obs_a, r_a, _, _, info_a = env.step(wild)
    env.reset(seed=0)
    obs_b, r_b, _, _, info_b = env.step(np.clip(wild, env.action_space.low, env.action_space.high))
    np.testing.assert_array_equal(obs_a, obs_b)
    assert r_a == r_b and info_a["action_clipped"] and not info_b["action_clipped"]


def test_invalid_actions_raise(env):
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"action\[2\] \(elevator\) = nan"):
        env.step(np.array([0.1, 0.0, np.nan, 0.0], np.float32))
    with pytest.raises(ValueError, match=r"action\[0\] \(thrust\) = inf"):
        env.step([np.inf, 0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"expected shape \(4,\).*got shape \(3,\)"):
        env.step(np.zeros(3, np.float32))
    with pytest.raises(ValueError, match=r"expected shape \(4,\).*got shape \(1, 4\)"):
        env.step(np.zeros((1, 4), np.float32))
    obs, *_ = env.step([0.1, 0.0, -0.4, 0.0])  # a plain list is accepted
    assert env.observation_space.contains(obs)


@pytest.mark.parametrize("action, kind", [
    (["0.5", "0", "0", "0"], "str"),
    (np.array(["0.5", "0", "0", "0"]), "strings"),
    (np.array([0.5, 0.0, 0.0, 0.0]) + 1j, "complex"),
    (np.array([True, False, False, True]), "booleans"),
    ([0.5, True, 0.0, 0.0], "bool"),
    ([0.5, None, 0.0, 0.0], "NoneType"),
    ([0.5, 0.0, 1 + 2j, 0.0], "complex"),
])
def test_non_real_actions_are_rejected_not_converted(env, action, kind):
    """Numeric strings, booleans and complex values were converted silently by numpy."""
    env.reset(seed=0)
    with pytest.raises(ValueError, match=rf"must be 4 real numbers.*{kind}"):
        env.unwrapped.step(action)
    obs, *_ = env.step(np.array([0.1, 0.0, -0.4, 0.0], np.int64) * 0 + np.array([0.1, 0.0, -0.4, 0.0]))
    assert env.observation_space.contains(obs)


def test_rate_limits_bound_control_changes(env):
    env.reset(seed=0)
    base = env.unwrapped
    limits = base.dynamics.rate_limits * base.dt
    previous = base.applied_controls
    for action in ([1.0, 1.0, 1.0, 1.0], [0.0, -1.0, -1.0, -1.0]):
        env.step(np.array(action, np.float32))
        change = np.abs(base.applied_controls - previous)
        assert np.all(change <= limits * (1 + 1e-12))
        np.testing.assert_allclose(change, limits, rtol=1e-12)
        previous = base.applied_controls


def _finite_in_space(space, obs):
    return obs.dtype == np.float32 and np.all(np.isfinite(obs)) and space.contains(obs)


def test_forced_crash_terminates_with_finite_observation():
    task = envs.LevelHoldTask(altitude_m=150.0, mach=0.5)
    env = gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady", turbulence="none", task=task)
    obs, info = env.reset(seed=0)
    dive = info["trim_action"].copy()
    dive[2] = 1.0  # elevator fully trailing edge down: nose down
    for _ in range(400):
        obs, reward, terminated, truncated, info = env.step(dive)
        assert _finite_in_space(env.observation_space, obs)
        if terminated:
            break
    assert terminated and info["termination_reason"] == "crash"
    assert info["reward_parts"]["termination"] == -100.0 and math.isfinite(reward)
    assert env.unwrapped.measurements().altitude_m == pytest.approx(0.0, abs=1e-6)  # the ground event stops at h = 0
    with pytest.raises(RuntimeError, match="after the episode terminated"):
        env.step(dive)
    env.close()


def test_structural_limit_and_non_finite_terminate():
    env = gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady", turbulence="none",
                   limits=envs.FlightLimits(wing_tip_deflection_m=0.5))
    _, info = env.reset(seed=0)
    obs, _, terminated, _, info = env.step(info["trim_action"])
    assert terminated and info["termination_reason"] == "structural_limit"
    env.close()
    env = gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady", turbulence="light")
    _, info = env.reset(seed=0)
    env.unwrapped._wind = lambda t, p: np.full(np.shape(p), np.nan)
    obs, reward, terminated, _, info = env.step(info["trim_action"])
    assert terminated and info["termination_reason"] == "non_finite"
    assert _finite_in_space(env.observation_space, obs) and math.isfinite(reward)
    env.close()


def test_structural_limits_terminate_on_the_compiled_period():
    """The finite-state envs step each period in one compiled call (row_kernels.period_rows): the common limits
    and a task's own (FlutterMargin-v1's wing tip twist, FlutterMarginEnv._task_termination) still end the episode
    at once when set below the trim's value, in the single and in the batched env."""
    env = gym.make("FlexSim/GTM-LevelHold-v0", turbulence="none", limits=envs.FlightLimits(wing_tip_deflection_m=0.5))
    _, info = env.reset(seed=0)
    _, _, terminated, _, info = env.step(info["trim_action"])
    assert terminated and info["termination_reason"] == "structural_limit"
    env.close()
    task = envs.WingFlutterMarginTask(wing_tip_twist_limit_rad=0.01)  # the trim twist is about 0.02 rad
    env = gym.make("FlexSim/GTM-FlutterMargin-v1", task=task)
    _, info = env.reset(seed=0)
    _, _, terminated, _, info = env.step(info["trim_action"])
    assert terminated and info["termination_reason"] == "structural_limit"
    env.close()
    venv = vector.WingFlutterMarginVectorEnv(2, task=task)
    _, info = venv.reset(seed=0)
    _, _, terminated, _, info = venv.step(np.asarray(info["trim_action"], np.float32))
    assert terminated.all() and list(info["termination_reason"]) == ["structural_limit"] * 2
    venv.close()


def test_array_actions_check_as_the_general_path(env):
    """A float32/float64 action array takes FlexSimEnv._check_action's fast path (4 Python floats): the same clipped
    values, bit for bit (signed zeros included: numpy's minimum/maximum return the second argument on ties), and the
    same clipped flag as the general path of the same numbers given as a list."""
    base = env.unwrapped
    cases = [[0.5, 0.1, -0.2, 0.0], [-0.0, -0.0, 0.0, -0.0], [0.0, -1.0, 1.0, -1.0], [1.0, 1.0, -1.0, 1.0],
             [2.0, -3.0, 0.5, 7.0], [-1e-30, 1.0000001, -1.0000001, 0.25]]
    for values in cases:
        for dtype in (np.float32, np.float64):
            arr = np.array(values, dtype)
            fast, fast_clipped = base._check_action(arr)
            general, general_clipped = base._check_action([float(v) for v in arr])
            assert fast.dtype == general.dtype == np.float64
            assert fast.tobytes() == general.tobytes() and fast_clipped == general_clipped, (values, dtype)
    with pytest.raises(ValueError, match=r"action: values must be finite"):
        base._check_action(np.array([0.5, np.nan, 0.0, 0.0], np.float32))
