"""Small array helpers shared across flexsim (no physics)."""

from __future__ import annotations

import numpy as np

__all__ = ["readonly", "frozen_array", "kernel_arg"]


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
