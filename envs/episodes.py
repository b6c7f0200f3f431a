"""Pieces shared by the task definitions: perturbed trim states, turbulence fields, angle wrapping."""

from __future__ import annotations

import numpy as np

from flexsim.model.layout import StateLayout
from flexsim.sim.disturbances import DrydenTurbulence

from flexsim.envs import row_kernels as _rk
from flexsim.envs.config import InitialPerturbation

__all__ = ["perturbed_state", "turbulence_field", "wrap_angle", "TURBULENCE_GRID_POINTS"]

#: Grid points of the Dryden field (1 m apart): a 16.4 km period, longer than any episode's flight path
#: (20 s at 300 m/s = 6 km) and >= 20 scale lengths at every altitude of the tasks.
TURBULENCE_GRID_POINTS = 2**14


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




def perturbed_state(x_trim: np.ndarray, layout: StateLayout, rng: np.random.Generator, pert: InitialPerturbation) -> np.ndarray:
    """The trim state plus uniform random perturbations (half-widths from ``pert``), drawn in a fixed order:
    roll and pitch, heading, body rates p q r, forward speed, altitude."""
    x = np.array(x_trim, dtype=float)
    eul = layout.euler.start
    x[eul : eul + 2] += rng.uniform(-pert.attitude_rad, pert.attitude_rad, 2)
    x[eul + 2] += rng.uniform(-pert.heading_rad, pert.heading_rad)
    x[layout.omega] += rng.uniform(-pert.body_rate_rad_s, pert.body_rate_rad_s, 3)
    x[layout.v.start] += rng.uniform(-pert.airspeed_m_s, pert.airspeed_m_s)
    x[layout.position.start + 2] -= rng.uniform(-pert.altitude_m, pert.altitude_m)
    return x


def turbulence_field(level: str, altitude_m: float, origin_ned_m: np.ndarray, heading_rad: float,
                     rng: np.random.Generator) -> DrydenTurbulence | None:
    """Dryden turbulence of MIL-F-8785C at ``level`` ("none" gives None), seeded from ``rng``, frozen along
    the straight line through ``origin_ned_m`` at ``heading_rad``."""
    if level == "none":
        return None
    seed = int(rng.integers(0, 2**31 - 1))
    return DrydenTurbulence.mil_f_8785c(altitude_m, level, seed=seed, heading_rad=heading_rad, origin_ned_m=np.asarray(origin_ned_m, float),
                                        n_points=TURBULENCE_GRID_POINTS)
