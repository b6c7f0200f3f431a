"""Worker of ``bench_envs.py --compare``: env steps per CPU-second of the flexsim found on sys.path, as JSON.

Runs against any revision with the batched envs (``vectorization_mode="vector_entry_point"``, since 2026-12-01);
only public APIs are used. ``single``: one ``gym.make`` env (all wrappers), ``--steps`` steps, then the same steps on
``env.unwrapped`` and the median CPU time of 5 resets with a cached trim; ``batched``:
``gym.make_vec(..., num_envs=N, vectorization_mode="vector_entry_point")``, ``--steps`` vector steps. Both after a
reset and warm-up steps (model build, trim, Jacobian, matrix functions and numba loading excluded); the actions are
the trim action plus a small sine per row. CPU time of the process (one thread: BLAS pinned to one thread).

Run: python benchmarks/_envs_worker.py single|batched [--n 256] [--steps 200] [--max-step-s 0.005]
"""

from __future__ import annotations

import argparse
import json
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import warnings  # noqa: E402

import gymnasium as gym  # noqa: E402
import numpy as np  # noqa: E402

warnings.filterwarnings("ignore", category=DeprecationWarning)  # the v0 ids' "out of date" notice

import flexsim.envs as envs  # noqa: E402

ENV_ID = "FlexSim/GTM-LevelHold-v0"


def _actions(trim: np.ndarray, k: int) -> np.ndarray:
    """Trim action (rows, 4) plus 0.01 sin(k + j), clipped to the action space, float32."""
    return np.clip(trim + 0.01 * np.sin(k + np.arange(4)), [0, -1, -1, -1], [1, 1, 1, 1]).astype(np.float32)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("mode", choices=("single", "batched"))
    parser.add_argument("--n", type=int, default=256)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--max-step-s", type=float, default=None, help="ETD2RK step (default: the tree's default)")
    args = parser.parse_args()
    kwargs = {} if args.max_step_s is None else {"integrator": envs.IntegratorSettings(method="ETD2RK", max_step_s=args.max_step_s)}
    if args.mode == "single":
        env = gym.make(ENV_ID, max_episode_steps=10**6, **kwargs)
        _, info = env.reset(seed=0)
        trim, n = np.asarray(info["trim_action"], float), 1
    else:
        env = gym.make_vec(ENV_ID, num_envs=args.n, vectorization_mode="vector_entry_point", max_episode_steps=10**6, **kwargs)
        _, info = env.reset(seed=0)
        trim, n = np.asarray(info["trim_action"], float).reshape(args.n, 4), args.n
    for k in range(3):
        env.step(_actions(trim, k))
    acts = [_actions(trim, k) for k in range(3, 3 + args.steps)]
    c0 = time.process_time()
    for a in acts:
        out = env.step(a)
        if args.mode == "single" and (out[2] or out[3]):
            raise RuntimeError(f"episode ended in the benchmark: {out[4].get('termination_reason')}")
    cpu = time.process_time() - c0
    result = {"env_steps_per_cpu_s": n * args.steps / cpu, "cpu_s": cpu, "env_steps": n * args.steps}
    if args.mode == "single":
        # the same steps on the unwrapped env (no PassiveEnvChecker, OrderEnforcing, TimeLimit), and resets of
        # known trims (seeds 1-5: the trim and matrix functions are cached after the first reset)
        base = env.unwrapped
        base.reset(seed=0)
        c0 = time.process_time()
        for a in acts:
            base.step(a)
        result["unwrapped_steps_per_cpu_s"] = args.steps / (time.process_time() - c0)
        resets = []
        for seed in range(1, 6):
            c0 = time.process_time()
            env.reset(seed=seed)
            resets.append(time.process_time() - c0)
        result["reset_ms"] = 1e3 * sorted(resets)[len(resets) // 2]
    env.close()
    print(json.dumps(result))


if __name__ == "__main__":
    main()
