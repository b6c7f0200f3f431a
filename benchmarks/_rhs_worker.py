"""Worker of bench_rhs.py: times the compiled right-hand side of the flexsim found on sys.path, prints JSON.

Runs against any revision with the compiled kernels (``flexsim._kernels.rhs``, ``AircraftModel.rhs_batch``; main
since 2026-12-01 evening). Times are per-thread CPU (time.thread_time) per right-hand side: the median of
``runs`` runs of ``calls`` calls after a warm-up, and the fastest run.
Usage: python _rhs_worker.py RUNS CALLS
"""

from __future__ import annotations

import json
import os
import statistics
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

#: (task, aero model, aircraft in one batched call)
TASKS = (("vacuum", None, 1), ("qs", "quasi-steady", 1), ("us", "unsteady", 1), ("us-batch-256", "unsteady", 256))


def _state(model, seed: int) -> np.ndarray:
    """A state with every coordinate non-zero (level flight at 3,048 m, 220 m/s, perturbed)."""
    rng = np.random.default_rng(seed)
    lay = model.layout
    x = 0.01 * rng.standard_normal(lay.n_states)
    x[lay.position] = [0.0, 0.0, -3048.0]
    x[lay.v] = [220.0, 1.0, 8.0]
    return x


def main() -> None:
    runs, calls = int(sys.argv[1]), int(sys.argv[2])
    from flexsim import _kernels as k
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel

    gtm = load_aircraft("gtm")
    out = {}
    for task, aero, n in TASKS:
        model = AircraftModel(gtm, aero=aero)
        u = np.array([4e4, 0.01, -0.02, 0.005])
        if n == 1:
            x = _state(model, 0)
            args = (*model.kernel_data, *k.NO_WIND, x, u)

            def one(args=args):
                return k.rhs(*args)
        else:
            xs = np.stack([_state(model, s) for s in range(n)])
            us = np.tile(u, (n, 1))

            def one(model=model, xs=xs, us=us):
                return model.rhs_batch(0.0, xs, us)
        result = one()
        reps = max(1, calls // n)
        times = []
        for _ in range(runs):
            t0 = time.thread_time()
            for _ in range(reps):
                one()
            times.append((time.thread_time() - t0) / (reps * n))
        out[task] = {"cpu_s": statistics.median(times), "min_s": min(times), "dx": np.asarray(result).tolist()}
    print(json.dumps(out))


if __name__ == "__main__":
    main()
