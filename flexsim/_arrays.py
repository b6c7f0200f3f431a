"""Small array helpers shared across flexsim (no physics)."""

from __future__ import annotations

import numpy as np

__all__ = ["readonly", "frozen_array", "kernel_arg", "group_bounds"]


def readonly(array: np.ndarray) -> np.ndarray:
    """Mark ``array`` read-only (frozen results and parameter bundles are immutable) and return it."""
    array.flags.writeable = False
    return array


def frozen_array(a, dtype=float) -> np.ndarray:
    """A C-contiguous read-only copy of ``a`` (frozen data of the compiled kernels, :mod:`flexsim._kernels`)."""
    out = np.array(a, dtype=dtype, order="C", copy=True)
    out.flags.writeable = False
    return out


def kernel_arg(a) -> np.ndarray:
    """``a`` as a writable C-contiguous float64 array (no copy when it already is one): a per-call argument of
    the compiled kernels, which are compiled for that one array type."""
    out = np.asarray(a, dtype=float)
    if not (out.flags.c_contiguous and out.flags.writeable):
        out = np.array(out, dtype=float, order="C")
    return out


def group_bounds(groups) -> tuple[int, ...]:
    """The first and end position of each group's fields in a flat argument list, 2 per group, for ``groups`` a
    sequence of NamedTuple classes in the order of the list: a compiled kernel called with the fields of its argument
    groups flat (numba types a flat argument list in its dispatcher, a tuple of arrays in Python, about 13 us more per
    call) takes them apart with these bounds, so the list and the kernel are defined by the same groups."""
    out, at = [], 0
    for g in groups:
        out += [at, at + len(g._fields)]
        at += len(g._fields)
    return tuple(out)
