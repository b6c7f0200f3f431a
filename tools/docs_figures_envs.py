"""Figures of docs/environments.md (the flutter tasks and the integration), computed from the environments and
``examples/agents/baselines.py`` / ``lqr_design.py`` / ``evaluate_baselines.py``; none is fast."""

from __future__ import annotations

import functools
import math

import numpy as np
from figure_text import exponent, figure, num, table

FLUTTER_IDS = {0: "FlexSim/GTM-FlutterMargin-v0", 1: "FlexSim/GTM-FlutterMargin-v1"}


@functools.cache
def _flutter_env(version: int):
    """The FlutterMargin env (unwrapped, default settings) with its baseline policy reset on seed 0."""
    import baselines

    env = _make(FLUTTER_IDS[version])
    policy = baselines.make_baseline(FLUTTER_IDS[version], env.unwrapped)
    _, info = env.reset(seed=0)
    policy.reset(info)  # designs / checks the feedback on the env's linearisation at the trim
    return env, policy


def _condition_text(version: int) -> str:
    f = _flutter_env(version)[0].unwrapped.flutter
    return (f"M {f.mach:.4f} ({f.speed_m_s:.1f} m/s, {f.frequency_rad_s:.{1 if version == 0 else 2}f} rad/s = "
            f"{f.frequency_rad_s / (2 * math.pi):.{1 if version == 0 else 2}f} Hz)")


@figure(fast=False)
def env_flutter_v0_point() -> str:
    """FlutterMargin-v0's open-loop flutter point (gtm_uncalibrated, finite state, 300 m) and its mode."""
    return f"{_condition_text(0)}, mode {_flutter_env(0)[0].unwrapped.flutter.mode}"


@figure(fast=False)
def env_flutter_v0_growth() -> str:
    """FlutterMargin-v0 at M_f + 0.01: open-loop growth of the fast modes and an episode (seed 0) holding the trim
    action: its end, and the fin tip twist there."""
    env, policy = _flutter_env(0)
    _, info = env.reset(seed=0)
    action, terminated, truncated = info["trim_action"], False, False
    while not (terminated or truncated):
        obs, _, terminated, truncated, info = env.step(action)
    fin_twist = abs(float(obs[env.unwrapped.observation_names.index("tip_twist_vtail_rad")]))
    return (f"its fastest-growing mode faster than 25 rad/s grows at {num(policy.open_loop_growth, '+.2f')} 1/s (full "
            f"linearisation sampled at 50 Hz, open loop); holding the trim controls (seed 0), the episode ends by "
            f"{info['termination_reason'].replace('_', ' ')} after {info['time_s']:.1f} s (fin tip twist {fin_twist:.3f} "
            f"rad against the {env.unwrapped.limits.fin_tip_twist_rad:g} rad limit)")


@figure(fast=False)
def env_flutter_v0_damper() -> str:
    """The best four-sensor fin damper of FlutterMargin-v0's baseline (``lqr_design.design_fin_damper``)."""
    policy = _flutter_env(0)[1]
    return f"reaches a growth rate of {num(policy.closed_loop_growth, '+.2f')} 1/s"


@figure(fast=False)
def env_flutter_v1_point() -> str:
    """FlutterMargin-v1's flutter point and the wing coordinates of its mode shape: the env's flutter search repeated
    for its ``FlutterPoint`` (the same call as ``flexsim.envs.flutter_margin`` makes), checked against the env's."""
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.trimming import SteadyManoeuvre

    u = _flutter_env(1)[0].unwrapped
    fp = FlutterAnalysis(u.aircraft, u.dynamics.aero).search(SteadyManoeuvre.level(u.task.altitude_m, mach=0.6),
                                                              mach_range=u.task.flutter_mach_range, mach_step=0.02)
    if abs(fp.mach - u.flutter.mach) > 1e-9:
        raise RuntimeError(f"flutter point M {fp.mach} differs from the env's M {u.flutter.mach}")
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
    equal = "to round-off" if diff < 1e-6 else f"within {exponent(diff)}"
    return (f"{_condition_text(1)}, mode {fp.mode.name}: in the mode shape the two "
            f"wings' first bending coordinates are {bend_phase:.0f} deg apart in phase and their first torsion "
            f"coordinates are equal ({equal}; torsion {ratio:.2f} rad per m of bending, "
            f"{abs(phase):.0f} deg phase)")


@figure(fast=False)
def env_flutter_v0_target() -> str:
    """FlutterMargin-v0's target Mach (M_f + 0.01)."""
    return f"M {_flutter_env(0)[0].unwrapped.target.mach:.4f}"


@figure(fast=False)
def env_flutter_v1_target() -> str:
    """FlutterMargin-v1's target Mach (M_f + 0.01)."""
    return f"M {_flutter_env(1)[0].unwrapped.target.mach:.4f}"


def _make(env_id: str, **kwargs):
    import warnings

    import gymnasium as gym

    import flexsim.envs  # noqa: F401  (registers the ids)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # gymnasium's "v0 is out of date" notice
        return gym.make(env_id, **kwargs)


@figure(fast=False)
def env_stiffness() -> str:
    """Eigenvalues of the Jacobian ETD2RK uses at LevelHold-v0's trim (9144 m, M 0.75, finite state)."""
    from flexsim.model.jacobian import jacobian

    u = _make("FlexSim/GTM-LevelHold-v0").unwrapped
    manoeuvre = u.task.manoeuvre
    point = u.dynamics.trim(manoeuvre)
    lay = u.dynamics.model.layout
    x = point.x if point.x.size == lay.n_states else np.concatenate([point.x, np.zeros(lay.n_inflow)])
    ev = np.linalg.eigvals(jacobian(u.dynamics.model, x, point.u, controls=False)[0])
    return (f"eigenvalues down to {num(ev.real.min(), '.0f')} 1/s, |λ| up to {np.abs(ev).max():.0f} 1/s at "
            f"{manoeuvre.altitude_m:g} m, M {u.task.mach:g}")


# FlutterMargin-v0's episodes fly just past its flutter point: its baseline return is 989.3-989.7 on two builds
@figure(fast=False, rtol=1e-3)
def env_baselines() -> str:
    """The markdown table of baseline and random returns (seeds 0-9, full episodes, default settings)."""
    import gymnasium as gym
    from baselines import BASELINES
    from evaluate_baselines import evaluate

    rows = []
    for env_id in BASELINES:
        limit = gym.spec(env_id).max_episode_steps
        result = evaluate(env_id, 10)
        base, rand = result["baseline"], result["random"]
        reasons = [r for r in rand["reasons"] if r]
        if not reasons:
            ending = "time limit"
        else:
            common = max(set(reasons), key=reasons.count)
            ending = f"{common.replace('_', ' ')} ({reasons.count(common)}/10), {rand['lengths'].mean():.0f} steps on average"
        label = env_id.removeprefix("FlexSim/").removeprefix("GTM-").removesuffix("-v0")
        rows.append([f"{label} (max {limit})", f"{base['returns'].mean():.1f} +- {base['returns'].std():.1f}",
                     f"{rand['returns'].mean():.1f} +- {rand['returns'].std():.1f}", ending])
    return table("| id | baseline return | random return | random episodes end by |", rows)
