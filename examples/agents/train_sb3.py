"""Train a Stable-Baselines3 agent on a flexsim task and compare it with the LQR baseline, the trim controls held and
random actions (SB3 and torch are optional, not flexsim dependencies).

    python -m pip install --find-links /opt/wheels "torch==2.13.0+cpu" "stable-baselines3>=2.4"   # CPU torch
    OMP_NUM_THREADS=1 python examples/agents/train_sb3.py --minutes 8 --shaping 10 --penalty 0.5 --out logs/agent   # PPO on LevelHold-v1

Training stops at ``--steps`` environment steps or after ``--minutes`` of wall time, whichever comes first.
Every ``--val-every`` steps the deterministic policy flies ``--val-episodes`` validation episodes (seeds 500, 501,
...) and the best policy so far is kept (:class:`Validation`). Then that policy and the last one fly
``--eval-episodes`` seeded episodes (seeds 0, 1, ...; training uses seeds from 1000), beside the classical
baseline of ``examples/agents/baselines.py`` (LQR), the trim action held and uniformly random actions, on the
same seeds, in ``--workers`` processes. The script prints the mean returns and the ratio to the baseline, writes
them to ``<out>/result.json`` (with the settings, wall times, the 1-minute load average sampled every 30 s, the
validation means, the training episodes' returns and each policy's mean reward parts) and draws the learning
curve (training episode returns and validation means against environment steps, with the evaluation means as
horizontal lines) to ``<out>/learning_curve.png``. ``--plot RESULT_JSON [--png PNG]`` redraws that figure from a
result.json alone.

The default task is ``FlexSim/GTM-LevelHold-v1``: on v0 the trim controls held already return 93 % of the LQR
baseline's return, so no learning can show there (docs/environments.md, "Training an agent").

What the learner sees (changed from the raw env; the env, its reward and ``info["reward_parts"]``
are unchanged):

* **Actions relative to the trim** (``--residual-scale`` s, default 0.1): the agent's action a in [-1, 1]^4
  commands ``clip(trim_action + s a)``, trim_action from the reset info. Why: the raw action box is
  [0, 1] x [-1, 1]^3 of the full control ranges, and a fresh Gaussian policy centred on 0 with unit spread
  commands zero thrust and random full-scale surfaces, which leaves the flight envelope within seconds; the
  task is local to the trim. An all-zero residual is the trim hold, which the evaluation reports beside
  the learned policy, so what learning adds is visible.
* **Optional reward shaping** (``--shaping`` w, default 0, training only): potential-based shaping
  ``gamma Phi(s') - Phi(s)`` (Ng, Harada & Russell 1999: it leaves the optimal policy unchanged) with
  ``Phi = -w (|altitude error| / 30 m + |heading error| / 3 deg)``, unsaturated over LevelHold-v1's start
  offsets, where the env's tracking costs saturate at 10 m and 2 deg. Training curves then show shaped returns.
* **Optional unsaturated tracking cost** (``--penalty`` p, default 0, training only): the learner's reward also
  has ``-p (|altitude error| / 30 m + |heading error| / 3 deg)`` per step. Unlike the shaping, this changes the
  training objective (not the env's reward, which the evaluation uses): the env's tracking costs are flat beyond
  10 m and 2 deg, and with gamma 0.99 (a horizon of about 100 steps, 2 s) a 20-30 m altitude capture gives the
  discounted env return no gradient toward the reference; potential-based shaping cannot add one (it leaves the
  advantages under the true value function unchanged). Both costs fall with the same errors.
* **Checkpoint choice on validation seeds** (``--val-every``, default every 100,000 steps; 0: the last policy):
  PPO's deterministic return rises and falls during training; the policy evaluated is the one with the best
  validation mean, chosen on seeds that neither training nor evaluation uses (SB3 ``EvalCallback``'s model
  selection).
* **Normalised observations** (SB3 ``VecNormalize``): the observations mix metres (altitude 9144), m/s and
  radians. PPO's rewards are also scaled by a running estimate of the return's spread (training only;
  evaluation returns are the env's own).

Speed: one environment step is one control period (50 Hz) of the flexible 252-state model. ``--vector
batched`` (default) steps the ``--envs`` aircraft in ``--processes`` batched envs (``gym.make_vec(...,
vectorization_mode="vector_entry_point")``, all aircraft of a process in one call; an SB3 ``VecEnv`` adapter,
:func:`make_batched_vec_env`); ``--vector subproc`` runs one single env per process (SB3 ``SubprocVecEnv``).
Torch runs on ``--torch-threads`` (default 1, which ran PPO 1.7 times faster than torch's default on 2 cores).
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parent))

import gymnasium as gym  # noqa: E402
import numpy as np  # noqa: E402

from flexsim import envs  # noqa: E402  (registers the FlexSim/* ids)

ALGORITHMS = ("PPO", "SAC", "TD3")
#: Seeds of the training environments start here (evaluation uses 0 .. episodes - 1).
TRAIN_SEED = 1000
#: Seeds of the validation episodes that choose the checkpoint (``--val-every``), apart from training and evaluation.
VALIDATION_SEED = 500


class TrimResidualAction(gym.ActionWrapper):
    """Actions as deviations from the episode's trim: the env gets ``clip(trim_action + scale * a)`` for
    ``a`` in [-1, 1]^4 (module docstring); the trim action comes from each reset's info."""

    def __init__(self, env: gym.Env, scale: float) -> None:
        super().__init__(env)
        if not (math.isfinite(scale) and 0.0 < scale <= 2.0):
            raise ValueError(f"scale = {scale!r}: must be in (0, 2] (fraction of the normalised action range)")
        self.scale = float(scale)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (4,), np.float32)
        self._trim = np.zeros(4)

    def reset(self, **kwargs):
        obs, info = self.env.reset(**kwargs)
        self._trim = np.asarray(info["trim_action"], dtype=np.float64)
        return obs, info

    def action(self, action):
        space = self.env.action_space
        a = self._trim + self.scale * np.clip(np.asarray(action, dtype=np.float64), -1.0, 1.0)
        return np.clip(a, space.low, space.high).astype(np.float32)


