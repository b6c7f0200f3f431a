"""Figures of docs/environments.md, for ``regenerate_docs_figures.py`` (registered through
``tools/docs_figures_usage.py``).

Each function returns the text of one ``<!-- figures:NAME -->`` region. The agent figures read the saved results of
the training runs (``docs/figures/agent_*_result.json``, written by ``examples/agents/train_sb3.py``; its
``--plot`` redraws their learning curves): training is not repeated, the text is what those runs measured. The
flutter-task, baseline and limitation figures come from the environments themselves and
``examples/agents/baselines.py`` / ``lqr_design.py``.
"""

from __future__ import annotations

import functools
import json
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
FIGURE_DIR = ROOT / "docs" / "figures"
sys.path.insert(0, str(Path(__file__).resolve().parent))
from docs_figures_static import _num  # noqa: E402


# --- the learning agent of docs/environments.md (saved results) -------------------------------------------------

@functools.cache
def _agent(name: str) -> dict:
    """``docs/figures/agent_<name>_result.json``."""
    return json.loads((FIGURE_DIR / f"agent_{name}_result.json").read_text(encoding="utf-8"))


def _pm(r: dict) -> str:
    return f"{r['mean_return']:.1f} +- {r['std_return']:.1f}"


def _agent_run(name: str) -> str:
    """Steps, training wall time and rate, evaluation time and the load of a run."""
    r = _agent(name)
    load = r["load_average_1min"]
    loads = (f"1-minute load average during training {load['min']:.1f}-{load['max']:.1f} (mean {load['mean']:.1f}, "
             f"sampled every 30 s)")
    if "setup_wall_s" not in r:
        # written before train_sb3.py timed the start-up apart: train_wall_s is start-up + budget (which counts from
        # the first step, so the budget was used up)
        budget = 60.0 * r["settings"]["minutes"]
        return (f"{r['train_steps']:,} steps in the {budget:.0f} s budget ({r['train_steps'] / budget:.0f} steps/s; "
                f"{r['train_wall_s']:.0f} s with the start-up), evaluation {r['eval_wall_s']:.0f} s, {loads}")
    return (f"{r['train_steps']:,} steps in {r['train_wall_s']:.0f} s ({r['train_steps_per_s']:.0f} steps/s) after a "
            f"start-up of {r['setup_wall_s']:.1f} s, evaluation {r['eval_wall_s']:.0f} s, {loads}")


def _agent_table(name: str, agent_label: str) -> str:
    r = _agent(name)
    seeds = r["seeds"]
    rows = [("", f"| policy, {r['env'].removeprefix('FlexSim/GTM-')}, seeds {seeds[0]}-{seeds[-1]} | return |"), ("", "|---|---|"),
            ("agent", f"| {agent_label} | **{_pm(r['agent'])}** ({len(r['agent']['terminations'])} terminations) |"),
            ("trim", f"| trim action held | {_pm(r['trim'])} |"), ("baseline", f"| LQR baseline | {_pm(r['baseline'])} |"),
            ("random", f"| random actions | {_pm(r['random'])} |")]
    return "\n" + "\n".join(line for _, line in rows) + "\n"


def agent_unshaped_run() -> str:
    """The 15-minute PPO run on LevelHold-v1 without shaping: steps, time, load."""
    return _agent_run("levelhold_v1_ppo")


def agent_unshaped_table() -> str:
    """Its evaluation returns over seeds 0-9."""
    return _agent_table("levelhold_v1_ppo", "PPO agent, deterministic")


def agent_unshaped_verdict() -> str:
    """Agent / LQR against trim hold / LQR, and the training curve's range, of the run without shaping."""
    r = _agent("levelhold_v1_ppo")
    learnt = r["agent_over_baseline"] > r["trim_over_baseline"]
    curve = r["training_curve"]["mean_return_100"]
    return (f"{r['agent_over_baseline']:.3f} of the LQR, {'above' if learnt else 'below'} the trim hold's "
            f"{r['trim_over_baseline']:.3f}**. The mean return of the last 100 training episodes (second curve below) "
            f"stays between {min(curve):.0f} and {max(curve):.0f} over the {r['train_steps'] / 1e3:.0f}k steps "
            f"(the trim hold: {r['trim']['mean_return']:.0f})")


def agent_short_runs() -> str:
    """Shorter runs under heavier load (their result.json in docs/figures)."""
    ppo, sac, sde = _agent("levelhold_v1_ppo_8min"), _agent("levelhold_v1_sac"), _agent("levelhold_v1_ppo_gsde")
    s = sac["settings"]
    return (f"{ppo['train_steps']:,} steps ({ppo['settings']['minutes']:g} min, same settings) {_pm(ppo['agent'])} on "
            f"seeds {ppo['seeds'][0]}-{ppo['seeds'][-1]}; SAC ({sac['train_steps']:,} steps, {s['net'].replace(',', 'x')}, "
            f"{s['gradient_steps']} gradient steps per {s['envs']} env steps) {_pm(sac['agent'])}; PPO with gSDE and initial "
            f"log-std {sde['settings']['log_std_init']:g} ({sde['train_steps']:,} steps) {_pm(sde['agent'])}")


