"""Speed of the gymnasium environments: steps per second at 50 Hz, solver choice, async speed-up.

1. Steps per second of one FlexSim/GTM-LevelHold-v0 (GTM m = n = 2, light turbulence) at the default
   50 Hz control rate, for each aerodynamic model and integrator (DOP853; Radau with the constant
   Jacobian of the trim), median over ``--repeats`` runs of ``--steps`` steps, with the right-hand-side
   evaluations and LU factorisations per step; plus the accuracy of each choice over 25 periods
   against DOP853 at rtol 1e-10 (altitude, pitch, tip deflection). Budget: >= 200 steps/s.
   The flutter fidelity: over 5 s of open-loop FlexSim/GTM-FlutterMargin-v0 (fin flutter growing at
   0.2 1/s), the fin tip twist amplitude of each method against the tight reference.
2. Async speed-up: env steps per second of ``gymnasium.make_vec(..., num_envs=2)`` in "async" mode over
   "sync" mode (2 cores; workers pin OpenBLAS to one thread).

Run: python benchmarks/bench_envs.py [--repeats 5] [--steps 200]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import gymnasium as gym  # noqa: E402
import numpy as np  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

import envs  # noqa: E402

ENV_ID = "FlexSim/GTM-LevelHold-v0"
BUDGET_STEPS_S = 200.0


def _actions(trim: np.ndarray, n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.clip(trim + rng.normal(0.0, 0.02, (n, 4)), [0, -1, -1, -1], [1, 1, 1, 1]).astype(np.float32)


def steps_per_second(aero: str, method: str, repeats: int, steps: int) -> dict[str, float]:
    """Median steps/s, nfev and LU factorisations per step of one env."""
    env = gym.make(ENV_ID, aero=aero, integrator=envs.IntegratorSettings(method=method), max_episode_steps=10 * steps)
    rates, nfev, nlu = [], [], []
    for r in range(repeats):
        _, info = env.reset(seed=r)
        actions = _actions(info["trim_action"], steps, r)
        calls = lus = 0
        t0 = time.perf_counter()
        for a in actions:
            _, _, terminated, truncated, info = env.step(a)
            calls += info["nfev"]
            lus += info["nlu"]
            if terminated or truncated:
                raise RuntimeError(f"episode ended early ({info.get('termination_reason')}) in the benchmark")
        rates.append(steps / (time.perf_counter() - t0))
        nfev.append(calls / steps)
        nlu.append(lus / steps)
    env.close()
    return {"steps_s": statistics.median(rates), "min": min(rates), "max": max(rates), "nfev": statistics.median(nfev),
            "nlu": statistics.median(nlu)}


def accuracy(aero: str, method: str, periods: int = 25) -> np.ndarray:
    """Largest |error| of altitude [m], pitch [rad], wing-tip deflection [m] against DOP853 rtol 1e-10."""
    env = gym.make(ENV_ID, aero=aero, turbulence="none", integrator=envs.IntegratorSettings(method=method))
    _, info = env.reset(seed=5)
    base = env.unwrapped
    dyn = base.dynamics
    x_ref = base.state
    worst = np.zeros(3)
    for k, a in enumerate(_actions(info["trim_action"], periods, 0)):
        env.step(a)
        sol = solve_ivp(dyn.model.rhs, (k * base.dt, (k + 1) * base.dt), x_ref, method="DOP853", args=(base.applied_controls,),
                        rtol=1e-10, atol=1e-12)
        x_ref = sol.y[:, -1]
        m, r = dyn.measure(base.state, 0.0), dyn.measure(x_ref, 0.0)
        worst = np.maximum(worst, [abs(m.altitude_m - r.altitude_m), abs(m.euler_rad[1] - r.euler_rad[1]),
                                   abs(m.tip_deflection_m["right_wing"] - r.tip_deflection_m["right_wing"])])
    env.close()
    return worst


def flutter_fidelity(method: str, periods: int = 250) -> tuple[float, float, float]:
    """Open-loop FlexSim/GTM-FlutterMargin-v0 (trim controls held) for ``periods``: largest |fin tip twist|
    over the last 0.5 s with ``method`` and with DOP853 at rtol 1e-10 [rad], and steps/s."""
    env = gym.make("FlexSim/GTM-FlutterMargin-v0", integrator=envs.IntegratorSettings(method=method), max_episode_steps=10 * periods)
    _, info = env.reset(seed=0)
    base = env.unwrapped
    dyn = base.dynamics
    x_ref = base.state
    amp = np.zeros(2)
    elapsed = 0.0
    for k in range(periods):
        t0 = time.perf_counter()
        env.step(info["trim_action"])
        elapsed += time.perf_counter() - t0
        x_ref = solve_ivp(dyn.model.rhs, (k * base.dt, (k + 1) * base.dt), x_ref, method="DOP853", args=(base.applied_controls,),
                          rtol=1e-10, atol=1e-12).y[:, -1]
        if k >= periods - 25:
            amp = np.maximum(amp, [abs(dyn.measure(base.state, 0.0).tip_twist_rad["vtail"]), abs(dyn.measure(x_ref, 0.0).tip_twist_rad["vtail"])])
    env.close()
    return float(amp[0]), float(amp[1]), periods / elapsed


def vector_rate(mode: str, steps: int) -> float:
    """Env steps per second (both sub-envs counted) of a 2-env vector env."""
    venv = gym.make_vec(ENV_ID, num_envs=2, vectorization_mode=mode, max_episode_steps=10 * steps)
    _, info = venv.reset(seed=[0, 1])
    actions = _actions(info["trim_action"][0], steps, 0)
    venv.step(np.stack([actions[0]] * 2))  # warm up (Jacobian, first solver start)
    t0 = time.perf_counter()
    for a in actions:
        venv.step(np.stack([a, a]))
    rate = 2 * steps / (time.perf_counter() - t0)
    venv.close()
    return rate


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--steps", type=int, default=200)
    args = parser.parse_args()
    print(f"{ENV_ID}, GTM m = n = 2, light turbulence, 50 Hz; median of {args.repeats} runs x {args.steps} steps")
    print(f"{'aero':13s} {'method':7s} {'steps/s':>8s} {'(min-max)':>14s} {'nfev/step':>9s} {'LU/step':>7s}   "
          f"accuracy over 0.5 s: altitude [m], pitch [rad], tip [m]")
    for aero in ("unsteady", "quasi-steady"):
        for method in ("DOP853", "Radau"):
            r = steps_per_second(aero, method, args.repeats, args.steps)
            err = accuracy(aero, method)
            auto = " (default)" if envs.IntegratorSettings().resolve(aero) == method else ""
            print(f"{aero:13s} {method:7s} {r['steps_s']:8.1f} {r['min']:6.1f}-{r['max']:6.1f} {r['nfev']:9.1f} {r['nlu']:7.1f}   "
                  f"{err[0]:.1e}, {err[1]:.1e}, {err[2]:.1e}{auto}", flush=True)
    print(f"budget: {BUDGET_STEPS_S:.0f} steps/s (one env, unsteady aero)")
    print("flutter fidelity, FlexSim/GTM-FlutterMargin-v0 open loop, 5 s: fin tip twist amplitude over the last 0.5 s")
    for method in ("DOP853", "Radau"):
        amp, ref, rate = flutter_fidelity(method)
        print(f"  {method:7s} {amp:.3e} rad vs reference {ref:.3e} rad ({100 * (amp / ref - 1):+.1f} %), {rate:.1f} steps/s", flush=True)
    sync = vector_rate("sync", args.steps)
    asyn = vector_rate("async", args.steps)
    print(f"vector env, 2 envs, default settings: sync {sync:.1f} env-steps/s, async {asyn:.1f} env-steps/s, "
          f"speed-up {asyn / sync:.2f} (on {os.cpu_count()} cores)")


if __name__ == "__main__":
    main()