def _import_sb3():
    try:
        import stable_baselines3 as sb3
        from stable_baselines3.common.callbacks import BaseCallback
        from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv, VecMonitor, VecNormalize
    except ImportError:
        sys.exit("train_sb3.py needs Stable-Baselines3 and torch, which flexsim does not install: "
                 "python -m pip install 'stable-baselines3>=2.4' (CPU torch: --find-links /opt/wheels 'torch==2.13.0+cpu')")
    return sb3, BaseCallback, DummyVecEnv, SubprocVecEnv, VecMonitor, VecNormalize


def _make_env(env_id: str, aero: str, scale: float, seed: int):
    def thunk():
        import flexsim.envs  # noqa: F401  (registers the ids in a spawned worker)

        env = TrimResidualAction(gym.make(env_id, aero=aero), scale)
        env.reset(seed=seed)
        return env
    return thunk


class ResidualBatch:
    """``num_envs`` aircraft of ``env_id`` in one batched env (``gym.make_vec(..., vectorization_mode="vector_entry_point")``,
    one call steps them all) with the actions of :class:`TrimResidualAction`; episodes restart in the step that ends
    them (gymnasium's SameStep autoreset). Aircraft i is seeded ``seed + i``."""

    def __init__(self, env_id: str, num_envs: int, aero: str, scale: float, seed: int, shaping: float = 0.0,
                 gamma: float = 0.99, penalty: float = 0.0) -> None:
        import flexsim.envs  # noqa: F401  (registers the ids in a spawned worker)

        self.venv = gym.make_vec(env_id, num_envs=num_envs, vectorization_mode="vector_entry_point", aero=aero,
                                 autoreset_mode="SameStep")
        single = self.venv.single_action_space
        self.low, self.high = single.low.astype(np.float64), single.high.astype(np.float64)
        self.observation_space = self.venv.single_observation_space
        self.num_envs, self.scale, self.seed = num_envs, scale, seed
        self.trim = np.zeros((num_envs, 4))
        self.shaping, self.penalty = shaping, penalty
        self.gamma = gamma
        names = self.venv.envs[0].observation_names
        self._i_errors = [names.index(n) for n in ("altitude_error_m", "heading_error_rad") if n in names]
        if max(shaping, penalty) > 0.0 and len(self._i_errors) != 2:
            raise ValueError(f"shaping = {shaping}, penalty = {penalty}: both must be 0 for {env_id}, which observes no "
                             "altitude_error_m and heading_error_rad")
        self._obs = None

    def potential(self, obs: np.ndarray) -> np.ndarray:
        """Phi = -shaping (|altitude error| / 30 m + |heading error| / 3 deg): unsaturated over the v1 start offsets."""
        return -self.shaping * self.tracking_error(obs)

    def tracking_error(self, obs: np.ndarray) -> np.ndarray:
        """|altitude error| / 30 m + |heading error| / 3 deg [-] (the v1 start offsets' bounds)."""
        e = np.abs(np.asarray(obs, dtype=np.float64)[..., self._i_errors])
        return e[..., 0] / 30.0 + e[..., 1] / math.radians(3.0)

    def _take_trim(self, info: dict) -> None:
        mask = info.get("_trim_action")
        if mask is not None:
            self.trim[mask] = np.asarray(info["trim_action"], dtype=np.float64)[mask]

    def reset(self) -> np.ndarray:
        obs, info = self.venv.reset(seed=self.seed)
        self.seed = None  # later resets continue each aircraft's random stream
        self._take_trim(info)
        self._obs = obs
        return obs

    def step(self, actions: np.ndarray) -> tuple:
        """obs, rewards, dones, infos (SB3 conventions: ``terminal_observation``, ``TimeLimit.truncated``)."""
        a = np.clip(self.trim + self.scale * np.clip(np.asarray(actions, dtype=np.float64), -1.0, 1.0), self.low, self.high)
        obs, rewards, terminated, truncated, info = self.venv.step(a.astype(np.float32))
        dones = terminated | truncated
        infos: list[dict] = [{} for _ in range(self.num_envs)]
        for i in np.flatnonzero(dones):
            infos[i]["terminal_observation"] = info["final_obs"][i]
            infos[i]["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
        self._take_trim(info)
        if self.shaping > 0.0 or self.penalty > 0.0:
            nxt = obs.copy()
            for i in np.flatnonzero(dones):
                nxt[i] = infos[i]["terminal_observation"]
        if self.penalty > 0.0:  # unsaturated tracking cost, training only
            rewards = rewards - self.penalty * self.tracking_error(nxt)
        if self.shaping > 0.0:  # potential-based shaping gamma Phi(s') - Phi(s) (Ng et al. 1999), training only
            phi_next = np.where(terminated, 0.0, self.potential(nxt))
            rewards = rewards + self.gamma * phi_next - self.potential(self._obs)
        self._obs = obs
        return obs, rewards.astype(np.float32), dones, infos

    def close(self) -> None:
        self.venv.close()


def _batch_worker(conn, args: tuple) -> None:
    """Worker process of :func:`make_batched_vec_env`: one :class:`ResidualBatch`, driven over a pipe."""
    batch = ResidualBatch(*args)
    while True:
        command, data = conn.recv()
        if command == "step":
            conn.send(batch.step(data))
        elif command == "reset":
            conn.send(batch.reset())
        else:
            batch.close()
            conn.close()
            return


def make_batched_vec_env(env_id: str, num_envs: int, aero: str, scale: float, seed: int, processes: int = 1, shaping: float = 0.0,
                         gamma: float = 0.99, penalty: float = 0.0):
    """An SB3 ``VecEnv`` of ``num_envs`` aircraft in ``processes`` batched envs (:class:`ResidualBatch`): in this
    process (1) or in worker processes, each stepping its share of the aircraft in one call. Aircraft i is
    seeded ``seed + i``."""
    from stable_baselines3.common.vec_env import VecEnv

    sizes = [len(c) for c in np.array_split(np.arange(num_envs), processes) if len(c)]
    starts = np.cumsum([0] + sizes[:-1])

    class BatchedVecEnv(VecEnv):
        def __init__(self) -> None:
            self.local = None
            self.pipes = []
            if len(sizes) == 1:
                self.local = ResidualBatch(env_id, num_envs, aero, scale, seed, shaping, gamma, penalty)
                space = self.local.observation_space
            else:
                ctx = multiprocessing.get_context("spawn")
                self.procs = []
                for n, start in zip(sizes, starts):
                    parent, child = ctx.Pipe()
                    proc = ctx.Process(target=_batch_worker, args=(child, (env_id, n, aero, scale, seed + int(start), shaping, gamma, penalty)), daemon=True)
                    proc.start()
                    child.close()
                    self.pipes.append(parent)
                    self.procs.append(proc)
                space = gym.make(env_id, aero=aero).observation_space
            super().__init__(num_envs, space, gym.spaces.Box(-1.0, 1.0, (4,), np.float32))

        def reset(self):
            if self.local is not None:
                return self.local.reset()
            for pipe in self.pipes:
                pipe.send(("reset", None))
            return np.concatenate([pipe.recv() for pipe in self.pipes])

        def step_async(self, actions) -> None:
            self._actions = np.asarray(actions)
            for pipe, n, start in zip(self.pipes, sizes, starts):
                pipe.send(("step", self._actions[start:start + n]))

        def step_wait(self):
            if self.local is not None:
                return self.local.step(self._actions)
            parts = [pipe.recv() for pipe in self.pipes]
            return (np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]),
                    np.concatenate([p[2] for p in parts]), [i for p in parts for i in p[3]])

        def close(self) -> None:
            if self.local is not None:
                self.local.close()
            for pipe, proc in zip(self.pipes, getattr(self, "procs", [])):
                pipe.send(("close", None))
                proc.join(timeout=10)

        def get_attr(self, attr_name, indices=None):
            if attr_name == "render_mode":
                return [None] * len(self._get_indices(indices))
            raise AttributeError(f"{attr_name}: the batched training env offers render_mode only")

        def set_attr(self, attr_name, value, indices=None) -> None:
            raise AttributeError(f"{attr_name}: the batched training env has no settable attributes")

        def env_method(self, method_name, *method_args, indices=None, **method_kwargs):
            raise AttributeError(f"{method_name}: the batched training env has no env methods")

        def env_is_wrapped(self, wrapper_class, indices=None):
            return [False] * len(self._get_indices(indices))

    return BatchedVecEnv()


