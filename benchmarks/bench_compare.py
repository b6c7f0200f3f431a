"""This tree against a reference revision, side by side in one run: CPU time, ratios and result differences.

For every task the worker (``benchmarks/_compare_worker.py``) runs in a fresh process on the reference tree
and on this tree, alternately (reference, this, reference, this, ...) ``--repeats`` times, so both see the
same machine load; each process reports the median per-thread CPU time of ``--inner`` runs after a warm-up.
The table gives the medians over the repeats, the ratio reference / this, and the largest relative
difference of the results (trim states, eigenvalues, flutter Mach and frequency, Jacobian entries,
simulated altitude and tip deflection). ``flexsim flutter`` and the whole turn + climb study (``study``) are timed as whole
commands (wall and CPU of the process tree), with their flutter points compared. The load average is printed before and after. The reference tree is extracted with
``git archive`` (default: main, the branch a change is compared against; any revision since 2026-12-01 works).

Also: one right-hand side per call (unsteady, quasi-steady, with Dryden turbulence, vacuum) and
the start-up of a process to its first right-hand side (with numba: the machine code loaded from the cache).

Targets: start-up <= 0.3 s per process; one US flutter point <= 0.4 s and <= 30x one dense eig of the same system (248 states);
``flexsim flutter`` <= 5 s; the whole study <= 30 s on 2 cores; 60 s of simulated flight >= 100x real time.

Run: python benchmarks/bench_compare.py [--reference REV] [--repeats 3] [--inner 1] [--tasks a,b,...]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORKER = os.path.join(HERE, "benchmarks", "_compare_worker.py")
TASKS = ("rhs-fs", "rhs-qs", "rhs-turb", "rhs-vacuum", "startup", "eval-qs", "eval-fs", "eval-us", "point-qs", "point-fs", "point-us", "jacobian-fs", "dense-eig",
         "flutter-cli", "study", "simulate-60s")
TARGETS = {"startup": "<= 0.3 s", "point-us": "<= 0.4 s", "flutter-cli": "<= 5 s", "study": "<= 30 s wall",
           "simulate-60s": ">= 100x real time"}
#: The whole turn + climb study of the paper's Figs. 7-16 (120 points, QS and US, 4 altitudes, local processes on
#: all cores), as ``flexsim sweep --turn`` and ``--climb`` run it; prints the rows' flutter Mach numbers as JSON.
_STUDY = ("import json; from flexsim.linear.study import climb_cases, run_study, turn_cases; "
          "rows = run_study(turn_cases('gtm') + climb_cases('gtm'), progress=False); "
          "print(json.dumps([[r.get('mach'), r.get('omega_rad_s'), r.get('evaluations')] for r in rows]))")


def _env(tree: str) -> dict:
    env = dict(os.environ, PYTHONPATH=tree, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    return env


def _run_worker(tree: str, task: str, inner: int) -> dict:
    if task == "startup":  # a fresh process: import, build the GTM model, first rhs (numba: machine code from the cache)
        code = ("import numpy as np; from flexsim.aircraft.toml_loader import load_aircraft; "
                "from flexsim.model.aircraft_model import AircraftModel; m = AircraftModel(load_aircraft('gtm')); "
                "x = m.layout.zeros(); x[2] = -3000.0; x[m.layout.v.start] = 200.0; m.rhs(0.0, x, np.zeros(4))")
        base = "import numpy, scipy.linalg, scipy.integrate"
        out = {}
        for key, src in (("all", code), ("base", base)):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-c", src], cwd=tree, env=_env(tree), check=True, capture_output=True)
            wall = time.perf_counter() - t0
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            out[key] = ((after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall)
        # the project's share: the whole process less a process importing numpy and scipy only
        return {"cpu_s": out["all"][0] - out["base"][0], "wall_s": out["all"][1] - out["base"][1]}
    if task in ("flutter-cli", "study"):
        cmd = ["-m", "flexsim.cli.main", "flutter", "gtm", "--json"] if task == "flutter-cli" else ["-c", _STUDY]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, *cmd], cwd=tree, env=_env(tree), check=True, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        res = {"cpu_s": cpu, "wall_s": wall}
        if task == "flutter-cli":
            res["rows"] = [[r.get("mach"), r.get("omega_rad_s"), r.get("evaluations")] for r in json.loads(out.stdout)["rows"]]
        else:
            res["rows"] = json.loads(out.stdout.strip().splitlines()[-1])
        return res
    out = subprocess.run([sys.executable, WORKER, task, str(inner)], cwd=tree, env=_env(tree), check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _rel(a, b) -> float:
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape:
        return float("nan")
    scale = np.maximum(np.abs(a), 1e-300)
    return float(np.max(np.abs(a - b) / scale)) if a.size else 0.0


def _rows_difference(old: list, new: list) -> str:
    """Largest relative difference of the flutter Mach numbers and frequencies of two runs' rows, and evaluations."""
    pairs = [(a, b) for a, b in zip(old, new) if a[0] is not None and b[0] is not None]
    dm = max((abs(a[0] - b[0]) / abs(a[0]) for a, b in pairs), default=float("nan"))
    dw = max((abs(a[1] - b[1]) / abs(a[1]) for a, b in pairs), default=float("nan"))
    missing = sum((a[0] is None) != (b[0] is None) for a, b in zip(old, new)) + abs(len(old) - len(new))
    ev = (sum(a[2] or 0 for a in old), sum(b[2] or 0 for b in new))
    return f"{len(pairs)} points: M_F {dm:.1e}, omega_F {dw:.1e}, {missing} found by one run only; evaluations {ev[0]} -> {ev[1]}"


