"""The fixed-step integrator of the environments (ETD2RK) inside FlightDynamics.

Checks:
* ``IntegratorSettings`` (one class, ``simulate``'s too): "auto" resolves to the method ``simulate`` takes
  for the same model in still air (``flexsim.sim.simulate.default_method``): ETD2RK for the finite-state and the
  quasi-steady model; ``substeps(period) = ceil(period / max_step_s)`` (exact integers); a ``max_step_s``
  outside [1e-4, 0.05] s raises ValueError naming field, value and range (the class, or the control periods'
  check); the periods' defaults are rtol 1e-3 and ``period_atol``.
* An env step with ETD2RK reports 2 right-hand sides per step (``nfev = 2 * substeps``) and no LU; the tasks'
  default steps (``default_max_step_s``): LevelHold 20 ms (1 step per 50 Hz period), GustAlleviation 10 ms,
  FlutterMargin 5 ms; an ``integrator`` passed in is used as given.
* Ground crossing inside a period: with the linear part replaced by J = 0 (ETD2RK is then Heun's
  method, exact for a constant right-hand side) and a constant sink rate of 10 m/s from 0.27 m, the
  crash is reported at t = 0.027 s in the second period with altitude 0 (1e-12; linear interpolation
  of a linear motion is exact) and the right-hand sides of the two steps taken (4).
* A non-finite state in step 3 of 4 returns the last finite state (after step 2, at t0 + 2h, 1e-15)
  with a failure message naming the step; a model error (non-finite wind) is reported as such.
* ``advance`` with ETD2RK refuses a span other than the control period.
"""

import math

import gymnasium as gym
import numpy as np
import pytest

from flexsim import envs
from flexsim.sim.fixed_step import ETD2RK
from flexsim.sim import IntegratorSettings
from flexsim.sim.periods import IntegrationState, check_period_settings, period_atol
from flexsim.sim.simulate import default_method


def test_auto_resolution_substeps_and_range():
    auto = envs.IntegratorSettings()
    assert envs.IntegratorSettings is IntegratorSettings  # one settings class, re-exported
    for aero in ("unsteady", "quasi-steady"):
        env = gym.make("FlexSim/GTM-LevelHold-v0", aero=aero)
        model = env.unwrapped.dynamics.model
        assert auto.resolve(model).method == default_method(model, None) == "ETD2RK" == env.unwrapped.dynamics.method
        assert envs.IntegratorSettings(method="Radau").resolve(model).method == "Radau"
        assert env.unwrapped.dynamics.rtol == 1e-3 and np.array_equal(env.unwrapped.dynamics.atol, period_atol(model.layout))
        env.close()
    assert [auto.substeps(dt) for dt in (0.02, 0.05, 0.001, 1.0 / 30.0, 0.005)] == [1, 3, 1, 2, 1]  # max_step_s 0.02 s
    assert envs.IntegratorSettings(max_step_s=0.01).substeps(0.02) == 2
    assert envs.IntegratorSettings(max_step_s=0.005).substeps(0.02) == 4
    for bad in (0.0, math.nan, "fast"):
        with pytest.raises(ValueError, match=r"max_step_s = .*: must be"):
            envs.IntegratorSettings(max_step_s=bad)
    for bad in (1e-5, 0.1):
        with pytest.raises(ValueError, match=r"max_step_s = .*: must be in \[0\.0001, 0\.05\] s"):
            check_period_settings(envs.IntegratorSettings(max_step_s=bad))
    with pytest.raises(ValueError, match=r"max_step_s = 0\.1: must be in \[0\.0001, 0\.05\] s"):
        gym.make("FlexSim/GTM-LevelHold-v0", integrator=envs.IntegratorSettings(max_step_s=0.1))
    with pytest.raises(ValueError, match=r"integrator.method = 'RK45': the control periods take one of auto, ETD2RK"):
        check_period_settings(envs.IntegratorSettings(method="RK45"))


def _level_hold(**kwargs):
    env = gym.make("FlexSim/GTM-LevelHold-v0", turbulence="none", **kwargs)
    _, info = env.reset(seed=0)
    return env, info