def agent_shaped_run() -> str:
    """The 9-minute PPO run with shaping: steps, time, load."""
    return _agent_run("levelhold_v1_ppo_shaped")


def agent_shaped_table() -> str:
    """Its evaluation returns over seeds 0-9."""
    r = _agent("levelhold_v1_ppo_shaped")
    return _agent_table("levelhold_v1_ppo_shaped",
                        f"PPO agent with shaping, deterministic ({r['settings']['minutes']:g} min)")


def agent_shaped_verdict() -> str:
    """Agent / LQR of the shaped run, the per-seed comparison with the trim hold and the training curve's range."""
    r = _agent("levelhold_v1_ppo_shaped")
    agent, trim = np.array(r["agent"]["returns"]), np.array(r["trim"]["returns"])
    wins = int(np.sum(agent > trim))
    every = "on every seed" if wins == len(agent) else f"on {wins} of {len(agent)} seeds"
    curve = r["training_curve"]["mean_return_100"]
    return (f"Agent / LQR = **{r['agent_over_baseline']:.3f}** (the target: 0.8), and the agent beats the trim "
            f"hold {every} (per-seed returns in the JSON: {agent.min():.0f}-{agent.max():.0f} against "
            f"{trim.min():.0f}-{trim.max():.0f}). The training curve shows the mean return of the last 100 training "
            f"episodes with the shaped reward (it includes the shaping terms, so its level is not the env's; the "
            f"per-episode returns of this run were not saved, the curve is copied from SB3's log into the JSON), "
            f"between {min(curve):.0f} and {max(curve):.0f}, ending at {curve[-1]:.0f}")


def agent_shaped_rerun() -> str:
    """The shaped run's command rerun on the current code (9 minutes, and stopped at the first run's step count)."""
    first, r, short = (_agent("levelhold_v1_ppo_shaped"), _agent("levelhold_v1_ppo_shaped_rerun"),
                       _agent("levelhold_v1_ppo_shaped_rerun_373k"))
    verdict = "below" if max(r["agent_over_baseline"], short["agent_over_baseline"]) < 0.8 else "at or above"
    seeds = [short["agent_over_baseline"]] + [_agent(f"levelhold_v1_ppo_shaped_rerun_373k_seed{k}")["agent_over_baseline"]
                                               for k in (1, 2)]
    return (f"the same command trained {r['train_steps']:,} steps in {r['train_wall_s']:.0f} s "
            f"({r['train_steps_per_s']:,.0f} steps/s, {r['train_steps_per_s'] / first['train_steps_per_s']:.1f}x the first "
            f"run's) and returned {_pm(r['agent'])}: **{r['agent_over_baseline']:.3f}** of the LQR; stopped at the first "
            f"run's {short['train_steps']:,} steps ({short['train_wall_s']:.0f} s) **{short['agent_over_baseline']:.3f}**, "
            f"{verdict} the target of 0.8 (trim hold / LQR {r['trim_over_baseline']:.3f}, random "
            f"{_pm(r['random'])}). The same {short['train_steps']:,} steps with training seeds 0, 1, 2 "
            f"(`--seed`): {', '.join(f'{x:.3f}' for x in seeds)} of the LQR (mean {np.mean(seeds):.3f}; "
            f"{sum(x >= 0.8 for x in seeds)} of {len(seeds)} at or above 0.8)")


#: The recipe's runs (``--shaping 10 --penalty 0.5``, checkpoint chosen on validation seeds), training seeds 0, 1, 2.
RECIPE_SEEDS = (0, 1, 2)


def _parts(r: dict, kind: str) -> dict:
    return r[kind]["mean_reward_parts"]


def agent_diagnosis() -> str:
    """Why the shaped recipe stalls: reward parts of the shaped-only agent (seed 0, 373,760 steps) against the LQR."""
    r = _agent("levelhold_v1_ppo_shaped_parts")
    agent, lqr, trim = (_parts(r, k) for k in ("agent", "baseline", "trim"))
    steps = int(round(agent["alive"]))
    return (f"the 373,760-step run of training seed 0 repeated with the reward parts recorded (again {r['train_steps']:,} steps "
            f"and {r['agent_over_baseline']:.3f} of the LQR: training is deterministic for a seed): over seeds 0-9 its mean altitude "
            f"cost is **{agent['altitude_error_m']:.1f}** per episode "
            f"(the LQR {lqr['altitude_error_m']:.1f}, the trim hold {trim['altitude_error_m']:.1f}; the cost saturates at "
            f"{-0.4 * steps:.0f} for {steps} steps), its heading cost {agent['heading_error_rad']:.1f} (the LQR "
            f"{lqr['heading_error_rad']:.1f}, the trim hold {trim['heading_error_rad']:.1f})")


