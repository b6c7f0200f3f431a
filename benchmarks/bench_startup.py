"""Where the start-up of a process goes: import, GTM model, first right-hand side (target <= 0.3 s beyond a
numpy + scipy process), beside the floor of numba itself.

Each repeat runs fresh processes, alternating (so every import and every numba cache load is paid, and a load
change hits all three alike): one that only imports numpy and scipy (the baseline); the numba floor, which also
imports numba and calls one trivial ``@njit(cache=True)`` function (``benchmarks/_numba_floor.py``) for the first
time — numba's one-off initialisation of its compilation target plus one cache load, paid by any library that
calls a cached numba function, before any of its own work; and flexsim's, which imports numba and flexsim, builds
the unsteady GTM model and evaluates one right-hand side. The last reports its CPU time per phase and every numba
dispatcher loaded from the on-disk cache on first call (the first one also pays numba's target initialisation).
Medians over the repeats; the load average is printed (CPU time is inflated less than wall time by other jobs).
Python's bytecode cache: the figures assume ``__pycache__`` is written (PYTHONDONTWRITEBYTECODE is removed from
the children's environment; the warm-up process writes it), as after ``pip install``.

``--compare [REV]``: also runs flexsim's process from a reference revision (default main) in the same alternation (base, floor, this tree, reference), and prints both sides'
phases, flexsim's own part of each and their ratio, and whether the two give bit-identical results (SHA-256 of
the packed model data and of the first right-hand side). The reference is extracted with ``git archive`` into
``~/.cache/flexsim-bench/<revision>``; numba's cache files of this tree are copied beside it when it has none
(numba keys them on the SHA-256 of the source, so only the entries of unchanged files are used; the others are
compiled by the warm-up process, 2-5 min of CPU), or it is taken from ``--reference-tree DIR``.

``--parts``: instead, where flexsim's own part goes: fresh processes that first pay numba's floor (import numba,
first call of the trivial cached function), then time import flexsim, loading the GTM file, the vortex-lattice
solve of its lift slopes, the structural model (and, separately, its inertia polynomial once more), the rest of the
unsteady model and the first right-hand side (the lattice solution and the structural model are cached by content within a
process, so the model build reuses them); medians of --repeats processes; with --compare / --reference-tree the
reference's processes alternate with this tree's and both columns are printed.

Run: python benchmarks/bench_startup.py [--repeats 3] [--compare [REV]] [--reference-tree DIR]
     python benchmarks/bench_startup.py --parts [--repeats 5] [--compare [REV]]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

CHILD = r"""
import json, sys, time
c0 = time.process_time()
import numpy, scipy.linalg, scipy.integrate, scipy.optimize
out = {"numpy_scipy": time.process_time() - c0}
if sys.argv[1] == "floor":
    c = time.process_time()
    import numba
    out["import_numba"] = time.process_time() - c
    c = time.process_time()
    from _numba_floor import add_one
    add_one(1.0)
    out["first_call"] = time.process_time() - c
if sys.argv[1] == "full":
    c = time.process_time()
    import numba
    from numba.core.dispatcher import Dispatcher
    out["import_numba"] = time.process_time() - c
    loads = []
    original = Dispatcher._compile_for_args

    def timed(self, *args, **kwargs):
        t = time.process_time()
        result = original(self, *args, **kwargs)
        loads.append([self.py_func.__name__, time.process_time() - t])
        return result

    Dispatcher._compile_for_args = timed
    c = time.process_time()
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    out["import_flexsim"] = time.process_time() - c
    c = time.process_time()
    model = AircraftModel(load_aircraft("gtm"), aero="unsteady")
    out["model"] = time.process_time() - c
    out["model_less_loads"] = out["model"] - sum(t for _, t in loads)
    x = model.pack(position_m=[0.0, 0.0, -9144.0], velocity=numpy.r_[[230.0, 0.0, 10.0], numpy.zeros(model.structure.dofs.n_v - 3)])
    c = time.process_time()
    dx = model.rhs(0.0, x, numpy.array([40e3, 0.0, 0.0, 0.0]))
    out["first_rhs"] = time.process_time() - c
    out["loads"] = loads
    import hashlib
    out["digest"] = hashlib.sha256(model.kernel_data.F.tobytes() + model.kernel_data.I.tobytes() + dx.tobytes()).hexdigest()
