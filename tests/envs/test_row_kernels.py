"""The compiled per-row outputs (flexsim/envs/row_kernels.py) against the one output layer of the simulator.

Measurements: air data, Mach, heading rate and structural sensors of off-trim states in a Dryden field equal
``OutputMaps.air_velocity_body`` + ``air_angles``, ``heading_rate``, ``flexsim.atmosphere.speed_of_sound`` and the
``ComponentSensor`` rows to 1e-12 relative (the same formulas; only the summation order of the sensor rows and libm
may differ, ~1e-16). Reward parts against the closed form of ``TrackingReward``; the angle wrap against
``math.remainder``.
"""

import math

import gymnasium as gym
import numpy as np
import pytest

from flexsim.atmosphere import speed_of_sound
from flexsim.envs.config import RewardTerm, TrackingReward
from flexsim.envs.dynamics import SENSOR_COMPONENTS
from flexsim.envs.episodes import wrap_angle
from flexsim.sim.outputs import air_angles, heading_rate


@pytest.fixture(scope="module")
def flying():
    """LevelHold-v0 in moderate turbulence after 10 steps, and 12 states spread around that state."""
    env = gym.make("FlexSim/GTM-LevelHold-v0", turbulence="moderate")
    _, info = env.reset(seed=4)
    for _ in range(10):
        env.step(info["trim_action"])
    base = env.unwrapped
    rng = np.random.default_rng(0)
    lay = base.dynamics.layout
    x = np.repeat(base.state[None, :], 12, axis=0)
    x[:, lay.euler] += rng.uniform(-1.2, 1.2, (12, 3))
    x[:, lay.omega] += rng.uniform(-0.5, 0.5, (12, 3))
    x[:, lay.v] *= rng.uniform(0.5, 1.5, (12, 3))
    x[:, lay.position] += rng.uniform(-300.0, 300.0, (12, 3))
    x[:, lay.q] += rng.uniform(-0.3, 0.3, (12, lay.nq))
    x[:, lay.s] += rng.uniform(-1.0, 1.0, (12, lay.nq))
    x[:, lay.xi] += rng.uniform(-0.02, 0.02, (12, lay.nxi))
    x[:, lay.eta] += rng.uniform(-0.5, 0.5, (12, lay.nxi))
    yield base, x
    env.close()


def _close(a, b, rtol=1e-12):
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert np.all(np.abs(a - b) <= rtol * np.maximum(np.abs(b), 1e-300) + 1e-300), (a, b)


@pytest.mark.parametrize("pack", [True, False])
def test_measurements_equal_the_output_layer(flying, pack):
    base, x = flying
    dyn = base.dynamics
    winds = [base.wind] * len(x)
    packed = dyn.model.pack_winds(winds) if pack else None  # compiled wind, or the wind callable per row
    t = np.full(len(x), 0.2)
    meas = dyn.measure_batch(x, t, winds, packed)
    out = dyn.outputs
    for i, xi in enumerate(x):
        v_air = out.air_velocity_body(0.2, xi, base.wind)
        speed, alpha, beta = air_angles(v_air)
        _close(meas.airspeed_m_s[i], speed)
        _close(meas.alpha_rad[i], alpha)
        _close(meas.beta_rad[i], beta)
        altitude = -xi[dyn.layout.position][2]
        _close(meas.altitude_m[i], altitude)
        _close(meas.mach[i], speed / speed_of_sound(altitude))
        _close(meas.heading_rate_rad_s[i], heading_rate(xi[dyn.layout.euler], xi[dyn.layout.velocity]))
        for c in SENSOR_COMPONENTS:
            sensor = dyn.sensors[c]
            for name in ("tip_deflection_m", "tip_deflection_rate_m_s", "tip_twist_rad", "tip_twist_rate_rad_s"):
                _close(getattr(meas, name)[c][i], getattr(sensor, name)(xi))
            if c != "vtail":
                _close(meas.root_bending_moment_n_m[c][i], sensor.root_bending_moment_n_m(xi))


def test_mach_outside_the_isa_range_is_nan(flying):
    base, x = flying
    x = x[:2].copy()
    x[0, base.dynamics.layout.position.start + 2] = -30_000.0  # 30 km: above the ISA model's 20 km
    meas = base.dynamics.measure_batch(x, np.zeros(2))
    assert math.isnan(meas.mach[0]) and math.isfinite(meas.mach[1])


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


def test_wrap_angle_is_the_ieee_remainder():
    angles = np.random.default_rng(1).uniform(-50.0, 50.0, 1000)
    _close(wrap_angle(angles), [math.remainder(a, 2 * math.pi) for a in angles], rtol=1e-15)
    assert wrap_angle(3.0 * math.pi / 2) == pytest.approx(-math.pi / 2, rel=1e-15)
    assert np.isnan(wrap_angle(np.array([np.nan, np.inf, -np.inf]))).all() and math.isnan(wrap_angle(math.inf))


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
