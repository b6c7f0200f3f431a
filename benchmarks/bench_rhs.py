"""Median cost of one right-hand-side evaluation of the GTM model.

Free-flying GTM, m = n = 2, from a state with every coordinate non-zero, three configurations:
structure + gravity + thrust (issue 2 budget <= 100 us); plus quasi-steady strip aerodynamics; plus
unsteady aerodynamics with N = 6 finite-state inflow states per strip (issue 3 budget <= 300 us).
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
    aircraft = load_aircraft("gtm").with_modes(2, 2)
    for label, aero, budget in (
        ("structure + gravity + thrust", None, 100),
        ("+ quasi-steady strip aerodynamics", "quasi-steady", None),
        ("+ unsteady aerodynamics, N = 6", "unsteady", 300),
    ):
        model = AircraftModel(aircraft, aero=aero)
        rng = np.random.default_rng(0)
        d = model.structure.dofs
        x = model.pack(
            position_m=[0, 0, -9144.0],
            euler_rad=[0.02, 0.05, 0.1],
            q=0.1 * rng.standard_normal(d.nq),
            xi=0.01 * rng.standard_normal(d.nxi),
            velocity=np.r_[[230.0, 1.0, 10.0], 0.01 * rng.standard_normal(d.n_v - 3)],
        )
        x[model.layout.inflow] = 0.1 * rng.standard_normal(model.layout.n_inflow)
        u = np.array([50e3, 0.01, -0.02, 0.005])
        for _ in range(200):
            model.rhs(0.0, x, u)
        times = []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            for _ in range(args.calls):
                model.rhs(0.0, x, u)
            times.append((time.perf_counter() - t0) / args.calls * 1e6)
        note = f"; budget {budget} us" if budget else ""
        print(f"GTM rhs, {label}: {model.layout.n_states} states")
        print(f"  median over {args.repeats} runs of {args.calls} calls: {statistics.median(times):.1f} us/call "
              f"(min {min(times):.1f}, max {max(times):.1f}){note}")


if __name__ == "__main__":
    main()