def agent_penalty_trials() -> str:
    """The trial runs that chose the penalty weight (step-limited, two at a time)."""
    def run(name: str) -> str:
        r = _agent(f"levelhold_v1_ppo_penalty_trial_{name}")
        chosen = r["validation"]["chosen_steps"]
        return (f"**{r['agent_over_baseline']:.3f}** of the LQR from training seed {r['settings']['seed']} "
                f"(checkpoint of {chosen:,} of {r['train_steps']:,} steps)")

    p02 = _agent("levelhold_v1_ppo_penalty_trial_p02_seed0")["settings"]["penalty"]
    p05 = _agent("levelhold_v1_ppo_penalty_trial_p05_seed1")["settings"]["penalty"]
    return (f"p = {p02:g} reached {run('p02_seed0')} but only {run('p02_seed1')}; p = {p05:g} reached {run('p05_seed1')}")


def agent_recipe_runs() -> str:
    """The recipe's three runs: steps, wall time, chosen checkpoint and result per training seed."""
    lines = []
    for seed in RECIPE_SEEDS:
        r = _agent(f"levelhold_v1_ppo_penalty_seed{seed}")
        load = r["load_average_1min"]
        lines.append(f"| {seed} | {r['train_steps']:,} in {r['train_wall_s']:.0f} s ({r['train_steps_per_s']:,.0f}/s; load "
                     f"{load['min']:.1f}-{load['max']:.1f}) | {r['validation']['chosen_steps']:,} | **{_pm(r['agent'])}** | "
                     f"**{r['agent_over_baseline']:.3f}** | {_pm(r['agent_last'])} "
                     f"({r['agent_last']['mean_return'] / r['baseline']['mean_return']:.3f}) | "
                     f"{len(r['agent']['terminations'])} |")
    head = ("| training seed | steps in the budget | checkpoint chosen at | agent return, seeds 0-9 | agent / LQR | "
            "last policy (/ LQR) | terminations |\n|---|---|---|---|---|---|---|")
    return "\n" + head + "\n" + "\n".join(lines) + "\n"


def agent_recipe_verdict() -> str:
    """The recipe against the 0.8 target and the reference policies of the same evaluation."""
    runs = [_agent(f"levelhold_v1_ppo_penalty_seed{seed}") for seed in RECIPE_SEEDS]
    ratios = [r["agent_over_baseline"] for r in runs]
    r0 = runs[0]
    parts, lqr = _parts(r0, "agent"), _parts(r0, "baseline")
    wall = max(r["train_wall_s"] + r["setup_wall_s"] + r["eval_wall_s"] for r in runs)
    return (f"agent / LQR {min(ratios):.3f}-{max(ratios):.3f} (mean {np.mean(ratios):.3f}; {sum(x >= 0.8 for x in ratios)} of "
            f"{len(ratios)} at or above the target of 0.8), each run at most {wall / 60:.1f} min from start to result on the 2 cores; "
            f"the same evaluation's LQR returns {_pm(r0['baseline'])}, the trim hold {_pm(r0['trim'])}, random actions "
            f"{_pm(r0['random'])}. Seed 0's agent costs {parts['altitude_error_m']:.1f} in altitude and "
            f"{parts['heading_error_rad']:.1f} in heading per episode (the LQR {lqr['altitude_error_m']:.1f} and "
            f"{lqr['heading_error_rad']:.1f}) and {parts['control_rate']:.1f} in control rate (the LQR {lqr['control_rate']:.1f})")


#: Learning-curve figures of docs/environments.md -> the run whose result.json draws them.
AGENT_CURVES = {"agent_learning_curve_levelhold_v1_ppo.png": "levelhold_v1_ppo",
                "agent_learning_curve_levelhold_v1_ppo_shaped.png": "levelhold_v1_ppo_shaped",
                "agent_learning_curve_levelhold_v1_ppo_penalty.png": "levelhold_v1_ppo_penalty_seed0"}


def draw_agent_curves() -> list[Path]:
    """Redraw the learning curves of docs/environments.md from their runs' result.json (``train_sb3.py --plot``)."""
    plot_result = _agents_module("train_sb3").plot_result
    return [plot_result(_agent(run), FIGURE_DIR / png) for png, run in AGENT_CURVES.items()]


def readme_agent() -> str:
    """README's one line on the learning agent: the recipe's result over its training seeds."""
    runs = [_agent(f"levelhold_v1_ppo_penalty_seed{seed}") for seed in RECIPE_SEEDS]
    ratios = [r["agent_over_baseline"] for r in runs]
    minutes = max(r["settings"]["minutes"] for r in runs)
    return (f"PPO (`examples/agents/train_sb3.py`) reaches {min(ratios):.2f}-{max(ratios):.2f} of the LQR baseline's return "
            f"in {minutes:g}-minute runs from {len(runs)} training seeds")


