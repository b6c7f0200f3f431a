"""Linearisation of the one nonlinear model about a trim (or any state).

A = d rhs / dx and B = d rhs / du by central differences of :meth:`AircraftModel.rhs`
(:func:`flexsim.model.jacobian.jacobian`: steps scaled to each state's magnitude, structured columns over
the inflow states); the same right-hand side as simulation and trim, inflow states included
(docs/reference/original-design.md §6). The states X, Y and psi do not appear in the equations and give
exact zero eigenvalues; the altitude Z enters only through the air density. For the eigen-analysis
of a steady manoeuvre they are removed (:attr:`LinearModel.reduced`), which also freezes the density at
the trim altitude, as the paper's time-invariant climbs require.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.jacobian import jacobian

__all__ = ["LinearModel", "linearize"]


@dataclass(frozen=True, eq=False)
class LinearModel:
    """x_dot = A dx + B du about (x0, u0), with the ignorable states removed.

    Attributes
    ----------
    a : ndarray, shape (m, m)
        State matrix over the kept states.
    b : ndarray, shape (m, 4)
    keep : ndarray of int, shape (m,)
        Indices of the kept states in the model's state vector (all but X, Y, Z, psi).
    x0 : ndarray, shape (n,)
    u0 : ndarray, shape (4,)
    """

    a: np.ndarray
    b: np.ndarray
    keep: np.ndarray
    x0: np.ndarray
    u0: np.ndarray

    def eig(self) -> tuple[np.ndarray, np.ndarray]:
        """Eigenvalues (m,) [1/s] and right eigenvectors (m, m) of A."""
        return np.linalg.eig(self.a)


def linearize(model: AircraftModel, x0: np.ndarray, u0: np.ndarray) -> LinearModel:
    """Linearise the model about (x0, u0), dropping X, Y, Z and psi for time invariance."""
    a, b = jacobian(model, np.asarray(x0, float), np.asarray(u0, float))
    lay = model.layout
    drop = set()
    if lay.rigid:
        drop |= set(range(lay.position.start, lay.position.stop))
        drop.add(lay.euler.start + 2)
    keep = np.array([i for i in range(lay.n_states) if i not in drop], dtype=int)
    return LinearModel(a[np.ix_(keep, keep)], b[keep], keep, np.asarray(x0, float).copy(), np.asarray(u0, float).copy())
