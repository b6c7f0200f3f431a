"""Ahead-of-time compilation (``numba.pycc``) of the right-hand side: can a process start below numba's floor?

The target is <= 0.3 s of start-up per process beyond numpy + scipy; ``bench_startup.py`` shows numba's own
floor (``import numba`` plus the first call of any cached function: numba's target initialisation) is already
about 0.8 s. This benchmark measures the alternative that avoids importing numba at run time: the GTM's entry
kernel :func:`flexsim._kernels.rhs` compiled ahead of time by ``numba.pycc`` from the same source (the dispatcher's
``py_func``; the kernels it calls are compiled into it) into an extension module in a temporary directory.

0. **numba's floor** (fresh processes, alternating, medians): ``import numba`` and the first call of a trivial
   cached function (``benchmarks/_numba_floor.py``), by default and under the settings that could plausibly
   touch it (``NUMBA_OPT=0``, ``NUMBA_DISABLE_INTEL_SVML=1``), and split: the implementation modules numba 0.68
   imports at its target initialisation imported before the first call, so the rest of the first call is the
   registration of typing and lowering templates, the runtime (NRT) compilation and the cache load.
1. **Build**: one process per CPU target exports ``rhs`` with the one signature the model calls it with (packed
   data F, I read-only; the wind arrays of :data:`flexsim._kernels.NO_WIND` read-only; x, u writable), for
   pycc's default generic x86-64 target and for ``target_cpu = "host"``; CPU time of the build (Python + gcc).
   The same process tries to export two small functions taking a tuple and a NamedTuple of arrays (the argument
   types of some kernels) and reports whether each compiles and runs.
2. **Start-up** (fresh processes, alternating, medians): a numpy + scipy process (the baseline), flexsim with
   numba's JIT as today (import numba and flexsim, build the unsteady GTM model, first rhs from the on-disk
   cache), and flexsim with the AOT module and *without numba*: ``numba`` is replaced in ``sys.modules`` by a
   stand-in whose ``njit`` returns the Python function unchanged (what ``NUMBA_DISABLE_JIT=1`` does to the
   decorator; it stands for a library whose kernel decorator imports numba only when a kernel without an AOT
   build is called), ``flexsim._kernels.rhs`` is the AOT function, and the process checks that no part of numba
   was imported. Kernels the model build calls (``dcm_321``) then run as Python.
3. **Per call**: one process with both (numba imported), blocks of rhs calls alternating JIT, AOT generic, AOT
   host; median CPU time per call of the blocks, ratios, and whether the three results are bit-identical.
4. **A fastmath kernel** (revisions with ``etd2rk_run_dense``; the one step kernel that replaced it takes grouped
   arguments, which pycc cannot export, and the section then says so): the compiled steps of ``simulate``
   (``flexsim.sim._step_kernels.etd2rk_run_dense``,
   whose matrix-vector products are compiled with ``fastmath={"reassoc", "contract"}``): the arguments of its
   first call in 1 s of the README's flight are recorded, the kernel is exported with the signature the JIT
   compiled (read from the dispatcher) for both targets, and JIT, AOT generic and AOT host are timed on copies of
   those arguments (alternating calls, medians) and their outputs compared.

5. **Census** (printed first): compiled functions per file, those called by name from plain Python functions, and
   the signatures in this tree's numba cache indexes: what a complete AOT build would have to export.

The pending deprecation of ``numba.pycc`` is printed as numba states it. The temporary build directory is
removed at the end unless ``--keep DIR`` names one to build into.

Run: python benchmarks/bench_aot.py [--repeats 5] [--keep DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]

BUILD = r"""
import json, sys, time, warnings
from pathlib import Path
out, cpu = sys.argv[1], sys.argv[2]
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    from numba.pycc import CC
from numba import njit, types
from flexsim import _kernels as k
from flexsim._kernels.layout import KernelData
import re
report = {"warning": re.sub(r"\x1b\[[0-9;]*m", "", " ".join(str(caught[0].message).split())) if caught else ""}
ro = lambda dt, nd: types.Array(dt, nd, "C", readonly=True)
f1 = types.Array(types.float64, 1, "C")
sig = f1(ro(types.float64, 1), ro(types.int64, 1), ro(types.float64, 2), ro(types.float64, 2), ro(types.float64, 2), f1, f1)
name = "flexsim_aot_" + cpu
cc = CC(name)
cc.output_dir = out
if cpu == "host":
    cc.target_cpu = "host"
