"""One BLAS thread for the library's own small-matrix work, set in-process with threadpoolctl.

The model's matrices are small (30 x 30 solves, 56 x 56 complex p-k matrices, 252 x 252 Jacobians): a
second BLAS thread only spins. Measured on 2026-12-01 (docs/reference/findings/performance.md §6.10): a US flutter
point took 4.7 s CPU with OpenBLAS's default of one thread per core against 2.35 s with one thread, for the
same wall time, and much more under contention. Environment variables (``OPENBLAS_NUM_THREADS``) act only
before numpy is imported, which a library cannot rely on, so the public entry points that do numerical
work (trim, linearisation and eigen-analysis, flutter searches, simulation, env stepping) run under
:func:`single_blas_thread`: threadpoolctl's ``ThreadpoolController.limit`` (about 10 us per call with a
controller built once per process; nested calls pass straight through). The limit is restored on exit.
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


def _get_controller() -> ThreadpoolController:
    # built on first use, after numpy and scipy have loaded their BLAS libraries (inspecting them costs ~4 ms)
    if not _controller:
        _controller.append(ThreadpoolController())
    return _controller[0]


def single_blas_thread(fn: F) -> F:
    """Decorator: run ``fn`` with every BLAS library of the process limited to one thread (module docstring)."""

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        if getattr(_state, "depth", 0):
            return fn(*args, **kwargs)
        _state.depth = 1
        try:
            with _get_controller().limit(limits=1, user_api="blas"):
                return fn(*args, **kwargs)
        finally:
            _state.depth = 0

    return wrapper  # type: ignore[return-value]
