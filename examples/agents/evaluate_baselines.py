"""Mean return of each classical baseline against a random policy over seeded episodes.

    python examples/agents/evaluate_baselines.py                      # all tasks, 10 seeds each
    python examples/agents/evaluate_baselines.py --episodes 3 --env FlexSim/GTM-Turn-v0

Prints one line per task (mean +- standard deviation of the return, mean length, terminations).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parent))

import gymnasium as gym  # noqa: E402
import numpy as np  # noqa: E402

from flexsim import envs  # noqa: E402,F401  (registers the ids)
from baselines import BASELINES, RandomPolicy, make_baseline, run_episode  # noqa: E402


def evaluate(env_id: str, episodes: int, first_seed: int = 0, **make_kwargs) -> dict[str, dict]:
    """Returns per policy ("baseline", "random"): returns, lengths, termination reasons."""
    env = gym.make(env_id, **make_kwargs)
    out = {}
    for label, policy in (("baseline", make_baseline(env_id, env)), ("random", RandomPolicy(env))):
        rows = [run_episode(env, policy, first_seed + k) for k in range(episodes)]
        out[label] = {"returns": np.array([r[0] for r in rows]), "lengths": np.array([r[1] for r in rows]),
                      "reasons": [r[2] for r in rows]}
    env.close()
    return out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--episodes", type=int, default=10)
    parser.add_argument("--env", action="append", choices=list(BASELINES), help="task id (repeatable; default all)")
    parser.add_argument("--aero", default="unsteady", choices=["unsteady", "quasi-steady"])
    args = parser.parse_args(argv)
    for env_id in args.env or list(BASELINES):
        t0 = time.perf_counter()
        result = evaluate(env_id, args.episodes, aero=args.aero)
        for label, r in result.items():
            crashes = {k: r["reasons"].count(k) for k in set(r["reasons"]) if k}
            print(f"{env_id:32s} {label:8s} return {r['returns'].mean():9.2f} +- {r['returns'].std():7.2f}  "
                  f"length {r['lengths'].mean():7.1f}  terminations {crashes}", flush=True)
        print(f"  ({time.perf_counter() - t0:.0f} s)", flush=True)


if __name__ == "__main__":
    main()
