"""Median cost of one right-hand-side evaluation of the GTM model (issue 2 budget: <= 100 us).

Structure + gravity + thrust, m = n = 2, free-flying, from a state with every coordinate non-zero.
Run: python benchmarks/bench_rhs.py [--repeats 7] [--calls 2000]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.model.aircraft_model import AircraftModel  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--calls", type=int, default=2000)
    args = parser.parse_args()
    model = AircraftModel(load_aircraft("gtm").with_modes(2, 2))
    rng = np.random.default_rng(0)
    d = model.structure.dofs
    x = model.pack(
        position_m=[0, 0, -9144.0],
        euler_rad=[0.02, 0.05, 0.1],
        q=0.1 * rng.standard_normal(d.nq),
        xi=0.01 * rng.standard_normal(d.nxi),
        velocity=np.r_[[230.0, 1.0, 10.0], 0.01 * rng.standard_normal(d.n_v - 3)],
    )
    u = np.array([50e3, 0.0, 0.0, 0.0])
    for _ in range(200):
        model.rhs(0.0, x, u)
    times = []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        for _ in range(args.calls):
            model.rhs(0.0, x, u)
        times.append((time.perf_counter() - t0) / args.calls * 1e6)
    print(f"GTM rhs (structure + gravity + thrust), m = n = 2, {model.layout.n_states} states")
    print(f"  median over {args.repeats} runs of {args.calls} calls: {statistics.median(times):.1f} us/call "
          f"(min {min(times):.1f}, max {max(times):.1f}); budget 100 us")


if __name__ == "__main__":
    main()
