"""Vector environments.

Checks: ``gymnasium.make_vec(id, num_envs=2, vectorization_mode="async")`` gives exactly the same
observations, rewards and terminations as ``"sync"`` for the same seeds over 10 steps (exact: the
workers run the same deterministic code), with DOP853 and with ETD2RK (quasi-steady aero for speed; BLAS
pinned to one thread by tests/conftest.py, as the workers are: the trim's dense linear algebra differs
in the last bits between thread counts); the async workers pin OpenBLAS to one thread
(``worker_blas_threads``), the sync ones are left alone (None).
"""

import gymnasium as gym
import numpy as np
import pytest

from flexsim import envs


def _run(mode, method):
    venv = gym.make_vec("FlexSim/GTM-GustAlleviation-v0", num_envs=2, vectorization_mode=mode, aero="quasi-steady",
                        integrator=envs.IntegratorSettings(method=method))
    obs, info = venv.reset(seed=[11, 12])
    trims = info["trim_action"]
    out = [obs]
    for k in range(10):
        action = np.clip(trims + 0.01 * np.sin(k + np.arange(4)), venv.single_action_space.low, venv.single_action_space.high)
        obs, reward, terminated, truncated, _ = venv.step(action.astype(np.float32))
        out += [obs, reward, terminated, truncated]
    threads = venv.get_attr("worker_blas_threads")
    venv.close()
    return out, threads


@pytest.mark.parametrize("method", ["DOP853", "ETD2RK"])
def test_async_equals_sync(method):
    sync, sync_threads = _run("sync", method)
    asyn, async_threads = _run("async", method)
    for a, b in zip(sync, asyn):
        np.testing.assert_array_equal(a, b)
    assert sync_threads == (None, None)
    assert all(t is not None and all(n == 1 for n in t) for t in async_threads)
