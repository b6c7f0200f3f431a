"""Real-time factor of simulate() on 60 s of GTM flight from level trim through a small gust.

GTM (notional), m = n = 2, unsteady aerodynamics with N = 6 inflow states per strip (252 states), level
trim at 9144 m and M 0.75, a 1-cos up-gust of 2 m/s and gradient length 30 m reached by the body origin
at t = 1 s. For the default integrator, the previous default and Radau (the earlier default) — ``--all``
adds ETD2RK 50 ms, Radau 1e-4/1e-5, LSODA, BDF and DOP853 1e-6 —: median wall time of ``--repeats`` runs
(integration, the one-off Jacobian and matrix functions, the 100 Hz samples; no log), the real-time factor 60 s /
wall time and 60 s / CPU time of the process (on a shared machine the wall time includes waiting for a core), the
ratio to the default's wall time measured in the same run, the cost counters, and the largest deviation from a
reference run (DOP853, rtol 1e-9) of altitude, airspeed and right-wing tip deflection sampled at 10 Hz. Then the
default and Radau once more with a 50 Hz flight log, to show the logging cost, and the accuracy on a growing
oscillation (Goland flutter onset). Target: the default integrator >= 100x faster than real time on one
core (OPENBLAS_NUM_THREADS=1).

The default with aerodynamics: ETD2RK (Cox & Matthews 2002) with fixed steps of DEFAULT_MAX_STEP["ETD2RK"] (20 ms
since the quintic dense output; 10 ms before, the "previous default"), the trim Jacobian as linear part, by the
compiled steps (flexsim.sim._step_kernels.etd2rk_rows, one row).

``--manoeuvres``: instead, the accuracy of the default, the previous default and Radau rtol 1e-3 on every named
manoeuvre of ``flexsim simulate`` against DOP853 at rtol 1e-9 (:func:`flexsim.sim.accuracy.manoeuvre_errors`, the
table of docs/simulation.md: largest errors of altitude, airspeed, bank angle and right-wing tip deflection at the
100 Hz samples; the tip error also relative to the tip excursion).

``--parts``: instead, the CPU time of the parts of one default run (compiled steps, dense output, events, matrix
functions, Jacobian, the rest).

``--compare [REV]``: instead, this tree against a reference revision (default main) side by side in one run: each side in its own process (``benchmarks/_simulate_worker.py``),
alternately (reference, this, reference, ...) ``--repeats`` times, so both see the same load; each process times
``--inner`` default runs of the scenario after a warm-up. Prints the median CPU time and real-time factor of each
side, their ratio, and the largest difference of the trajectories (100 Hz samples): per group of the state layout
relative to the group's largest magnitude, and of altitude, airspeed and tip deflection in SI units; then the same
with every run writing a 50 Hz flight log (MCAP, in a temporary directory). The reference
is extracted with ``git archive`` into ``~/.cache/flexsim-bench/<revision>`` (kept with numba's cache of its kernels:
the first run compiles them, 2-7 min of CPU), or taken from ``--reference-tree``.

Run: python benchmarks/bench_simulate.py [--duration 60] [--repeats 3] [--all] [--candidates Radau:1e-3,ETD2RK:0.02]
     python benchmarks/bench_simulate.py --manoeuvres
     python benchmarks/bench_simulate.py --parts
     python benchmarks/bench_simulate.py --compare [REV] [--reference-tree DIR] [--repeats 3] [--inner 3]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# measure the flexsim of this checkout (python puts benchmarks/ on sys.path, not the repository root)
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from flexsim.sim.accuracy import manoeuvre_errors  # noqa: E402
from flexsim.sim.manoeuvres import build_manoeuvre, manoeuvre_names  # noqa: E402
from flexsim.sim.simulate import DEFAULT_MAX_STEP, IntegratorSettings, simulate  # noqa: E402
from flexsim.sim.run_settings import EventSettings, OutputSettings  # noqa: E402

TARGET_RTF = 100.0
#: (label, method, fixed step [s] for ETD2RK or rtol): the default first, then the previous default and Radau
#: (the earlier default); ``--all`` adds the rest.
DEFAULT = ("default", "ETD2RK", DEFAULT_MAX_STEP["ETD2RK"])
PREVIOUS = ("previous default", "ETD2RK", 0.01)
RADAU = ("Radau (earlier default)", "Radau", 1e-3)
OTHERS = [("", "ETD2RK", 0.05), ("", "Radau", 1e-4), ("", "Radau", 1e-5), ("", "LSODA", 1e-4), ("", "BDF", 1e-4),
          ("", "DOP853", 1e-6)]

from _simulate_worker import scenario  # noqa: E402  (the GTM model, its level trim and the gust)

HERE = Path(__file__).resolve().parents[1]
from _reference import reference_tree as checkout_of  # noqa: E402  (benchmarks/_reference.py)
WORKER = HERE / "benchmarks" / "_simulate_worker.py"
#: Default reference of --compare: the branch a change is compared against.
COMPARE_REFERENCE = "main"


def compare(ref: Path, repeats: int, inner: int, duration: float, log: bool = False) -> None:
    """This tree against the reference tree, side by side (module docstring, ``--compare``); ``log``: every run
    writes a 50 Hz flight log (MCAP) into a temporary directory."""
    print(f"default simulate{' with a 50 Hz flight log' if log else ''}, {duration:g} s of the gust scenario: reference {ref} against this tree {HERE}; "
          f"{repeats} alternating process pairs x {inner} runs; load average {os.getloadavg()[0]:.2f} at start", flush=True)
    runs: dict[str, list[dict]] = {"ref": [], "this": []}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(repeats):
            for side, tree in (("ref", ref), ("this", HERE)):
                env = dict(os.environ, PYTHONPATH=str(tree), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
                out = subprocess.run([sys.executable, str(WORKER), str(inner), str(duration), f"{tmp}/{side}.npz"] + (["log"] if log else []),
                                     cwd=tree, env=env, check=True, capture_output=True, text=True)
                runs[side].append(json.loads(out.stdout.strip().splitlines()[-1]))
        samples = {side: dict(np.load(f"{tmp}/{side}.npz")) for side in runs}
    med = {side: {k: statistics.median(t for r in runs[side] for t in r[k]) for k in ("cpu_s", "wall_s")} for side in runs}
    print(f"{'':<10} {'CPU [s]':>8} {'RTF (CPU)':>10} {'wall [s]':>9} {'RTF (wall)':>10}  status")
    for side, label in (("ref", "reference"), ("this", "this tree")):
        m = med[side]
        print(f"{label:<10} {m['cpu_s']:8.3f} {duration / m['cpu_s']:10.1f} {m['wall_s']:9.3f} {duration / m['wall_s']:10.1f}  "
              f"{runs[side][-1]['status']}")
    print(f"ratio reference / this tree: CPU {med['ref']['cpu_s'] / med['this']['cpu_s']:.2f}x, wall "
          f"{med['ref']['wall_s'] / med['this']['wall_s']:.2f}x (medians of {repeats * inner} runs per side)")
    a, b = samples["this"], samples["ref"]
    if a["t"].shape != b["t"].shape or not np.allclose(a["t"], b["t"], rtol=1e-12, atol=0.0):
        print(f"trajectories: different sample times ({a['t'].size} against {b['t'].size} samples)")
    else:
        worst = []
        for name, (lo, hi) in runs["ref"][-1]["layout"].items():
            if hi > lo:
                scale = np.abs(b["x"][:, lo:hi]).max()
                worst.append((float(np.abs(a["x"][:, lo:hi] - b["x"][:, lo:hi]).max() / scale) if scale else 0.0, name))
        rel, group = max(worst)
        print(f"largest trajectory difference (100 Hz samples): {rel:.1e} of the largest |{group}| (per group of the "
              f"state layout); altitude {np.abs(a['altitude'] - b['altitude']).max():.1e} m, airspeed "
              f"{np.abs(a['airspeed'] - b['airspeed']).max():.1e} m/s, right-wing tip "
              f"{np.abs(a['tip'] - b['tip']).max():.1e} m")
    print(f"target: >= {TARGET_RTF:g}x real time (CPU); load average {os.getloadavg()[0]:.2f} at the end")


def errors(result, reference) -> tuple[float, float, float]:
    """Largest |difference| of altitude [m], airspeed [m/s] and right-wing tip deflection [m] at 10 Hz."""
    k = np.arange(0, min(result.t.size, reference.t.size), 10)
    return (float(np.abs(result.altitude_m[k] - reference.altitude_m[k]).max()),
            float(np.abs(result.airspeed_m_s[k] - reference.airspeed_m_s[k]).max()),
            float(np.abs(result.tip_deflection_m()[k] - reference.tip_deflection_m()[k]).max()))


def manoeuvre_accuracy() -> None:
    """Errors of the default, the previous default and Radau on every named manoeuvre against DOP853 at rtol 1e-9
    (:func:`flexsim.sim.accuracy.manoeuvre_errors`, the table of docs/simulation.md) with the wall times."""
    print(f"accuracy on the named manoeuvres against DOP853 rtol 1e-9 (load average {os.getloadavg()[0]:.2f})")
    for name in manoeuvre_names():
        rows = manoeuvre_errors(name)
        print(f"{name}: {rows[0].duration_s:g} s; tip excursion {rows[0].tip_excursion_m:.3g} m", flush=True)
        for e in rows:
            parts = []
            if e.altitude_m is not None:
                parts += [f"alt {e.altitude_m:.1e} m", f"V {e.airspeed_m_s:.1e} m/s", f"phi {e.bank_deg:.1e} deg"]
            parts.append(f"tip {e.tip_m:.1e} m ({e.tip_relative:.1e} of the excursion)")
            print(f"  {e.choice.label + ', ' + e.choice.name:<34} {e.status:<10} {e.wall_time_s:6.2f} s wall, {e.nfev:6d} rhs: "
                  + ", ".join(parts), flush=True)


def cost_parts(model, point, gust, duration: float) -> None:
    """CPU time of the parts of one default run (process time around each part; the rest is the Python loop, the
    samples' bookkeeping, the set-up and the result)."""
    import flexsim.sim.compiled_run as cr
    import flexsim.sim.fixed_step as fs
    import flexsim.sim.simulate as sm
    from flexsim.sim import _step_kernels as sk

    spent: dict[str, float] = {}
    originals = []
    labels: list[str] = []

    def timed(owner, attr: str, label: str) -> None:
        fn = getattr(owner, attr)
        originals.append((owner, attr, fn))
        labels.append(label)

        def wrapper(*args, **kwargs):
            c0 = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                spent[label] = spent.get(label, 0.0) + time.process_time() - c0
        setattr(owner, attr, wrapper)

    timed(sk, "etd2rk_rows", "compiled steps (2 rhs + 3 mat-vecs per step)")
    timed(cr._Steps, "__call__", "dense output (samples, event times)")
    timed(cr, "_chunk_events", "events")
    timed(fs, "phi_functions", "matrix functions")
    timed(sm, "jacobian", "Jacobian")
    try:
        c0 = time.process_time()
        simulate(model, point, duration, wind=gust)
        total = time.process_time() - c0
    finally:
        for owner, attr, fn in originals:
            setattr(owner, attr, fn)
    print(f"CPU time of the parts of one default run ({total:.3f} s CPU, load average {os.getloadavg()[0]:.2f}):")
    for label in labels:
        t = spent.get(label, 0.0)
        print(f"  {label:<48} {t:7.3f} s  {100 * t / total:5.1f} %")
    rest = total - sum(t for label, t in spent.items() if not label.startswith("  "))
    print(f"  {'rest (Python loop, samples, set-up, result)':<48} {rest:7.3f} s  {100 * rest / total:5.1f} %")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--duration", type=float, default=60.0, help="simulated time [s] (default 60)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--all", action="store_true", help="also ETD2RK 50 ms, Radau 1e-4/1e-5, LSODA, BDF, DOP853 1e-6")
    parser.add_argument("--manoeuvres", action="store_true", help="accuracy on the named manoeuvres instead")
    parser.add_argument("--parts", action="store_true", help="instead, the CPU time of the parts of one default run")
    parser.add_argument("--compare", nargs="?", const=COMPARE_REFERENCE, default=None, metavar="REV",
                        help=f"instead, this tree against REV side by side (default {COMPARE_REFERENCE})")
    parser.add_argument("--reference-tree", type=Path, default=None, help="with --compare: a checkout to compare against")
    parser.add_argument("--inner", type=int, default=3, help="with --compare: timed runs per process")
    parser.add_argument("--candidates", default=None,
                        help="comma-separated method:rtol (ETD2RK: method:step [s]) pairs, e.g. Radau:1e-3,ETD2RK:0.02")
    args = parser.parse_args()
    if args.manoeuvres:
        manoeuvre_accuracy()
        return
    if args.compare or args.reference_tree:
        ref = args.reference_tree.resolve() if args.reference_tree else checkout_of(args.compare or COMPARE_REFERENCE)
        for log in (False, True):
            compare(ref, args.repeats, args.inner, args.duration, log)
        return
    model, point, gust = scenario()
    if args.parts:
        simulate(model, point, 0.1, wind=gust)  # load the compiled kernels (not timed)
        cost_parts(model, point, gust, args.duration)
        return
    print(f"GTM m = n = 2, unsteady N = 6: {model.layout.n_states} states; level trim M 0.75 at 9144 m; "
          f"1-cos gust 2 m/s, H = 30 m at t = 1 s; {args.duration:g} s simulated; median of {args.repeats} runs; "
          f"load average {os.getloadavg()[0]:.2f} at start")
    simulate(model, point, 0.1, wind=gust)  # load the compiled kernels (not timed)
    t0 = time.perf_counter()
    reference = simulate(model, point, args.duration, integrator=IntegratorSettings(method="DOP853", rtol=1e-9),
                         wind=gust)
    print(f"reference DOP853 rtol 1e-9: {time.perf_counter() - t0:.1f} s wall, {reference.nfev} rhs evaluations")
    print(f"{'':<24} {'method':<8} {'h/rtol':>6} {'wall [s]':>9} {'cpu [s]':>8} {'RTF':>7} {'RTF cpu':>7} {'x default':>9} "
          f"{'nfev':>7} {'nlu':>5} {'njev':>4}   {'err alt [m]':>11} {'err V [m/s]':>11} {'err tip [m]':>11}")
    candidates = [DEFAULT, PREVIOUS, RADAU] + (OTHERS if args.all else [])
    if args.candidates:
        candidates = [("", c.split(":")[0], float(c.split(":")[1])) for c in args.candidates.split(",")]
    default_wall = None
    for label, method, rtol in candidates:
        walls, cpus = [], []
        for _ in range(args.repeats):
            c0 = time.process_time()
            if method == "ETD2RK":
                result = simulate(model, point, args.duration,
                                  integrator=IntegratorSettings(method=method, max_step_s=rtol), wind=gust)
            else:
                result = simulate(model, point, args.duration,
                                  integrator=IntegratorSettings(method=method, rtol=rtol), wind=gust)
            cpus.append(time.process_time() - c0)
            walls.append(result.wall_time_s)
        wall, cpu = statistics.median(walls), statistics.median(cpus)
        if default_wall is None:
            default_wall = wall
        if not result.completed:
            print(f"{label:<24} {method:<8} {rtol:6.0e}   FAILED after {wall:.2f} s wall, {result.nfev} rhs evaluations: "
                  f"{result.reason}", flush=True)
            continue
        e = errors(result, reference)
        flag = "  below target" if label == "default" and args.duration / wall < TARGET_RTF else ""
        print(f"{label:<24} {method:<8} {rtol:6.0e} {wall:9.2f} {cpu:8.2f} {args.duration / wall:7.1f} {args.duration / cpu:7.1f} "
              f"{wall / default_wall:9.2f} {result.nfev:7d} {result.nlu:5d} {result.njev:4d}   {e[0]:11.2e} {e[1]:11.2e} "
              f"{e[2]:11.2e}{flag}", flush=True)
    for method in ("ETD2RK", "Radau"):
        with tempfile.TemporaryDirectory() as tmp:
            result = simulate(model, point, args.duration,
                              output=OutputSettings(log_path=os.path.join(tmp, "bench.mcap")), wind=gust,
                              integrator=IntegratorSettings(method=method))
        print(f"{method} (default step/rtol) with a 50 Hz flight log: {result.wall_time_s:.2f} s wall, "
              f"RTF {result.real_time_factor:.1f}")
    print(f"target: the default >= {TARGET_RTF:g}x real time on one core; load average {os.getloadavg()[0]:.2f} at the end")
    flutter = build_manoeuvre("flutter-onset")
    ref = flutter.simulate(integrator=IntegratorSettings(method="DOP853", rtol=1e-9),
                           events=EventSettings(wing_tip_deflection_m=100.0), t_end_s=3.1).tip_deflection_m()
    peak = np.abs(ref).max()
    print(f"accuracy on a growing oscillation: Goland flutter onset (1.05 x flutter speed) for 3.1 s (the tip "
          f"amplitude grows to {peak:.2f} m, DOP853 rtol 1e-9), largest tip-deflection error relative to that amplitude")
    for method, rtol in (("ETD2RK", DEFAULT[2]), ("ETD2RK", 0.01), ("Radau", 1e-3), ("Radau", 1e-4), ("DOP853", 1e-6)):
        step = {"max_step_s": rtol} if method == "ETD2RK" else {"rtol": rtol}
        r = flutter.simulate(integrator=IntegratorSettings(method=method, **step),
                             events=EventSettings(wing_tip_deflection_m=100.0),
                             t_end_s=3.1)
        rel = np.abs(r.tip_deflection_m() - ref).max() / np.abs(ref).max()
        print(f"  {method} {'h' if method == 'ETD2RK' else 'rtol'} {rtol:.0e}: {rel:.1e}, {r.wall_time_s:.2f} s wall")


if __name__ == "__main__":
    main()
