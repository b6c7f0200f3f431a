"""The control periods of the environments alone (``flexsim.sim.periods.advance_period``), this tree against a reference.

Two cases, each timed in fresh processes alternating between the reference and this tree (so both see the same load),
the GTM with the finite-state model at 9144 m, default integrator (ETD2RK, one 20 ms step per 50 Hz period), still air:

* ``one``: one aircraft about one trim, 500 periods: CPU microseconds per period (median of 7 runs per process);
* ``mixed``: 8 aircraft about 8 different trims (230 + 5 i m/s: no shared ETD2RK stepper), 100 periods: CPU seconds
  (median of 5 runs per process), and the sum of the final states (equal in both trees when the results are).

Medians over ``--repeats`` processes per side; the load average is printed. The reference is extracted with
``git archive`` (``benchmarks/_reference.py``; default ``main``).

Run: python benchmarks/bench_periods.py [--compare REV] [--repeats 3]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(HERE, "benchmarks"))
from _reference import reference_tree  # noqa: E402

_WORKER = r'''
import json, sys, time
import numpy as np
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.periods import ActuatorRates, FlightDynamics, IntegratorSettings, advance_period, pack_period_winds
try:
    from flexsim.trimming import SteadyManoeuvre
except ImportError:
    from flexsim.trim import SteadyManoeuvre
case = sys.argv[1]
dyn = FlightDynamics(AircraftModel(load_aircraft("gtm"), aero="unsteady"), IntegratorSettings(), ActuatorRates(), 0.02)
n_rows, periods, runs = (1, 500, 7) if case == "one" else (8, 100, 5)
mans = [SteadyManoeuvre(speed_m_s=230.0 + 5.0 * i, altitude_m=9144.0) for i in range(n_rows)]
points = [dyn.trim(m) for m in mans]
states = [dyn.start(m) for m in mans]
x0, u0 = np.array([p.x for p in points]), np.array([p.u for p in points])
dyns, winds = [dyn] * n_rows, [None] * n_rows
packed = pack_period_winds(dyns, winds)

def run(n):
    x, u = x0.copy(), u0.copy()
    for k in range(n):
        r = advance_period(dyns, states, x, u, u, np.full(n_rows, k), winds, packed)
        x, u = r.outcome.x, r.u
    return x

run(5)
times = []
for _ in range(runs):
    t0 = time.thread_time()
    x = run(periods)
    times.append(time.thread_time() - t0)
print(json.dumps({"cpu_s": sorted(times)[runs // 2], "periods": periods, "state_sum": float(np.sum(x))}))
'''


def _run(tree: str, case: str) -> dict:
    env = dict(os.environ, PYTHONPATH=tree, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", _WORKER, case], cwd=tree, env=env, check=True, capture_output=True,
                         text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--compare", default="main", help="git revision to compare against (default main)")
    parser.add_argument("--repeats", type=int, default=3, help="processes per side and case")
    args = parser.parse_args()
    ref = str(reference_tree(args.compare))
    print(f"load average before: {open('/proc/loadavg').read().split()[:3]}; reference {args.compare}, this tree {HERE}")
    for case in ("one", "mixed"):
        runs: dict[str, list[dict]] = {"ref": [], "new": []}
        _run(ref, case), _run(HERE, case)  # warm-up: numba caches, bytecode
        for _ in range(args.repeats):
            runs["ref"].append(_run(ref, case))
            runs["new"].append(_run(HERE, case))
        med = {side: statistics.median(r["cpu_s"] for r in rs) for side, rs in runs.items()}
        per = 1e6 / runs["new"][0]["periods"] if case == "one" else 1.0
        unit = "us per period" if case == "one" else "s per 100 periods of 8 rows"
        same = runs["ref"][-1]["state_sum"] == runs["new"][-1]["state_sum"]
        print(f"{case:<6} ref {med['ref'] * per:9.4g}  this {med['new'] * per:9.4g} {unit}  x{med['ref'] / med['new']:.2f}  "
              f"final states' sum equal: {same}")
    print(f"load average after: {open('/proc/loadavg').read().split()[:3]}")


if __name__ == "__main__":
    main()
