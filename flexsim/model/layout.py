"""The state vector: a flat float64 array with a frozen layout giving named slices.

    x = [R (3), Theta (3), q (nq), xi (nxi), v (3), omega (3), s (nq), eta (nxi), lambda (n_inflow)]

R = [X, Y, Z] inertial position of the body origin o (north-east-down, altitude H = -Z) [m];
Theta = [phi, theta, psi] 3-2-1 Euler angles [rad]; q, xi bending [m] and torsion [rad] coordinates;
V = [v, omega, s, eta] the global velocity vector of eq. (9) (body axes) [m/s, rad/s, m/s, rad/s];
lambda the finite-state inflow states of every aerodynamic strip [m/s]. In a restrained model the blocks
R, Theta, v, omega are empty; in a quasi-rigid model q, xi, s, eta are empty.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

__all__ = ["StateLayout"]


@dataclass(frozen=True)
class StateLayout:
    """Named slices of the flat state vector (see module docstring).

    Attributes
    ----------
    rigid : bool
        Whether the rigid-body blocks (R, Theta, v, omega) are present.
    nq, nxi : int
        Numbers of active bending and torsion coordinates.
    n_inflow : int
        Number of aerodynamic inflow states.
    """

    rigid: bool
    nq: int
    nxi: int
    n_inflow: int = 0

    @cached_property
    def _n6(self) -> int:
        return 3 if self.rigid else 0

    @cached_property
    def position(self) -> slice:
        """R = [X, Y, Z] [m], inertial north-east-down."""
        return slice(0, self._n6)

    @cached_property
    def euler(self) -> slice:
        """[phi, theta, psi] [rad]."""
        return slice(self._n6, 2 * self._n6)

    @cached_property
    def q(self) -> slice:
        """Bending coordinates [m]."""
        a = 2 * self._n6
        return slice(a, a + self.nq)

    @cached_property
    def xi(self) -> slice:
        """Torsion coordinates [rad]."""
        a = 2 * self._n6 + self.nq
        return slice(a, a + self.nxi)

    @cached_property
    def velocity(self) -> slice:
        """The active part of V = [v, omega, s, eta] (eq. 9)."""
        a = 2 * self._n6 + self.nq + self.nxi
        return slice(a, a + 2 * self._n6 + self.nq + self.nxi)

    @cached_property
    def v(self) -> slice:
        """Body-axes velocity of o, [U, V, W] [m/s]."""
        a = self.velocity.start
        return slice(a, a + self._n6)

    @cached_property
    def omega(self) -> slice:
        """Body angular velocity [P, Q, R] [rad/s]."""
        a = self.velocity.start + self._n6
        return slice(a, a + self._n6)

    @cached_property
    def s(self) -> slice:
        """Bending rates [m/s]."""
        a = self.velocity.start + 2 * self._n6
        return slice(a, a + self.nq)

    @cached_property
    def eta(self) -> slice:
        """Torsion rates [rad/s]."""
        a = self.velocity.start + 2 * self._n6 + self.nq
        return slice(a, a + self.nxi)

    @cached_property
    def inflow(self) -> slice:
        """Finite-state inflow states [m/s]."""
        a = self.velocity.stop
        return slice(a, a + self.n_inflow)

    @cached_property
    def n_states(self) -> int:
        """Length of the state vector."""
        return self.inflow.stop

    @cached_property
    def configuration(self) -> slice:
        """Positions block [R, Theta, q, xi] (the generalized coordinates)."""
        return slice(0, self.velocity.start)

    def zeros(self) -> np.ndarray:
        """A zero state vector, shape (n_states,)."""
        return np.zeros(self.n_states)