def agent_v0() -> str:
    """The 15-minute PPO run on LevelHold-v0: trim hold against the LQR, and the agent."""
    r = _agent("levelhold_v0_ppo")
    ratio = r["trim"]["mean_return"] / r["baseline"]["mean_return"]
    return (f"the trim action held returns {_pm(r['trim'])} over seeds {r['seeds'][0]}-{r['seeds'][-1]}, "
            f"{100 * ratio:.0f} % of the LQR baseline's {_pm(r['baseline'])}")


def agent_v0_run() -> str:
    r = _agent("levelhold_v0_ppo")
    return (f"{r['train_steps']:,} steps) returned {_pm(r['agent'])}: {r['agent_over_baseline']:.3f} of the LQR, which "
            f"{'passes' if r['agent_over_baseline'] >= 0.8 else 'misses'} the target of 80 % "
            f"{'without beating' if r['agent']['mean_return'] < r['trim']['mean_return'] else 'and beats'} the trim hold")



# --- docs/environments.md: the flutter tasks ------------------------------------------------------------------------

FLUTTER_IDS = {0: "FlexSim/GTM-FlutterMargin-v0", 1: "FlexSim/GTM-FlutterMargin-v1"}


def _agents_module(name: str):
    """``examples/agents/<name>.py`` (baselines, lqr_design) as a module."""
    sys.path.insert(0, str(ROOT / "examples" / "agents"))
    import importlib

    return importlib.import_module(name)


@functools.cache
def _flutter_env(version: int):
    """The FlutterMargin env (unwrapped, default settings) with its baseline policy reset on seed 0."""
    import warnings

    import gymnasium as gym

    import flexsim.envs  # noqa: F401  (registers the ids)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # gymnasium's "v0 is out of date" notice
        env = gym.make(FLUTTER_IDS[version])
    policy = _agents_module("baselines").make_baseline(FLUTTER_IDS[version], env.unwrapped)
    _, info = env.reset(seed=0)
    policy.reset(info)  # designs / checks the feedback on the env's linearisation at the trim
    return env, policy


def _flutter_point(version: int):
    """The env's flutter search repeated for its ``FlutterPoint`` (mode shape, symmetry): the same call as
    ``flexsim.envs.flutter_margin`` makes, checked against the env's condition."""
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.trim import SteadyManoeuvre

    u = _flutter_env(version)[0].unwrapped
    fp = FlutterAnalysis(u.aircraft, u.dynamics.aero).search(SteadyManoeuvre.level(u.task.altitude_m, mach=0.6),
                                                              mach_range=u.task.flutter_mach_range, mach_step=0.02)
    if abs(fp.mach - u.flutter.mach) > 1e-9:
        raise RuntimeError(f"flutter point M {fp.mach} differs from the env's M {u.flutter.mach}")
    return fp


def _condition_text(version: int) -> str:
    f = _flutter_env(version)[0].unwrapped.flutter
    return (f"M {f.mach:.4f} ({f.speed_m_s:.1f} m/s, {f.frequency_rad_s:.{1 if version == 0 else 2}f} rad/s = "
            f"{f.frequency_rad_s / (2 * math.pi):.{1 if version == 0 else 2}f} Hz)")


def env_flutter_v0_point() -> str:
    """FlutterMargin-v0's open-loop flutter point (gtm_uncalibrated, finite state, 300 m) and its dominant DOF."""
    return f"{_condition_text(0)}, dominant DOF {_flutter_env(0)[0].unwrapped.flutter.mode}"


def env_flutter_v0_hz() -> str:
    return f"{_flutter_env(0)[0].unwrapped.flutter.frequency_rad_s / (2 * math.pi):.1f} Hz"


def env_flutter_v1_hz() -> str:
    return f"{_flutter_env(1)[0].unwrapped.flutter.frequency_rad_s / (2 * math.pi):.1f} Hz"


def env_flutter_v0_target() -> str:
    return f"M {_flutter_env(0)[0].unwrapped.target.mach:.4f}"


def env_flutter_v1_target() -> str:
    return f"M {_flutter_env(1)[0].unwrapped.target.mach:.4f}"


def _trim_hold(version: int, seed: int) -> dict:
    """One episode with the trim action held: return, end time, reason and the final wing/fin tip figures."""
    env = _flutter_env(version)[0]
    _, info = env.reset(seed=seed)
    action, total = info["trim_action"], 0.0
    while True:
        obs, reward, terminated, truncated, info = env.step(action)
        total += reward
        if terminated or truncated:
            break
    names = env.unwrapped.observation_names
    tip = {n: abs(float(obs[names.index(n)])) for n in names if n.startswith(("tip_twist_", "tip_deflection_"))
           and "rate" not in n}
    return {"return": total, "time_s": info["time_s"], "reason": info["termination_reason"], "tip": tip}


