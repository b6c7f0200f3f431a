"""Cost of the flutter analysis on the GTM (m = n = 2): one evaluation, one flutter point, the level table.

Budgets: one flutter point (QS) <= 2 s; the whole study <= 5 min on this 2-core machine.
Prints medians over --repeats runs. ``--study`` also times the whole study of the paper's Figs. 7-16:
level turns R = 5-12 km (8 radii) and climbs gamma = -15..15 deg (7 angles) at 0, 3048, 6096, 9144 m,
QS and US (Theodorsen p-k): 120 flutter points, local processes (all cores), as ``flexsim sweep``.
``--breakdown`` splits one US evaluation (sea level, M 0.68) into its parts — trim, linearisation, the p-k
state matrix, the start eig, the p-k roots (with their iteration and full-eig counts), classification — and
times one dense eig with vectors of the 248-state finite-state system beside it (one US point
<= 0.4 s and <= 30x that eig). CPU times of this thread (time.thread_time), medians.
The US flutter point is printed with its CPU time beside one dense eig (CPU) of the same aircraft's 248-state
finite-state system at the flutter trim. ``--table`` times ``flexsim flutter`` (wall and CPU of all its processes)
of this tree beside ``--against REV`` (default main; ``git archive`` kept in ``~/.cache/flexsim-bench``, or
``--reference-tree DIR``), fresh processes alternating, medians, with the largest difference of their results.
``--loads`` prints the CPU time numba spends loading each compiled function from its cache in one worker job of
``flexsim flutter`` (paid once per process), this tree beside ``--against``; ``--study --study-against`` also runs
the reference's study in a fresh process and compares the 120 rows.
Run: python benchmarks/bench_flutter.py [--repeats 3] [--table [--against REV]] [--study [--study-against]] [--breakdown] [--loads]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
# measure the flexsim of this checkout (python puts benchmarks/ on sys.path, not the repository root)
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.linear.flutter import FlutterAnalysis  # noqa: E402
from flexsim.trimming import SteadyManoeuvre  # noqa: E402


def _median(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def _cpu_median(fn, repeats: int) -> tuple[float, object]:
    out = fn()  # warm-up
    times = []
    for _ in range(repeats):
        t0 = time.thread_time()
        out = fn()
        times.append(time.thread_time() - t0)
    return statistics.median(times), out


def breakdown(repeats: int) -> None:
    """Where one US (Theodorsen p-k) evaluation spends its time, beside one dense eig of the 248-state system."""
    import numpy as np

    from flexsim.aero.pk import pk_roots
    from flexsim.linear.linearize import linearize
    from flexsim.linear.stability import _classify, _pk, pk_state_matrix
    from flexsim.linear.symmetry import mirror_bases
    from flexsim.trimming import trim

    gtm = load_aircraft("gtm")
    an = FlutterAnalysis(gtm, "theodorsen")
    man = SteadyManoeuvre.level(0.0, mach=0.68)
    neighbour = trim(an.qs, SteadyManoeuvre.level(0.0, mach=0.63), check_limits=False)
    t_cold, point = _cpu_median(lambda: trim(an.qs, man, check_limits=False), repeats)
    t_warm, _ = _cpu_median(lambda: trim(an.qs, man, guess=neighbour, check_limits=False), repeats)
    t_lin, lin = _cpu_median(lambda: linearize(an.qs, point.x, point.u), repeats)
    t_mat, a_of = _cpu_median(lambda: pk_state_matrix(an.qs, an.fs, lin), repeats)
    t_split, _ = _cpu_median(lambda: _pk(an.qs, an.fs, lin, "inverse-iteration", True), repeats)
    t_full, _ = _cpu_median(lambda: _pk(an.qs, an.fs, lin, "inverse-iteration", False), repeats)
    vals0, vecs0 = np.linalg.eig(lin.a)
    t_cls, _ = _cpu_median(lambda: _classify(an.qs, lin, vals0, vecs0, "theodorsen"), repeats)
    counts = []
    for basis in mirror_bases(an.qs, lin.keep):
        part = a_of.projected(basis)
        vals, vecs = np.linalg.eig(part.a_qs)
        track = np.flatnonzero((vals.imag > 0.5) & (vals.real >= -20.0))
        roots = pk_roots(part, vals[track], vecs[:, track])
        counts.append((basis.shape[1], track.size, sum(r.iterations for r in roots), sum(r.full_eigs for r in roots)))
    t_eval, _ = _cpu_median(lambda: an.evaluate(man, neighbour), repeats)
    x_fs = np.concatenate([point.x, np.zeros(an.fs.layout.n_inflow)])
    a_fs = linearize(an.fs, x_fs, point.u).a
    t_dense, _ = _cpu_median(lambda: np.linalg.eig(a_fs), max(repeats, 5))
    print(f"one US evaluation, sea level, M 0.68 (CPU, median of {repeats}): {t_eval * 1e3:.1f} ms, of which")
    print(f"  trim from the M 0.63 trim {t_warm * 1e3:6.1f} ms   (cold start {t_cold * 1e3:.1f} ms)")
    print(f"  linearisation            {t_lin * 1e3:6.1f} ms   ({lin.a.shape[0]} states)")
    print(f"  p-k state matrix         {t_mat * 1e3:6.1f} ms")
    print(f"  p-k roots + classification {(t_split - t_mat) * 1e3:4.1f} ms   (classification alone {t_cls * 1e3:.1f} ms); "
          "symmetric + antisymmetric halves " + " + ".join(f"{n} states ({k} roots, {it} iterations, {f} full eigs)"
                                                         for n, k, it, f in counts))
    print(f"    reference: the full {lin.a.shape[0]}-state matrix {(t_full - t_mat) * 1e3:.1f} ms "
          f"(halves x{(t_full - t_mat) / max(t_split - t_mat, 1e-9):.2f})")
    print(f"one dense eig with vectors of the {a_fs.shape[0]}-state finite-state system: {t_dense * 1e3:.1f} ms "
          f"(30x = {30 * t_dense:.2f} s); one US evaluation = {t_eval / t_dense:.1f}x that eig")

    class Timed(FlutterAnalysis):  # the CPU time of every evaluation of one search
        def evaluate(self, *args, **kwargs):
            t0 = time.thread_time()
            out = super().evaluate(*args, **kwargs)
            self.cpu.append(time.thread_time() - t0)
            return out

    timed = Timed(gtm, "theodorsen")
    timed.cpu = []
    timed.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95))  # warm-up
    timed.cpu = []
    t0 = time.thread_time()
    timed.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95))
    total = time.thread_time() - t0
    print(f"one US flutter point, sea level (after one warm-up): {total:.3f} s CPU, its {len(timed.cpu)} evaluations "
          + ", ".join(f"{c * 1e3:.1f}" for c in timed.cpu) + " ms")


HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from _reference import reference_tree as checkout_of  # noqa: E402  (benchmarks/_reference.py)

#: Run in a fresh process by ``--loads``: numba's start-up (first compiled call), then one job of ``flexsim flutter``
#: (QS and US searches at sea level sharing their trims, :func:`flexsim.linear.study.run_points`) as a worker runs
#: it, with the CPU time numba spends loading each compiled function from its on-disk cache.
LOADS_SCRIPT = """
import time, numba.core.caching as caching
loads = {}
load = caching.Cache.load_overload
def timed(self, sig, target_context):
    t = time.thread_time()
    try:
        return load(self, sig, target_context)
    finally:
        loads[self._name] = loads.get(self._name, 0.0) + time.thread_time() - t
