"""Configuration-dependent mass matrix M(q) and the derivatives of the kinetic energy.

Source: Tuzcu & Nguyen (2014) eqs. (7)-(10), (12) and the dT/dq_i terms of eq. (33). With the kinematic
map G(q) = G0 + sum_k q_k G1_k of :mod:`flexsim.structure.kinematic_map` (only the omega columns of A
depend on q) and the section mass matrices Mbar_p of :mod:`flexsim.structure.sections`::

    T = 1/2 V^T M(q) V,   M(q) = sum_p G_p(q)^T Mbar_p G_p(q)
      = M0 + [H q in the omega columns] + [(H q)^T in the omega rows] + [q^T M2 q in the omega block]

The "inertia invariants" M0 (n_v, n_v), H (n_v, 3, nq) and M2 (3, 3, nq, nq) are computed once when the
model is built; the right-hand side then needs a few small dense contractions and no loop over sections
(the compiled kernel :func:`flexsim._kernels.inertia`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim import _kernels as _k
from flexsim._arrays import kernel_arg
from flexsim.aircraft.definition import Aircraft
from flexsim.structure.kinematic_map import DofIndex, point_maps
from flexsim.structure.sections import mass_points

__all__ = ["InertiaPolynomial"]

_W = slice(3, 6)


@dataclass(frozen=True, eq=False)
class InertiaPolynomial:
    """M(q) as a polynomial of degree 2 in the bending coordinates (eqs. 8-10).

    Attributes
    ----------
    m0 : ndarray, shape (n_v, n_v)
        Mass matrix of the undeformed aircraft [kg, kg m, kg m^2 by block].
    h : ndarray, shape (n_v, 3, nq)
        Linear coefficients: M[:, omega] += h @ q and M[omega, :] += (h @ q)^T.
    m2 : ndarray, shape (3, 3, nq, nq)
        Quadratic coefficients of the omega-omega block: M[omega, omega] += m2 : q q.
    """

    m0: np.ndarray
    h: np.ndarray
    m2: np.ndarray

    @classmethod
    def from_aircraft(cls, aircraft: Aircraft, dofs: DofIndex) -> "InertiaPolynomial":
        """Integrate the kinetic energy of every mass point (eq. 7) into M0, H and M2."""
        n_v, nq = dofs.n_v, dofs.nq
        m0 = np.zeros((n_v, n_v))
        h = np.zeros((n_v, 3, nq))
        m2 = np.zeros((3, 3, nq, nq))
        points = mass_points(aircraft)
        for name, x, mbar in zip(points.component, points.x, points.mbar):
            maps = point_maps(aircraft, dofs, aircraft.component(name), x)
            g0, g1 = maps.g0, maps.g1
            m0 += np.einsum("pai,pab,pbj->ij", g0, mbar, g0)
            # G1 lives in rows 0-2 (A) only: Mbar[:, :, 0:3] couples it.
            h += np.einsum("pai,pab,pbck->ick", g0, mbar[:, :, 0:3], g1)
            m2 += np.einsum("pbak,pbc,pcdl->adkl", g1, mbar[:, 0:3, 0:3], g1)
        m0 = 0.5 * (m0 + m0.T)
        for arr in (m0, h, m2):
            arr.setflags(write=False)
        return cls(m0, h, m2)

    def mass_matrix(self, q: np.ndarray) -> np.ndarray:
        """M(q), shape (n_v, n_v) (eqs. 8-10), for bending coordinates q (nq,) [m]."""
        return self.evaluate(np.zeros(self.m0.shape[0]), q, np.zeros_like(q))[0]

    def dT_dq(self, v: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Partial derivative of T = 1/2 V^T M(q) V with respect to q (eq. 33), shape (nq,) [N].

        Parameters
        ----------
        v : ndarray, shape (n_v,)
            Global velocity vector V.
        q : ndarray, shape (nq,)
        """
        return self.evaluate(v, q, np.zeros_like(q))[1]

    def mdot_v(self, v: np.ndarray, q: np.ndarray, s: np.ndarray) -> np.ndarray:
        """dM/dt V = sum_k s_k (dM/dq_k) V, shape (n_v,), with s = dq/dt (nq,) [m/s]."""
        return self.evaluate(v, q, s)[2]

    def evaluate(self, v: np.ndarray, q: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """M(q), dT/dq and dM/dt V in one pass sharing the contractions (the right-hand side's path).

        With m2q = M2 . q (3, 3, nq) and the symmetry M2[a, d, k, l] = M2[d, a, l, k]:
        M_oo += m2q . q;  dT/dq = V^T H_k omega + omega^T m2q[:, :, k] omega;
        (dM/dt V)_o += (m2q . s) omega + (m2q . s)^T omega.

        Returns
        -------
        m : ndarray, shape (n_v, n_v)
        dT_dq : ndarray, shape (nq,)
        mdot_v : ndarray, shape (n_v,)
        """
        return _k.inertia(self.m0, self.h, self.m2, kernel_arg(v), kernel_arg(q), kernel_arg(s))
