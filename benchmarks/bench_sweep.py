"""Distributed sweeps at point granularity: serial against a Dask ``LocalCluster`` of 1 and 2 workers.

A small turn study (default: QS, 2 altitudes x 4 radii = 8 points, 2 chains) is run

1. serially with whole chains (each point seeded with the previous flutter Mach: today's default);
2. serially with ``chain_length=1`` (every point an independent task, unseeded);
3. on a ``distributed.LocalCluster`` of 1 and of 2 worker processes (one thread each) with ``chain_length=1``.

It prints the wall time of each run side by side, checks that the cluster runs give exactly the rows of
the serial ``chain_length=1`` run (the same cut gives the same results everywhere), and gives the task-time
distribution of the points (per-thread CPU seconds of the serial runs, robust to a loaded machine:
median, p90, max, and the cost of building the models in a fresh worker) with the speed-up it predicts for
W workers: greedy list scheduling of the measured task times in
submission order, each task charged the model build as if every task ran on a cold worker (an upper
bound on the time; a worker keeps up to 8 built models).

Run: python benchmarks/bench_sweep.py [--models QS] [--altitudes 0 9144] [--radii 5000 7000 9000 11000]
"""

from __future__ import annotations

import argparse
import datetime
import heapq
import json
import os
import statistics
import sys
import time

# measure the flexsim of this checkout (python puts benchmarks/ on sys.path, not the repository root)
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from flexsim.linear.study import run_point, run_study, turn_cases  # noqa: E402

def _run(cases, **kwargs) -> tuple[list[dict], list[float], float]:
    seconds: list[float] = []
    t0 = time.perf_counter()
    rows = run_study(cases, progress=False, on_point=lambda c, r, s: seconds.append(s), **kwargs)
    return rows, seconds, time.perf_counter() - t0


def _serial(cases, seeded: bool) -> tuple[list[dict], list[float], float]:
    """The serial run, point by point in this process (what ``run_study(workers=1)`` does, with
    ``chain_length`` None when ``seeded``, else 1): rows, per-point CPU seconds (this thread), wall."""
    rows, cpu, guess, key = [], [], None, None
    t0 = time.perf_counter()
    for case in cases:
        if case.chain_key != key:
            key, guess = case.chain_key, None
        c0 = time.thread_time()
        row, _ = run_point(case, guess if seeded else None)
        cpu.append(time.thread_time() - c0)
        guess = row.get("mach", guess)
        rows.append(row)
    return rows, cpu, time.perf_counter() - t0


def _text(rows: list[dict]) -> str:
    """Rows as JSON (NaN compares equal to NaN here)."""
    return json.dumps(rows, sort_keys=True, default=str)


def _makespan(tasks: list[float], workers: int) -> float:
    """Greedy list scheduling in submission order (each task to the first free worker)."""
    free = [0.0] * workers
    for t in tasks:
        start = heapq.heappop(free)
        heapq.heappush(free, start + t)
    return max(free)


def _percentile(values: list[float], q: float) -> float:
    s = sorted(values)
    return s[min(len(s) - 1, int(round(q * (len(s) - 1))))]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--models", nargs="+", default=["QS"])
    parser.add_argument("--altitudes", type=float, nargs="+", default=[0.0, 9144.0])
    parser.add_argument("--radii", type=float, nargs="+", default=[5000.0, 7000.0, 9000.0, 11000.0])
    args = parser.parse_args()
    from dask.distributed import LocalCluster

    cases = turn_cases("gtm", radii_m=args.radii, altitudes_m=args.altitudes, models=args.models)
    print(f"bench_sweep {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, {len(cases)} points "
          f"({', '.join(args.models)}; altitudes {args.altitudes}; radii {args.radii}), load {os.getloadavg()[0]:.1f}")
    c0 = time.thread_time()
    cases[0].analysis()
    build = time.thread_time() - c0
    whole, whole_s, whole_wall = _serial(cases, seeded=True)
    single, single_s, single_wall = _serial(cases, seeded=False)
    results = {}
    for n in (1, 2):
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            results[n] = _run(cases, scheduler=cluster.scheduler_address, chain_length=1)
    print(f"{'run':44s} {'wall [s]':>9s} {'speed-up':>9s}  rows")
    print(f"{'serial, whole chains (default)':44s} {whole_wall:9.1f} {'':>9s}  reference of the default")
    print(f"{'serial, chain_length=1':44s} {single_wall:9.1f} {1.0:9.2f}  reference of chain_length=1")
    for n, (rows, _, wall) in results.items():
        same = "identical" if _text(rows) == _text(single) else "DIFFERENT"
        print(f"{f'LocalCluster {n} worker(s), chain_length=1':44s} {wall:9.1f} {single_wall / wall:9.2f}  {same} to serial")
    diff = max(abs(a["mach"] - b["mach"]) for a, b in zip(whole, single) if "mach" in a and "mach" in b)
    print(f"largest |M_F(whole chains) - M_F(chain_length=1)| = {diff:.2e} (the seed moves the search's bracket)")
    print(f"per-point CPU time [s], serial: seeded (whole chains) median {statistics.median(whole_s):.2f}, "
          f"p90 {_percentile(whole_s, 0.9):.2f}, max {max(whole_s):.2f}; unseeded (chain_length=1) median "
          f"{statistics.median(single_s):.2f}, p90 {_percentile(single_s, 0.9):.2f}, max {max(single_s):.2f}; "
          f"model build in a fresh worker {build:.2f}")
    cold = [s + build for s in single_s]
    total = sum(cold)
    print("predicted speed-up of a W-worker cluster over one worker, chain_length=1, every task on a cold worker "
          f"(sum {total:.1f} s; bound: {len(cases)} points, the longest {max(cold):.1f} s):")
    for w in (1, 2, 4, 8, 16, 32, 64):
        span = _makespan(cold, w)
        print(f"  W = {w:3d}: makespan {span:7.1f} s, speed-up {total / span:5.2f}")
    print(f"  (whole chains stop at {len({c.chain_key for c in cases})} chains: speed-up <= "
          f"{sum(whole_s) / max(sum(whole_s[i:i + len(args.radii)]) for i in range(0, len(whole_s), len(args.radii))):.2f})")


if __name__ == "__main__":
    main()