cc.export("rhs", sig)(k.rhs.py_func)
c = time.process_time()
cc.compile()
report["build_python_cpu"] = time.process_time() - c
if cpu == "generic":  # argument types: a tuple and a NamedTuple of arrays (one module each: a second module of
    import importlib      # the same name would not be loaded again by the same process)
    import numpy as np
    sys.path.insert(0, out)
    def total(pair):
        return pair[0].sum() + pair[1].sum()
    i1 = types.Array(types.int64, 1, "C")
    cases = (("tuple", "UniTuple of two float64 arrays", types.UniTuple(f1, 2), (np.ones(3), np.ones(2))),
             ("named", "NamedTuple KernelData(F float64, I int64)", types.NamedTuple([f1, i1], KernelData),
              KernelData(np.ones(3), np.ones(2, np.int64))))
    for tag, label, typ, arg in cases:
        try:
            t = CC("flexsim_aot_" + tag)
            t.output_dir = out
            t.export("total", types.float64(typ))(total)
            t.compile()
            mod = importlib.import_module("flexsim_aot_" + tag)
            report[label] = f"compiles and runs: {mod.total(arg)!r} (expected 5.0)"
            if tag == "tuple":  # no type check at the boundary: an int64 array where float64 was exported
                report["wrong type passed"] = (f"the float64 export called with (float64, int64) arrays returns "
                                               f"{mod.total((np.ones(3), np.ones(2, np.int64)))!r} without an error "
                                               f"(expected 5.0)")
        except Exception as exc:
            report[label] = "fails: " + type(exc).__name__ + ": " + " ".join(str(exc).split())[:160]
print(json.dumps(report))
"""

FLOOR = r"""
import json, sys, time
import numpy, scipy.linalg, scipy.integrate, scipy.optimize
c = time.process_time()
import numba
out = {"import_numba": time.process_time() - c}
c = time.process_time()
if sys.argv[1] == "split":  # the modules numba 0.68 imports at its target initialisation (core/cpu.py,
    import importlib      # core/typing/context.py: load_additional_registries), imported beforehand
    for name in ("numba.cpython.builtins", "numba.cpython.charseq", "numba.cpython.unicode", "numba.cpython.listobj",
                 "numba.cpython.setobj", "numba.cpython.hashing", "numba.np.linalg", "numba.np.arraymath",
                 "numba.np.arrayobj", "numba.np.npyimpl", "numba.np.npdatetime", "numba.np.random.generator_methods",
                 "numba.np.polynomial.polynomial_functions", "numba.typed.typeddict", "numba.typed.typedlist",
                 "numba.typed.typedset", "numba.experimental.jitclass", "numba.misc.cffiimpl",
                 "numba.core.typing.cffi_utils", "numba.core.typing.npydecl", "numba.cpython.mathimpl",
                 "numba.cpython.cmathimpl", "numba.cpython.randomimpl"):
        importlib.import_module(name)
