"""BLAS threads in vector-env workers.

The right-hand side and Radau's LU factorisations are small dense linear algebra, which gains nothing
from BLAS threads and slows down badly when several processes each start a thread pool on the same cores
(``docs/reference/ecosystem.md`` §5: 212 ms with one thread, 0.7-1.5 s with the default). An
:class:`gymnasium.vector.AsyncVectorEnv` worker forked from a parent that already loaded OpenBLAS does not
read ``OPENBLAS_NUM_THREADS`` again, so the environments call :func:`limit_blas_threads` when they are
built inside a worker process: it sets the variables (for processes the worker starts) and calls
``openblas_set_num_threads`` on every OpenBLAS library loaded in the process (numpy's and scipy's).
"""

from __future__ import annotations

import ctypes
import os
from pathlib import Path

__all__ = ["limit_blas_threads", "blas_thread_counts"]

_ENV_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def _openblas_functions(kind: str) -> list:
    """``openblas_{kind}_num_threads`` functions of the OpenBLAS libraries loaded in this process (Linux)."""
    maps = Path("/proc/self/maps")
    if not maps.exists():
        return []
    paths = sorted({line.split()[-1] for line in maps.read_text().splitlines() if "openblas" in line.lower() and line.split()[-1].startswith("/")})
    found = []
    for path in paths:
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for name in (f"openblas_{kind}_num_threads", f"openblas_{kind}_num_threads64_",
                     f"scipy_openblas_{kind}_num_threads", f"scipy_openblas_{kind}_num_threads64_"):
            func = getattr(lib, name, None)
            if func is not None:
                found.append(func)
                break
    return found


def limit_blas_threads(n: int = 1) -> list[int]:
    """Set ``OPENBLAS_NUM_THREADS``/``OMP_NUM_THREADS``/``MKL_NUM_THREADS`` to ``n`` and apply it to the
    loaded OpenBLAS libraries; returns their thread counts afterwards (empty if none was found)."""
    if not isinstance(n, int) or n < 1:
        raise ValueError(f"n = {n!r}: must be an integer >= 1")
    for var in _ENV_VARS:
        os.environ[var] = str(n)
    for func in _openblas_functions("set"):
        func.argtypes = [ctypes.c_int]
        func(n)
    return blas_thread_counts()


def blas_thread_counts() -> list[int]:
    """Thread counts of the OpenBLAS libraries loaded in this process."""
    counts = []
    for func in _openblas_functions("get"):
        func.restype = ctypes.c_int
        counts.append(int(func()))
    return counts