def env_flutter_v0_growth() -> str:
    """FlutterMargin-v0 at M_f + 0.01: open-loop growth of the fast modes and the trim hold of seed 0."""
    env, policy = _flutter_env(0)
    hold = _trim_hold(0, 0)
    limit = env.unwrapped.limits
    return (f"its fastest-growing mode faster than 25 rad/s grows at {_num(policy.open_loop_growth, '+.2f')} 1/s (full "
            f"linearisation sampled at 50 Hz, open loop); holding the trim controls (seed 0), the episode ends by "
            f"{hold['reason'].replace('_', ' ')} after {hold['time_s']:.1f} s (fin tip twist {hold['tip']['tip_twist_vtail_rad']:.3f} "
            f"rad against the {limit.fin_tip_twist_rad:g} rad limit)")


def env_flutter_v0_damper() -> str:
    """The best four-sensor fin damper of FlutterMargin-v0's baseline (``lqr_design.design_fin_damper``)."""
    policy = _flutter_env(0)[1]
    return f"reaches a growth rate of {_num(policy.closed_loop_growth, '+.2f')} 1/s"



def _fin_rate_window(control_rate_hz: float) -> dict:
    """Gains k [rad per rad/s] of the fin tip twist rate alone on the rudder (delta_r = -k x rate, sampled at
    ``control_rate_hz`` with a zero-order hold) for which every mode faster than 25 rad/s of FlutterMargin-v0's
    full linear model decays: a scan of +-1e-4..1 (``lqr_design.design_fin_damper``'s range, 4x denser), then
    Brent on the edges of the stable run; without one, the best gain of the scan."""
    from scipy.optimize import brentq

    if control_rate_hz == 50.0:
        u = _flutter_env(0)[0].unwrapped
    else:
        u = _make_flutter(0, control_rate_hz=control_rate_hz).unwrapped
    dyn = u.dynamics
    point = dyn.trim(u.target)
    rows = _agents_module("baselines").fin_sensor_rows(dyn)[:1]
    growths = _agents_module("lqr_design").rudder_feedback_growths(dyn.model, point.x, point.u, u.dt, rows)

    def fast(k: float) -> float:
        return growths(np.array([k]))[0]

    out = {}
    for sign in (1.0, -1.0):
        grid = sign * np.logspace(-4, 0, 161)
        rates = np.array([fast(k) for k in grid])
        out.setdefault("best", []).append((float(rates.min()), float(grid[rates.argmin()])))
        stable = np.flatnonzero(rates < 0.0)
        if stable.size:
            i0, i1 = stable[0], stable[-1]
            lo = brentq(fast, grid[i0 - 1], grid[i0], xtol=1e-7) if i0 > 0 else grid[0]
            hi = brentq(fast, grid[i1], grid[i1 + 1], xtol=1e-7) if i1 + 1 < grid.size else grid[-1]
            out["window"] = tuple(sorted((lo, hi), key=abs))
    out["best"] = min(out["best"])
    return out


def _window_text(w: dict) -> str:
    if "window" not in w:
        rate, k = w["best"]
        return (f"does not stabilise it at any gain of +-1e-4 to 1 rad/(rad/s) (the best, k = {_num(k, '.3f')}, leaves "
                f"{_num(rate, '+.3f')} 1/s)")
    lo, hi = w["window"]
    return f"is stabilising for gains {_num(lo, '.4f')} to {_num(hi, '.4f')} rad/(rad/s), a {hi / lo:.2g}-fold range"


def _make_flutter(version: int, **kwargs):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        return _make(FLUTTER_IDS[version], **kwargs)


def env_flutter_v0_window() -> str:
    """Fin-twist-rate feedback alone on FlutterMargin-v0 at 50 Hz: the stabilising gains, if any."""
    return f"fin-twist-rate feedback alone (every mode faster than 25 rad/s to decay) {_window_text(_fin_rate_window(50.0))}"


def env_flutter_v0_window_100() -> str:
    """The same at a 100 Hz control rate."""
    return f"fin-twist-rate feedback alone {_window_text(_fin_rate_window(100.0))}"


