"""Batched environments (``gym.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")``).

Checks:
* for every FlexSim id, each sub-environment of the batched env follows the single env made with the
  same seed (``seed + i``) and fed the same actions: states equal to 1e-9 relative (|dx| <= 1e-9 (1 + |x|);
  ETD2RK's products are GEMMs over the rows instead of GEMVs, so rounding differs: about 1e-13 seen
  after 20 steps), observations to 1e-5 relative (float32), rewards to 1e-9, terminations exactly;
  with DOP853 (integrated aircraft by aircraft) exactly;
* gymnasium 1.x semantics: ``metadata["autoreset_mode"]``; with the time limit hit every 3 steps, the
  NextStep and SameStep autoresets give the same observations, rewards, terminations, truncations and
  ``final_obs`` as ``SyncVectorEnv`` of the same id and seeds (the reference implementation of the
  convention); ``Disabled`` requires a masked reset; the info arrays carry ``_key`` masks;
* :func:`flexsim.sim.periods.advance_rows` reports a crash, a non-finite state and a model error per row exactly as
  ``FlightDynamics.advance`` does for that aircraft alone (stubbed right-hand sides as in test_integrator, and the
  compiled rows: ground, an altitude outside the ISA range, a normal period); many rows (matrix products over the
  rows) follow the single env (row by row) to rounding;
* bad input (wrong action shape, NaN in one row, num_envs 0, a FlightDynamics of other settings) raises
  a ValueError naming the field.
"""

import copy

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

from flexsim import envs
from flexsim.sim import periods
from flexsim.sim.fixed_step import ETD2RK


def advance_batch(dynamics, states, x, u, t0, t1, winds):
    """:func:`flexsim.sim.periods.advance_rows` as one StepOutcome per row."""
    out = periods.advance_rows(dynamics, states, x, u, t0, t1, winds)
    return [out.row(i) for i in range(len(dynamics))]


def _actions(trim, k, space):
    a = trim + 0.01 * np.sin(k + np.arange(4))[None, :]
    return np.clip(a, space.low, space.high).astype(np.float32)


def _compare_with_single(env_id, steps, n=3, seed=20, exact=False, **kwargs):
    venv = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", **kwargs)
    assert venv.metadata["autoreset_mode"] == AutoresetMode.NEXT_STEP
    assert venv.observation_space.shape == (n, *venv.single_observation_space.shape)
    obs, info = venv.reset(seed=seed)
    singles = [gym.make(env_id, **kwargs) for _ in range(n)]
    first = [s.reset(seed=seed + i) for i, s in enumerate(singles)]
    for i, (o, inf) in enumerate(first):
        np.testing.assert_array_equal(o, obs[i])
        np.testing.assert_array_equal(inf["trim_action"], info["trim_action"][i])
    worst = 0.0
    for k in range(steps):
        a = _actions(info["trim_action"], k, venv.single_action_space)
        obs, reward, term, trunc, vinfo = venv.step(a)
        for i, s in enumerate(singles):
            o, r, te, tr, sinfo = s.step(a[i])
            x_single, x_batch = s.unwrapped.state, venv.envs[i].state
            if exact:
                np.testing.assert_array_equal(x_batch, x_single)
                assert r == reward[i]
            else:
                err = np.max(np.abs(x_batch - x_single) / (1.0 + np.abs(x_single)))
                worst = max(worst, err)
                assert err <= 1e-9, (env_id, k, i, err)
                assert r == pytest.approx(reward[i], rel=1e-9, abs=1e-9)
            np.testing.assert_allclose(obs[i], o, rtol=1e-5, atol=1e-6)
            assert (te, tr) == (term[i], trunc[i])
            assert sinfo["termination_reason"] == vinfo["termination_reason"][i]
            assert vinfo["_reward_parts"][i] and vinfo["reward_parts"]["alive"][i] == sinfo["reward_parts"]["alive"]
    venv.close()
    for s in singles:
        s.close()
    return worst


@pytest.mark.parametrize("env_id", list(envs.ENV_IDS))
def test_each_sub_env_follows_the_single_env(env_id):
    _compare_with_single(env_id, steps=8)