def _row(info: dict, i: int) -> dict:
    """The info of aircraft ``i`` from a batched info dict (value arrays with ``_key`` masks, nested dicts)."""
    return {k: (_row(v, i) if isinstance(v, dict) else v[i]) for k, v in info.items() if not k.startswith("_")}


def _evaluate(job: tuple) -> tuple[str, list[tuple[int, float, int, str, dict[str, float]]]]:
    """Seeded episodes of one policy ("agent", "baseline", "trim", "random") in a worker process: aircraft i of one
    batched env (``gym.make_vec(..., vectorization_mode="vector_entry_point")``, which follows the single env of the
    same seed and actions to rounding) flies seed ``seeds[i]``; returns (seed, return, steps, termination reason,
    reward parts) per episode (:func:`fly`)."""
    kind, seeds, env_id, aero, scale, model_path, algo, stats = job
    import flexsim.envs  # noqa: F401
    from baselines import RandomPolicy, make_baseline

    n = len(seeds)
    venv = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", aero=aero, autoreset_mode="SameStep")
    obs, info = venv.reset(seed=list(seeds))
    trim = np.asarray(info["trim_action"], dtype=np.float64)
    low, high = venv.single_action_space.low, venv.single_action_space.high
    if kind == "baseline":
        policies = [make_baseline(env_id, env) for env in venv.envs]
        for i, policy in enumerate(policies):
            if hasattr(policy, "_designs"):
                policy._designs = policies[0]._designs  # one LQR design per trim for all aircraft (they share one model)
            policy.reset(_row(info, i))

        def act(o):
            return np.array([policy(row) for policy, row in zip(policies, o)])
    elif kind == "random":
        policies = [RandomPolicy(env) for env in venv.envs]
        for i, (policy, seed) in enumerate(zip(policies, seeds)):
            policy.reset(_row(info, i), seed=seed)

        def act(o):
            return np.array([policy(row) for policy, row in zip(policies, o)])
    elif kind.startswith("agent"):
        import stable_baselines3 as sb3
        import torch

        torch.set_num_threads(1)
        act = agent_actor(getattr(sb3, algo).load(model_path, device="cpu"), stats, trim, scale, low, high)
    else:
        def act(o):
            return trim
    flown = fly(venv, obs, act)
    venv.close()
    return kind, [(seed, *episode) for seed, episode in zip(seeds, flown)]