def test_env_step_counts_and_defaults():
    env, info = _level_hold()
    dyn = env.unwrapped.dynamics
    assert dyn.method == "ETD2RK" and dyn.substeps == 1  # 20 ms steps (default_max_step_s)
    _, _, terminated, _, info = env.step(info["trim_action"])
    assert not terminated and info["nfev"] == 2 and info["nlu"] == 0 and info["solver_failure"] == ""
    env.close()
    gust = gym.make("FlexSim/GTM-GustAlleviation-v0")
    assert gust.unwrapped.dynamics.substeps == 2  # 10 ms steps: the structural response is the task's subject
    gust.close()
    explicit = gym.make("FlexSim/GTM-GustAlleviation-v0", integrator=envs.IntegratorSettings(max_step_s=0.02))
    assert explicit.unwrapped.dynamics.substeps == 1  # an integrator passed in is used as given
    explicit.close()
    flutter = gym.make("FlexSim/GTM-FlutterMargin-v0")
    assert flutter.unwrapped.dynamics.method == "ETD2RK" and flutter.unwrapped.dynamics.substeps == 4  # 5 ms steps
    flutter.close()


def test_crash_located_within_the_period(monkeypatch):
    env, _ = _level_hold(aero="quasi-steady", integrator=envs.IntegratorSettings(method="ETD2RK", max_step_s=0.005))
    dyn = env.unwrapped.dynamics
    n = dyn.layout.n_states
    state = IntegrationState(stepper=ETD2RK(np.zeros((n, n)), dyn.dt / dyn.substeps))
    z = dyn.layout.position.start + 2
    sink = np.zeros(n)
    sink[z] = 10.0  # down-rate [m/s]
    # the model is immutable: the right-hand side is replaced on its class, for this test only
    monkeypatch.setattr(type(dyn.model), "rhs", lambda self, t, x, u, wind=None: sink)
    x = np.zeros(n)
    x[z] = -0.27
    first = dyn.advance(state, x, np.zeros(4), 0.0, 0.02)
    assert not first.crashed and first.x[z] == pytest.approx(-0.07, abs=1e-12) and first.nfev == 8
    second = dyn.advance(first.state, first.x, np.zeros(4), 0.02, 0.04)
    assert second.crashed and second.failure == ""
    assert second.time_s == pytest.approx(0.027, abs=1e-12)
    assert second.x[z] == pytest.approx(0.0, abs=1e-12)
    assert second.nfev == 4
    env.close()


def test_non_finite_state_and_model_error_are_reported(monkeypatch):
    env, info = _level_hold(integrator=envs.IntegratorSettings(method="ETD2RK", max_step_s=0.005))
    dyn = env.unwrapped.dynamics
    state = env.unwrapped._batch.states[0]
    x0, u0 = env.unwrapped.state, env.unwrapped.applied_controls
    h = dyn.dt / dyn.substeps
    rhs = type(dyn.model).rhs
    monkeypatch.setattr(type(dyn.model), "rhs",
                        lambda self, t, x, u, wind=None: rhs(self, t, x, u, wind) if t < 2.5 * h else np.full_like(x, np.nan))
    out = dyn.advance(state, x0, u0, 0.0, dyn.dt)
    assert out.failure == "non-finite state: ETD2RK step 3 of 4 from t = 0.01 s"
    assert out.time_s == pytest.approx(2 * h, abs=1e-15) and np.all(np.isfinite(out.x)) and out.nfev == 6
    assert not out.crashed
    monkeypatch.undo()
    with pytest.raises(ValueError, match=r"t1 - t0 = 0\.01 s: ETD2RK steps whole control periods, must be dt = 0\.02 s"):
        dyn.advance(state, x0, u0, 0.0, 0.01)
    env.close()
    env = gym.make("FlexSim/GTM-LevelHold-v0", turbulence="light")
    _, info = env.reset(seed=0)
    env.unwrapped._wind = lambda t, p: np.full(np.shape(p), np.nan)
    _, _, terminated, _, info = env.step(info["trim_action"])
    assert terminated and info["termination_reason"] == "non_finite"
    assert info["solver_failure"].startswith("model error: wind(t, positions) returned")
    env.close()