def env_flutter_gtm_sea_level() -> str:
    """The calibrated gtm's first flutter point at sea level (finite state, the v1 task's Mach range)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.trim import SteadyManoeuvre

    fp = FlutterAnalysis(load_aircraft("gtm"), "unsteady").search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95),
                                                                  mach_step=0.02)
    return f"a {fp.frequency_rad_s:.0f} rad/s {fp.mode_symmetry} {fp.mode.dominant_dof} mode at M {fp.mach:.2f}"


def env_flutter_v1_point() -> str:
    """FlutterMargin-v1's flutter point and the wing coordinates of its mode shape."""
    fp = _flutter_point(1)
    labels, shape = list(fp.labels), fp.mode_shape

    def coord(c: str, kind: str) -> complex:
        return complex(shape[labels.index(f"{c}_wing {kind} 1")])

    bend = {c: coord(c, "bending") for c in ("right", "left")}
    tors = {c: coord(c, "torsion") for c in ("right", "left")}
    bend_phase = math.degrees(abs(np.angle(bend["left"] / bend["right"])))
    tors_ratio = abs(tors["left"] / tors["right"])
    ratio = abs(tors["right"] / bend["right"])
    phase = math.degrees(np.angle(tors["left"] / bend["left"]))
    diff = abs(tors_ratio - 1)
    equal = "to round-off" if diff < 1e-6 else f"within {diff:.0e}".replace("e-0", "e-")
    return (f"{_condition_text(1)}, dominant DOF {fp.mode.dominant_dof}, {fp.mode_symmetry}: in the mode shape the two "
            f"wings' first bending coordinates are {bend_phase:.0f} deg apart in phase and their first torsion "
            f"coordinates are equal ({equal}; torsion {ratio:.2f} rad per m of bending, "
            f"{abs(phase):.0f} deg phase)")


def _wing_damper_growths() -> dict:
    """Largest growth rate of the fast modes of FlutterMargin-v1's sampled closed loop against the damper gain."""
    env, policy = _flutter_env(1)
    u = env.unwrapped
    dyn = u.dynamics
    row = np.zeros(dyn.layout.n_states)
    for c in ("right_wing", "left_wing"):
        row[dyn.sensors[c].eta_idx] += 0.5 * dyn.sensors[c].psi_tip
    elastic_growth = _agents_module("baselines").elastic_growth

    def growth(k: float) -> float:
        damper = np.zeros((4, dyn.layout.n_states))
        damper[1] = k * row
        return elastic_growth(u, policy.gains, damper)

    return {"k": policy.damper_gain, "growth": growth, "full": policy.lqr.full_model_growth}


@functools.cache
def _wing_damper_window() -> tuple[float, float, float, float]:
    """Open-loop and design-gain growth, and the damper gains where the fast modes' growth crosses zero."""
    from scipy.optimize import brentq

    d = _wing_damper_growths()
    g, k = d["growth"], d["k"]
    lo = brentq(g, 0.0, k, xtol=1e-5) if g(0.0) > 0 > g(k) else math.nan
    hi = brentq(g, k, 4 * k, xtol=1e-5) if g(4 * k) > 0 > g(k) else math.nan
    return g(0.0), g(k), lo, hi


def env_flutter_v1_damper() -> str:
    """FlutterMargin-v1's aileron damper: growth without and with it, the stable gain window, the whole loop."""
    d = _wing_damper_growths()
    open_loop, closed, lo, hi = _wing_damper_window()
    return (f"{_num(open_loop, '+.2f')} 1/s without the damper and {_num(closed, '+.2f')} 1/s with it (k = {d['k']:g}); "
            f"the fast modes are stable for k between {lo:.4f} and {hi:.4f}; the largest growth rate of the whole closed "
            f"loop is {_num(d['full'], '+.3f')} 1/s")


def env_flutter_v1_open_loop() -> str:
    return f"{_num(_wing_damper_window()[0], '+.2f')} 1/s"


def env_flutter_v1_trim_hold() -> str:
    """FlutterMargin-v1 with the trim controls held over seeds 0-9: how and when the episodes end."""
    env = _flutter_env(1)[0]
    holds = [_trim_hold(1, seed) for seed in range(10)]
    reasons = {h["reason"] for h in holds}
    task, limits = env.unwrapped.task, env.unwrapped.limits
    twist = [max(h["tip"]["tip_twist_right_wing_rad"], h["tip"]["tip_twist_left_wing_rad"]) for h in holds]
    by_twist = all(t > task.wing_tip_twist_limit_rad for t in twist)
    deflection = max(max(h["tip"]["tip_deflection_right_wing_m"], h["tip"]["tip_deflection_left_wing_m"]) for h in holds)
    fin = max(h["tip"]["tip_twist_vtail_rad"] for h in holds)
    returns = np.array([h["return"] for h in holds])
    times = [h["time_s"] for h in holds]
    trim_twist = _flutter_env(1)[0].unwrapped.dynamics.trim(env.unwrapped.target).tip_twist_rad
    ends = ("by the wing tip twist limit" if reasons == {"structural_limit"} and by_twist else f"by {', '.join(sorted(reasons))}")
    return (f"every one of seeds 0-9 ends {ends} (|twist| > {task.wing_tip_twist_limit_rad:g} rad on either half, "
            f"`task.wing_tip_twist_limit_rad`; trim twist {trim_twist:.3f} rad) after {min(times):.1f}-{max(times):.1f} s "
            f"(return {returns.mean():.0f} +- {returns.std():.0f}); the largest final wing deflection is {deflection:.2f} m "
            f"(limit {limits.wing_tip_deflection_m:g} m) and fin twist {fin:.3f} rad (limit {limits.fin_tip_twist_rad:g} rad)")