def agent_actor(model, stats: dict, trim: np.ndarray, scale: float, low: np.ndarray, high: np.ndarray):
    """Actions of the deterministic policy ``model`` on raw observations: normalised with the frozen ``VecNormalize``
    statistics ``stats`` (mean, var, eps, clip), then ``clip(trim + scale * a)`` (:class:`TrimResidualAction`)."""
    mean, sd = np.asarray(stats["mean"]), np.sqrt(np.asarray(stats["var"]) + stats["eps"])

    def act(obs: np.ndarray) -> np.ndarray:
        z = np.clip((obs - mean) / sd, -stats["clip"], stats["clip"]).astype(np.float32)
        return np.clip(trim + scale * np.clip(model.predict(z, deterministic=True)[0], -1.0, 1.0), low, high)
    return act


def fly(venv, obs: np.ndarray, act) -> list[tuple[float, int, str, dict[str, float]]]:
    """Fly every aircraft of a batched env (``SameStep`` autoreset) from ``obs`` to the end of its first episode with
    actions ``act(obs)``; returns (return, steps, termination reason or "", sums of ``info["reward_parts"]``) per
    aircraft."""
    n = len(obs)
    totals, steps, reasons = np.zeros(n), np.zeros(n, dtype=int), [""] * n
    parts: dict[str, np.ndarray] = {}
    flying = np.ones(n, dtype=bool)
    while flying.any():
        obs, reward, terminated, truncated, info = venv.step(np.asarray(act(obs), dtype=np.float32))
        done = terminated | truncated
        for source, rows in ((info.get("reward_parts", {}), flying & ~done), (info.get("final_info", {}).get("reward_parts", {}), flying & done)):
            for name, values in source.items():
                if not name.startswith("_"):
                    parts.setdefault(name, np.zeros(n))[rows] += np.asarray(values, dtype=np.float64)[rows]
        totals[flying] += reward[flying]
        steps[flying] += 1
        for i in np.flatnonzero(flying & done):
            flying[i] = False
            reasons[i] = str(info["final_info"]["termination_reason"][i]) if terminated[i] else ""
    return [(float(totals[i]), int(steps[i]), reasons[i], {k: float(v[i]) for k, v in parts.items()}) for i in range(n)]


