"""The first flutter search's compile split over two cores (first run after an install only).

A first flutter search compiles the right-hand side (``rhs_batch`` and the term kernels it calls), the aerodynamic
force and the p-k kernels: 33-35 s of CPU in one process on the 2-core machine, 2026-12-05 (``rhs_batch`` 25 s of
it, of which ``assemble`` 14 s, ``aero_evaluate`` 5.3 s, ``strip_wind_at`` 4.5 s, ``block_solve`` 1.9 s; the p-k
kernels 5.8 s; ``aerodynamic_force`` 1.9 s). numba compiles a called kernel before its caller and, for a new
signature, first looks for it in its on-disk cache; so the work splits into two groups:

* this process (:func:`compile_here`): ``aero_evaluate`` (the strips), then ``assemble`` (loading the terms below
  from the cache), then ``aerodynamic_force``, which reuses them: about 15 s;
* a second process (:func:`start`, :func:`compile_group`): first the terms ``assemble`` reaches after the strips
  (inertia, elasticity, parasite drag, slender bodies), then the other callees of ``rhs_batch`` (the wind at the
  strips, the block elimination, the inflow rate), then the p-k kernels: 20 s of CPU;

after which ``rhs_batch`` itself compiles here (about 4 s), loading the second group's kernels from the cache.
Measured side by side, an empty cache: 36-37 s wall in one process, 21-25 s split, output identical
(``docs/performance.md``, ``benchmarks/results/2026-12-05-first-run.json``). A signature below that no longer
matches a kernel (the kernel changed) only costs the other core's time: the search then compiles the kernel itself,
as without this module (tests/linear/test_precompile.py checks that every signature is one the search compiles).
The second process runs only when a core is idle: the 1-minute load average, which counts this process, below the
cores - 0.5 (on a busy machine two compiles compete for the same cores: measured at load 4-5, the first
``flexsim flutter`` took 66 and 99 s with the second process against 85, 82 and 71 s without, 48-52 s of CPU
against 40-41 s, 2026-12-04).
"""

from __future__ import annotations

import os
import subprocess
import sys

__all__ = ["start", "compile_group", "compile_here"]


def _types():
    from numba import types as t

    def arr(dtype, ndim, readonly=False):
        return t.Array(dtype, ndim, "C", readonly=readonly)

    return t, arr


def _signatures() -> list[tuple[object, tuple]]:
    """(dispatcher, argument types) of the second process's group, as ``rhs_batch`` and the search call them."""
    import importlib

    from flexsim import _kernels
    from flexsim.aero import pk
    from flexsim.linear import _pk_kernels

    t, arr = _types()
    f8, i8, c16 = t.float64, t.int64, t.complex128
    F, I = arr(f8, 1, True), arr(i8, 1, True)  # the packed model data (read-only)
    solve = importlib.import_module("flexsim._kernels.solve")  # the module: flexsim._kernels.solve is a function
    v, rho = arr(f8, 1), f8  # a state's part (q, xi, V, f) and the air density
    return [  # first what this process's assemble reaches after aero_evaluate, then the rest of rhs_batch, then p-k
        (_kernels.inertia_term, (F, I, v, v)),
        (_kernels.elastic_force, (F, I, v, v, v, v)),
        (_kernels.parasite_drag, (F, I, v, v, rho)),
        (_kernels.body_force, (F, I, v, v, rho)),
        (_kernels.strip_wind_at, (F, I, arr(f8, 2, True), arr(f8, 2, True), arr(f8, 2, True), arr(f8, 1))),
        (solve.block_solve, (arr(f8, 2), arr(f8, 1), arr(i8, 1, True), arr(i8, 1, True))),
        (_kernels.inflow_rate, (F, I, arr(f8, 2), arr(f8, 1), arr(f8, 1), arr(f8, 1), arr(f8, 1))),
        (pk._assemble, (arr(f8, 2), arr(f8, 2), arr(c16, 2), arr(c16, 1))),
        (pk._track_kernel, (arr(f8, 2), arr(f8, 2), arr(c16, 2), arr(f8, 1), c16, arr(c16, 1), i8, i8, f8)),
        (_pk_kernels.w34_jacobian, (F, arr(i8, 1, True), arr(f8, 1, True), arr(i8, 1, True), arr(f8, 1),
                                    arr(f8, 1), i8, i8, i8, arr(i8, 1), i8, i8)),
    ]


def _signatures_here() -> list[tuple[object, tuple]]:
    """(dispatcher, argument types) of this process's group, as ``rhs_batch`` and the search call them."""
    from flexsim import _kernels

    t, arr = _types()
    f8, i8 = t.float64, t.int64
    F, I = arr(f8, 1, True), arr(i8, 1, True)
    args = (F, I, arr(f8, 1), arr(f8, 1), arr(f8, 2), t.boolean)  # x, u, strip wind (n_s, 3), whether any
    v = arr(f8, 1)
    aero = (F, I, v, v, v, v, v, f8, f8, arr(f8, 2), t.boolean)  # q, xi, V, lambda, u, rho, Mach, strip wind, any
    return [(_kernels.aero_evaluate, aero), (_kernels.assemble, args), (_kernels.aerodynamic_force, args)]


def _compile(signatures) -> None:
    for dispatcher, args in signatures:
        try:
            dispatcher.compile(args)
        except Exception:  # noqa: BLE001 - a stale signature: the search compiles the kernel itself
            pass


def compile_group() -> None:
    """Compile (and so cache) the second process's group in this process; a signature numba refuses is skipped."""
    _compile(_signatures())


def compile_here() -> None:
    """Compile this process's group (while :func:`start`'s process compiles the other); a stale signature is skipped."""
    _compile(_signatures_here())


def start(parent_pid: int | None = None) -> subprocess.Popen | None:
    """A background process compiling the second group, when this machine has an idle second core and the group is
    not in numba's cache; None otherwise. It ends with this process (``PR_SET_PDEATHSIG``) and shows no progress."""
    from flexsim._numba_cache import is_cached

    cores = os.cpu_count() or 1
    if cores < 2 or os.environ.get("NUMBA_DISABLE_JIT") == "1":
        return None
    if hasattr(os, "getloadavg") and os.getloadavg()[0] > cores - 0.5:  # no idle core: a second compile only competes
        return None
    try:
        if is_cached(*(d for d, _ in _signatures())):
            return None
    except Exception:  # noqa: BLE001
        return None
    code = ("from flexsim.linear.study import end_with_parent; end_with_parent(%d); "
            "from flexsim.linear._precompile import compile_group; compile_group()") % (parent_pid or os.getpid())
    env = {**os.environ, "FLEXSIM_COMPILE_PROGRESS": "0"}
    return subprocess.Popen([sys.executable, "-c", code], env=env, stdin=subprocess.DEVNULL,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
