"""Pieces shared by the task definitions: angle wrapping; the perturbed trim states and turbulence fields of
:mod:`flexsim.sim.initial_states`, re-exported."""

from __future__ import annotations

import numpy as np

from flexsim.sim.initial_states import TURBULENCE_GRID_POINTS, perturbed_state, turbulence_field

from flexsim.envs import row_kernels as _rk

__all__ = ["perturbed_state", "turbulence_field", "wrap_angle", "TURBULENCE_GRID_POINTS"]


def wrap_angle(angle_rad):
    """``angle_rad`` wrapped to [-pi, pi] [rad] (NaN stays NaN; an infinity gives NaN): a float, or an array of
    the same shape for an array. The exact ``fmod`` by 2 pi plus one exact (Sterbenz) correction by 2 pi, the
    compiled :func:`flexsim.envs.row_kernels.wrap` (the observations' wrap too)."""
    if (type(angle_rad) is np.ndarray and angle_rad.ndim == 1 and angle_rad.dtype == np.float64
            and angle_rad.flags.c_contiguous):  # the task errors' case
        out = np.empty(angle_rad.shape[0])
        _rk.wrap_rows(angle_rad, out)
        return out
    if np.ndim(angle_rad) == 0:
        return float(_rk.wrap(float(angle_rad)))
    a = np.asarray(angle_rad, dtype=float)
    out = np.empty(a.shape)
    _rk.wrap_rows(a.reshape(-1), out.reshape(-1))
    return out