out["imports"] = time.process_time() - c
from _numba_floor import add_one
c = time.process_time()
add_one(1.0)
out["first_call"] = time.process_time() - c
print(json.dumps(out))
"""

STARTUP = r"""
import json, sys, time
c0 = time.process_time()
import numpy, scipy.linalg, scipy.integrate, scipy.optimize
out = {"numpy_scipy": time.process_time() - c0}
kind = sys.argv[1]
if kind != "base":
    c = time.process_time()
    if kind == "jit":
        import numba
    else:  # the AOT module and no numba (module docstring)
        import types as _types
        stand_in = _types.ModuleType("numba")
        stand_in.njit = lambda *args, **kwargs: args[0] if args and callable(args[0]) else (lambda f: f)
        sys.modules["numba"] = stand_in
        sys.path.insert(0, sys.argv[2])
        import flexsim_aot_generic
    out["import_numba_or_aot"] = time.process_time() - c
    c = time.process_time()
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim import _kernels
    if kind == "aot":
        _kernels.rhs = flexsim_aot_generic.rhs
    out["import_flexsim"] = time.process_time() - c
    c = time.process_time()
    model = AircraftModel(load_aircraft("gtm"), aero="unsteady")
    out["model"] = time.process_time() - c
    x = model.pack(position_m=[0.0, 0.0, -9144.0], velocity=numpy.r_[[230.0, 0.0, 10.0], numpy.zeros(model.structure.dofs.n_v - 3)])
    c = time.process_time()
    dx = model.rhs(0.0, x, numpy.array([40e3, 0.0, 0.0, 0.0]))
    out["first_rhs"] = time.process_time() - c
    out["numba_modules"] = sorted(m for m in sys.modules if m.startswith("numba.") or m == "llvmlite")
    import hashlib
    out["digest"] = hashlib.sha256(dx.tobytes()).hexdigest()
out["total"] = time.process_time() - c0
print(json.dumps(out))
"""

PER_CALL = r"""
import json, sys, time, statistics
import numpy as np
sys.path.insert(0, sys.argv[1])
blocks, calls = int(sys.argv[2]), int(sys.argv[3])
import flexsim_aot_generic, flexsim_aot_host
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim import _kernels as k
model = AircraftModel(load_aircraft("gtm"), aero="unsteady")
rng = np.random.default_rng(0)
x = model.pack(position_m=[0.0, 0.0, -9144.0], velocity=np.r_[[230.0, 0.0, 10.0], np.zeros(model.structure.dofs.n_v - 3)])
x = x + 0.01 * rng.standard_normal(x.size) * (np.abs(x) > 0)
u = np.array([40e3, 0.01, -0.02, 0.0])
F, I = model.kernel_data
gusts, turb, grid = k.NO_WIND
kernels = {"jit": k.rhs, "aot_generic": flexsim_aot_generic.rhs, "aot_host": flexsim_aot_host.rhs}
results = {name: f(F, I, gusts, turb, grid, x, u) for name, f in kernels.items()}
times = {name: [] for name in kernels}
for _ in range(blocks):
    for name, f in kernels.items():
        c = time.process_time()
        for _ in range(calls):
            f(F, I, gusts, turb, grid, x, u)
        times[name].append((time.process_time() - c) / calls)
ref = results["jit"]
print(json.dumps({"per_call": {n: statistics.median(t) for n, t in times.items()},
                  "identical": {n: bool(np.array_equal(r, ref)) for n, r in results.items()},
                  "max_rel_diff": {n: float(np.max(np.abs(r - ref)) / np.max(np.abs(ref))) for n, r in results.items()}}))
"""


STEP = r"""
import json, sys, time, statistics, warnings, importlib
import numpy as np
out, blocks = sys.argv[1], int(sys.argv[2])
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.simulate import simulate
from flexsim.trimming import SteadyManoeuvre, trim
from flexsim.sim import _step_kernels as sk
if not hasattr(sk, "etd2rk_run_dense"):
    print(json.dumps({"skipped": "the compiled ETD2RK step of this tree (etd2rk_rows) takes grouped arguments (NamedTuples "
                      "of arrays), which numba.pycc exports (scalars and arrays) cannot take"}))
    sys.exit(0)
