"""Rigid-aircraft peers beside FlexSim in one run: JSBSim raw steps/s and PyFlyt's fixed-wing env steps/s.

The peers are not flexsim dependencies. They install from the package index into their own virtual
environment (PyFlyt pins numpy < 2, which flexsim does not support, so they cannot share flexsim's):

    python3 -m venv /tmp/peers --system-site-packages && /tmp/peers/bin/pip install jsbsim pyflyt

Each measurement runs in a subprocess with its own interpreter (``--peers-python``, default
``/tmp/peers/bin/python``; FlexSim with this interpreter), one after the other, median of ``--repeats``
runs, per-thread CPU time (the figures are per core). What is compared:

* JSBSim (1.x, C++): ``FGFDMExec.run()`` of the bundled Cessna 172P (``c172p``) at its default 120 Hz
  integration rate, after ``run_ic()``: one rigid 6-DOF step with its table-lookup aerodynamics.
* PyFlyt ``PyFlyt/Fixedwing-Waypoints-v3`` (PyBullet physics at 240 Hz, 30 Hz agent steps): ``env.step``
  with random actions, resets on episode end counted in.
* FlexSim ``FlexSim/GTM-LevelHold-v0`` (50 Hz agent steps, each 4 ETD2RK steps of the 252-state flexible
  model with unsteady strips): ``env.step`` near trim; and the batched env at N = 256
  (:mod:`flexsim.envs.vector`), env-steps per CPU-second.

These are different classes of model (rigid 6-DOF against a flexible aircraft with 192 inflow states): the
ratios say what the flexible model costs, not which code is better.

Run: python benchmarks/bench_peers.py [--repeats 3] [--peers-python /tmp/peers/bin/python]
"""

from __future__ import annotations

import argparse
import datetime
import os
import statistics
import subprocess
import sys
import textwrap

# measure the flexsim of this checkout (python puts benchmarks/ on sys.path, not the repository root)
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

JSBSIM = """
import time, jsbsim
fdm = jsbsim.FGFDMExec(None)
fdm.set_debug_level(0)
fdm.load_model("c172p")
fdm["ic/h-sl-ft"] = 5000.0
fdm["ic/vc-kts"] = 100.0
fdm.run_ic()
n = 20000
c0 = time.thread_time()
for _ in range(n):
    fdm.run()
print(n / (time.thread_time() - c0), 1.0 / fdm.get_delta_t())
"""

PYFLYT = """
import time, warnings
warnings.filterwarnings("ignore")
import gymnasium as gym, PyFlyt.gym_envs  # noqa: F401
env = gym.make("PyFlyt/Fixedwing-Waypoints-v3")
env.reset(seed=0)
env.action_space.seed(0)
n = 2000
c0 = time.thread_time()
for _ in range(n):
    _, _, term, trunc, _ = env.step(env.action_space.sample())
    if term or trunc:
        env.reset()
print(n / (time.thread_time() - c0), env.unwrapped.agent_hz if hasattr(env.unwrapped, "agent_hz") else 30)
"""

FLEXSIM = """
import os, time
import numpy as np, gymnasium as gym
from flexsim import envs  # noqa: F401
env = gym.make("FlexSim/GTM-LevelHold-v0", max_episode_steps=10_000)
_, info = env.reset(seed=0)
a = info["trim_action"]
env.step(a)
n = 200
c0 = time.thread_time()
for _ in range(n):
    env.step(a)
single = n / (time.thread_time() - c0)
venv = gym.make_vec("FlexSim/GTM-LevelHold-v0", num_envs=256, vectorization_mode="vector_entry_point")
_, info = venv.reset(seed=0)
venv.step(info["trim_action"])
c0 = time.process_time()
for _ in range(3):
    venv.step(info["trim_action"])
print(single, 256 * 3 / (time.process_time() - c0))
"""


def _measure(python: str, code: str, repeats: int) -> tuple[list[float], float] | str:
    """(rates of each repeat, second figure of the last) or why it failed."""
    rates, extra = [], float("nan")
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    for _ in range(repeats):
        try:
            out = subprocess.run([python, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=600, env=env)
        except (OSError, subprocess.TimeoutExpired) as exc:
            return f"{type(exc).__name__}: {exc}"
        if out.returncode != 0:
            return (out.stderr.strip().splitlines() or ["exit code %d" % out.returncode])[-1]
        first, second = (float(v) for v in out.stdout.split()[-2:])
        rates.append(first)
        extra = second
    return rates, extra


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--peers-python", default="/tmp/peers/bin/python")
    args = parser.parse_args()
    print(f"bench_peers {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC; load {os.getloadavg()[0]:.1f}; "
          f"steps per CPU-second of one thread (per core), median of {args.repeats}")
    flex = _measure(sys.executable, FLEXSIM, args.repeats)
    if isinstance(flex, str):
        raise SystemExit(f"FlexSim failed: {flex}")
    flex_rate = statistics.median(flex[0])
    rows = [("FlexSim GTM-LevelHold-v0, one env (50 Hz, flexible, 252 states)", flex_rate, "steps/s"),
            ("FlexSim GTM-LevelHold-v0, batched N = 256", flex[1], "env-steps/s (one run)")]
    for label, code in (("JSBSim c172p FGFDMExec.run()", JSBSIM), ("PyFlyt Fixedwing-Waypoints-v3 env.step", PYFLYT)):
        got = _measure(args.peers_python, code, args.repeats)
        if isinstance(got, str):
            print(f"  {label}: not measured ({got})")
            continue
        rows.append((f"{label} ({got[1]:.0f} Hz steps)", statistics.median(got[0]), "steps/s"))
    for label, rate, unit in rows:
        print(f"  {label:72s} {rate:10.0f} {unit}   x{rate / flex_rate:8.1f} of the FlexSim single env")


if __name__ == "__main__":
    main()
