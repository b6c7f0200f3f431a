"""The start of an episode of the environments: the trim state randomly perturbed, and a frozen turbulence field.

All quantities SI and radians; the state layout is :class:`~flexsim.model.layout.StateLayout`'s.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.errors import positive_number
from flexsim.model.layout import StateLayout
from flexsim.sim.disturbances import DrydenTurbulence

__all__ = ["InitialPerturbation", "perturbed_state", "turbulence_field", "TURBULENCE_GRID_POINTS"]

#: Grid points of the Dryden field (1 m apart): a 16.4 km period, longer than any episode's flight path
#: (20 s at 300 m/s = 6 km) and >= 20 scale lengths at every altitude of the tasks.
TURBULENCE_GRID_POINTS = 2**14


@dataclass(frozen=True)
class InitialPerturbation:
    """Half-widths of the uniform random perturbation added to the trim state at reset.

    Attributes
    ----------
    attitude_rad : float
        Roll and pitch [rad] (default 0.01).
    heading_rad : float
        Yaw [rad] (default 0.01).
    body_rate_rad_s : float
        Each body rate p, q, r [rad/s] (default 0.005).
    airspeed_m_s : float
        Forward body velocity u [m/s] (default 1).
    altitude_m : float
        Altitude [m] (default 5).
    """

    attitude_rad: float = 0.01
    heading_rad: float = 0.01
    body_rate_rad_s: float = 0.005
    airspeed_m_s: float = 1.0
    altitude_m: float = 5.0

    def __post_init__(self) -> None:
        for name in ("attitude_rad", "heading_rad", "body_rate_rad_s", "airspeed_m_s", "altitude_m"):
            object.__setattr__(self, name, positive_number(name, getattr(self, name), allow_zero=True))


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