def _stats(venv) -> dict:
    """The observation normalisation of an SB3 ``VecNormalize`` as plain numbers (frozen for evaluation)."""
    rms = venv.obs_rms
    return {"mean": rms.mean.tolist(), "var": rms.var.tolist(), "clip": float(venv.clip_obs), "eps": float(venv.epsilon)}


class Validation:
    """Checkpoint choice on validation episodes (the model selection of SB3's ``EvalCallback``): every
    ``args.val_every`` steps the deterministic policy flies ``args.val_episodes`` seeded episodes (seeds
    ``VALIDATION_SEED``, ... : neither the training seeds nor the evaluation seeds 0, 1, ...) in one batched env
    in the learner's process, on the env's own reward; the policy with the highest mean return so far is saved to
    ``path`` with its observation statistics. The evaluation then flies that policy and the last one.

    Not SB3's ``EvalCallback`` itself: that one flies whichever episodes its env's random stream gives next (here
    every validation flies the same seeded episodes, so checkpoints are compared on equal terms), saves the model
    without the ``VecNormalize`` statistics it was trained with, and steps single envs (here one batched call flies
    all validation aircraft)."""

    def __init__(self, args: argparse.Namespace, path: Path) -> None:
        self.args, self.path = args, path
        self.seeds = list(range(VALIDATION_SEED, VALIDATION_SEED + args.val_episodes))
        self.venv = gym.make_vec(args.env, num_envs=args.val_episodes, vectorization_mode="vector_entry_point", aero=args.aero,
                                 autoreset_mode="SameStep")
        self.next_steps = args.val_every
        self.history: list[tuple[int, float]] = []
        self.best: dict | None = None
        self.wall_s = 0.0

    def __call__(self, model, steps: int, stats: dict) -> float:
        """Fly the validation episodes with ``model`` after ``steps`` training steps; returns their mean return."""
        t0 = time.perf_counter()
        obs, info = self.venv.reset(seed=self.seeds)
        space = self.venv.single_action_space
        act = agent_actor(model, stats, np.asarray(info["trim_action"], dtype=np.float64), self.args.residual_scale, space.low,
                          space.high)
        mean = float(np.mean([episode[0] for episode in fly(self.venv, obs, act)]))
        self.history.append((steps, mean))
        if self.best is None or mean > self.best["mean_return"]:
            self.best = {"steps": steps, "mean_return": mean, "stats": stats}
            model.save(self.path)
        self.next_steps = steps + self.args.val_every
        self.wall_s += time.perf_counter() - t0
        print(f"validation after {steps} steps: mean return {mean:.1f} over seeds {self.seeds[0]}-{self.seeds[-1]} "
              f"(best {self.best['mean_return']:.1f} after {self.best['steps']} steps)", flush=True)
        return mean


