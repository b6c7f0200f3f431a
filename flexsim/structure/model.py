"""The structural model of the whole aircraft, built once from its definition.

Bundles, for the equations of motion (eq. 33): the index of elastic coordinates, the inertia polynomial
M(q) (eqs. 7-10), the stiffness matrices (eqs. 14-16) and the thrust map (eqs. 17-24). Everything here
is precomputed at construction; nothing is mutated afterwards.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from flexsim._immutable import Immutable, freeze_arrays
from flexsim.aircraft.definition import Aircraft
from flexsim.structure.inertia import InertiaPolynomial
from flexsim.structure.kinematic_map import DofIndex, PointMaps, point_maps
from flexsim.structure.loads import ThrustMap
from flexsim.structure.mirror import MirrorOperator, mirror_operator
from flexsim.structure.stiffness import stiffness_matrices

__all__ = ["StructuralModel", "MassProperties", "structural_model"]


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


class StructuralModel(Immutable):
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
        self._check_assembled()

    def _dof_label(self, i: int) -> str:
        """Name of elastic coordinate ``i`` (0-based in [s, eta]) as ``<component> bending|torsion <k>``."""
        for kind, table, offset in (("bending", self.dofs.bending, 0), ("torsion", self.dofs.torsion, self.dofs.nq)):
            for name, sl in table.items():
                if sl.start + offset <= i < sl.stop + offset:
                    return f"{name} {kind} {i - sl.start - offset + 1}"
        return f"elastic coordinate {i}"

    def _check_assembled(self) -> None:
        """Derived quantities of the assembled structure must be physical.

        Checks, each raising :class:`~flexsim.errors.AircraftDefinitionError` with the value and the
        allowed range: the elastic mass block M0_ee is positive definite (every shape function carries
        mass); the inertia tensor about the CG is positive definite (cancellation from absurd masses
        gives negative principal inertias); the clamped elastic frequencies, K_ee phi = omega^2 M0_ee phi,
        lie in :data:`~flexsim.aircraft.definition.PLAUSIBLE` ``["elastic_frequency_rad_s"]``.
        """
        from scipy.linalg import eigh

        from flexsim.aircraft.definition import PLAUSIBLE
        from flexsim.errors import AircraftDefinitionError

        src = self.aircraft.source
        m0 = self.inertia.m0
        mp = self.mass_properties
        if not (np.isfinite(mp.mass_kg) and mp.mass_kg > 0.0):
            raise AircraftDefinitionError(f"{src}: assembled mass = {mp.mass_kg!r} kg: must be a finite number > 0")
        principal = np.linalg.eigvalsh(mp.inertia_cg_kg_m2)
        if not (np.all(np.isfinite(principal)) and principal.min() > 1e-12 * max(1.0, principal.max())):
            raise AircraftDefinitionError(
                f"{src}: principal moments of inertia about the CG = {principal.tolist()} kg m^2: must all be > 0 "
                f"(the inertia tensor must be positive definite; check masses and positions)")
        n_el = self.dofs.nq + self.dofs.nxi
        if n_el == 0:
            return
        m_ee = m0[6:, 6:]
        diag = np.diag(m_ee)
        zero = np.flatnonzero(~(diag > 1e-12 * max(1.0, np.abs(diag).max())))
        if zero.size:
            raise AircraftDefinitionError(
                f"{src}: generalised mass of {self._dof_label(int(zero[0]))} = {float(diag[zero[0]]):.3g}: must be > 0 "
                f"(the shape function moves no mass)")
        try:
            lam = eigh(self.stiffness[6:, 6:], m_ee, eigvals_only=True)
        except np.linalg.LinAlgError:
            raise AircraftDefinitionError(f"{src}: the elastic mass matrix is not positive definite (a component's "
                                          f"shape functions move no mass)") from None
        omega = np.sqrt(np.clip(lam, 0.0, None))
        lo, hi, unit = PLAUSIBLE["elastic_frequency_rad_s"]
        bad = np.flatnonzero(~((omega >= lo) & (omega <= hi)))
        if bad.size:
            i = int(bad[0]) if omega[bad[0]] < lo else int(bad[-1])
            raise AircraftDefinitionError(
                f"{src}: clamped elastic frequency {i + 1} of {omega.size} = {omega[i]:.4g} {unit}: outside the plausible "
                f"range [{lo:g}, {hi:g}] {unit} (check the units of stiffness and mass)")

    def point_maps(self, component: str, x: np.ndarray) -> PointMaps:
        """Kinematic maps of points at stations ``x`` [m] of ``component`` (eqs. 5-6, 18)."""
        return point_maps(self.aircraft, self.dofs, self.aircraft.component(component), x)

    @cached_property
    def mirror(self) -> MirrorOperator | None:
        """Left-right mirror of the coordinates V (:mod:`flexsim.structure.mirror`); None if asymmetric."""
        mirror = mirror_operator(self.aircraft, self.dofs)
        freeze_arrays(mirror)
        return mirror

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
        props = MassProperties(mass, cg, 0.5 * (j_cg + j_cg.T))
        freeze_arrays(props)
        return props


def structural_model(aircraft: Aircraft) -> StructuralModel:
    """The :class:`StructuralModel` of ``aircraft``, built once per content (and source file) in a process.

    A structural model depends on its aircraft only and is immutable (sealed, read-only arrays; its cached
    properties such as the mirror are computed once from the same inputs), so every model of one aircraft — a
    flutter analysis builds two or three, a study worker one per setting — shares it instead of re-assembling the
    inertia polynomial, stiffness and mirror (about 0.1 s each).
    """
    return _structural_model_of(aircraft.content_key(), aircraft.source)


@functools.lru_cache(maxsize=16)
def _structural_model_of(key, source) -> StructuralModel:
    return StructuralModel(key.aircraft)
