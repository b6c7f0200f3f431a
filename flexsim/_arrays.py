"""Small array helpers shared across flexsim (no physics)."""

from __future__ import annotations

import numpy as np

__all__ = ["readonly"]


def readonly(array: np.ndarray) -> np.ndarray:
    """Mark ``array`` read-only (frozen results and parameter bundles are immutable) and return it."""
    array.flags.writeable = False
    return array