jit = sk.etd2rk_run_dense
captured = []
def record(*args):
    captured.append(tuple(a.copy() if isinstance(a, np.ndarray) else a for a in args))
    return jit(*args)
sk.etd2rk_run_dense = record
model = AircraftModel(load_aircraft("gtm"), aero="unsteady")
level = trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))
u = level.u.copy()
u[2] += 0.02
simulate(model, level, 1.0, controls=u)
sk.etd2rk_run_dense = jit
sig = jit.signatures[0]
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    from numba.pycc import CC
report = {"n_args": len(sig)}
kernels = {"jit": jit}
sys.path.insert(0, out)
for cpu in ("generic", "host"):
    cc = CC("flexsim_aot_step_" + cpu)
    cc.output_dir = out
    if cpu == "host":
        cc.target_cpu = "host"
    cc.export("etd2rk_run_dense", jit.overloads[sig].signature.return_type(*sig))(jit.py_func)
    c = time.process_time()
    cc.compile()
    report["build_python_cpu_" + cpu] = time.process_time() - c
    kernels["aot_" + cpu] = importlib.import_module("flexsim_aot_step_" + cpu).etd2rk_run_dense
fresh = lambda: tuple(a.copy() if isinstance(a, np.ndarray) else a for a in captured[0])
results = {}
with np.errstate(all="ignore"):
    for name, f in kernels.items():
        args = fresh()
        done = f(*args)
        results[name] = (done, args[-4:])  # ts, xs, fs, the dense means: the outputs
    times = {name: [] for name in kernels}
    for _ in range(blocks):
        for name, f in kernels.items():
            args = fresh()
            c = time.process_time()
            f(*args)
            times[name].append(time.process_time() - c)
ref_done, ref = results["jit"]
valid = (ref_done + 1, ref_done + 1, ref_done + 1, ref_done)  # rows written: times, states, derivatives, means
report["steps"] = int(ref_done)
report["per_call"] = {n: statistics.median(t) for n, t in times.items()}
report["identical"] = {n: bool(d == ref_done and all(np.array_equal(a[:k], b[:k]) for a, b, k in zip(o, ref, valid)))
                       for n, (d, o) in results.items()}
report["max_rel_diff"] = {n: max(float(np.max(np.abs(a[:k] - b[:k])) / np.max(np.abs(b[:k])))
                                 for a, b, k in zip(o, ref, valid)) for n, (d, o) in results.items()}
print(json.dumps(report))
"""


def census() -> None:
    """What an AOT build would have to export: compiled functions per file (decorated with numba's ``njit`` or
    flexsim's wrappers of it), those whose names are called inside plain Python functions of the package (an upper
    bound: a name is counted when any call uses it), and the signatures in this tree's numba cache indexes."""
    import ast
    import pickle

    def compiled(dec: ast.expr) -> bool:
        text = ast.unparse(dec)
        return any(t in text for t in ("njit", "kernel", "_jit", "_numba"))

    files = sorted(HERE.glob("flexsim/**/*.py")) + sorted(HERE.glob("envs/**/*.py"))
    trees = {f: ast.parse(f.read_text(encoding="utf-8")) for f in files}
    per_file, names = {}, set()
    for f, tree in trees.items():
        found = [n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef) and any(map(compiled, n.decorator_list))]
        if found:
            per_file[str(f.relative_to(HERE))] = len(found)
            names.update(found)
    called = set()
    for tree in trees.values():
        for fn in ast.walk(tree):
            if isinstance(fn, ast.FunctionDef) and not any(map(compiled, fn.decorator_list)):
                for call in ast.walk(fn):
                    if isinstance(call, ast.Call):
                        f = call.func
                        name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", None)
                        if name in names:
                            called.add(name)
    n_index = n_sig = 0
    for index in HERE.glob("**/__pycache__/*.nbi"):
        if "benchmarks" in index.parts:
            continue
        with open(index, "rb") as fh:
            pickle.load(fh)  # numba's version
            _, overloads = pickle.loads(fh.read())
        n_index, n_sig = n_index + 1, n_sig + len(overloads)
    print(f"census: {len(names)} compiled functions in {len(per_file)} files "
          f"({', '.join(f'{k} {v}' for k, v in per_file.items())}); {len(called)} of them called by name from plain "
          f"Python functions (upper bound); numba's cache indexes of this tree: {n_index} functions, {n_sig} signatures")


