"""Train a Stable-Baselines3 agent on a flexsim task (SB3 is optional and not a flexsim dependency).

    python -m pip install "stable-baselines3>=2.4"
    python examples/agents/train_sb3.py --env FlexSim/GTM-GustAlleviation-v0 --algo SAC --steps 200000 --envs 2

One environment steps at about 550-570 steps/s on a quiet core with its default integrator (the speed table of
``docs/environments.md``, ``benchmarks/bench_envs.py``); the learner's updates come on top (PPO with 2 workers
measured about 40 steps/s on a loaded 2-core machine, 2026-12-01). Use several worker processes (``--envs``;
each worker pins its BLAS to one thread); torch is limited to one thread (``--torch-threads``), which ran PPO
1.7 times faster than torch's default on 2 cores. Expect hours, not minutes, for a useful policy. Observations are normalised with ``VecNormalize`` (physical units differ
by orders of magnitude); the trained model and the normalisation statistics are saved to ``--out``.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from flexsim import envs  # noqa: E402  (registers the FlexSim/* ids)

ALGORITHMS = ("SAC", "PPO", "TD3")


def _import_sb3():
    try:
        import stable_baselines3 as sb3
        from stable_baselines3.common.env_util import make_vec_env
        from stable_baselines3.common.vec_env import SubprocVecEnv, VecNormalize
    except ImportError:
        sys.exit("train_sb3.py needs Stable-Baselines3, which flexsim does not install: "
                 "python -m pip install 'stable-baselines3>=2.4'")
    return sb3, make_vec_env, SubprocVecEnv, VecNormalize


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--env", default="FlexSim/GTM-GustAlleviation-v0", choices=list(envs.ENV_IDS))
    parser.add_argument("--algo", default="SAC", choices=ALGORITHMS)
    parser.add_argument("--steps", type=int, default=200_000, help="total environment steps")
    parser.add_argument("--envs", type=int, default=2, help="parallel worker processes")
    parser.add_argument("--aero", default="unsteady", choices=["unsteady", "quasi-steady"])
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, default=Path("sb3_flexsim"))
    parser.add_argument("--torch-threads", type=int, default=1, help="torch intra-op threads of the learner [1]")
    args = parser.parse_args(argv)
    if args.torch_threads < 1:
        parser.error(f"--torch-threads = {args.torch_threads}: must be >= 1")
    sb3, make_vec_env, SubprocVecEnv, VecNormalize = _import_sb3()
    import torch

    torch.set_num_threads(args.torch_threads)
    vec_cls = SubprocVecEnv if args.envs > 1 else None
    venv = make_vec_env(args.env, n_envs=args.envs, seed=args.seed, env_kwargs={"aero": args.aero}, vec_env_cls=vec_cls)
    venv = VecNormalize(venv, norm_obs=True, norm_reward=False)
    model = getattr(sb3, args.algo)("MlpPolicy", venv, seed=args.seed, verbose=1)
    model.learn(total_timesteps=args.steps)
    args.out.mkdir(parents=True, exist_ok=True)
    model.save(args.out / f"{args.algo.lower()}_{args.env.split('/')[-1]}")
    venv.save(str(args.out / "vecnormalize.pkl"))
    print(f"saved the model and the VecNormalize statistics to {args.out}/; compare with the classical baseline: "
          f"python examples/agents/evaluate_baselines.py --env {args.env}")


if __name__ == "__main__":
    main()