def test_level_hold_20_steps_and_dop853_exact():
    assert _compare_with_single("FlexSim/GTM-LevelHold-v0", steps=20, aero="quasi-steady") <= 1e-9
    _compare_with_single("FlexSim/GTM-LevelHold-v0", steps=3, n=2, exact=True, aero="quasi-steady",
                         integrator=envs.IntegratorSettings(method="DOP853"))


@pytest.mark.parametrize("mode", [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP])
def test_autoreset_matches_sync_vector_env(mode):
    kw = dict(aero="quasi-steady", max_episode_steps=3)
    batched = gym.make_vec("FlexSim/GTM-GustAlleviation-v0", num_envs=2, vectorization_mode="vector_entry_point",
                           autoreset_mode=mode, **kw)
    sync = gym.make_vec("FlexSim/GTM-GustAlleviation-v0", num_envs=2, vectorization_mode="sync",
                        vector_kwargs={"autoreset_mode": mode}, **kw)
    assert batched.metadata["autoreset_mode"] == sync.metadata["autoreset_mode"] == mode
    ob, ib = batched.reset(seed=[4, 9])
    os_, is_ = sync.reset(seed=[4, 9])
    np.testing.assert_array_equal(ob, os_)
    ended = 0
    for k in range(8):
        a = _actions(ib["trim_action"], k, batched.single_action_space)
        rb = batched.step(a)
        rs = sync.step(a)
        np.testing.assert_allclose(rb[0], rs[0], rtol=1e-5, atol=1e-6)
        np.testing.assert_allclose(rb[1], rs[1], rtol=1e-9, atol=1e-9)
        np.testing.assert_array_equal(rb[2], rs[2])
        np.testing.assert_array_equal(rb[3], rs[3])
        assert set(rb[4]) == set(rs[4])
        if "final_obs" in rs[4]:
            np.testing.assert_array_equal(rb[4]["_final_obs"], rs[4]["_final_obs"])
            for i in np.flatnonzero(rs[4]["_final_obs"]):
                np.testing.assert_allclose(rb[4]["final_obs"][i], rs[4]["final_obs"][i], rtol=1e-5, atol=1e-6)
        ended += int(rb[3].sum())
    assert ended >= 2  # the time limit did end episodes (2 envs x steps 3 and 6, or 4 and 8)
    batched.close()
    sync.close()


def test_disabled_autoreset_needs_a_masked_reset():
    venv = gym.make_vec("FlexSim/GTM-LevelHold-v0", num_envs=2, vectorization_mode="vector_entry_point",
                        autoreset_mode="Disabled", aero="quasi-steady", max_episode_steps=1)
    _, info = venv.reset(seed=0)
    _, _, _, trunc, _ = venv.step(info["trim_action"])
    assert trunc.tolist() == [True, True]
    with pytest.raises(RuntimeError, match=r"sub-environments \[0, 1\] ended"):
        venv.step(info["trim_action"])
    venv.reset(options={"reset_mask": np.array([True, True])})
    venv.step(info["trim_action"])
    venv.close()


def test_batched_failures_equal_the_single_aircraft_outcomes():
    venv = envs.vector.LevelHoldVectorEnv(3, aero="quasi-steady", integrator=envs.IntegratorSettings(method="ETD2RK", max_step_s=0.005))
    venv.reset(seed=0)
    # one FlightDynamics per row, each with its own stand-in model (shallow copies: shared caches)
    dyns = [copy.copy(venv.envs[0].dynamics) for _ in venv.envs]
    n = dyns[0].layout.n_states
    z = dyns[0].layout.position.start + 2
    stepper = ETD2RK(np.zeros((n, n)), dyns[0].dt / dyns[0].substeps)
    sink = np.zeros(n)
    sink[z] = 10.0  # down-rate [m/s]: row 0 crashes within the period

    class Model:  # stand-in models: crash, non-finite after 2.5 substeps, model error
        def __init__(self, rhs):
            self.rhs = rhs

    h = stepper.h

    def error(t, x, u, wind=None):
        raise ValueError("stub failure")

    models = [Model(lambda t, x, u, wind=None: sink),
              Model(lambda t, x, u, wind=None: sink * 0.0 if t < 2.5 * h else np.full_like(x, np.nan)),
              Model(error)]
    for dyn, model in zip(dyns, models):
        dyn.model = model
    states = [periods.IntegrationState(stepper=stepper) for _ in dyns]
    x = np.zeros((3, n))
    x[:, z] = -0.07
    u = np.zeros((3, 4))
    t0, t1 = np.zeros(3), np.full(3, dyns[0].dt)
    batch = advance_batch(dyns, states, x, u, t0, t1, [None] * 3)
    for i, dyn in enumerate(dyns):
        alone = dyn.advance(states[i], x[i], u[i], 0.0, dyn.dt)
        assert (batch[i].crashed, batch[i].failure, batch[i].nfev) == (alone.crashed, alone.failure, alone.nfev)
        assert batch[i].time_s == pytest.approx(alone.time_s, abs=1e-15)
        np.testing.assert_allclose(batch[i].x, alone.x, atol=1e-15)
    assert batch[0].crashed and batch[0].time_s == pytest.approx(0.007, abs=1e-12)
    assert batch[1].failure == "non-finite state: ETD2RK step 3 of 4 from t = 0.01 s"
    assert batch[2].failure == "model error: stub failure"


