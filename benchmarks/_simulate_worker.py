"""Worker of ``bench_simulate.py --compare``: times the default ``simulate`` of the flexsim found on sys.path on the
benchmark's scenario and saves the last run's samples.

Runs against any revision with ``flexsim.sim.simulate.simulate`` and the GTM unsteady model (main since 2026-12-01).
Times are process CPU (time.process_time) and wall (perf_counter) of ``runs`` runs of ``duration`` simulated seconds
after a short warm-up run (which loads the compiled kernels). Prints JSON; writes t, x, altitude, airspeed and the
right-wing tip deflection of the last run to the .npz path given.
With a fourth argument ``log``, every timed run also writes a 50 Hz flight log (MCAP) into a temporary directory.
Usage: python _simulate_worker.py RUNS DURATION OUT.npz [log]
"""

from __future__ import annotations

import json
import os
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402



def _trimming():
    """The trim subpackage of the flexsim on sys.path: ``flexsim.trimming``, or ``flexsim.trim`` in revisions before
    its rename (the reference tree of a side-by-side run)."""
    import importlib

    try:
        return importlib.import_module("flexsim.trimming")
    except ImportError:
        return importlib.import_module("flexsim.trim")

def _log_option(path: str) -> dict:
    """The flight-log keyword of simulate in the tree measured: an OutputSettings since simulate takes settings
    objects, ``log_path`` before (the benchmarks run older trees side by side)."""
    try:
        from flexsim.sim.run_settings import OutputSettings
    except ImportError:
        return {"log_path": path}
    return {"output": OutputSettings(log_path=path)}


def scenario():
    """GTM m = n = 2, unsteady N = 6 (252 states), level trim at 9144 m and M 0.75, a 1-cos up-gust of 2 m/s and
    gradient length 30 m reached by the body origin at t = 1 s: (model, trim point, gust)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.kinematics import dcm_321
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.sim.disturbances import OneMinusCosineGust
    SteadyManoeuvre, trim = _trimming().SteadyManoeuvre, _trimming().trim

    still = AircraftModel(load_aircraft("gtm"), aero="unsteady")
    point = trim(still, SteadyManoeuvre.level(9144.0, mach=0.75))
    velocity_ned = dcm_321(*point.x[still.layout.euler]).T @ point.x[still.layout.v]
    gust = OneMinusCosineGust.encounter(2.0, 30.0, position_ned_m=point.x[still.layout.position],
                                        velocity_ned_m_s=velocity_ned, start_time_s=1.0)
    return still, point, gust


def main() -> None:
    import tempfile

    runs, duration, out = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
    log = len(sys.argv) > 4 and sys.argv[4] == "log"
    from flexsim.sim.simulate import simulate

    model, point, gust = scenario()
    simulate(model, point, 0.1, wind=gust)  # load the compiled kernels (not timed)
    cpu, wall = [], []
    for _ in range(runs):
        with tempfile.TemporaryDirectory() as tmp:
            options = _log_option(os.path.join(tmp, "bench.mcap")) if log else {}
            c0, w0 = time.process_time(), time.perf_counter()
            result = simulate(model, point, duration, wind=gust, **options)
            cpu.append(time.process_time() - c0)
            wall.append(time.perf_counter() - w0)
    np.savez(out, t=result.t, x=result.x, altitude=result.altitude_m, airspeed=result.airspeed_m_s,
             tip=result.tip_deflection_m())
    print(json.dumps({"cpu_s": cpu, "wall_s": wall, "status": result.status, "nfev": result.nfev,
                      "layout": {name: [getattr(model.layout, name).start, getattr(model.layout, name).stop]
                                 for name in ("position", "euler", "q", "xi", "v", "omega", "s", "eta", "inflow")}}))


if __name__ == "__main__":
    main()
