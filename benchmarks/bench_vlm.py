"""Median wall time of one vortex-lattice solve (``flexsim.aero.vlm.solve_vlm``) at 512 panels.

A mirrored swept wing (8 x 24 panels per half) and a swept tail (4 x 16) give 512 panels; the budget
(< 1 s, measured ~0.06 s idle) used to be a timed unit test and lives here instead (targets belong in
benchmarks, never in tests). Run: python benchmarks/bench_vlm.py [--repeats 7]
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time

# measure the flexsim of this checkout (python puts benchmarks/ on sys.path, not the repository root)
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from flexsim.aero.vlm import LiftingSurface, solve_vlm  # noqa: E402

BUDGET_S = 1.0


def swept_surface(name, root_chord, taper, semispan, sweep_le_deg, apex, n_chordwise, n_spanwise) -> LiftingSurface:
    """Mirrored straight-tapered swept surface with its root leading edge at ``apex`` [m]."""
    x0, y0, z0 = apex
    tip = [x0 + semispan * math.tan(math.radians(sweep_le_deg)), y0 + semispan, z0]
    return LiftingSurface(name, le_m=np.array([[x0, y0, z0], tip]), chord_m=np.array([root_chord, root_chord * taper]),
                          n_chordwise=n_chordwise, n_spanwise=n_spanwise, spacing="cosine", mirror=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    wing = swept_surface("wing", 2.0, 0.4, 7.0, 30.0, (0.0, 0.0, 0.0), 8, 24)
    tail = swept_surface("htail", 1.0, 0.5, 2.5, 35.0, (9.0, 0.0, 0.5), 4, 16)
    n_panels = wing.n_panels + tail.n_panels
    timings = []
    for _ in range(args.repeats):
        start = time.perf_counter()
        solve_vlm([wing, tail])
        timings.append(time.perf_counter() - start)
    median = statistics.median(timings)
    verdict = "within" if median < BUDGET_S else "OVER"
    print(f"VLM solve, {n_panels} panels: median {median * 1e3:.1f} ms over {args.repeats} "
          f"(budget {BUDGET_S:.1f} s: {verdict}, ratio {median / BUDGET_S:.3f})")


if __name__ == "__main__":
    main()
