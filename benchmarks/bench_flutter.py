"""Cost of the flutter analysis on the GTM (m = n = 2): one evaluation, one flutter point, the level table.

Issue 4 budgets: one flutter point (QS) <= 2 s; the whole study <= 5 min on this 2-core machine.
Prints medians over --repeats runs. ``--study`` also times the whole study of the paper's Figs. 7-16:
level turns R = 5-12 km (8 radii) and climbs gamma = -15..15 deg (7 angles) at 0, 3048, 6096, 9144 m,
QS and US (Theodorsen p-k): 120 flutter points, local processes (all cores), as ``flexsim sweep``.
Run: python benchmarks/bench_flutter.py [--repeats 3] [--table] [--study]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.linear.flutter import FlutterAnalysis  # noqa: E402
from flexsim.trim import SteadyManoeuvre  # noqa: E402


def _median(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--table", action="store_true", help="also time `flexsim flutter` (2 settings x 4 altitudes x QS, US)")
    parser.add_argument("--study", action="store_true", help="also time the whole turn + climb study (120 points)")
    args = parser.parse_args()
    gtm = load_aircraft("gtm")
    man = SteadyManoeuvre.level(0.0, mach=0.85)
    for model in ("quasi-steady", "unsteady", "theodorsen"):
        analysis = FlutterAnalysis(gtm, model)
        t = _median(lambda: analysis.evaluate(man), args.repeats)
        print(f"one trim + linearisation + eigen-analysis ({model:>12}): {t * 1e3:8.1f} ms (median of {args.repeats})")
    for model in ("quasi-steady", "unsteady", "theodorsen"):
        analysis = FlutterAnalysis(gtm, model)
        point = analysis.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95))
        t = _median(lambda: analysis.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95)), args.repeats)
        budget = "  (budget 2 s)" if model == "quasi-steady" else ""
        print(f"one flutter point, sea level, M 0.5-0.95 grid 0.05 + Brent 1e-4 ({model:>12}): {t:6.2f} s "
              f"[M_F {point.mach:.4f}, {point.evaluations} evaluations]{budget}")
    if args.table:
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "flexsim.cli.main", "flutter", "gtm", "--json"], check=True, capture_output=True)
        print(f"`flexsim flutter` (paper-replication + physical settings x 4 altitudes x QS, US, 2 processes): {time.perf_counter() - t0:6.1f} s")
    if args.study:
        from flexsim.linear.study import climb_cases, run_study, turn_cases

        cases = turn_cases("gtm") + climb_cases("gtm")
        t0 = time.perf_counter()
        rows = run_study(cases, progress=False)
        elapsed = time.perf_counter() - t0
        ok = sum("mach" in r for r in rows)
        print(f"whole study (turn + climb, 4 altitudes, QS + US): {ok}/{len(rows)} flutter points in {elapsed:6.1f} s "
              f"= {elapsed / 60:.2f} min on {os.cpu_count()} cores (budget 5 min)")


if __name__ == "__main__":
    main()