def _env(**extra: str) -> dict:
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", **extra)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env.pop("NUMBA_DISABLE_JIT", None)
    env["PYTHONPATH"] = os.pathsep.join([str(HERE), str(HERE / "benchmarks"), env.get("PYTHONPATH", "")])
    return env


def _child(code: str, *args: str, **extra: str) -> dict:
    done = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, env=_env(**extra), cwd=HERE)
    if done.returncode:
        raise RuntimeError(f"child failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeats", type=int, default=5, help="fresh processes of each kind (start-up)")
    parser.add_argument("--blocks", type=int, default=9, help="alternating blocks of rhs calls (per call)")
    parser.add_argument("--calls", type=int, default=2000, help="rhs calls per block")
    parser.add_argument("--keep", type=Path, default=None, help="build into this directory and keep it")
    args = parser.parse_args()
    import numba

    out = args.keep.resolve() if args.keep else Path(tempfile.mkdtemp(prefix="flexsim-aot-"))
    out.mkdir(parents=True, exist_ok=True)
    print(f"numba {numba.__version__}; load average {os.getloadavg()[0]:.2f} at start; building into {out}")
    census()
    try:
        floor_settings = {"default": {}, "split": {}, "NUMBA_OPT=0": {"NUMBA_OPT": "0"},
                          "NUMBA_DISABLE_INTEL_SVML=1": {"NUMBA_DISABLE_INTEL_SVML": "1"}}
        for label, extra in floor_settings.items():  # warm-up: numba's cache of the trivial function per setting
            _child(FLOOR, label, **extra)
        floor = {label: [] for label in floor_settings}
        for _ in range(args.repeats):
            for label, extra in floor_settings.items():
                floor[label].append(_child(FLOOR, label, **extra))
        print(f"numba's floor, CPU s, median of {args.repeats} fresh processes each (alternating): import numba, then the "
              "first call of a trivial cached function (numba's target initialisation + one cache load)")
        for label, rows in floor.items():
            m = {key: statistics.median(r[key] for r in rows) for key in rows[0]}
            what = ("the modules numba imports at its target initialisation imported beforehand" if label == "split"
                    else label)
            print(f"  {what:<74} import {m['import_numba']:.3f}  +imports {m['imports']:.3f}  first call "
                  f"{m['first_call']:.3f}  sum {sum(m.values()):.3f}")
        report = {}
        for cpu in ("generic", "host"):
            c, w = _children_cpu(), time.time()
            report[cpu] = _child(BUILD, str(out), cpu)
            size = sum(f.stat().st_size for f in out.glob(f"flexsim_aot_{cpu}.*"))
            print(f"build, target {cpu}: {_children_cpu() - c:.1f} s CPU (Python {report[cpu]['build_python_cpu']:.1f} s, "
                  f"the rest gcc), {time.time() - w:.1f} s wall, extension module {size / 1e6:.2f} MB")
        print(f"numba.pycc says: {report['generic']['warning'] or '(no warning)'}")
        for key, value in report["generic"].items():
            if "Tuple" in key:
                print(f"export with a {key}: {value}")
            if key == "wrong type passed":
                print(f"no type check: {value}")

        _child(STARTUP, "jit"), _child(STARTUP, "aot", str(out))  # warm-up: bytecode and numba caches written
        rows = {"base": [], "jit": [], "aot": []}
        for _ in range(args.repeats):
            rows["base"].append(_child(STARTUP, "base"))
            rows["jit"].append(_child(STARTUP, "jit"))
            rows["aot"].append(_child(STARTUP, "aot", str(out)))
        med = lambda kind, key: statistics.median(r[key] for r in rows[kind])  # noqa: E731
        base = med("base", "total")
        print(f"start-up, CPU s, median of {args.repeats} fresh processes each (alternating); numpy + scipy process "
              f"{base:.3f} s")
        print(f"  {'':<40} {'JIT (today)':>12} {'AOT, no numba':>14}")
        for key, label in (("import_numba_or_aot", "import numba / the AOT module"),
                           ("import_flexsim", "import flexsim (loader, model)"),
                           ("model", "GTM unsteady model (load + build)"), ("first_rhs", "first right-hand side")):
            print(f"  {label:<40} {med('jit', key):12.3f} {med('aot', key):14.3f}")
        for kind in ("jit", "aot"):  # each process's own time beyond its numpy + scipy imports (less noisy than the
            for r in rows[kind]:     # difference of medians of different processes, printed after it)
                r["beyond"] = r["total"] - r["numpy_scipy"]
        jit, aot = med("jit", "beyond"), med("aot", "beyond")
        print(f"  {'beyond numpy + scipy (target <= 0.3 s)':<40} {jit:12.3f} {aot:14.3f}   (x{jit / aot:.1f}; median "
              "over the processes of their total less their own numpy + scipy import)")
        print(f"  {'  the same as a difference of medians':<40} {med('jit', 'total') - base:12.3f} "
              f"{med('aot', 'total') - base:14.3f}   (total less the numpy + scipy process)")
        leaked = sorted({m for r in rows["aot"] for m in r["numba_modules"]})
        print(f"  numba modules imported by the AOT processes: {leaked or 'none'}")
        same = len({r["digest"] for k in ("jit", "aot") for r in rows[k]}) == 1
        print(f"  first rhs bit-identical between JIT and AOT processes: {'yes' if same else 'NO'}")

        per = _child(PER_CALL, str(out), str(args.blocks), str(args.calls))
        t = per["per_call"]
        print(f"per rhs call (GTM unsteady, still air), CPU us, median of {args.blocks} alternating blocks of "
              f"{args.calls} calls:")
        for name in ("jit", "aot_generic", "aot_host"):
            print(f"  {name:<12} {t[name] * 1e6:7.1f} us  x{t[name] / t['jit']:.2f} of JIT  "
                  f"bit-identical to JIT: {'yes' if per['identical'][name] else 'no'} "
                  f"(largest difference {per['max_rel_diff'][name]:.1e} of max|x_dot|)")

        step = _child(STEP, str(out), str(args.blocks))
        if "skipped" in step:
            print(f"the compiled steps of simulate: not measured, {step['skipped']}")
            print(f"load average {os.getloadavg()[0]:.2f} at the end")
            return
        t = step["per_call"]
        print(f"the compiled steps of simulate (etd2rk_run_dense, {step['n_args']} arguments, whose matrix-vector products "
              f"are compiled with fastmath reassoc+contract), one call of {step['steps']} ETD2RK steps of the GTM "
              f"(the first chunk of 1 s of the README's flight), CPU ms, median of {args.blocks} alternating calls; "
              f"build {step['build_python_cpu_generic']:.1f} s / {step['build_python_cpu_host']:.1f} s CPU in Python "
              "(generic / host):")
        for name in ("jit", "aot_generic", "aot_host"):
            print(f"  {name:<12} {t[name] * 1e3:7.2f} ms  x{t[name] / t['jit']:.2f} of JIT  "
                  f"bit-identical to JIT: {'yes' if step['identical'][name] else 'no'} "
                  f"(largest difference {step['max_rel_diff'][name]:.1e} of the largest output)")
        print(f"load average {os.getloadavg()[0]:.2f} at the end")
    finally:
        if args.keep is None:
            shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    main()
