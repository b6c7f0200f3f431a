"""Median CPU cost of one compiled right-hand side of the GTM, this tree against a reference revision side by side.

Four tasks, GTM m = n = 2 (30 velocities, 37 strips), from a state with every coordinate non-zero: structure +
gravity + thrust (``vacuum``, 60 states), quasi-steady strip aerodynamics (``qs``, 60 states), unsteady
aerodynamics with N = 6 finite-state inflow states per strip (``us``, 252 states) -- one call of the kernel
``flexsim._kernels.rhs`` each -- and 256 unsteady aircraft in one ``AircraftModel.rhs_batch`` call (per aircraft).
Each side runs in its own process (``benchmarks/_rhs_worker.py``), alternately (reference, this, reference, ...)
``--repeats`` times, so both see the same machine load; a process reports per-thread CPU medians after a warm-up.
The table gives the medians over the processes, the ratio reference / this and the largest difference of the
derivatives, max |dx_this - dx_ref| / max |dx_ref|.

The reference (default ``main``) is extracted with
``git archive`` into ``~/.cache/flexsim-bench/<revision>`` (kept, so that numba's cache of its kernels survives
between runs: the first run compiles them, 2-7 min of CPU), or taken from ``--reference-tree``.

Run: python benchmarks/bench_rhs.py [--reference REV | --reference-tree DIR] [--repeats 3] [--runs 7] [--calls 2000]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parents[1]
from _reference import reference_tree as checkout_of  # noqa: E402  (benchmarks/_reference.py)
WORKER = HERE / "benchmarks" / "_rhs_worker.py"


def _run(tree: Path, runs: int, calls: int) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    out = subprocess.run([sys.executable, str(WORKER), str(runs), str(calls)], cwd=tree, env=env, check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--reference", default="main", help="git revision to compare against (default main)")
    parser.add_argument("--reference-tree", type=Path, help="an existing checkout to compare against instead")
    parser.add_argument("--repeats", type=int, default=3, help="alternating process pairs")
    parser.add_argument("--runs", type=int, default=7, help="timed runs per process and task (median)")
    parser.add_argument("--calls", type=int, default=2000, help="right-hand sides per timed run")
    args = parser.parse_args()
    ref = args.reference_tree.resolve() if args.reference_tree else checkout_of(args.reference)
    print(f"load average before: {open('/proc/loadavg').read().split()[:3]}; {os.cpu_count()} CPUs; reference {ref}, "
          f"this tree {HERE}", flush=True)
    results = {"ref": [], "this": []}
    for _ in range(args.repeats):
        for side, tree in (("ref", ref), ("this", HERE)):
            results[side].append(_run(tree, args.runs, args.calls))
    print(f"{'task':<14} {'reference':>11} {'this tree':>11} {'ratio':>7}   {'fastest runs':>23} {'ratio':>6}   "
          f"max |d dx| / max |dx|")
    for task in results["ref"][0]:
        med = {s: statistics.median(r[task]["cpu_s"] for r in results[s]) for s in results}
        low = {s: min(r[task]["min_s"] for r in results[s]) for s in results}
        old, new = np.asarray(results["ref"][-1][task]["dx"]), np.asarray(results["this"][-1][task]["dx"])
        diff = np.max(np.abs(new - old)) / np.max(np.abs(old))
        print(f"{task:<14} {med['ref'] * 1e6:8.1f} us {med['this'] * 1e6:8.1f} us {med['ref'] / med['this']:6.2f}x   "
              f"{low['ref'] * 1e6:8.1f} us {low['this'] * 1e6:8.1f} us {low['ref'] / low['this']:5.2f}x   {diff:.1e}")
    print(f"(CPU per right-hand side; us-batch-256: per aircraft of one batched call. Medians of {args.repeats} processes "
          f"per side, each the median of {args.runs} runs of {args.calls} calls; 'fastest runs': the fastest run of "
          "each side, the least disturbed by other load.)")
    print(f"load average after: {open('/proc/loadavg').read().split()[:3]}")


if __name__ == "__main__":
    main()
