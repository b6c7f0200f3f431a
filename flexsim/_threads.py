"""One BLAS thread for the library's own small-matrix work, set in-process with threadpoolctl.

The model's matrices are small (30 x 30 solves, 56 x 56 complex p-k matrices, 252 x 252 Jacobians): a
second BLAS thread only spins. Measured on 2026-12-01 (``benchmarks/results/blas-threads.json``): a US flutter
point took 4.7 s CPU with OpenBLAS's default of one thread per core against 2.35 s with one thread, for the
same wall time, and much more under contention. Environment variables (``OPENBLAS_NUM_THREADS``) act only
before numpy is imported, which a library cannot rely on, so the public entry points that do numerical
work (trim, linearisation and eigen-analysis, flutter searches, simulation, env stepping) run under
:func:`single_blas_thread`: each BLAS library that threadpoolctl finds (once per process) and that is not at
one thread is set to one (``set_num_threads``) and restored on exit; nested calls pass straight through.
"""

from __future__ import annotations

import functools
import threading
from typing import Callable, TypeVar

from threadpoolctl import ThreadpoolController

__all__ = ["single_blas_thread"]

F = TypeVar("F", bound=Callable)

_state = threading.local()
_controller: list[ThreadpoolController] = []
_blas: list[list] = []


def _get_controller() -> ThreadpoolController:
    # built on first use, after numpy and scipy have loaded their BLAS libraries (inspecting them costs ~4 ms)
    if not _controller:
        _controller.append(ThreadpoolController())
    return _controller[0]


def _blas_libraries() -> list:
    """threadpoolctl's controllers of the BLAS libraries loaded in the process (found once)."""
    if not _blas:
        _blas.append([lib for lib in _get_controller().lib_controllers if lib.user_api == "blas"])
    return _blas[0]


def single_blas_thread(fn: F) -> F:
    """Decorator: run ``fn`` with every BLAS library of the process limited to one thread (module docstring).

    Only the libraries not at one thread already are set (and restored on exit): with the process at one BLAS
    thread the call costs a thread-count query per library (a few us) instead of threadpoolctl's ``limit``
    (about 10 us idle, 100 us on a loaded machine: it inspects every library on entry), which matters for
    calls made every control period (the environments' ``advance_rows``)."""

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        if getattr(_state, "depth", 0):
            return fn(*args, **kwargs)
        _state.depth = 1
        changed = []
        try:
            for lib in _blas_libraries():
                n = lib.num_threads
                if n is not None and n != 1:
                    lib.set_num_threads(1)
                    changed.append((lib, n))
            return fn(*args, **kwargs)
        finally:
            for lib, n in reversed(changed):
                lib.set_num_threads(n)
            _state.depth = 0

    return wrapper  # type: ignore[return-value]