out["total"] = time.process_time() - c0
print(json.dumps(out))
"""


PARTS = r"""
import json, sys, time
T = time.process_time
import numpy, scipy.linalg, scipy.integrate, scipy.optimize
import numba
from _numba_floor import add_one
add_one(1.0)
out = {}
c = T()
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.aero.lift_slopes import _incompressible_vlm
from flexsim.structure.inertia import InertiaPolynomial
from flexsim.structure.model import DofIndex, structural_model
out["import flexsim"] = T() - c
c = T(); aircraft = load_aircraft("gtm"); out["load the GTM file"] = T() - c
c = T(); _incompressible_vlm(aircraft.content_key()); out["vortex-lattice lift slopes (592 panels)"] = T() - c
c = T(); structural_model(aircraft); out["structural model"] = T() - c
c = T(); InertiaPolynomial.from_aircraft(aircraft, DofIndex.from_aircraft(aircraft)); out["  of which the inertia polynomial M0, H, M2 (again)"] = T() - c
c = T(); model = AircraftModel(aircraft, aero="unsteady"); out["rest of the unsteady model (first dcm_321 load)"] = T() - c
x = model.pack(position_m=[0.0, 0.0, -9144.0], velocity=numpy.r_[[230.0, 0.0, 10.0], numpy.zeros(model.structure.dofs.n_v - 3)])
c = T(); model.rhs(0.0, x, numpy.array([40e3, 0.0, 0.0, 0.0])); out["first right-hand side (rhs cache load)"] = T() - c
print(json.dumps(out))
"""

HERE = Path(__file__).resolve().parents[1]
from _reference import reference_tree as checkout_of  # noqa: E402  (benchmarks/_reference.py)
#: Default reference of --compare: the branch a change is compared against.
COMPARE_REFERENCE = "main"


def run(kind: str, root: Path = HERE, code: str = CHILD) -> dict:
    """One fresh process of ``kind`` (base, floor, full) with the flexsim of the checkout ``root``."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPATH"] = os.pathsep.join([str(root), str(HERE / "benchmarks"), env.get("PYTHONPATH", "")])
    done = subprocess.run([sys.executable, "-c", code, kind], capture_output=True, text=True, env=env, check=True,
                          cwd=root)
    return json.loads(done.stdout.strip().splitlines()[-1])


