"""Worker of bench_compare.py: runs one task with the flexsim found on sys.path and prints JSON.

Runs against any revision of the project since 2026-12-01 (it uses only APIs present then).
Times are per-thread CPU seconds (time.thread_time) of the task after one warm-up, median of --inner runs.
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



def _trimming():
    """The trim subpackage of the flexsim on sys.path: ``flexsim.trimming``, or ``flexsim.trim`` in revisions before
    its rename (the reference tree of a side-by-side run)."""
    import importlib

    try:
        return importlib.import_module("flexsim.trimming")
    except ImportError:
        return importlib.import_module("flexsim.trim")

def _timed(fn, inner: int) -> tuple[float, object]:
    out = fn()  # warm-up (caches, lazy imports)
    times = []
    for _ in range(inner):
        t0 = time.thread_time()
        out = fn()
        times.append(time.thread_time() - t0)
    return statistics.median(times), out


def _jacobian():
    try:
        from flexsim.model.jacobian import jacobian
    except ImportError:  # revisions before flexsim.model.jacobian
        from flexsim.linear.linearize import jacobian
    return jacobian


def main() -> None:
    task, inner = sys.argv[1], int(sys.argv[2])
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import FlutterAnalysis
    SteadyManoeuvre = _trimming().SteadyManoeuvre

    gtm = load_aircraft("gtm")
    res: dict = {"task": task}
    if task.startswith("eval-"):  # one trim + linearisation + eigen-analysis
        model = {"eval-qs": "quasi-steady", "eval-fs": "unsteady", "eval-us": "theodorsen"}[task]
        analysis = FlutterAnalysis(gtm, model)
        cases = [SteadyManoeuvre.level(h, mach=m) for h in (0.0, 9144.0) for m in (0.7433, 0.90)]
        t, out = _timed(lambda: [analysis.evaluate(c) for c in cases], inner)
        res["cpu_s"] = t / len(cases)
        res["trim_x"] = [list(map(float, p.x)) for p, _ in out]
        res["eigs"] = [[[float(m.eigenvalue.real), float(m.eigenvalue.imag)] for m in s.modes] for _, s in out]
        res["flutter_function"] = [float(s.max_real("elastic")) for _, s in out]
    elif task.startswith("point-"):
        model = {"point-qs": "quasi-steady", "point-fs": "unsteady", "point-us": "theodorsen"}[task]
        analysis = FlutterAnalysis(gtm, model)
        t, p = _timed(lambda: analysis.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95)), inner)
        res.update(cpu_s=t, mach=float(p.mach), frequency_rad_s=float(p.frequency_rad_s), evaluations=p.evaluations)
    elif task == "jacobian-fs":
        from flexsim.model.aircraft_model import AircraftModel
        trim = _trimming().trim

        qs, fs = AircraftModel(gtm, aero="quasi-steady"), AircraftModel(gtm, aero="unsteady")
        point = trim(qs, SteadyManoeuvre.level(3048.0, mach=0.7))
        x = np.concatenate([point.x, np.zeros(fs.layout.n_inflow)])
        jac = _jacobian()
        t, (a, _) = _timed(lambda: jac(fs, x, point.u), inner)
        res.update(cpu_s=t, jac_max=float(np.abs(a).max()), jac=a.ravel()[:: 97].tolist())
    elif task == "dense-eig":
        from flexsim.linear.linearize import linearize
        from flexsim.model.aircraft_model import AircraftModel
        trim = _trimming().trim

        qs, fs = AircraftModel(gtm, aero="quasi-steady"), AircraftModel(gtm, aero="unsteady")
        point = trim(qs, SteadyManoeuvre.level(0.0, mach=0.85))
        a_fs = linearize(fs, np.concatenate([point.x, np.zeros(fs.layout.n_inflow)]), point.u).a
        a_qs = linearize(qs, point.x, point.u).a
        res["cpu_s"], _ = _timed(lambda: np.linalg.eig(a_fs), max(inner, 5))
        res["eig56_cpu_s"], _ = _timed(lambda: np.linalg.eig(a_qs), max(inner, 20))
        res["n_fs"], res["n_qs"] = a_fs.shape[0], a_qs.shape[0]
    elif task == "simulate-60s":
        sys.path.insert(0, os.path.join(os.getcwd(), "benchmarks"))
        from bench_simulate import scenario
        from flexsim.sim.simulate import simulate

        sc = scenario()  # (model, point) before the wind was passed per call; (model, point, gust) since
        model, point, gust = sc if len(sc) == 3 else (*sc, None)
        method = os.environ.get("FLEXSIM_BENCH_METHOD", "auto")  # e.g. ETD2RK:0.01 (fixed step [s])
        kw = {"wind": gust} if gust is not None else {}
        if method.startswith("ETD2RK"):
            step = float(method.split(":")[1])
            try:  # simulate takes an IntegratorSettings; the older trees measured side by side take loose keywords
                from flexsim.sim.run_settings import OutputSettings  # noqa: F401  (present with the settings API)
                from flexsim.sim.simulate import IntegratorSettings
                kw.update(integrator=IntegratorSettings(method="ETD2RK", max_step_s=step))
            except ImportError:
                kw.update(method="ETD2RK", max_step=step)
        t, r = _timed(lambda: simulate(model, point, 60.0, **kw), inner)
        k = np.arange(0, r.t.size, 10)
        res.update(cpu_s=t, rtf=60.0 / t, nfev=int(r.nfev), altitude_m=r.altitude_m[k].tolist(),
                   tip_m=r.tip_deflection_m()[k].tolist(), airspeed_m_s=r.airspeed_m_s[k].tolist())
    elif task.startswith("rhs-"):  # one right-hand side of the GTM at a fixed state (per call)
        from flexsim.model.aircraft_model import AircraftModel

        aero = {"rhs-fs": "unsteady", "rhs-qs": "quasi-steady", "rhs-turb": "unsteady", "rhs-vacuum": None}[task]
        model = AircraftModel(gtm, aero=aero)
        wind = None
        if task == "rhs-turb":
            from flexsim.sim.disturbances import DrydenTurbulence

            wind = DrydenTurbulence.mil_f_8785c(3048.0, "moderate", seed=1)
        rng = np.random.default_rng(0)
        lay = model.layout
        x = 0.01 * rng.standard_normal(lay.n_states)
        x[lay.position] = [0.0, 0.0, -3048.0]
        x[lay.v] = [220.0, 1.0, 8.0]
        u = np.array([4e4, 0.01, -0.02, 0.005])
        calls = 2000

        def run():
            for _ in range(calls):
                dx = model.rhs(0.0, x, u, wind)
            return dx

        t, dx = _timed(run, inner)
        res.update(cpu_s=t / calls, dx=dx.tolist())
    else:
        raise SystemExit(f"unknown task {task!r}")
    print(json.dumps(res))


if __name__ == "__main__":
    main()
