"""The geometrically nonlinear aircraft against the linear model on the bundled PHC HALE, side by side in one run.

Cases (CPU seconds of this process, one BLAS thread as the analyses use; medians of ``--repeats`` after one warm-up
run that compiles the kernels):

* ``trim``: one level trim at 20 km, 25 m/s — linear ``fs.trim`` against nonlinear ``fs.trim_flexible``
  (8 elements per wing, 48 strains, from a cold start);
* ``force``: one evaluation of the equations — the linear model's right-hand side (``model.rhs``, compiled) against
  the nonlinear aircraft's ``steady_residual`` at its trim (beam kinematics and strip loads compiled, sums NumPy);
* ``rhs``: one right-hand side of the equations of motion in time — the linear ``model.rhs`` against the nonlinear
  free-flight equations with quasi-steady strips, ``FlexibleAircraft.free_flight_rate`` (what the time-domain run,
  the environment and the free aircraft's spectrum evaluate), at the trim's state;
* ``flutter``: one flutter point of level flight — linear ``fs.flutter(..., "theodorsen")`` against
  ``fs.flexible_flutter(..., (20, 45), speed_step_m_s=2.5)``.
* ``env (reset + 50 steps)``: one second of the HALE gust task at 50 Hz holding the trim's controls —
  ``FlexSim/HALE-GustAlleviation-v0`` (linear structure, ETD2RK kernel) against ``-v1`` (nonlinear beams, 4 elements
  per wing, two ROS2 steps of 10 ms per control period).

The issue's target for a nonlinear flutter point is 5x the linear one; the ratio is printed, not asserted.

Run: python benchmarks/bench_nonlinear.py [--repeats 3]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import gymnasium as gym  # noqa: E402

import flexsim as fs  # noqa: E402
import flexsim.envs  # noqa: E402,F401  (registers the environments)


def _cpu(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    level = fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0)
    lin_trim = fs.trim(model, level)
    nl_trim = fs.trim_flexible(model, level)
    fs.flutter(model, level, "theodorsen")
    flex = nl_trim.aircraft
    quat = np.array([np.cos(nl_trim.theta_rad / 2), 0.0, np.sin(nl_trim.theta_rad / 2), 0.0])
    u_lin = lin_trim.u

    def nl_force():
        for _ in range(10):
            flex.steady_residual(nl_trim.strains, quat, nl_trim.velocity_m_s, nl_trim.rate_rad_s, nl_trim.controls,
                                 nl_trim.density_kg_m3, 9.80665)

    def lin_force():
        for _ in range(10):
            model.rhs(0.0, lin_trim.x, u_lin)

    structure = flex.free_structure(9.80665)
    y0 = nl_trim.state()

    def nl_rhs():
        for _ in range(10):
            flex.free_flight_rate(structure, 0.0, y0, nl_trim.controls, nl_trim.density_kg_m3)

    lin_force(), nl_rhs()  # warm-up: loads the linear right-hand side, compiles the block exponential
    envs = {v: gym.make(f"FlexSim/HALE-GustAlleviation-{v}") for v in ("v0", "v1")}

    def episode_second(version):
        env = envs[version]
        _, info = env.reset(seed=0)
        for _ in range(50):
            env.step(info["trim_action"])

    episode_second("v0"), episode_second("v1")  # warm-up: the env's kernels and trims

    rows = [
        ("trim", lambda: fs.trim(model, level), lambda: fs.trim_flexible(model, level)),
        ("force (x10)", lin_force, nl_force),
        ("rhs (x10)", lin_force, nl_rhs),
        ("flutter", lambda: fs.flutter(model, level, "theodorsen"),
         lambda: fs.flexible_flutter(model, level, (20.0, 45.0), speed_step_m_s=2.5)),
        ("env (reset + 50 steps)", lambda: episode_second("v0"), lambda: episode_second("v1")),
    ]
    print(f"PHC HALE, 20 km; CPU s, median of {args.repeats}; load {os.getloadavg()[0]:.2f}")
    print(f"{'case':<24}{'linear':>12}{'nonlinear':>12}{'nonlinear/linear':>18}")
    for name, lin, nl in rows:
        a, b = _cpu(lin, args.repeats), _cpu(nl, args.repeats)
        print(f"{name:<24}{a:>12.4f}{b:>12.4f}{b / a:>18.1f}")


if __name__ == "__main__":
    main()