def parts(repeats: int, ref: Path | None) -> None:
    """--parts: flexsim's own start-up by part (module docstring); with a reference, its processes alternate with
    this tree's."""
    print(f"load average {os.getloadavg()[0]:.2f} at start; CPU seconds after numba's floor, median of {repeats} "
          "fresh processes" + ("" if ref is None else f", alternating with the reference {ref}"))
    trees = {"this": HERE} if ref is None else {"this": HERE, "reference": ref}
    for root in trees.values():
        run("parts", root, PARTS)  # warm-up
    rows = {name: [] for name in trees}
    for _ in range(repeats):
        for name, root in trees.items():
            rows[name].append(run("parts", root, PARTS))
    med = {name: {k: statistics.median(r[k] for r in rs) for k in rs[0]} for name, rs in rows.items()}
    print(f"  {'':<52} " + " ".join(f"{name:>10}" for name in trees))
    for key in med["this"]:
        print(f"  {key:<52} " + " ".join(f"{med[name][key]:10.3f}" for name in trees) + " s")
    print(f"  {'sum of the medians (without the again)':<52} "
          + " ".join(f"{sum(v for k, v in med[name].items() if not k.startswith(' ')):10.3f}" for name in trees) + " s")
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--compare", nargs="?", const=COMPARE_REFERENCE, default=None, metavar="REV",
                        help=f"also run a reference revision side by side (default {COMPARE_REFERENCE})")
    parser.add_argument("--reference-tree", type=Path, default=None, help="with --compare: a checkout to compare against")
    parser.add_argument("--parts", action="store_true", help="where flexsim's own part goes (module docstring)")
    args = parser.parse_args()
    ref = None
    if args.compare or args.reference_tree:
        ref = args.reference_tree.resolve() if args.reference_tree else checkout_of(args.compare)
    if args.parts:
        parts(args.repeats, ref)
        return
    print(f"load average {os.getloadavg()[0]:.2f} at start; CPU seconds, median of {args.repeats} fresh processes")
    run("floor"), run("full")  # warm-up: numba's on-disk caches and Python's bytecode cache written
    if ref is not None:
        run("full", ref)
    base, floor, full, full_ref = [], [], [], []
    for _ in range(args.repeats):
        base.append(run("base"))
        floor.append(run("floor"))
        full.append(run("full"))
        if ref is not None:
            full_ref.append(run("full", ref))
    med = lambda rows, key: statistics.median(r[key] for r in rows)  # noqa: E731
    print(f"numpy + scipy only process: {med(base, 'total'):.3f} s")
    print(f"numba floor (import numba + first call of a trivial cached function): {med(floor, 'total') - med(base, 'total'):.3f} s "
          f"beyond numpy + scipy (import {med(floor, 'import_numba'):.3f} s, first call {med(floor, 'first_call'):.3f} s)")
    print("flexsim:")
    for key, label in (("numpy_scipy", "import numpy + scipy"), ("import_numba", "import numba"),
                       ("import_flexsim", "import flexsim (loader, model)"), ("model", "GTM unsteady model (load + build)"),
                       ("model_less_loads", "  less numba's loads during it"), ("first_rhs", "first right-hand side"),
                       ("total", "total")):
        print(f"  {label:<36} {med(full, key):.3f} s")
    # Each process's own time beyond its numpy + scipy imports (the import of numpy + scipy scatters by more than
    # flexsim's part between processes); numba's floor: import numba (same process) + the floor processes' first call.
    first_call = med(floor, "first_call")
    beyond = lambda r: r["total"] - r["numpy_scipy"]  # noqa: E731
    own_of = lambda r: beyond(r) - r["import_numba"] - first_call  # noqa: E731
    extra, own = statistics.median(map(beyond, full)), statistics.median(map(own_of, full))
    print(f"start-up beyond numpy + scipy (each process's total less its own numpy + scipy import): {extra:.3f} s "
          f"(target <= 0.3 s), of which the numba floor {extra - own:.3f} s (import numba in the same process + the "
          f"first call above) and flexsim's own {own:.3f} s")
    if ref is not None:
        own_ref = statistics.median(map(own_of, full_ref))
        print(f"reference {ref}:")
        print(f"  {'':<36} {'this':>7} {'reference':>10}")
        for key, label in (("import_flexsim", "import flexsim (loader, model)"), ("model", "GTM unsteady model (load + build)"),
                           ("model_less_loads", "  less numba's loads during it"), ("first_rhs", "first right-hand side"),
                           ("total", "total")):
            print(f"  {label:<36} {med(full, key):7.3f} {med(full_ref, key):10.3f} s")
        print(f"  flexsim's own part: {own:.3f} s against {own_ref:.3f} s (x{own_ref / own:.2f}; start-up beyond "
              f"numpy + scipy {extra:.3f} s against {statistics.median(map(beyond, full_ref)):.3f} s)")
        phases = lambda r: r["import_flexsim"] + r["model"] + r["first_rhs"]  # noqa: E731
        this_p, ref_p = statistics.median(map(phases, full)), statistics.median(map(phases, full_ref))
        print(f"  import flexsim + model + first rhs, median per process (numba's first-call initialisation included "
              f"in both): {this_p:.3f} s against {ref_p:.3f} s, {ref_p - this_p:.3f} s less")
        same = {r["digest"] for r in full} == {r["digest"] for r in full_ref} and len({r["digest"] for r in full}) == 1
        print(f"  results (packed model data and first rhs) bit-identical to the reference: {'yes' if same else 'NO'}")
    names = [n for n, _ in full[0]["loads"]]
    print("numba dispatchers loaded from the cache on first call (the first includes numba's target initialisation):")
    for i, name in enumerate(names):
        print(f"  {name:<24} {statistics.median(r['loads'][i][1] for r in full):.3f} s")
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