def plot_result(result: dict, path: Path) -> Path:
    """Draw the learning curve of a run from its ``result.json`` contents to ``path`` (PNG), without training.

    The training episodes' returns (``result["training_episodes"]``: grey dots and a running mean over at least one
    batch of aircraft) or, for runs that saved none, SB3's mean of the last 100 training episodes
    (``result["training_curve"]``); with shaping (``settings["shaping"] > 0``) these are shaped returns, and the
    labels say so. Horizontal lines: the evaluation means of the agent, the LQR baseline, the trim hold and random
    actions on the env's own reward."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    settings = result["settings"]
    shaping, penalty = float(settings.get("shaping", 0.0)), float(settings.get("penalty", 0.0))
    changes = [f"--shaping {shaping:g}"] * (shaping > 0) + [f"--penalty {penalty:g}"] * (penalty > 0)
    reward = f"training reward: env + {' + '.join(changes)}" if changes else "env reward"
    fig, ax = plt.subplots(figsize=(7.5, 6.5))
    episodes, curve = result.get("training_episodes"), result.get("training_curve")
    if episodes and episodes["steps"]:
        steps, returns = np.asarray(episodes["steps"], float), np.asarray(episodes["return"], float)
        ax.plot(steps, returns, ".", ms=3, color="0.6", label=f"training episodes (stochastic policy, {reward})")
        k = max(len(returns) // 20, int(settings.get("envs", 1)))  # at least one batch: its aircraft end their episodes together
        if len(returns) >= 2 * k >= 4:
            smooth = np.convolve(returns, np.ones(k) / k, mode="valid")
            ax.plot(steps[k - 1:], smooth, color="C0", label=f"training: running mean of {k} episodes")
    elif curve and curve["steps"]:
        ax.plot(curve["steps"], curve["mean_return_100"], color="C0", drawstyle="steps-post",
                label=f"training: mean of the last 100 episodes (stochastic policy, {reward})")
    val = result.get("validation")
    if val and val["steps"]:
        seeds_v = val["seeds"]
        ax.plot(val["steps"], val["mean_return"], "o-", ms=3, lw=1, color="C1",
                label=f"validation: deterministic policy, env reward, seeds {seeds_v[0]}-{seeds_v[-1]}")
        if val.get("chosen_steps") is not None:
            ax.plot([val["chosen_steps"]], [max(val["mean_return"])], "*", ms=10, color="C1", label="checkpoint chosen")
    agent = f"agent ({' '.join(changes)})" if changes else "agent"
    chosen = (val or {}).get("chosen_steps")
    for key, color, label in (("agent", "C0", f"{agent}, deterministic" + ("" if chosen is None else f", {chosen} steps")),
                              ("agent_last", "C9", f"{agent}, last policy"), ("baseline", "C3", "LQR baseline"),
                              ("trim", "C2", "trim action held"), ("random", "C7", "random actions")):
        if key not in result:
            continue
        ax.axhline(result[key]["mean_return"], color=color, ls="--", lw=1,
                   label=f"{label}: {result[key]['mean_return']:.0f} (eval mean, env reward)")
    seeds = result["seeds"]
    ax.set_title(f"{result['algo']} on {result['env']}{' with ' + ', '.join(changes) + ' (training only)' if changes else ''}\n"
                 f"{result['train_steps']} steps in {result['train_wall_s'] / 60:.1f} min; eval seeds {seeds[0]}-{seeds[-1]}",
                 fontsize=9)
    ax.set_xlabel("environment steps")
    ax.set_ylabel("episode return")
    ax.xaxis.set_major_formatter(matplotlib.ticker.EngFormatter())
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12))
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return Path(path)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--env", default="FlexSim/GTM-LevelHold-v1", choices=list(envs.ENV_IDS))
    parser.add_argument("--algo", default="PPO", choices=ALGORITHMS)
    parser.add_argument("--steps", type=int, default=10_000_000, help="most environment steps [%(default)s]")
    parser.add_argument("--minutes", type=float, default=15.0, help="wall-time budget of the training [%(default)s min]")
    parser.add_argument("--vector", default="batched", choices=["batched", "subproc"],
                        help="batched: all aircraft in one gymnasium VectorEnv in this process; subproc: one process per aircraft [%(default)s]")
    parser.add_argument("--envs", type=int, default=16, help="aircraft flown in parallel (subproc: worker processes) [%(default)s]")
    parser.add_argument("--processes", type=int, default=2, help="batched: processes sharing the --envs aircraft [%(default)s]")
    parser.add_argument("--workers", type=int, default=2, help="processes of the evaluation [%(default)s]")
    parser.add_argument("--aero", default="unsteady", choices=["unsteady", "quasi-steady"])
    parser.add_argument("--residual-scale", type=float, default=0.1, help="action = trim + scale * a, a in [-1, 1] [%(default)s]")
    parser.add_argument("--gamma", type=float, default=0.99, help="discount factor [%(default)s]")
    parser.add_argument("--n-steps", type=int, default=64, help="PPO: steps per aircraft per update [%(default)s]")
    parser.add_argument("--batch-size", type=int, default=256, help="minibatch size [%(default)s]")
    parser.add_argument("--epochs", type=int, default=10, help="PPO: epochs per update [%(default)s]")
    parser.add_argument("--lr", type=float, default=3e-4, help="learning rate [%(default)s]")
    parser.add_argument("--gradient-steps", type=int, default=1, help="SAC/TD3: gradient steps per step of the --envs aircraft [%(default)s]")
    parser.add_argument("--learning-starts", type=int, default=1000, help="SAC/TD3: steps of random actions before learning [%(default)s]")
    parser.add_argument("--net", default="64,64", help="hidden layer sizes of policy and value nets [%(default)s]")
    parser.add_argument("--log-std-init", type=float, default=-1.0, help="PPO: initial log standard deviation of the actions [%(default)s]")
    parser.add_argument("--penalty", type=float, default=0.0,
                        help="batched: weight of an unsaturated per-step cost on altitude and heading errors (training only) [%(default)s]")
    parser.add_argument("--shaping", type=float, default=0.0,
                        help="batched: weight of the potential-based shaping on altitude and heading errors (training only) [%(default)s]")
    parser.add_argument("--sde", action="store_true", help="PPO: generalised state-dependent exploration (gSDE, resampled every 8 steps)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--eval-episodes", type=int, default=10, help="seeded evaluation episodes per policy [%(default)s]")
    parser.add_argument("--val-every", type=int, default=100_000,
                        help="fly the deterministic policy on the validation seeds every this many steps and keep the best "
                             "checkpoint (0: keep the last policy) [%(default)s]")
    parser.add_argument("--val-episodes", type=int, default=10,
                        help=f"validation episodes (seeds {VALIDATION_SEED}, {VALIDATION_SEED + 1}, ...) [%(default)s]")
    parser.add_argument("--out", type=Path, default=Path("logs/agent"))
    parser.add_argument("--torch-threads", type=int, default=1, help="torch intra-op threads of the learner [1]")
    parser.add_argument("--plot", type=Path, metavar="RESULT_JSON",
                        help="only redraw the learning curve of a finished run from its result.json (no training; "
                             "to --png, default: learning_curve.png beside the json)")
    parser.add_argument("--png", type=Path, help="with --plot: the PNG to write")
    args = parser.parse_args(argv)
    if args.plot is not None:
        try:
            result = json.loads(args.plot.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            parser.error(f"--plot {args.plot}: cannot read a result.json ({exc})")
        print(f"drew {plot_result(result, args.png or args.plot.with_name('learning_curve.png'))}")
        return
    for name in ("steps", "envs", "processes", "workers", "torch_threads", "eval_episodes", "n_steps", "batch_size", "epochs", "gradient_steps",
                 "val_episodes"):
        if getattr(args, name) < 1:
            parser.error(f"--{name.replace('_', '-')} = {getattr(args, name)}: must be >= 1")
    if args.val_every < 0:
        parser.error(f"--val-every = {args.val_every}: must be >= 0 (0: no validation, the last policy is evaluated)")
    if not args.minutes > 0:
        parser.error(f"--minutes = {args.minutes}: must be > 0")
    for name in ("shaping", "penalty"):
        value = getattr(args, name)
        if not (math.isfinite(value) and value >= 0.0) or (value > 0.0 and args.vector != "batched"):
            parser.error(f"--{name} = {value}: must be a finite number >= 0, and > 0 only with --vector batched")
    if not 0.0 < args.gamma < 1.0:
        parser.error(f"--gamma = {args.gamma}: must be in (0, 1)")
    try:
        net = [int(n) for n in args.net.split(",")]
        assert all(n >= 1 for n in net)
    except (ValueError, AssertionError):
        parser.error(f"--net = {args.net!r}: must be comma-separated positive layer sizes, e.g. 64,64")
    sb3, BaseCallback, DummyVecEnv, SubprocVecEnv, VecMonitor, VecNormalize = _import_sb3()
    import torch

    torch.set_num_threads(args.torch_threads)
    args.out.mkdir(parents=True, exist_ok=True)
    first_seed = TRAIN_SEED + 100 * args.seed
    if args.vector == "batched":
        venv = make_batched_vec_env(args.env, args.envs, args.aero, args.residual_scale, first_seed, args.processes, args.shaping,
                                    args.gamma, args.penalty)
    else:
        fns = [_make_env(args.env, args.aero, args.residual_scale, first_seed + i) for i in range(args.envs)]
        venv = SubprocVecEnv(fns) if args.envs > 1 else DummyVecEnv(fns)
    # PPO: rewards scaled by the running spread of the return; SAC/TD3 learn from a replay buffer of raw rewards
    venv = VecNormalize(VecMonitor(venv), norm_obs=True, norm_reward=args.algo == "PPO", gamma=args.gamma)
    curve: list[tuple[int, float]] = []
    loads: list[float] = []
    deadline = [math.inf]
    started = [math.nan]
    stem = f"{args.algo.lower()}_{args.env.split('/')[-1]}"
    validation = Validation(args, args.out / f"{stem}_best") if args.val_every > 0 else None

    class Budget(BaseCallback):
        def _on_training_start(self) -> None:
            started[0] = time.monotonic()  # after the envs are built and reset (numba compilation on a first run)
            deadline[0] = started[0] + 60.0 * args.minutes  # the budget counts from the first step
            self.next_load = 0.0

        def _on_step(self) -> bool:
            for info in self.locals.get("infos", []):
                if "episode" in info:
                    curve.append((self.num_timesteps, float(info["episode"]["r"])))
            if validation is not None and self.num_timesteps >= validation.next_steps:
                validation(self.model, self.num_timesteps, _stats(venv))
            now = time.monotonic()
            if now >= self.next_load:  # the 1-minute load average, every 30 s
                loads.append(os.getloadavg()[0])
                self.next_load = now + 30.0
            return now < deadline[0]

    policy_kwargs = {"net_arch": net}
    if args.algo == "PPO":
        model = sb3.PPO("MlpPolicy", venv, seed=args.seed, n_steps=args.n_steps, batch_size=args.batch_size, n_epochs=args.epochs,
                        learning_rate=args.lr, gamma=args.gamma, gae_lambda=0.95, use_sde=args.sde, sde_sample_freq=8 if args.sde else -1,
                        policy_kwargs={**policy_kwargs, "log_std_init": args.log_std_init}, verbose=1)
    else:
        model = getattr(sb3, args.algo)("MlpPolicy", venv, seed=args.seed, gamma=args.gamma, learning_rate=args.lr,
                                        batch_size=args.batch_size, gradient_steps=args.gradient_steps,
                                        learning_starts=args.learning_starts, policy_kwargs=policy_kwargs, verbose=1)
    t0 = time.perf_counter()
    model.learn(total_timesteps=args.steps, callback=Budget())
    train_s = time.monotonic() - started[0]  # training only; start-up (env builds, first reset) is setup_s
    setup_s = time.perf_counter() - t0 - train_s
    model.save(args.out / stem)
    venv.save(str(args.out / "vecnormalize.pkl"))
    stats = _stats(venv)
    steps_done = model.num_timesteps
    venv.close()

    t1 = time.perf_counter()
    seeds = list(range(args.eval_episodes))
    if validation is not None and validation.best is not None:  # the checkpoint chosen on the validation seeds, and the last policy
        kinds = ("agent", "agent_last", "baseline", "trim", "random")
        jobs = [("agent", seeds, args.env, args.aero, args.residual_scale, str(validation.path), args.algo, validation.best["stats"]),
                ("agent_last", seeds, args.env, args.aero, args.residual_scale, str(args.out / stem), args.algo, stats)]
    else:
        kinds = ("agent", "baseline", "trim", "random")
        jobs = [("agent", seeds, args.env, args.aero, args.residual_scale, str(args.out / stem), args.algo, stats)]
    jobs += [(kind, seeds, args.env, args.aero, args.residual_scale, "", args.algo, None) for kind in kinds if not kind.startswith("agent")]
    with ProcessPoolExecutor(max_workers=args.workers, mp_context=multiprocessing.get_context("spawn")) as pool:
        episodes = dict(pool.map(_evaluate, jobs))
    result: dict = {"env": args.env, "algo": args.algo, "train_steps": steps_done, "train_wall_s": train_s,
                    "train_steps_per_s": steps_done / train_s, "setup_wall_s": setup_s, "eval_wall_s": time.perf_counter() - t1,
                    "load_average_1min": {"min": min(loads), "mean": float(np.mean(loads)), "max": max(loads), "samples": loads},
                    "settings": {k: (str(v) if isinstance(v, Path) else v) for k, v in vars(args).items()}, "seeds": seeds}
    for kind in kinds:
        returns = np.array([e[1] for e in episodes[kind]])
        names = episodes[kind][0][4]
        result[kind] = {"mean_return": float(returns.mean()), "std_return": float(returns.std()), "returns": returns.tolist(),
                        "terminations": [e[3] for e in episodes[kind] if e[3]],
                        "mean_reward_parts": {k: float(np.mean([e[4][k] for e in episodes[kind]])) for k in names}}
    result["agent_over_baseline"] = result["agent"]["mean_return"] / result["baseline"]["mean_return"]
    result["trim_over_baseline"] = result["trim"]["mean_return"] / result["baseline"]["mean_return"]
    result["training_episodes"] = {"steps": [c[0] for c in curve], "return": [c[1] for c in curve]}
    if validation is not None:
        result["validation"] = {"seeds": validation.seeds, "steps": [v[0] for v in validation.history],
                                "mean_return": [v[1] for v in validation.history], "wall_s": validation.wall_s,
                                "chosen_steps": None if validation.best is None else validation.best["steps"]}
    (args.out / "result.json").write_text(json.dumps(result, indent=1))
    plot_result(result, args.out / "learning_curve.png")
    print(f"trained {steps_done} steps in {train_s:.0f} s ({steps_done / train_s:.0f} steps/s, load average "
          f"{min(loads):.1f}-{max(loads):.1f}); evaluation over seeds 0-{args.eval_episodes - 1} ({result['eval_wall_s']:.0f} s):")
    chosen = result.get("validation", {}).get("chosen_steps")
    for kind, label in (("agent", "agent (deterministic)" if chosen is None else f"agent at {chosen} steps"),
                        ("agent_last", f"agent at {steps_done} steps"), ("baseline", "LQR baseline"), ("trim", "trim action held"),
                        ("random", "random actions")):
        if kind not in result:
            continue
        r = result[kind]
        print(f"  {label:24s} return {r['mean_return']:8.1f} +- {r['std_return']:6.1f}  terminations {len(r['terminations'])}")
    ok = result["agent_over_baseline"] >= 0.8
    print(f"agent / LQR = {result['agent_over_baseline']:.3f} ({'meets' if ok else 'below'} the 0.8 target), "
          f"trim hold / LQR = {result['trim_over_baseline']:.3f}; curve {args.out / 'learning_curve.png'}, numbers {args.out / 'result.json'}")


if __name__ == "__main__":
    main()