caching.Cache.load_overload = timed
from flexsim.atmosphere import isa
isa(0.0)
loads.clear()
from flexsim.linear.study import StudyCase, run_points
t = time.thread_time()
rows = run_points([StudyCase("gtm", "QS", 0.0), StudyCase("gtm", "US", 0.0)])
total = time.thread_time() - t
for name, sec in sorted(loads.items(), key=lambda kv: -kv[1]):
    print(f"    {sec * 1e3:6.1f} ms  {name.split(' at ')[0].replace('<function ', '')}")
print(f"  {sum(loads.values()) * 1e3:.0f} ms of cache loads in the job's {total * 1e3:.0f} ms CPU "
      f"({sum(r[0].get('evaluations', 0) for r in rows)} evaluations)")
"""


def loads(trees: dict[str, str]) -> None:
    """CPU time of numba's cache loads in one worker job of ``flexsim flutter`` (every worker pays them once), per tree."""
    for name, tree in trees.items():
        env = dict(os.environ, PYTHONPATH=tree, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
        print(f"numba cache loads of one worker job (QS + US at sea level), {name}:", flush=True)
        subprocess.run([sys.executable, "-c", LOADS_SCRIPT], cwd=tree, env=env, check=True)


TABLE_COMMAND = ["-m", "flexsim.cli.main", "flutter", "gtm", "--json"]


def _run_table(tree: str) -> tuple[float, float, dict]:
    """Wall and CPU seconds (all its processes) of ``flexsim flutter gtm --json`` run from ``tree``, and its output."""
    import json
    import resource

    env = dict(os.environ, PYTHONPATH=tree, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, *TABLE_COMMAND], cwd=tree, env=env, check=True, capture_output=True, text=True).stdout
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, json.loads(out)