def env_flutter_v1_closed_loop() -> str:
    """FlutterMargin-v1 with its baseline, seed 0: the antisymmetric twist-rate amplitude at the start and the end."""
    env, policy = _flutter_env(1)
    obs, info = env.reset(seed=0)
    policy.reset(info)
    i = env.unwrapped.observation_names.index("wing_twist_rate_rad_s")
    rates, times = [abs(float(obs[i]))], [0.0]
    while True:
        obs, _, terminated, truncated, info = env.step(policy(obs))
        rates.append(abs(float(obs[i])))
        times.append(info["time_s"])
        if terminated or truncated:
            break
    rates, times = np.array(rates), np.array(times)
    first, last = rates[times <= 1.0].max(), rates[times >= times[-1] - 1.0].max()
    end = "" if truncated else f" (it ended by {info['termination_reason']})"
    return (f"the twist-rate amplitude falls from {first:.2f} rad/s in the first second to {last:.1g} rad/s in the last "
            f"one of the {times[-1]:.0f} s{end}")



# --- docs/environments.md: integration, baselines, limitations ------------------------------------------------------

def _make(env_id: str, **kwargs):
    import warnings

    import gymnasium as gym

    import flexsim.envs  # noqa: F401  (registers the ids)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # gymnasium's "v0 is out of date" notice
        return gym.make(env_id, **kwargs)


def env_stiffness() -> str:
    """Eigenvalues of the Jacobian ETD2RK uses at LevelHold-v0's trim (9144 m, M 0.75, finite state)."""
    from flexsim.model.jacobian import jacobian

    u = _make("FlexSim/GTM-LevelHold-v0").unwrapped
    manoeuvre = u.task.manoeuvre
    point = u.dynamics.trim(manoeuvre)
    lay = u.dynamics.model.layout
    x = point.x if point.x.size == lay.n_states else np.concatenate([point.x, np.zeros(lay.n_inflow)])
    ev = np.linalg.eigvals(jacobian(u.dynamics.model, x, point.u, controls=False)[0])
    return (f"eigenvalues down to {_num(ev.real.min(), '.0f')} 1/s, |λ| up to {np.abs(ev).max():.0f} 1/s at "
            f"{manoeuvre.altitude_m:g} m, M {u.task.mach:g}")


def env_v0_rms() -> str:
    """LevelHold-v0 (light turbulence): rms altitude and airspeed errors with the trim held and with the LQR."""
    env = _make("FlexSim/GTM-LevelHold-v0")
    policy = _agents_module("baselines").make_baseline("FlexSim/GTM-LevelHold-v0", env.unwrapped)
    rms: dict[str, dict[int, tuple[float, float]]] = {"trim": {}, "lqr": {}}
    for kind in rms:
        for seed in (0, 1, 2):
            obs, info = env.reset(seed=seed)
            trim_action = info["trim_action"]
            if kind == "lqr":
                policy.reset(info)
            alt, speed = [], []
            while True:
                obs, _, terminated, truncated, info = env.step(trim_action if kind == "trim" else policy(obs))
                alt.append(info["task_errors"]["altitude_error_m"])
                speed.append(info["task_errors"]["airspeed_error_m_s"])
                if terminated or truncated:
                    break
            rms[kind][seed] = (float(np.sqrt(np.mean(np.square(alt)))), float(np.sqrt(np.mean(np.square(speed)))))
    return rms


@functools.cache
def _v0_rms() -> dict:
    return env_v0_rms()


def env_v0_rms_altitude() -> str:
    r = _v0_rms()
    return f"rms altitude error {r['trim'][0][0]:.1f} m with the trim held, {r['lqr'][0][0]:.2f} m with the LQR"


def env_v0_rms_airspeed() -> str:
    r = _v0_rms()

    def span(kind: str) -> str:
        v = [r[kind][s][1] for s in r[kind]]
        return f"{min(v):.2f}-{max(v):.2f} m/s"

    return f"{span('trim')} rms with the trim held, {span('lqr')} with the LQR"


def env_bryson() -> str:
    """LevelHold-v0's LQR without the softening: the largest growth rate of the sampled full closed loop."""
    u = _make("FlexSim/GTM-LevelHold-v0").unwrapped
    baselines, lqr_design = _agents_module("baselines"), _agents_module("lqr_design")
    dyn = u.dynamics
    point = dyn.trim(u.task.manoeuvre)
    max_control = baselines.LevelHoldLqr.max_control_fraction * dyn.u_high
    design = lqr_design.design_rigid_lqr(dyn.model, point.x, point.u, baselines.LevelHoldLqr.max_state, max_control,
                                         dt_s=u.dt, max_softening=0)
    return f"on LevelHold-v0 the Bryson design alone leaves the sampled full loop growing at {_num(design.full_model_growth, '+.1f')} 1/s"



