"""Generalized forces of applied forces and moments through virtual work (eqs. 17-24, 32).

A force f and a moment mu (component axes) applied at a point with kinematic map G(q) (virtual
displacements have the form of the velocities, eq. 18) contribute the generalized force

    Q = G(q)^T [f; mu]            (n_v,)

to the equations for V = [v, omega, s, eta]: the rows are the resultant force F (eq. 20), the resultant
moment about o (eqs. 21-22), and the generalized forces U_i, Psi_i of bending and torsion (eqs. 23-24).
Gravity (eq. 32) needs no separate map: a uniform field g_b acting on every mass element gives exactly
Q_g = M(q) [g_b; 0; ...], because G(q) [g_b; 0; ...] = [C_i g_b; 0] for every point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.aircraft.definition import Aircraft
from flexsim.structure.kinematic_map import DofIndex, PointMaps, point_maps

__all__ = ["generalized_force", "ThrustMap"]


def generalized_force(maps: PointMaps, q: np.ndarray, f: np.ndarray, mu: np.ndarray | None = None) -> np.ndarray:
    """Generalized force of forces/moments at k points (eqs. 17-24): sum_j G_j(q)^T [f_j; mu_j].

    Parameters
    ----------
    maps : PointMaps
        Kinematic maps of the k points (component axes).
    q : ndarray, shape (nq,)
        Bending coordinates [m].
    f : ndarray, shape (k, 3)
        Forces at the points' reference points, component axes [N].
    mu : ndarray, shape (k, 3), optional
        Moments about the reference points, component axes [N m].

    Returns
    -------
    ndarray, shape (n_v,)
        [F (N), M about o (N m), U (N), Psi (N m)].
    """
    g = maps.at(q)
    out = np.einsum("kai,ka->i", g[:, 0:3, :], f)
    if mu is not None:
        out += np.einsum("kai,ka->i", g[:, 3:6, :], mu)
    return out


@dataclass(frozen=True, eq=False)
class ThrustMap:
    """Generalized force of the engine thrust, Q_T = T_e (t0 + t1 q) (eqs. 17, 20-24).

    The total thrust T_e [N] is shared equally by the engines and acts along body x at each engine point
    (the paper's F_e = [T_e, 0, 0]^T).

    Attributes
    ----------
    t0 : ndarray, shape (n_v,)
    t1 : ndarray, shape (n_v, nq)
        Only the omega rows are non-zero (the moment arm changes with bending).
    """

    t0: np.ndarray
    t1: np.ndarray

    @classmethod
    def from_aircraft(cls, aircraft: Aircraft, dofs: DofIndex) -> "ThrustMap":
        """Precompute the thrust map of all engines (zero when there is none)."""
        t0 = np.zeros(dofs.n_v)
        t1 = np.zeros((dofs.n_v, dofs.nq))
        n_e = len(aircraft.engines)
        for eng in aircraft.engines:
            comp = aircraft.component(eng.component)
            x = np.clip(comp.station_of(eng.position_m), 0.0, comp.length_m)
            c = comp.dcm
            rho = c @ (eng.position_m - comp.root_m - x * comp.axes_in_body[:, 0])
            f = c @ np.array([1.0 / n_e, 0.0, 0.0])
            w = np.concatenate([f, np.cross(rho, f)])
            maps = point_maps(aircraft, dofs, comp, np.array([x]))
            t0 += maps.g0[0].T @ w
            t1[3:6, :] += np.einsum("bal,b->al", maps.g1[0], w[0:3])
        t0.setflags(write=False)
        t1.setflags(write=False)
        return cls(t0, t1)

    def force(self, thrust_n: float, q: np.ndarray) -> np.ndarray:
        """Q_T, shape (n_v,), for total thrust ``thrust_n`` [N] and bending coordinates q [m]."""
        return thrust_n * (self.t0 + self.t1 @ q)