def table(against: str, reference_tree: str | None, repeats: int) -> None:
    """``flexsim flutter`` (<= 5 s wall on the idle 2-core machine) of this tree beside ``against``: fresh
    processes alternating (after one untimed run of each), medians; and the largest relative difference of M_F and
    omega_F between the two outputs."""
    ref = reference_tree or str(checkout_of(against))
    label = reference_tree or against
    trees = {"this tree": HERE, label: ref}
    print(f"`flexsim flutter` (paper-replication + physical settings x 4 altitudes x QS, US = 16 searches; process start-up "
          f"and worker pool included), this tree against {label}: median of {repeats} alternating runs, "
          f"load {os.getloadavg()[0]:.1f} at the start", flush=True)
    times: dict[str, list] = {name: [] for name in trees}
    outputs = {name: _run_table(tree)[2] for name, tree in trees.items()}  # untimed: numba cache, page cache
    for r in range(repeats):
        for name in (list(trees) if r % 2 == 0 else list(trees)[::-1]):
            wall, cpu, _ = _run_table(trees[name])
            times[name].append((wall, cpu))
    for name, values in times.items():
        wall = statistics.median(w for w, _ in values)
        cpu = statistics.median(c for _, c in values)
        print(f"  {name:<16} {wall:6.2f} s wall (target <= 5 s)   {cpu:6.2f} s CPU of all its processes")
    ratio = statistics.median(w for w, _ in times["this tree"]) / statistics.median(w for w, _ in times[label])
    rows = [(a, b) for a, b in zip(outputs["this tree"]["rows"], outputs[label]["rows"])]
    diff = max((abs(a[k] - b[k]) / abs(b[k]) for a, b in rows for k in ("mach", "omega_rad_s") if k in a and k in b),
               default=float("nan"))
    print(f"  wall ratio this tree / {label}: {ratio:.2f}; largest relative difference of M_F and omega_F: {diff:.1e} "
          f"(load {os.getloadavg()[0]:.1f} at the end)")


STUDY_SCRIPT = """
import json, sys, time
from flexsim.linear.study import climb_cases, run_study, turn_cases
t0 = time.perf_counter()
rows = run_study(turn_cases("gtm") + climb_cases("gtm"), progress=False)
print(json.dumps({"wall": time.perf_counter() - t0, "rows": rows}, default=str))
"""


