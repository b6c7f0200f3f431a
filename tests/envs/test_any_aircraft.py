"""The environments on an aircraft that is not the GTM: the task at the aircraft's cruise point, the limits from its
envelope and its trim (envs/aircraft_defaults.py), a rigid fin's sensors reading zero; the GTM's defaults unchanged."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

from flexsim import envs  # noqa: F401  (registers the ids)
from flexsim.atmosphere import isa_density, speed_of_sound
from flexsim.envs.aircraft_defaults import MIN_TURN_RADIUS_M, WING_DEFLECTION_FRACTION
from flexsim.envs.config import FlightLimits
from flexsim.envs.level_hold import LevelHoldTask
from flexsim.envs.turn import TurnTask
from tests.cli.small_aircraft import rc_glider_toml

ENVELOPE = "min_speed_eas_m_s = 6.0\nmax_speed_eas_m_s = 30.0\ncruise_altitude_m = 500.0\ncruise_speed_m_s = 10.0"


@pytest.fixture(scope="module")
def glider(tmp_path_factory):
    path = tmp_path_factory.mktemp("rc") / "rc.toml"
    path.write_text(rc_glider_toml(ENVELOPE, rigid_fin=True))
    return str(path)


def test_level_hold_flies_the_glider_at_its_cruise_point(glider):
    env = gym.make("FlexSim/GTM-LevelHold-v0", aircraft=glider, aero="quasi-steady", turbulence="none")
    task, limits = env.unwrapped.task, env.unwrapped.limits
    assert task.altitude_m == 500.0 and task.mach * speed_of_sound(500.0) == pytest.approx(10.0, rel=1e-12)
    obs, info = env.reset(seed=0)
    trim = env.unwrapped.dynamics.trim(task.manoeuvre)
    # limits: the trim's tip deflection + 0.3 x the 1 m wing; the envelope's lower end (6 m/s EAS) as TAS at 500 m
    assert limits.wing_tip_deflection_m == pytest.approx(abs(trim.tip_deflection_m) + WING_DEFLECTION_FRACTION * 1.0,
                                                         rel=1e-12)
    assert limits.min_airspeed_m_s == pytest.approx(6.0 * math.sqrt(1.225 / float(isa_density(500.0))), rel=1e-12)
    names = env.unwrapped.observation_names
    fin = [names.index(f"tip_deflection_vtail_m"), names.index("tip_twist_vtail_rad")]
    steps = 0
    for _ in range(50):
        obs, _, terminated, truncated, step_info = env.step(info["trim_action"])
        steps += 1
        assert obs[fin].tolist() == [0.0, 0.0]  # the rigid fin does not deform
        if terminated or truncated:
            break
    assert steps == 50 and step_info["termination_reason"] == ""
    env.close()


def test_turn_keeps_the_gtm_tasks_bank_angles(glider):
    """R ~ V^2 at the same bank angles, from 100 m at least: 10 m/s gives (7000, 12000) x (10 / V_GTM)^2 < 100 m, so
    the range starts at 100 m and keeps its ratio 12/7."""
    env = gym.make("FlexSim/GTM-Turn-v0", aircraft=glider, aero="quasi-steady")
    lo, hi = env.unwrapped.task.radius_range_m
    v_gtm = TurnTask().manoeuvre.speed_m_s
    assert 7000.0 * (10.0 / v_gtm) ** 2 < MIN_TURN_RADIUS_M
    assert lo == MIN_TURN_RADIUS_M and hi == pytest.approx(MIN_TURN_RADIUS_M * 12.0 / 7.0, rel=1e-12)
    env.close()


def test_the_gtm_keeps_its_documented_defaults():
    env = gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady")
    assert env.unwrapped.task == LevelHoldTask() and env.unwrapped.limits == FlightLimits()
    env.close()


def test_a_given_task_and_limits_are_used_as_given(glider):
    task, limits = LevelHoldTask(altitude_m=800.0, mach=0.03), FlightLimits(min_airspeed_m_s=5.0)
    env = gym.make("FlexSim/GTM-LevelHold-v0", aircraft=glider, aero="quasi-steady", task=task, limits=limits)
    assert env.unwrapped.task is task and env.unwrapped.limits is limits
    assert np.all(np.isfinite(env.reset(seed=1)[0]))
    env.close()


def test_wing_flutter_margin_searches_the_aircrafts_own_flutter_point():
    """mAEWing1 (no [envelope]): the flutter point is searched from its stall estimate to M 0.95 at 300 m, and found at
    its body-freedom flutter near M 0.099-0.10 (flexsim/aircraft/data/maewing1.md: 33.7 m/s at sea level with p-k;
    here the finite-state model at 300 m, within 5 %); flown open loop just beyond it, the flutter grows."""
    env = gym.make("FlexSim/GTM-FlutterMargin-v1", aircraft="maewing1")
    u = env.unwrapped
    assert u.task.flutter_mach_range[0] < 0.05 and u.task.flutter_mach_range[1] == 0.95
    assert u.flutter.speed_m_s == pytest.approx(33.66, rel=0.05)
    assert u.limits.min_airspeed_m_s < u.flutter.speed_m_s < u.limits.max_mach * speed_of_sound(300.0)
    _, info = env.reset(seed=0)
    for _ in range(200):
        *_, terminated, truncated, step_info = env.step(info["trim_action"])
        if terminated or truncated:
            break
    assert step_info["termination_reason"] == "structural_limit"
    env.close()
