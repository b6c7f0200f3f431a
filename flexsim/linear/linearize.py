"""Linearisation of the one nonlinear model about a trim (or any state).

A = d rhs / dx and B = d rhs / du by central differences of :meth:`AircraftModel.rhs`
(:func:`flexsim.model.jacobian.jacobian`: steps scaled to each state's magnitude, structured columns over
the inflow states); the same right-hand side as simulation and trim, inflow states included
(docs/design.md, "Trim, linearisation, flutter, calibration"). The states X, Y and psi do not appear in the equations and give
exact zero eigenvalues; the altitude Z enters only through the air density. For the eigen-analysis
of a steady manoeuvre they are removed (:attr:`LinearModel.reduced`), which also freezes the density at
the trim altitude, as the paper's time-invariant climbs require.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.io.vocabulary import CONTROL_NAMES
from flexsim.model.aircraft_model import AircraftModel, check_model
from flexsim.model.jacobian import jacobian
from flexsim.model.naming import state_names
from flexsim.trimming.solver import TrimPoint

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
    state_names : tuple of str
        Vocabulary names of the kept states (:func:`flexsim.model.naming.state_names`), shape (m,).
    input_names : tuple of str
        Names of the inputs, :data:`flexsim.io.vocabulary.CONTROL_NAMES`.
    """

    a: np.ndarray
    b: np.ndarray
    keep: np.ndarray
    x0: np.ndarray
    u0: np.ndarray
    state_names: tuple[str, ...] = ()
    input_names: tuple[str, ...] = CONTROL_NAMES

    def eig(self) -> tuple[np.ndarray, np.ndarray]:
        """Eigenvalues (m,) [1/s] and right eigenvectors (m, m) of A."""
        return np.linalg.eig(self.a)


def linearize(model: AircraftModel, x0: TrimPoint | np.ndarray, u0: np.ndarray | None = None) -> LinearModel:
    """Linearise the model about an operating point, dropping X, Y, Z and psi for time invariance.

    Parameters
    ----------
    model : AircraftModel
    x0 : TrimPoint or ndarray, shape (n_states,)
        A trim point (which supplies its controls, as python-control's ``OperatingPoint``) or a state.
    u0 : ndarray, shape (4,), optional
        Controls [T_e (N), delta_a, delta_e, delta_r (rad)]; required with a state, not with a trim point.

    Returns
    -------
    LinearModel
        With the names of its states and inputs.
    """
    check_model(model)
    if isinstance(x0, TrimPoint):
        if u0 is not None:
            raise ValueError("u0: a TrimPoint supplies its own controls; give u0 only with a state vector")
        x0, u0 = x0.x, x0.u
    elif u0 is None:
        raise ValueError("u0: the controls (4 numbers) are required when x0 is a state vector")
    a, b = jacobian(model, np.asarray(x0, float), np.asarray(u0, float))
    lay = model.layout
    drop = set()
    if lay.rigid:
        drop |= set(range(lay.position.start, lay.position.stop))
        drop.add(lay.euler.start + 2)
    keep = np.array([i for i in range(lay.n_states) if i not in drop], dtype=int)
    names = state_names(model)
    return LinearModel(a[np.ix_(keep, keep)], b[keep], keep, np.asarray(x0, float).copy(), np.asarray(u0, float).copy(),
                       tuple(names[i] for i in keep))
