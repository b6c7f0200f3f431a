"""Speed of the gymnasium environments: steps per second at 50 Hz, integrator choice, async speed-up.

1. Steps per second of one FlexSim/GTM-LevelHold-v0 (GTM m = n = 2, light turbulence) at the default
   50 Hz control rate, for each aerodynamic model and integrator: ETD2RK (fixed 20 ms steps, LevelHold's default,
   and 10 and 5 ms, linear part the trim Jacobian), DOP853, Radau (constant trim Jacobian). Median over ``--repeats``
   runs of ``--steps`` steps after a warm-up reset and step; the repeats of all integrators are interleaved (repeat 1 of each, then
   repeat 2, ...) so that a drifting machine load affects them alike. Also the right-hand-side
   evaluations and LU factorisations per step, the share of the step spent outside the integration
   (``flexsim.sim.periods.advance_period``: rate limits, integration and measurements) (termination, task errors,
   observation, reward, info), and the accuracy of each choice over 25 periods against DOP853
   at rtol 1e-10 (altitude, pitch, tip deflection). Budget: >= 200 steps/s (unsteady aero); target:
   >= 2,000 steps/s.
2. The flutter fidelity: over 5 s of open-loop FlexSim/GTM-FlutterMargin-v0 (fin flutter growing at
   about 0.25 1/s), the fin tip twist amplitude of each integrator against the tight reference, and steps/s.
3. Async speed-up: env steps per second of ``gymnasium.make_vec(..., num_envs=2)`` in "async" mode over
   "sync" mode, default settings (2 cores; workers pin OpenBLAS to one thread), median of the ratios of 5
   alternating runs of each, with the number of cores other processes kept busy meanwhile (the speed-up needs a
   free core per worker).

4. Batched envs (``--batched``, or ``--batched-only`` for this section alone): env-steps per CPU-second
   (all processes of the run counted: "per core") of N = 1, 16, 256 aircraft of LevelHold-v0 (default
   settings) in ``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")``
   (:class:`flexsim.envs.vector.FlexSimVectorEnv`, one ``advance_period`` call per step) beside the single
   env, gymnasium's ``SyncVectorEnv`` and ``AsyncVectorEnv`` (N = 1 and 16; at 256 each of their
   sub-envs builds its own model, trim and matrix exponential, about 1 s each, and the async one starts
   256 processes: skipped unless ``--sync-256``); median of ``--repeats`` runs of about 512 env-steps
   each (at least 3 steps), reset and one warm-up step excluded. Target: >= 10,000
   env-steps/s per core at 256 aircraft.

5. One env and 256 batched envs side by side with a reference revision (``--compare [REV]``, or ``--compare-only``
   for this section alone; default reference main): one env (``gym.make``, all wrappers) steps per CPU-second, the same steps on
   the unwrapped env and the time of a reset (cached trim), and N = 256 batched env-steps per CPU-second
   (``vector_entry_point``), each tree's default integrator and both at the reference's 10 ms ETD2RK step, in
   fresh processes (``benchmarks/_envs_worker.py`` of this tree) alternating reference and this tree ``--repeats``
   times; medians, ratios, targets 2,000 and 10,000. The reference is extracted with
   ``git archive`` into a directory kept between runs (its numba cache with it), ``--reference-tree PATH`` uses
   a checkout instead.

Run: python benchmarks/bench_envs.py [--repeats 5] [--steps 200] [--batched | --batched-only] [--sync-256]
     [--compare [REV] | --compare-only [REV]] [--reference-tree PATH]
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import json
import statistics
import subprocess
import sys
import time

# measure the flexsim of this checkout (python puts benchmarks/ on sys.path, not the repository root)
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import gymnasium as gym  # noqa: E402
import numpy as np  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from flexsim import envs  # noqa: E402
from flexsim.envs import base as env_base  # noqa: E402

ENV_ID = "FlexSim/GTM-LevelHold-v0"
BUDGET_STEPS_S = 200.0
TARGET_STEPS_S = 2_000.0
#: (label, settings) of the integrators compared.
INTEGRATORS = (
    ("ETD2RK 20ms", envs.IntegratorSettings(method="ETD2RK", max_step_s=0.02)),
    ("ETD2RK 10ms", envs.IntegratorSettings(method="ETD2RK", max_step_s=0.01)),
    ("ETD2RK 5ms", envs.IntegratorSettings(method="ETD2RK", max_step_s=0.005)),
    ("DOP853", envs.IntegratorSettings(method="DOP853")),
    ("Radau", envs.IntegratorSettings(method="Radau")),
)


def _actions(trim: np.ndarray, n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.clip(trim + rng.normal(0.0, 0.02, (n, 4)), [0, -1, -1, -1], [1, 1, 1, 1]).astype(np.float32)


class _Timed:
    """Wraps the integration of a step (``advance_period``, called by ``FlexSimEnv._step_rows``) to add up its time."""

    def __init__(self, advance) -> None:
        self.advance, self.seconds = advance, 0.0

    def __call__(self, *args, **kwargs):
        t0 = time.perf_counter()
        out = self.advance(*args, **kwargs)
        self.seconds += time.perf_counter() - t0
        return out


def steps_per_second(aero: str, repeats: int, steps: int) -> dict[str, dict[str, float]]:
    """Per integrator label: median steps/s (min, max), nfev and LU per step, share of time outside the integration."""
    made = {label: gym.make(ENV_ID, aero=aero, integrator=settings, max_episode_steps=10 * steps) for label, settings in INTEGRATORS}
    timer = _Timed(env_base.advance_period)
    env_base.advance_period = timer
    for env in made.values():
        # trim, Jacobian and matrix functions, and the first step, which loads the compiled period from numba's
        # cache (about 0.1-0.5 s: it fell in the first timed run before, whose rate was then a third of the others')
        _, info = env.reset(seed=0)
        env.step(info["trim_action"])
    runs = {label: {"rate": [], "nfev": [], "nlu": [], "outside": []} for label in made}
    for r in range(repeats):
        for label, env in made.items():
            _, info = env.reset(seed=r)
            actions = _actions(info["trim_action"], steps, r)
            calls = lus = 0
            timer.seconds = 0.0
            t0 = time.perf_counter()
            for a in actions:
                _, _, terminated, truncated, info = env.step(a)
                calls += info["nfev"]
                lus += info["nlu"]
                if terminated or truncated:
                    raise RuntimeError(f"episode ended early ({info.get('termination_reason')}) in the benchmark")
            elapsed = time.perf_counter() - t0
            runs[label]["rate"].append(steps / elapsed)
            runs[label]["nfev"].append(calls / steps)
            runs[label]["nlu"].append(lus / steps)
            runs[label]["outside"].append(1.0 - timer.seconds / elapsed)
    env_base.advance_period = timer.advance
    for env in made.values():
        env.close()
    return {label: {"steps_s": statistics.median(v["rate"]), "min": min(v["rate"]), "max": max(v["rate"]),
                    "nfev": statistics.median(v["nfev"]), "nlu": statistics.median(v["nlu"]),
                    "outside": statistics.median(v["outside"])} for label, v in runs.items()}


def accuracy(aero: str, settings: envs.IntegratorSettings, periods: int = 25) -> np.ndarray:
    """Largest |error| of altitude [m], pitch [rad], wing-tip deflection [m] against DOP853 rtol 1e-10."""
    env = gym.make(ENV_ID, aero=aero, turbulence="none", integrator=settings)
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


def flutter_fidelity(settings: envs.IntegratorSettings, periods: int = 250) -> tuple[float, float, float]:
    """Open-loop FlexSim/GTM-FlutterMargin-v0 (trim controls held) for ``periods``: largest |fin tip twist|
    over the last 0.5 s with ``settings`` and with DOP853 at rtol 1e-10 [rad], and steps/s."""
    env = gym.make("FlexSim/GTM-FlutterMargin-v0", integrator=settings, max_episode_steps=10 * periods)
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


def _cpu_seconds(pids: list[int]) -> tuple[float, float] | None:
    """(busy CPU seconds of the whole machine, CPU seconds of the processes ``pids``), from /proc (None
    where it is missing)."""
    try:
        with open("/proc/stat") as f:
            ticks = [int(v) for v in f.readline().split()[1:]]
        mine = 0
        for pid in pids:
            with open(f"/proc/{pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            mine += int(fields[11]) + int(fields[12])  # utime, stime
    except OSError:
        return None
    hz = os.sysconf("SC_CLK_TCK")
    return (sum(ticks) - ticks[3] - ticks[4]) / hz, mine / hz


def vector_rates(steps: int, repeats: int = 5) -> tuple[list[float], list[float], float]:
    """Env steps per second (both sub-envs counted) of a 2-env vector env, sync and async, default settings,
    one per repeat, and the median number of cores other processes kept busy meanwhile (NaN if unknown);
    the two modes alternate ``repeats`` times (process start-up, reset and one warm-up step excluded)."""
    rates: dict[str, list[float]] = {"sync": [], "async": []}
    others = []
    for _ in range(repeats):
        for mode in rates:
            venv = gym.make_vec(ENV_ID, num_envs=2, vectorization_mode=mode, max_episode_steps=10 * steps)
            pids = [os.getpid()] + [p.pid for p in getattr(venv, "processes", [])]
            _, info = venv.reset(seed=[0, 1])
            actions = _actions(info["trim_action"][0], steps, 0)
            venv.step(np.stack([actions[0]] * 2))
            before = _cpu_seconds(pids)
            t0 = time.perf_counter()
            for a in actions:
                venv.step(np.stack([a, a]))
            wall = time.perf_counter() - t0
            after = _cpu_seconds(pids)
            venv.close()
            rates[mode].append(2 * steps / wall)
            if before is not None and after is not None:
                others.append(((after[0] - before[0]) - (after[1] - before[1])) / wall)
    return rates["sync"], rates["async"], statistics.median(others) if others else math.nan


BATCH_SIZES = (1, 16, 256)
TARGET_BATCHED = 10_000.0


def _per_cpu_second(make, n: int, steps: int, repeats: int) -> tuple[float, float]:
    """Median env-steps per CPU-second of all processes of the vector env ``make()`` (n envs), and per
    wall second; ``steps`` vector steps per repeat after reset and one warm-up step."""
    per_cpu, per_wall = [], []
    venv = make()
    pids = [os.getpid()] + [p.pid for p in getattr(venv, "processes", [])]
    for r in range(repeats):
        _, info = venv.reset(seed=100 * r)
        trim = np.asarray(info["trim_action"], dtype=np.float64).reshape(n, 4)
        acts = [np.clip(trim + 0.01 * np.sin(k + r + np.arange(4)), [0, -1, -1, -1], [1, 1, 1, 1]).astype(np.float32)
                for k in range(steps + 1)]
        venv.step(acts[0])
        before, c0, t0 = _cpu_seconds(pids), time.process_time(), time.perf_counter()
        for a in acts[1:]:
            venv.step(a)
        wall = time.perf_counter() - t0
        after = _cpu_seconds(pids)
        cpu = (after[1] - before[1]) if before is not None and after is not None and len(pids) > 1 else time.process_time() - c0
        per_cpu.append(n * steps / max(cpu, 1e-9))
        per_wall.append(n * steps / wall)
    venv.close()
    return statistics.median(per_cpu), statistics.median(per_wall)


def batched_rates(repeats: int, sync_256: bool) -> None:
    """Section 4 of the module docstring: prints a table of env-steps per CPU-second and per wall second."""
    print(f"batched envs, {ENV_ID}, default settings: env-steps per CPU-second of the whole run (per core) / per wall "
          f"second, median of {repeats}; {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}", flush=True)
    env = gym.make(ENV_ID, max_episode_steps=10_000)
    single_cpu, single_wall = [], []
    for r in range(repeats):
        _, info = env.reset(seed=r)
        acts = _actions(info["trim_action"], 101, r)
        env.step(acts[0])
        c0, t0 = time.thread_time(), time.perf_counter()
        for a in acts[1:]:
            env.step(a)
        single_cpu.append(100 / (time.thread_time() - c0))
        single_wall.append(100 / (time.perf_counter() - t0))
    env.close()
    base = statistics.median(single_cpu)
    print(f"  {'single env (gym.make)':38s} {'N = 1':>7s} {base:9.0f} / {statistics.median(single_wall):7.0f}   1.00", flush=True)
    for n in BATCH_SIZES:
        steps = max(3, 512 // n)
        modes = [("FlexSimVectorEnv (vector_entry_point)", "vector_entry_point")]
        if n <= 16 or sync_256:
            modes += [("gymnasium SyncVectorEnv", "sync"), ("gymnasium AsyncVectorEnv", "async")]
        for label, mode in modes:
            def make():
                return gym.make_vec(ENV_ID, num_envs=n, vectorization_mode=mode, max_episode_steps=10_000)
            cpu, wall = _per_cpu_second(make, n, steps, repeats)
            print(f"  {label:38s} {f'N = {n}':>7s} {cpu:9.0f} / {wall:7.0f}   {cpu / base:4.2f}", flush=True)
    print(f"  target: {TARGET_BATCHED:,.0f} env-steps/s per core at N = 256; last column: per-core ratio to the "
          "single env of the same run")


#: The default reference of section 5: the branch a change is compared against.
COMPARE_REFERENCE = "main"
#: The ETD2RK step both trees are also measured at in section 5 (the reference's default).
COMPARE_STEP_S = 0.01
HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from _reference import reference_tree as checkout_of  # noqa: E402  (benchmarks/_reference.py)
WORKER = os.path.join(HERE, "benchmarks", "_envs_worker.py")


def _worker(tree: str, mode: str, steps: int, max_step_s: float | None) -> dict:
    """The figures of one worker process on ``tree`` (``benchmarks/_envs_worker.py``; this tree's worker, which uses
    public APIs only): env-steps per CPU-second, and for ``single`` the unwrapped env's and the reset time."""
    cmd = [sys.executable, WORKER, mode, "--steps", str(steps)] + ([] if max_step_s is None else ["--max-step-s", str(max_step_s)])
    env = dict(os.environ, PYTHONPATH=tree, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    out = subprocess.run(cmd, cwd=tree, env=env, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def compare(reference: str, reference_tree: str | None, repeats: int) -> None:
    """Section 5 of the module docstring."""
    ref = reference_tree or str(checkout_of(reference))
    label = reference_tree or reference
    print(f"one env and 256 batched envs: this tree against {label}, fresh processes alternating, median of {repeats}; env-steps per "
          f"CPU-second; {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}", flush=True)
    # about 0.3-1 s of CPU per worker run: 300 single steps or 4 vector steps were 0.1 s and spread 1.7x under load
    rows = (("one env, LevelHold-v0, default integrator", "single", 1000, None, TARGET_STEPS_S),
            (f"one env, ETD2RK {COMPARE_STEP_S * 1e3:g} ms (both trees)", "single", 1000, COMPARE_STEP_S, TARGET_STEPS_S),
            ("256 batched (vector_entry_point), default", "batched", 8, None, TARGET_BATCHED),
            (f"256 batched, ETD2RK {COMPARE_STEP_S * 1e3:g} ms (both trees)", "batched", 8, COMPARE_STEP_S, TARGET_BATCHED))
    for text, mode, steps, h, target in rows:
        runs: dict[str, list[dict]] = {"ref": [], "new": []}
        for _ in range(repeats):
            for side, tree in (("ref", ref), ("new", HERE)):
                runs[side].append(_worker(tree, mode, steps, h))

        def med(side, key="env_steps_per_cpu_s"):
            values = [run[key] for run in runs[side] if key in run]
            return statistics.median(values) if values else math.nan

        r, n = med("ref"), med("new")
        rates = [run["env_steps_per_cpu_s"] for run in runs["new"]]
        print(f"  {text:48s} reference {r:8.0f}   this tree {n:8.0f} ({min(rates):.0f}-{max(rates):.0f})   x{n / r:5.2f}   "
              f"target {target:,.0f}: {'met' if n >= target else 'not met'}", flush=True)
        if mode == "single":
            print(f"  {'  same steps unwrapped (no gym.make wrappers)':48s} reference {med('ref', 'unwrapped_steps_per_cpu_s'):8.0f}   "
                  f"this tree {med('new', 'unwrapped_steps_per_cpu_s'):8.0f}", flush=True)
            print(f"  {'  reset of a cached trim [ms CPU]':48s} reference {med('ref', 'reset_ms'):8.2f}   this tree "
                  f"{med('new', 'reset_ms'):8.2f}", flush=True)
    print(f"  load after: {os.getloadavg()[0]:.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--batched", action="store_true", help="also section 4: batched envs at N = 1, 16, 256")
    parser.add_argument("--batched-only", action="store_true", help="section 4 alone")
    parser.add_argument("--sync-256", action="store_true", help="section 4: gymnasium's sync/async vector envs at N = 256 too")
    parser.add_argument("--compare", nargs="?", const=COMPARE_REFERENCE, default=None, metavar="REV",
                        help=f"also section 5: against REV (default {COMPARE_REFERENCE})")
    parser.add_argument("--compare-only", nargs="?", const=COMPARE_REFERENCE, default=None, metavar="REV", help="section 5 alone")
    parser.add_argument("--reference-tree", default=None, help="section 5: a checkout to compare against instead of REV")
    args = parser.parse_args()
    if args.compare_only:
        print(f"{datetime.date.today()}")
        compare(args.compare_only, args.reference_tree, args.repeats)
        return
    if args.batched_only:
        print(f"{datetime.date.today()}")
        batched_rates(args.repeats, args.sync_256)
        return
    print(f"{datetime.date.today()}: {ENV_ID}, GTM m = n = 2, light turbulence, 50 Hz; median of {args.repeats} interleaved "
          f"runs x {args.steps} steps; {os.cpu_count()} cores")
    print(f"{'aero':13s} {'method':11s} {'steps/s':>8s} {'(min-max)':>14s} {'nfev/step':>9s} {'LU/step':>7s} {'outside':>7s}   "
          f"accuracy over 0.5 s: altitude [m], pitch [rad], tip [m]")
    unsteady = {}
    for aero in ("unsteady", "quasi-steady"):
        default = gym.make(ENV_ID, aero=aero).unwrapped.dynamics.method
        rates = steps_per_second(aero, args.repeats, args.steps)
        if aero == "unsteady":
            unsteady = rates
        for label, settings in INTEGRATORS:
            r = rates[label]
            err = accuracy(aero, settings)
            auto = " (default)" if default == settings.method and settings.max_step_s == 0.02 else ""
            print(f"{aero:13s} {label:11s} {r['steps_s']:8.1f} {r['min']:6.1f}-{r['max']:6.1f} {r['nfev']:9.1f} {r['nlu']:7.1f} "
                  f"{100 * r['outside']:6.1f}%   {err[0]:.1e}, {err[1]:.1e}, {err[2]:.1e}{auto}", flush=True)
    print(f"budget: {BUDGET_STEPS_S:.0f} steps/s, target {TARGET_STEPS_S:,.0f} steps/s (one env, unsteady aero); ETD2RK / Radau = "
          f"{unsteady['ETD2RK 20ms']['steps_s'] / unsteady['Radau']['steps_s']:.2f}, ETD2RK / DOP853 = "
          f"{unsteady['ETD2RK 20ms']['steps_s'] / unsteady['DOP853']['steps_s']:.2f} (medians of the same run)")
    print("flutter fidelity, FlexSim/GTM-FlutterMargin-v0 open loop, 5 s: fin tip twist amplitude over the last 0.5 s")
    for label, settings in INTEGRATORS:
        amp, ref, rate = flutter_fidelity(settings)
        print(f"  {label:11s} {amp:.3e} rad vs reference {ref:.3e} rad ({100 * (amp / ref - 1):+.1f} %), {rate:.1f} steps/s", flush=True)
    sync, asyn, others = vector_rates(args.steps)
    ratios = [a / s for s, a in zip(sync, asyn)]
    print(f"vector env, 2 envs, default settings, {len(ratios)} alternating runs: sync {statistics.median(sync):.1f} env-steps/s, "
          f"async {statistics.median(asyn):.1f} env-steps/s, speed-up {statistics.median(ratios):.2f} (runs {min(ratios):.2f}-{max(ratios):.2f}; "
          f"{os.cpu_count()} cores; other processes kept {others:.1f} cores busy meanwhile)")
    if args.batched:
        batched_rates(args.repeats, args.sync_256)
    if args.compare:
        compare(args.compare, args.reference_tree, args.repeats)


if __name__ == "__main__":
    main()
