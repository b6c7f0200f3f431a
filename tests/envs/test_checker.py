"""Registration and gymnasium's env checker.

Checks: the seven ids are registered once (registering again is a no-op); ``gymnasium.utils.env_checker.
check_env`` passes without warnings for every id (but the linear-range note of the HALE's trim), its render check included (on a headless machine the
instances offer "rgb_array" only, and ``render_mode="human"`` fails at once with a clear message);
the spaces are float32 Boxes with finite bounds and ``observation_structure`` tiles the observation.
Tolerances: exact (structural checks).
"""

import sys
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from flexsim import envs
from flexsim.io.viewer import ViewerUnavailableError

#: The one line a reset says when its trim bends a wing beyond the linear structure's range (the HALE's does, by design:
#: tests/envs/test_linear_range_reset.py); every other warning fails the check.
LINEAR_RANGE_NOTE = r".*linear structure beyond its range"


def test_ids_registered_once():
    before = {k: gym.registry[k] for k in envs.ENV_IDS}
    envs.register_envs()
    assert set(envs.ENV_IDS) <= set(gym.registry)
    assert all(gym.registry[k] is before[k] for k in envs.ENV_IDS)
    assert [gym.registry[k].max_episode_steps for k in envs.ENV_IDS] == [1000, 1000, 1000, 500, 1000, 1000, 500]


@pytest.mark.parametrize("env_id", list(envs.ENV_IDS))
def test_check_env_passes(env_id):
    env = gym.make(env_id)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.filterwarnings("ignore", message=LINEAR_RANGE_NOTE)
        check_env(env.unwrapped, skip_render_check=True)  # with the render check: the test below
    space = env.observation_space
    assert space.dtype == np.float32 and np.all(np.isfinite(space.low)) and np.all(np.isfinite(space.high))
    assert env.action_space.dtype == np.float32
    np.testing.assert_array_equal(env.action_space.low, [0, -1, -1, -1])
    np.testing.assert_array_equal(env.action_space.high, [1, 1, 1, 1])
    structure = env.unwrapped.observation_structure
    covered = np.concatenate([np.arange(space.shape[0])[s] for s in structure.values()])
    np.testing.assert_array_equal(covered, np.arange(space.shape[0]))
    assert len(env.unwrapped.observation_names) == space.shape[0]
    env.close()


def test_invalid_arguments_name_field_and_range():
    with pytest.raises(ValueError, match="aero = 'bogus'"):
        envs.LevelHoldEnv(aero="bogus")
    with pytest.raises(ValueError, match=r"control_rate_hz = 0: must be a number in \[5, 1000\] Hz"):
        envs.LevelHoldEnv(control_rate_hz=0)
    with pytest.raises(ValueError, match="turbulence = 'stormy'"):
        envs.LevelHoldEnv(turbulence="stormy")
    with pytest.raises(ValueError, match="render_mode = 'ansi'"):
        envs.LevelHoldEnv(render_mode="ansi")
    with pytest.raises(ValueError, match="task = .*must be a LevelHoldTask"):
        envs.LevelHoldEnv(task=envs.TurnTask())
    with pytest.raises(ValueError, match="method = 'RK4'"):
        envs.IntegratorSettings(method="RK4")
    with pytest.raises(ValueError, match=r"radius_range_m = \(100.0, 200.0\)"):
        envs.TurnTask(radius_range_m=(100.0, 200.0))
    with pytest.raises(ValueError, match="aero = 'quasi-steady': no usable open-loop flutter point"):
        envs.FlutterMarginEnv(aero="quasi-steady")
    with pytest.raises(ValueError, match="subject = 'tail'"):
        envs.FlutterMarginTask(subject="tail")
    with pytest.raises(ValueError, match="FlutterMarginEnv observes fin_twist_rate_rad_s, not wing_twist_rate_rad_s"):
        envs.FlutterMarginEnv(task=envs.WingFlutterMarginTask())
    assert envs.RewardTerm("e", 0, 1.0).weight == 0.0 and envs.InitialPerturbation(altitude_m=0).altitude_m == 0.0
    with pytest.raises(ValueError, match=r"RewardTerm\(e\).weight = -1: must be a finite number >= 0"):
        envs.RewardTerm("e", -1, 1.0)
    with pytest.raises(ValueError, match=r"RewardTerm\(e\).scale = 0: must be a finite number > 0"):
        envs.RewardTerm("e", 1, 0)
    with pytest.raises(ValueError, match=r"altitude_m = nan: must be a finite number >= 0"):
        envs.InitialPerturbation(altitude_m=float("nan"))


def test_flutter_margin_v1_seeds_antisymmetric_wing_torsion():
    """v1: calibrated gtm, flutter at M 0.690 (36.9 rad/s) at 300 m; the seed is an equal first-torsion rate
    on both wing halves (antisymmetric in the coordinates of docs/conventions.md), observed at index 10."""
    env = gym.make("FlexSim/GTM-FlutterMargin-v1")
    u = env.unwrapped
    assert abs(u.flutter.mach - 0.6904) < 2e-3 and abs(u.flutter.frequency_rad_s - 36.93) < 0.2
    assert "wing" in u.flutter.mode
    obs, info = env.reset(seed=4)
    meas = u.dynamics.measure(u._x, 0.0)
    right, left = meas.tip_twist_rate_rad_s["right_wing"], meas.tip_twist_rate_rad_s["left_wing"]
    assert 0.04 < abs(right) < 0.11 and abs(right - left) < 0.02 * abs(right)
    assert u.observation_names[10] == "wing_twist_rate_rad_s"
    assert obs[10] == pytest.approx(0.5 * (right + left), rel=1e-5)
    env.close()


@pytest.mark.parametrize("env_id", list(envs.ENV_IDS))
def test_check_env_with_render_check_passes_headless(env_id, monkeypatch):
    """gymnasium's default check_env on a machine without a display: "human" is not offered, "rgb_array" works."""
    for name in ("DISPLAY", "WAYLAND_DISPLAY", "WAYLAND_SOCKET"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setattr(sys, "platform", "linux")
    env = gym.make(env_id)
    assert env.unwrapped.metadata["render_modes"] == ["rgb_array"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.filterwarnings("ignore", message=LINEAR_RANGE_NOTE)
        check_env(env.unwrapped)
    with pytest.raises(ViewerUnavailableError, match="render_mode = 'human': cannot open a Rerun viewer: no display"):
        gym.make(env_id, render_mode="human")


def test_pickling_an_environment_is_refused_with_the_way_to_share_it():
    """An environment cannot travel to another process (compiled models, integrator state): pickling it, single or
    vector, raises a TypeError that says how to make one there, instead of pickle's message about a local function."""
    import pickle

    env = gym.make("FlexSim/GTM-LevelHold-v1")
    with pytest.raises(TypeError, match=r"cannot be pickled .*make a new one there with gymnasium.make\(id, \*\*kwargs\)"):
        pickle.dumps(env)
    vec = gym.make_vec("FlexSim/GTM-LevelHold-v1", num_envs=2, vectorization_mode="vector_entry_point")
    with pytest.raises(TypeError, match=r"VectorEnv cannot be pickled .*gymnasium.make_vec"):
        pickle.dumps(vec)
    env.close()
    vec.close()