def env_qs_flutter() -> str:
    """Growth of the quasi-steady GTM's critical elastic mode at the cruise trims of LevelHold and GustAlleviation
    (the whole known-limitation bullet: whether it flutters there)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.trim import SteadyManoeuvre

    gtm = load_aircraft("gtm")
    analysis = FlutterAnalysis(gtm, "quasi-steady")
    parts = []
    for h, mach in ((9144.0, 0.75), (6000.0, 0.7)):
        _, spectrum = analysis.evaluate(SteadyManoeuvre.level(h, mach=mach))
        crit = spectrum.critical("elastic")
        parts.append((crit.eigenvalue.real, f"{_num(crit.eigenvalue.real, '+.2f')} 1/s at {h:g} m, M {mach:g}"))
    figures = f"least-damped elastic mode {crit.dominant_dof}: " + ", ".join(text for _, text in parts)
    if any(rate > 0 for rate, _ in parts):
        return (f"The quasi-steady GTM flutters at the cruise condition of the tasks ({figures}): use "
                f"`aero=\"quasi-steady\"` only for short runs.")
    return (f"The quasi-steady GTM (with its {100 * gtm.structural_damping_ratio:g} % structural damping) is stable at the cruise conditions of the tasks "
            f"({figures}).")


def env_turn_sideslip() -> str:
    """The paper's steady turn at the Turn task's condition and R = +8000 m: sideslip and rudder."""
    u = _make("FlexSim/GTM-Turn-v0").unwrapped
    from flexsim.trim import SteadyManoeuvre

    point = u.dynamics.trim(SteadyManoeuvre.turn(u.task.altitude_m, 8000.0, mach=u.task.mach))
    return (f"{_num(math.degrees(point.beta), '+.1f')} deg at R = +8000 m, with the sign of R) and the trim needs about "
            f"{abs(math.degrees(point.u[3])):.1f} deg of rudder")


#: The figures of this module: region name -> (function, fast: checked in the default test suite).
ENV_FIGURES = {
    "agent-v0": (agent_v0, True),
    "agent-v0-run": (agent_v0_run, True),
    "agent-unshaped-run": (agent_unshaped_run, True),
    "agent-unshaped-table": (agent_unshaped_table, True),
    "agent-unshaped-verdict": (agent_unshaped_verdict, True),
    "agent-short-runs": (agent_short_runs, True),
    "agent-shaped-run": (agent_shaped_run, True),
    "agent-shaped-table": (agent_shaped_table, True),
    "agent-shaped-verdict": (agent_shaped_verdict, True),
    "agent-shaped-rerun": (agent_shaped_rerun, True),
    "agent-diagnosis": (agent_diagnosis, True),
    "agent-penalty-trials": (agent_penalty_trials, True),
    "agent-recipe-runs": (agent_recipe_runs, True),
    "agent-recipe-verdict": (agent_recipe_verdict, True),
    "readme-agent": (readme_agent, True),
    "env-flutter-v0-point": (env_flutter_v0_point, False),
    "env-flutter-v0-hz": (env_flutter_v0_hz, False),
    "env-flutter-v1-hz": (env_flutter_v1_hz, False),
    "env-flutter-v0-target": (env_flutter_v0_target, False),
    "env-flutter-v1-target": (env_flutter_v1_target, False),
    "env-flutter-v0-growth": (env_flutter_v0_growth, False),
    "env-flutter-v0-damper": (env_flutter_v0_damper, False),
    "env-flutter-v0-window": (env_flutter_v0_window, False),
    "env-flutter-v0-window-100": (env_flutter_v0_window_100, False),
    "env-flutter-gtm-sea-level": (env_flutter_gtm_sea_level, False),
    "env-flutter-v1-point": (env_flutter_v1_point, False),
    "env-flutter-v1-open-loop": (env_flutter_v1_open_loop, False),
    "env-flutter-v1-trim-hold": (env_flutter_v1_trim_hold, False),
    "env-flutter-v1-damper": (env_flutter_v1_damper, False),
    "env-flutter-v1-closed-loop": (env_flutter_v1_closed_loop, False),
    "env-stiffness": (env_stiffness, False),
    "env-bryson": (env_bryson, False),
    "env-v0-rms-altitude": (env_v0_rms_altitude, False),
    "env-v0-rms-airspeed": (env_v0_rms_airspeed, False),
    "env-qs-flutter": (env_qs_flutter, False),
    "env-turn-sideslip": (env_turn_sideslip, False),
}
