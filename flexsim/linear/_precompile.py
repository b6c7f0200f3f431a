"""The p-k kernels compiled in a second process while the first compiles the right-hand side (first run only).

A first flutter search compiles, one after the other, the right-hand side with its term kernels (``rhs_batch``:
25.5 s of 38 s of CPU in the first ``flexsim flutter`` measured on the 2-core machine, 2026-12-04) and then the p-k
kernels and the aerodynamic force (12.7 s). The second group does not depend on the first, so on a machine with a
second core :func:`start` compiles it there from the signatures below while this process compiles the first;
numba saves both to its cache, and this process loads the second group from it when the search reaches it (a
dispatcher looks in the cache before it compiles a new signature). A signature that no longer matches a kernel
(the kernel changed) only costs the other core's time: this process then compiles the kernel itself, as without
this module. It runs only when a core is idle (:func:`idle_cores`, at least 0.8 over 0.2 s): measured on the
2-core machine at load 4-5 (other jobs), the first `flexsim flutter` took 66 and 99 s with the helper against 85, 82
and 71 s without, the two compiles competing for the same busy cores (48-52 s of CPU against 40-41 s).
"""

from __future__ import annotations

import os
import subprocess
import sys

__all__ = ["start", "compile_group", "idle_cores"]


def _signatures() -> list[tuple[object, tuple]]:
    """(dispatcher, argument types) of the p-k group, as the flutter search calls them."""
    from numba import types as t

    from flexsim import _kernels
    from flexsim.aero import pk
    from flexsim.linear import _pk_kernels

    def arr(dtype, ndim, readonly=False):
        return t.Array(dtype, ndim, "C", readonly=readonly)

    f8, i8, c16 = t.float64, t.int64, t.complex128
    return [
        (pk._assemble, (arr(f8, 2), arr(f8, 2), arr(c16, 2), arr(c16, 1))),
        (pk._track_kernel, (arr(f8, 2), arr(f8, 2), arr(c16, 2), arr(f8, 1), c16, arr(c16, 1), i8, i8, f8)),
        (_pk_kernels.w34_jacobian, (arr(f8, 1, True), arr(i8, 1, True), arr(f8, 1, True), arr(i8, 1, True), arr(f8, 1),
                                    arr(f8, 1), i8, i8, i8, arr(i8, 1), i8, i8)),
        (_kernels.aerodynamic_force, (arr(f8, 1, True), arr(i8, 1, True), arr(f8, 1), arr(f8, 1), arr(f8, 2), t.boolean)),
    ]


def compile_group() -> None:
    """Compile (and so cache) the p-k group in this process; a signature numba refuses is skipped."""
    for dispatcher, args in _signatures():
        try:
            dispatcher.compile(args)
        except Exception:  # noqa: BLE001 - a stale signature: the search compiles the kernel itself
            pass


def idle_cores(window_s: float = 0.2) -> float:
    """Idle cores now: the idle share of all cores' time over ``window_s`` [s] (``/proc/stat``, Linux) times the
    number of cores; elsewhere ``cores − 1-minute load average``. Not the load average alone: right after
    ``pip install`` it still counts the install's minute of work while the machine is already idle."""
    import time

    cores = os.cpu_count() or 1

    def sample():
        with open("/proc/stat", encoding="ascii") as f:
            values = [float(v) for v in f.readline().split()[1:]]
        return values[3] + (values[4] if len(values) > 4 else 0.0), sum(values)  # idle + iowait, total

    try:
        idle0, total0 = sample()
        time.sleep(window_s)
        idle1, total1 = sample()
    except (OSError, ValueError, IndexError):
        return cores - os.getloadavg()[0] if hasattr(os, "getloadavg") else 0.0
    return cores * (idle1 - idle0) / max(total1 - total0, 1e-9)


def start(parent_pid: int | None = None) -> subprocess.Popen | None:
    """A background process compiling the p-k group, when this machine has an idle second core and the group is not
    in numba's cache; None otherwise. It ends with this process (``PR_SET_PDEATHSIG``) and shows no progress."""
    from flexsim._numba_cache import is_cached

    cores = os.cpu_count() or 1
    if cores < 2 or os.environ.get("NUMBA_DISABLE_JIT") == "1":
        return None
    if idle_cores() < 0.8:  # no idle core: a second compile only competes
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