def _difference(task: str, old: dict, new: dict) -> str:
    if task.startswith("rhs-"):
        d = np.max(np.abs(np.subtract(old["dx"], new["dx"]))) / np.max(np.abs(old["dx"]))
        return f"per call; rhs max |d dx| / max |dx| = {d:.1e}"
    if task == "startup":
        return "import + model + first rhs, less a numpy/scipy-only process"
    if task.startswith("eval-"):
        dx = max(_rel(a, b) / 1.0 for a, b in zip(old["trim_x"], new["trim_x"]))
        de, missing = 0.0, 0
        for ea, eb in zip(old["eigs"], new["eigs"]):
            za = np.array([complex(*e) for e in ea])
            zb = np.array([complex(*e) for e in eb])
            d = np.abs(za[:, None] - zb[None, :]).min(axis=1) / np.maximum(np.abs(za), 1e-300)
            de = max(de, float(np.max(d[d < 1e-6])) if np.any(d < 1e-6) else 0.0)
            missing += int(np.sum(np.abs(zb[:, None] - za[None, :]).min(axis=1) >= 1e-6 * np.maximum(np.abs(zb), 1e-300)))
        dg = _rel(old["flutter_function"], new["flutter_function"])
        return f"trim x {dx:.1e}, eigenvalues {de:.1e} (+{missing} roots new), max Re(elastic) {dg:.1e}"
    if task.startswith("point-"):
        return (f"M_F {_rel(old['mach'], new['mach']):.1e} ({new['mach']:.6f}), omega_F "
                f"{_rel(old['frequency_rad_s'], new['frequency_rad_s']):.1e}, evaluations {old['evaluations']}/{new['evaluations']}")
    if task == "jacobian-fs":
        d = np.max(np.abs(np.array(old["jac"]) - np.array(new["jac"]))) / old["jac_max"]
        return f"max |dJ| / max |J| {d:.1e} (sampled entries)"
    if task == "simulate-60s":
        return (f"altitude {np.max(np.abs(np.subtract(old['altitude_m'], new['altitude_m']))):.1e} m, tip "
                f"{np.max(np.abs(np.subtract(old['tip_m'], new['tip_m']))):.1e} m; RTF {old['rtf']:.1f} -> {new['rtf']:.1f}")
    return ""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--reference", default="main", help="git revision to compare against (default main)")
    parser.add_argument("--repeats", type=int, default=3, help="alternating process pairs per task")
    parser.add_argument("--inner", type=int, default=1, help="timed runs per process (after one warm-up)")
    parser.add_argument("--tasks", default=",".join(TASKS), help=f"comma-separated subset of {', '.join(TASKS)}")
    args = parser.parse_args()
    tasks = [t for t in args.tasks.split(",") if t]
    unknown = sorted(set(tasks) - set(TASKS))
    if unknown:
        parser.error(f"--tasks: unknown {', '.join(unknown)}; choose from {', '.join(TASKS)}")
    print(f"load average before: {open('/proc/loadavg').read().split()[:3]}; {os.cpu_count()} CPUs; "
          f"reference {args.reference}, this tree {HERE}")
    with tempfile.TemporaryDirectory() as ref_tree:
        archive = subprocess.run(["git", "-C", HERE, "archive", args.reference], check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", ref_tree], input=archive, check=True)
        rows = []
        eig = None
        for task in tasks:
            runs = {"ref": [], "new": []}
            for _ in range(args.repeats):
                for side, tree in (("ref", ref_tree), ("new", HERE)):
                    runs[side].append(_run_worker(tree, task, args.inner))
            med = {s: statistics.median(r["cpu_s"] for r in runs[s]) for s in runs}
            extra = ""
            if task in ("flutter-cli", "study", "startup"):
                walls = {s: statistics.median(r["wall_s"] for r in runs[s]) for s in runs}
                extra = f"wall {walls['ref']:.2f} -> {walls['new']:.2f} s (x{walls['ref'] / walls['new']:.2f}); CPU of the process tree"
                if task != "startup":
                    extra += "; " + _rows_difference(runs["ref"][-1]["rows"], runs["new"][-1]["rows"])
            elif task == "dense-eig":
                eig = statistics.median(r["cpu_s"] for r in runs["new"] + runs["ref"])
                e56 = statistics.median(r["eig56_cpu_s"] for r in runs["new"] + runs["ref"])
                extra = f"one dense eig: {eig * 1e3:.1f} ms at {runs['new'][0]['n_fs']} states, {e56 * 1e3:.2f} ms at {runs['new'][0]['n_qs']}"
            else:
                extra = _difference(task, runs["ref"][-1], runs["new"][-1])
            rows.append((task, med["ref"], med["new"], extra))
            if task.startswith("rhs-"):
                print(f"{task:<13} ref {med['ref'] * 1e6:8.1f} us  this {med['new'] * 1e6:8.1f} us  x{med['ref'] / med['new']:5.2f}   "
                      f"{extra}", flush=True)
                continue
            print(f"{task:<13} ref {med['ref']:8.3f} s   this {med['new']:8.3f} s   x{med['ref'] / med['new']:5.2f}   "
                  f"{TARGETS.get(task, '')}   {extra}", flush=True)
        if eig is not None:
            for task, _, new, _ in rows:
                if task in ("eval-us", "point-us", "point-fs", "eval-fs"):
                    print(f"{task}: {new / eig:.1f}x one dense eig of the 248-state system (target for point-us: <= 30x)")
    print(f"load average after: {open('/proc/loadavg').read().split()[:3]}")


if __name__ == "__main__":
    main()
