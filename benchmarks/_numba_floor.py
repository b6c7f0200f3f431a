"""A trivial cached numba function: bench_startup.py times its first call in a fresh process (after ``import
numba``), i.e. what any numba-compiled library pays before its own code: numba's target initialisation and one
load from the on-disk cache."""

from numba import njit


@njit(cache=True)
def add_one(x: float) -> float:
    """x + 1 (nothing to compute: only the dispatch and cache load are timed)."""
    return x + 1.0
