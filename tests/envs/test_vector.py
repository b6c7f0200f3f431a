"""Vector environments.

Checks: ``gymnasium.make_vec(id, num_envs=2, vectorization_mode="async")`` gives exactly the same
observations, rewards and terminations as ``"sync"`` for the same seeds over 10 steps (exact: the
workers run the same deterministic code); the async workers pin OpenBLAS to one thread
(``worker_blas_threads``), the sync ones are left alone (None).
"""

import gymnasium as gym
import numpy as np

import envs  # noqa: F401


def _run(mode):
    venv = gym.make_vec("FlexSim/GTM-GustAlleviation-v0", num_envs=2, vectorization_mode=mode, aero="quasi-steady")
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


def test_async_equals_sync():
    sync, sync_threads = _run("sync")
    asyn, async_threads = _run("async")
    for a, b in zip(sync, asyn):
        np.testing.assert_array_equal(a, b)
    assert sync_threads == (None, None)
    assert all(t is not None and all(n == 1 for n in t) for t in async_threads)
