"""BLAS threads of a process, for the workers of vector environments (the public counterpart of the library's
in-process :func:`flexsim._threads.single_blas_thread`).

The right-hand side and Radau's LU factorisations are small dense linear algebra, which gains nothing
from BLAS threads and slows down badly when several processes each start a thread pool on the same cores
(``docs/reference/ecosystem.md`` §5: 212 ms with one thread, 0.7-1.5 s with the default). An
:class:`gymnasium.vector.AsyncVectorEnv` worker forked from a parent that already loaded OpenBLAS does not
read ``OPENBLAS_NUM_THREADS`` again, so the environments call :func:`limit_blas_threads` when they are
built inside a worker process: it sets the variables (for processes the worker starts) and limits every
BLAS library loaded in the process (numpy's and scipy's OpenBLAS, or MKL) through ``threadpoolctl``.
"""

from __future__ import annotations

import os

from threadpoolctl import threadpool_info, threadpool_limits

__all__ = ["limit_blas_threads", "blas_thread_counts"]

_ENV_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def limit_blas_threads(n: int = 1) -> list[int]:
    """Set ``OPENBLAS_NUM_THREADS``/``OMP_NUM_THREADS``/``MKL_NUM_THREADS`` to ``n`` and limit the loaded
    BLAS libraries to ``n`` threads for the rest of the process; returns their thread counts afterwards
    (empty if none was found)."""
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ValueError(f"n = {n!r}: must be an integer >= 1")
    for var in _ENV_VARS:
        os.environ[var] = str(n)
    threadpool_limits(limits=n, user_api="blas")
    return blas_thread_counts()


def blas_thread_counts() -> list[int]:
    """Thread counts of the BLAS libraries loaded in this process (``threadpoolctl.threadpool_info``)."""
    return [int(info["num_threads"]) for info in threadpool_info() if info["user_api"] == "blas"]
