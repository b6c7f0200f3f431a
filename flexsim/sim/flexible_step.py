"""Fixed-step flight of the geometrically nonlinear aircraft: the Rosenbrock W-method ROS2 with a frozen Jacobian.

The state and its rate are those of :func:`flexsim.sim.flexible_run.simulate_flexible`
(``y = [X (3), quaternion (4), ε (n), v (3), ω (3), ε̇ (n)]``, the rate
:meth:`~flexsim.model.flexible_aircraft.FlexibleAircraft.free_flight_rate`, quasi-steady strips). The beams' roots reach
thousands of rad/s (1718 rad/s on the 4-element HALE), so an explicit step would be held to ~1 ms by stability; an
implicit one needs the Jacobian, which costs one right-hand side per state. ROS2 (Verwer, Spee, Blom & Hundsdorfer,
SIAM J. Sci. Comput. 20(4), 1999, §2) is linearly implicit and L-stable, and of second order for *any* matrix ``W``
in place of the Jacobian (a W-method), so ``W = I − γ h J(y_trim)`` is factored once, at the trim, and each step costs
two right-hand sides and two triangular solves::

    W k1 = f(t, y_n)
    W k2 = f(t + h, y_n + h k1) − 2 k1
    y_{n+1} = y_n + (3/2) h k1 + (1/2) h k2,        γ = 1 + 1/√2

The quaternion is normalised after each step. Accuracy against the error-controlled BDF run of
:func:`~flexsim.sim.flexible_run.simulate_flexible` (the HALE, 4 elements, a 10 m/s 1-cos gust, 1.5 s): tip
deflection within 3.2 / 1.5 / 0.77 cm at h = 20 / 10 / 5 ms (``tests/sim/test_flexible_step.py``). SI units, radians,
body axes x forward, z down.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from flexsim.errors import positive_number
from flexsim.model.flexible_aircraft import FlexibleAircraft
from flexsim.structure.free_flexible import FreeFlexibleStructure, quaternion_matrix

__all__ = ["FlexibleStepper", "GAMMA", "body_wind", "strip_wind"]

#: ROS2's diagonal coefficient, 1 + 1/√2 (L-stable; Verwer et al. 1999).
GAMMA = 1.0 + 1.0 / math.sqrt(2.0)


def body_wind(wind: Callable | None, t: float, y: NDArray) -> NDArray:
    """The wind field ``wind(t, positions_ned (1, 3)) -> (1, 3)`` (NED [m/s], :mod:`flexsim.sim.disturbances`) at the
    body origin of state ``y``, in body axes [m/s]; zeros without a wind."""
    if wind is None:
        return np.zeros(3)
    w = np.asarray(wind(t, y[None, :3]), float).reshape(3)
    return quaternion_matrix(y[3:7] / np.linalg.norm(y[3:7])).T @ w


def strip_wind(wind: Callable | None, t: float, y: NDArray) -> Callable | None:
    """The wind field ``wind(t, positions_ned (k, 3)) -> (k, 3)`` (NED [m/s], :mod:`flexsim.sim.disturbances`) at points
    of the aircraft in state ``y``: a function of body-axis positions ``p`` (k, 3) [m] returning the wind at
    ``X + C p`` (NED) in body axes, ``Cᵀ w`` (k, 3) [m/s] — each strip meets a gust where it is (the gust's penetration
    along the span and from the wing to the tail); None without a wind."""
    if wind is None:
        return None
    c = quaternion_matrix(y[3:7] / np.linalg.norm(y[3:7]))
    origin = np.asarray(y[:3], float)

    def at(points_body: NDArray) -> NDArray:
        points = np.asarray(points_body, float).reshape(-1, 3)
        return np.asarray(wind(t, origin[None, :] + points @ c.T), float).reshape(-1, 3) @ c

    return at


@dataclass(frozen=True, eq=False)
class FlexibleStepper:
    """ROS2 steps of length ``step_s`` of one aircraft at one density (module docstring).

    Attributes
    ----------
    aircraft : FlexibleAircraft
    structure : FreeFlexibleStructure
        The aircraft's structure with the flight's gravity.
    density_kg_m3 : float
    step_s : float
        h [s].
    lu : tuple
        ``scipy.linalg.lu_factor(I − γ h J)`` with ``J`` the Jacobian at the state the stepper was built about.
    """

    aircraft: FlexibleAircraft
    structure: FreeFlexibleStructure
    density_kg_m3: float
    step_s: float
    lu: tuple

    @classmethod
    def about(cls, aircraft: FlexibleAircraft, structure: FreeFlexibleStructure, y: NDArray, u: NDArray,
              density_kg_m3: float, step_s: float) -> "FlexibleStepper":
        """The stepper whose ``W`` is built from the Jacobian at state ``y`` and controls ``u`` (no wind).

        Parameters
        ----------
        step_s : float
            h [s], in (0, 0.05].
        """
        if positive_number("step_s", step_s, "s") > 0.05:
            raise ValueError(f"step_s = {step_s!r}: must be a step in (0, 0.05] s")
        jac = aircraft.free_flight_jacobian(structure, y, u, density_kg_m3, columns=slice(None))
        w = np.eye(jac.shape[0]) - GAMMA * float(step_s) * jac
        return cls(aircraft, structure, float(density_kg_m3), float(step_s), scipy.linalg.lu_factor(w))

    def rate(self, t: float, y: NDArray, u: NDArray, wind: Callable | None) -> NDArray:
        """``dy/dt`` with controls ``u`` and the wind field ``wind`` at each strip (:func:`strip_wind`)."""
        return self.aircraft.free_flight_rate(self.structure, t, y, u, self.density_kg_m3, strip_wind(wind, t, y))

    def advance(self, t: float, y: NDArray, u: NDArray, wind: Callable | None, steps: int) -> NDArray:
        """``y`` after ``steps`` steps from time ``t`` with controls ``u`` held (a new array).

        Parameters
        ----------
        t : float
            Time of ``y`` [s].
        y : ndarray, shape (7 + 2 n + 6,)
        u : ndarray, shape (4,)
            ``[T [N], δa, δe, δr [rad]]``.
        wind : callable or None
            A wind field (:func:`body_wind`).
        steps : int
        """
        h = self.step_s
        y = np.array(y, float)
        for k in range(int(steps)):
            tk = t + k * h
            k1 = scipy.linalg.lu_solve(self.lu, self.rate(tk, y, u, wind))
            k2 = scipy.linalg.lu_solve(self.lu, self.rate(tk + h, y + h * k1, u, wind) - 2.0 * k1)
            y = y + (1.5 * h) * k1 + (0.5 * h) * k2
            y[3:7] /= np.linalg.norm(y[3:7])
        return y