def study_against(against: str, reference_tree: str | None) -> None:
    """The whole study (120 points) in a fresh process of this tree and of the reference, one after the other:
    wall times and the largest relative difference of M_F and omega_F over the rows (rows in the same order)."""
    import json

    ref = reference_tree or str(checkout_of(against))
    out = {}
    for name, tree in (("this tree", HERE), (reference_tree or against, ref)):
        env = dict(os.environ, PYTHONPATH=tree, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
        done = subprocess.run([sys.executable, "-c", STUDY_SCRIPT], cwd=tree, env=env, check=True, capture_output=True, text=True)
        out[name] = json.loads(done.stdout)
        print(f"whole study, {name}: {out[name]['wall']:.1f} s wall (load {os.getloadavg()[0]:.1f})", flush=True)
    a, b = out.values()
    diff = max((abs(x[k] - y[k]) / abs(y[k]) for x, y in zip(a["rows"], b["rows"]) for k in ("mach", "omega_rad_s")
                if k in x and k in y), default=float("nan"))
    same = sum(x == y for x, y in zip(a["rows"], b["rows"]))
    print(f"  {same}/{len(a['rows'])} rows identical; largest relative difference of M_F and omega_F: {diff:.1e}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--table", action="store_true", help="also time `flexsim flutter` (2 settings x 4 altitudes x QS, US)")
    parser.add_argument("--study", action="store_true", help="also time the whole turn + climb study (120 points)")
    parser.add_argument("--breakdown", action="store_true", help="also split one US evaluation into its parts")
    parser.add_argument("--against", default="main", metavar="REV",
                        help="--table: the revision timed beside this tree (git archive, kept in ~/.cache/flexsim-bench) [main]")
    parser.add_argument("--reference-tree", metavar="DIR", help="--table: time this checkout instead of --against")
    parser.add_argument("--loads", action="store_true", help="numba's cache loads in one worker job, this tree and "
                        "--against (fresh processes)")
    parser.add_argument("--study-against", action="store_true", help="with --study: also run the study of --against "
                        "in a fresh process and compare the 120 rows")
    args = parser.parse_args()
    print(f"load average: {open('/proc/loadavg').read().split()[:3]}; {os.cpu_count()} CPUs")
    if args.breakdown:
        breakdown(args.repeats)
    if args.loads:
        label = args.reference_tree or args.against
        loads({"this tree": HERE, label: args.reference_tree or str(checkout_of(args.against))})
    gtm = load_aircraft("gtm")
    man = SteadyManoeuvre.level(0.0, mach=0.85)
    for model in ("quasi-steady", "unsteady", "theodorsen"):
        analysis = FlutterAnalysis(gtm, model)
        t = _median(lambda: analysis.evaluate(man), args.repeats)
        print(f"one trim + linearisation + eigen-analysis ({model:>12}): {t * 1e3:8.1f} ms (median of {args.repeats})")
    for model in ("quasi-steady", "unsteady", "theodorsen"):
        analysis = FlutterAnalysis(gtm, model)
        point = analysis.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95))
        t = _median(lambda: analysis.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95)), args.repeats)
        t_cpu, _ = _cpu_median(lambda: analysis.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95)), args.repeats)
        budget = "  (budget 2 s)" if model == "quasi-steady" else ""
        if model == "theodorsen":  # target: <= 0.4 s and <= 30x one dense eig of the 248-state finite-state system
            import numpy as np

            from flexsim.linear.linearize import linearize

            trim_point = point.trim
            x_fs = np.concatenate([trim_point.x, np.zeros(analysis.fs.layout.n_inflow)])
            a_fs = linearize(analysis.fs, x_fs, trim_point.u).a
            t_dense, _ = _cpu_median(lambda: np.linalg.eig(a_fs), max(args.repeats, 5))
            budget = (f"\n    CPU {t_cpu:.2f} s (target <= 0.4 s) = {t_cpu / t_dense:.0f}x one dense eig with vectors of the "
                      f"{a_fs.shape[0]}-state finite-state system, {t_dense * 1e3:.1f} ms CPU (target <= 30x)")
        print(f"one flutter point, sea level, M 0.5-0.95 grid 0.05 + Brent 1e-4 ({model:>12}): {t:6.2f} s "
              f"[M_F {point.mach:.4f}, {point.evaluations} evaluations]{budget}")
    if args.table:
        table(args.against, args.reference_tree, max(args.repeats, 3))
    if args.study:
        from flexsim.linear.study import climb_cases, run_study, turn_cases

        cases = turn_cases("gtm") + climb_cases("gtm")
        t0 = time.perf_counter()
        rows = run_study(cases, progress=False)
        elapsed = time.perf_counter() - t0
        ok = sum("mach" in r for r in rows)
        print(f"whole study (turn + climb, 4 altitudes, QS + US): {ok}/{len(rows)} flutter points in {elapsed:6.1f} s "
              f"= {elapsed / 60:.2f} min on {os.cpu_count()} cores (budget 5 min)")
        if args.study_against:
            study_against(args.against, args.reference_tree)


if __name__ == "__main__":
    main()
