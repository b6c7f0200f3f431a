"""The structural model of the whole aircraft, built once from its definition.

Bundles, for the equations of motion (eq. 33): the index of elastic coordinates, the inertia polynomial
M(q) (eqs. 7-10), the stiffness matrices (eqs. 14-16) and the thrust map (eqs. 17-24). Everything here
is precomputed at construction; nothing is mutated afterwards.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from flexsim.aircraft.definition import Aircraft
from flexsim.structure.inertia import InertiaPolynomial
from flexsim.structure.kinematic_map import DofIndex, PointMaps, point_maps
from flexsim.structure.loads import ThrustMap
from flexsim.structure.mirror import MirrorOperator, mirror_operator
from flexsim.structure.stiffness import stiffness_matrices

__all__ = ["StructuralModel", "MassProperties"]


@dataclass(frozen=True)
class MassProperties:
    """Mass, centre of gravity and inertia tensor of the undeformed aircraft (body axes).

    Attributes
    ----------
    mass_kg : float
    cg_m : ndarray, shape (3,)
        Centre of gravity relative to the body origin o, body axes [m].
    inertia_cg_kg_m2 : ndarray, shape (3, 3)
        Inertia tensor about the CG, body axes [kg m^2]: diagonal Ixx, Iyy, Izz; off-diagonal
        -Ixy, -Ixz, -Iyz (products of inertia I_xz = int x z dm).
    """

    mass_kg: float
    cg_m: np.ndarray
    inertia_cg_kg_m2: np.ndarray

    @property
    def ixx_iyy_izz_ixz(self) -> tuple[float, float, float, float]:
        """(Ixx, Iyy, Izz, Ixz) about the CG [kg m^2], Ixz = int x z dm (body axes)."""
        j = self.inertia_cg_kg_m2
        return float(j[0, 0]), float(j[1, 1]), float(j[2, 2]), float(-j[0, 2])


class StructuralModel:
    """Precomputed structural dynamics of an aircraft definition (eqs. 1-24, 32-33).

    Parameters
    ----------
    aircraft : Aircraft

    Attributes
    ----------
    aircraft : Aircraft
    dofs : DofIndex
    inertia : InertiaPolynomial
    k_bending : ndarray, shape (nq, nq)  [N/m]
    k_torsion : ndarray, shape (nxi, nxi)  [N m/rad]
    thrust : ThrustMap
    """

    def __init__(self, aircraft: Aircraft) -> None:
        self.aircraft = aircraft
        self.dofs = DofIndex.from_aircraft(aircraft)
        self.inertia = InertiaPolynomial.from_aircraft(aircraft, self.dofs)
        self.k_bending, self.k_torsion = stiffness_matrices(aircraft, self.dofs)
        self.thrust = ThrustMap.from_aircraft(aircraft, self.dofs)

    def point_maps(self, component: str, x: np.ndarray) -> PointMaps:
        """Kinematic maps of points at stations ``x`` [m] of ``component`` (eqs. 5-6, 18)."""
        return point_maps(self.aircraft, self.dofs, self.aircraft.component(component), x)

    @cached_property
    def mirror(self) -> MirrorOperator | None:
        """Left-right mirror of the coordinates V (:mod:`flexsim.structure.mirror`); None if asymmetric."""
        return mirror_operator(self.aircraft, self.dofs)

    @cached_property
    def stiffness(self) -> np.ndarray:
        """Stiffness in V coordinates, shape (n_v, n_v): zero on the rigid-body block (eq. 15)."""
        k = np.zeros((self.dofs.n_v, self.dofs.n_v))
        nq = self.dofs.nq
        k[6 : 6 + nq, 6 : 6 + nq] = self.k_bending
        k[6 + nq :, 6 + nq :] = self.k_torsion
        k.setflags(write=False)
        return k

    def damping(self, ratio: float) -> np.ndarray:
        """Modal structural damping on the elastic coordinates, shape (n_el, n_el) [N s/m ...].

        C = M_ee Phi diag(2 zeta omega_i) Phi^T M_ee with (omega_i, Phi) the mass-normalised modes of the
        elastic block (body clamped: K_ee phi = omega^2 M0_ee phi), so that every clamped mode gets the
        damping ratio ``ratio`` (not in the paper, whose structure is undamped; common practice in flutter
        analysis, e.g. g = 2 zeta = 0.02).
        """
        if ratio == 0.0:
            return np.zeros((self.dofs.n_v - 6, self.dofs.n_v - 6))
        from scipy.linalg import eigh

        m_ee = self.inertia.m0[6:, 6:]
        lam, phi = eigh(self.stiffness[6:, 6:], m_ee)
        omega = np.sqrt(np.clip(lam, 0.0, None))
        mp = m_ee @ phi
        return (mp * (2.0 * ratio * omega)[None, :]) @ mp.T

    @cached_property
    def mass_properties(self) -> MassProperties:
        """Mass, CG and inertia about the CG of the undeformed aircraft, from M0 (eq. 8)."""
        m0 = self.inertia.m0
        mass = float(m0[0, 0])
        # M_v,omega = -skew(S) with S = m r_cg (first moment about o)
        s = np.array([m0[1, 5], m0[2, 3], m0[0, 4]])
        cg = s / mass
        j_o = m0[3:6, 3:6]
        j_cg = j_o - mass * (cg @ cg * np.eye(3) - np.outer(cg, cg))
        return MassProperties(mass, cg, 0.5 * (j_cg + j_cg.T))