def test_bad_input_is_named():
    venv = gym.make_vec("FlexSim/GTM-LevelHold-v0", num_envs=2, vectorization_mode="vector_entry_point", aero="quasi-steady")
    _, info = venv.reset(seed=1)
    with pytest.raises(ValueError, match=r"actions: expected shape \(2, 4\)"):
        venv.step(info["trim_action"][0])
    bad = info["trim_action"].copy()
    bad[1, 2] = np.nan
    with pytest.raises(ValueError, match=r"actions\[1\]: action: values must be finite, got action\[2\] \(elevator\)"):
        venv.step(bad)
    with pytest.raises(ValueError, match="num_envs = 0: must be an integer >= 1"):
        envs.vector.LevelHoldVectorEnv(0)
    with pytest.raises(ValueError, match="dynamics: was built with aero = 'quasi-steady', this env has aero = 'unsteady'"):
        envs.LevelHoldEnv(dynamics=venv.envs[0].dynamics)
    venv.close()


def test_compiled_rows_report_as_the_single_aircraft_advance():
    """Few rows go through the compiled ETD2RK kernel (periods.COMPILED_ROWS_BELOW): a crash, an altitude outside
    the ISA range (model error, with the model's message) and a normal period equal FlightDynamics.advance of each
    aircraft alone (same matrix-vector arithmetic: to 1e-12)."""
    venv = envs.vector.LevelHoldVectorEnv(3, turbulence="none")  # unsteady aero: ETD2RK
    venv.reset(seed=0)
    dyns = [e.dynamics for e in venv.envs]
    states = [venv._batch.states[i] for i in range(3)]
    lay = dyns[0].layout
    x = np.array([e.state for e in venv.envs])
    x[0, lay.position.start + 2] = -0.05  # 5 cm above the ground, 0.3 rad nose down: ground within the first substep
    x[0, lay.euler.start + 1] = -0.3
    x[1, lay.position.start + 2] = -30_000.0  # above the ISA range of the model
    u = np.array([e.applied_controls for e in venv.envs])
    t0, t1 = np.zeros(3), np.full(3, dyns[0].dt)
    batch = advance_batch(dyns, states, x, u, t0, t1, [None] * 3)
    assert periods.COMPILED_ROWS_BELOW > 3
    for i, dyn in enumerate(dyns):
        alone = dyn.advance(states[i], x[i], u[i], 0.0, dyn.dt)
        assert (batch[i].crashed, batch[i].failure, batch[i].nfev) == (alone.crashed, alone.failure, alone.nfev), i
        assert batch[i].time_s == pytest.approx(alone.time_s, abs=1e-15)
        np.testing.assert_allclose(batch[i].x, alone.x, rtol=1e-12, atol=1e-12)
    assert batch[0].crashed and batch[1].failure.startswith("model error: ") and "ISA range" in batch[1].failure
    assert batch[2].failure == "" and not batch[2].crashed and batch[2].time_s == dyns[0].dt
    venv.close()


def test_products_over_rows_follow_the_compiled_single_env(monkeypatch):
    """Many rows step as GEMMs over the rows, one row through the compiled kernel: with the threshold at 2 the 3-row
    batch takes the products and each single env the kernel; states equal to 1e-9 relative (rounding only)."""
    monkeypatch.setattr(periods, "COMPILED_ROWS_BELOW", 2)
    assert _compare_with_single("FlexSim/GTM-LevelHold-v0", steps=8) <= 1e-9
