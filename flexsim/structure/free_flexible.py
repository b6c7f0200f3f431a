"""A free-flying rigid body with geometrically exact strain-based beams clamped to it (equations of motion).

Formulation
-----------
Meirovitch & Tuzcu's Lagrange equations in quasi-coordinates (the paper's eq. 2, ``docs/design.md``): the
generalized velocities are ``V = [v, ω, ε̇]`` — the body-axes velocity [m/s] of the body origin ``o``, the body
angular velocity [rad/s] (body components) and the strain rates of all beams — and the configuration is
``[X, quaternion, ε]``. The beams are the strain-based beams of Su & Cesnik (Int. J. Solids Struct. 48, 2011,
eqs. 1-12; :mod:`flexsim.structure.strain_beam`) clamped to the body at their root positions and orientations in
body axes, as in the free-flying strain-based aircraft of Shearer & Cesnik (J. Aircraft 44(5), 2007, eqs. 1-20)
and Su & Cesnik (J. Aircraft 47(5), 2010).

Kinematic map (Shearer & Cesnik 2007 eq. 9, in body axes): a section's mass centre at ``r_c(ε)`` moves with
``u = v + ω × r_c + J_c(ε) ε̇ = L(ε) V`` and turns with ``w = ω + J_θ(ε) ε̇ = A(ε) V``; the kinetic energy is
``T = ½ Vᵀ M(ε) V`` with ``M = Σ ∫ (m Lᵀ L + Aᵀ R I Rᵀ A) ds`` plus the rigid body's share. The equations in
quasi-coordinates (the paper's eq. 2; Meirovitch & Tuzcu 2004) are written here in Kane's equivalent form, which
needs no derivative of ``M``: with the partial velocities ``L`` and ``A`` as the virtual-power weights,

    M(ε) V̇ = Q − Σ ∫ [Lᵀ m b + Aᵀ β] ds − (rigid body's ω × terms),                                   (1)

    b = ω × ṙ_c + r̈_c|ε̈=0 + ω × u,      β = I_s (α_rel|ε̈=0 + ω × w) + w × I_s w,      I_s = R I Rᵀ,

where ``r̈_c|ε̈=0 = J̇_c ε̇`` and ``α_rel|ε̈=0 = J̇_θ ε̇`` are the accelerations of the section relative to the body
at zero strain acceleration. ``Lᵀ m b`` expands to ``[m b, r_c × m b, J_cᵀ m b]``, which is the paper's
``d/dt ∂T/∂V`` terms with the transport terms ``ω̃ ∂T/∂v`` etc. (eq. 2, first two rows) and ``−∂T/∂ε``
(its elastic rows), collected. ``Q = [F, M_o, −K ε + Q_ε]``: the elastic force ``K ε`` (Su & Cesnik eq. 6) and
gravity (optional).

The relative accelerations are exact: along the path ``ε + t ε̇`` each element's transform ``G = exp(ℓ ξ^)``
(SE(3), 4 × 4) and its first two time derivatives are the blocks of one matrix exponential,

    exp([[A, E, 0], [0, A, E], [0, 0, A]]) = [[G, Ġ, G̈/2], [0, G, Ġ], [0, 0, G]],   A = ℓ ξ^, E = ℓ ξ̇^,

(the Fréchet derivatives of the exponential; Higham, *Functions of Matrices*, 2008, theorem 3.6 and §10.6), and
the chain ``T_{j+1} = T_j G_j`` is differentiated by the product rule. No finite differences enter the equations,
so energy and momenta are conserved to the integrator's accuracy.

Frames and units: body axes x forward, y right, z down (``docs/conventions.md``), origin ``o``; the inertial frame
north-east-down. The quaternion ``[q0, q1, q2, q3]`` (scalar first) rotates body components into inertial ones,
``x_inertial = C(q) x_body`` (no gimbal lock). SI units throughout.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import cho_factor, cho_solve, eigh

from flexsim._arrays import frozen_array
from flexsim.structure import _strain_kernels as _kern
from flexsim.structure.strain_beam import (BeamProperties, beam_kinematics, mass_points,
                                           stiffness_matrix)

__all__ = ["RigidBody", "FreeFlexibleStructure", "Conserved", "quaternion_matrix", "initial_state",
           "generalized_mass_matrix", "free_flight_rhs", "conserved_quantities", "free_free_frequencies",
           "beam_relative_motion", "steady_generalized_force"]


def _hat(v: NDArray) -> NDArray:
    """Skew-symmetric matrices ``v^`` (``v^ w = v × w``), shape (..., 3, 3)."""
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def _cross(a: NDArray, b: NDArray) -> NDArray:
    """``a × b`` over the last axis (length 3), broadcast; explicit components (cheaper than ``np.cross`` on the
    small arrays of the equations)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    if a.shape == b.shape or b.ndim == 1:
        shape = a.shape
    else:
        shape = b.shape if a.ndim == 1 else np.broadcast_shapes(a.shape, b.shape)
    out = np.empty(shape)
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def _vee(m: NDArray) -> NDArray:
    """Axial vector of the skew part of ``m`` (..., 3, 3)."""
    return 0.5 * np.stack([m[..., 2, 1] - m[..., 1, 2], m[..., 0, 2] - m[..., 2, 0], m[..., 1, 0] - m[..., 0, 1]], -1)


@dataclass(frozen=True)
class RigidBody:
    """The rigid part of a free-flying structure (validated, frozen).

    Parameters
    ----------
    mass_kg : float
        Mass ``m_b`` [kg], >= 0 (0: the beams alone, joined rigidly at their roots).
    cg_m : array_like, shape (3,)
        Mass centre in body axes [m].
    inertia_kg_m2 : array_like, shape (3, 3)
        Inertia tensor about the mass centre, body axes [kg m²]; symmetric positive semi-definite.
    """

    mass_kg: float
    cg_m: ArrayLike = field(default_factory=lambda: np.zeros(3))
    inertia_kg_m2: ArrayLike = field(default_factory=lambda: np.zeros((3, 3)))

    def __post_init__(self) -> None:
        m = self.mass_kg
        if isinstance(m, bool) or not isinstance(m, (int, float, np.floating)) or not (np.isfinite(m) and m >= 0):
            raise ValueError(f"mass_kg = {m!r}: must be a finite number >= 0 [kg]")
        object.__setattr__(self, "mass_kg", float(m))
        cg = np.array(self.cg_m, dtype=float)
        if cg.shape != (3,) or not np.all(np.isfinite(cg)):
            raise ValueError(f"cg_m = {self.cg_m!r}: must be 3 finite numbers [m]")
        object.__setattr__(self, "cg_m", frozen_array(cg))
        inertia = np.array(self.inertia_kg_m2, dtype=float)
        if inertia.shape != (3, 3) or not np.all(np.isfinite(inertia)):
            raise ValueError(f"inertia_kg_m2 has shape {inertia.shape}: must be a finite 3 x 3 matrix [kg m^2]")
        asym = np.abs(inertia - inertia.T).max()
        low = np.linalg.eigvalsh(0.5 * (inertia + inertia.T)).min()
        scale = max(np.abs(inertia).max(), 1e-300)
        if asym > 1e-12 * scale or low < -1e-12 * scale:
            raise ValueError(f"inertia_kg_m2 must be symmetric positive semi-definite (asymmetry {asym:.3e}, "
                             f"smallest eigenvalue {low:.3e} kg m^2; allowed: 0 and >= 0)")
        object.__setattr__(self, "inertia_kg_m2", frozen_array(0.5 * (inertia + inertia.T)))


@dataclass(frozen=True)
class FreeFlexibleStructure:
    """A rigid body with strain-based beams clamped to it (validated, frozen).

    Parameters
    ----------
    body : RigidBody
    beams : tuple of BeamProperties
        Each beam's ``root_position_m`` and ``root_rotation`` are in body axes (its "global" frame is the body
        frame). A wing continuous through the centreline is two beams rooted at the same point.
    gravity_m_s2 : array_like, shape (3,)
        Acceleration of gravity in inertial (north-east-down) components [m/s²]; default none (vacuum, no gravity).
    damping_ratio : float
        Modal structural damping ratio ζ in [0, 1) of every mode of the beams with the body clamped (:meth:`damping`;
        the linear model's convention, :meth:`flexsim.structure.model.StructuralModel.damping`); default 0.

    The generalized coordinates are numbered ``[6 rigid-body, beam 0's strains, beam 1's strains, ...]``.
    """

    body: RigidBody
    beams: tuple = ()
    gravity_m_s2: ArrayLike = field(default_factory=lambda: np.zeros(3))
    damping_ratio: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.body, RigidBody):
            raise ValueError(f"body = {self.body!r}: must be a RigidBody")
        beams = tuple(self.beams)
        for i, b in enumerate(beams):
            if not isinstance(b, BeamProperties):
                raise ValueError(f"beams[{i}] = {b!r}: must be a BeamProperties")
        object.__setattr__(self, "beams", beams)
        g = np.array(self.gravity_m_s2, dtype=float)
        if g.shape != (3,) or not np.all(np.isfinite(g)):
            raise ValueError(f"gravity_m_s2 = {self.gravity_m_s2!r}: must be 3 finite numbers [m/s^2]")
        object.__setattr__(self, "gravity_m_s2", frozen_array(g))
        z = self.damping_ratio
        if isinstance(z, bool) or not isinstance(z, (int, float, np.floating)) or not 0.0 <= z < 1.0:
            raise ValueError(f"damping_ratio = {z!r}: must be a damping ratio in [0, 1)")
        object.__setattr__(self, "damping_ratio", float(z))
        rigid = generalized_mass_matrix(self, np.zeros(self.n_strains))[:6, :6]
        if np.linalg.eigvalsh(rigid).min() <= 1e-12 * max(np.abs(rigid).max(), 1e-300):
            raise ValueError("body and beams together have a singular rigid-body mass matrix (mass or an inertia "
                             "of the undeformed structure is zero): give the body mass_kg > 0 or inertia_kg_m2")

    @property
    def n_strains(self) -> int:
        """Total number of strain coordinates ``n``."""
        return sum(b.n_coordinates for b in self.beams)

    @property
    def n_velocities(self) -> int:
        """``6 + n``: the length of ``V``."""
        return 6 + self.n_strains

    @property
    def n_states(self) -> int:
        """``3 + 4 + n + 6 + n``: ``[X, quaternion, ε, V]``."""
        return 7 + self.n_strains + self.n_velocities

    def strain_slices(self) -> list[slice]:
        """The slice of each beam's strains in ``ε``."""
        out, start = [], 0
        for b in self.beams:
            out.append(slice(start, start + b.n_coordinates))
            start += b.n_coordinates
        return out

    def stiffness(self) -> NDArray[np.float64]:
        """``blockdiag(K_beam)``, shape (n, n) (Su & Cesnik 2011 eq. 6)."""
        return self._stiffness.copy()

    def damping(self) -> NDArray[np.float64]:
        """Modal structural damping on the strains, shape (n, n) [N m s ...]: ``C = M Φ diag(2 ζ ω_i) Φᵀ M`` with
        ``(ω_i, Φ)`` the mass-normalised modes of the beams with the body clamped (``K φ = ω² M φ``, ``M`` the strain
        block of :func:`generalized_mass_matrix` at ``ε = 0``), so that each of them has the damping ratio ζ; the
        generalized force ``−C ε̇`` (the linear model's convention, not in the paper, whose structure is undamped)."""
        return np.zeros((self.n_strains,) * 2) if self._damping is None else self._damping.copy()

    @cached_property
    def _damping(self) -> NDArray[np.float64] | None:
        """:meth:`damping`, built once (read-only); None when ζ = 0."""
        if self.damping_ratio == 0.0 or self.n_strains == 0:
            return None
        mass = generalized_mass_matrix(self, np.zeros(self.n_strains))[6:, 6:]
        try:
            lam, phi = eigh(self._stiffness, 0.5 * (mass + mass.T))
        except np.linalg.LinAlgError:
            raise ValueError(f"damping_ratio = {self.damping_ratio!r}: the beams' mass matrix is singular (a strain "
                             "moves no mass: give the sections' inertias), so their modes, and a modal damping, are "
                             "not defined") from None
        mp = mass @ phi
        return frozen_array((mp * (2.0 * self.damping_ratio * np.sqrt(np.clip(lam, 0.0, None)))[None, :]) @ mp.T)

    @cached_property
    def _stiffness(self) -> NDArray[np.float64]:
        """:meth:`stiffness`, built once (read-only)."""
        k = np.zeros((self.n_strains, self.n_strains))
        for b, s in zip(self.beams, self.strain_slices()):
            k[s, s] = stiffness_matrix(b)
        return frozen_array(k)


def quaternion_matrix(quat: ArrayLike) -> NDArray[np.float64]:
    """``C(q)``, body to inertial components, of the normalised quaternion ``[q0, q1, q2, q3]`` (scalar first)."""
    q0, q1, q2, q3 = np.asarray(quat, dtype=float) / np.linalg.norm(quat)
    return np.array([[q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
                     [2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1)],
                     [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3]])


def initial_state(structure: FreeFlexibleStructure, *, position_m: ArrayLike = (0.0, 0.0, 0.0),
                  quaternion: ArrayLike = (1.0, 0.0, 0.0, 0.0), strains: ArrayLike | None = None,
                  velocity_m_s: ArrayLike = (0.0, 0.0, 0.0), rate_rad_s: ArrayLike = (0.0, 0.0, 0.0),
                  strain_rates: ArrayLike | None = None) -> NDArray[np.float64]:
    """The state ``y = [X (3), quaternion (4), ε (n), v (3), ω (3), ε̇ (n)]``, checked field by field."""
    n = structure.n_strains
    parts = []
    for name, value, size in (("position_m", position_m, 3), ("quaternion", quaternion, 4),
                              ("strains", np.zeros(n) if strains is None else strains, n),
                              ("velocity_m_s", velocity_m_s, 3), ("rate_rad_s", rate_rad_s, 3),
                              ("strain_rates", np.zeros(n) if strain_rates is None else strain_rates, n)):
        arr = np.array(value, dtype=float).ravel()
        if arr.shape != (size,) or not np.all(np.isfinite(arr)):
            raise ValueError(f"{name} = {value!r}: must be {size} finite numbers")
        parts.append(arr)
    norm = np.linalg.norm(parts[1])
    if not 1e-6 < norm:
        raise ValueError(f"quaternion = {quaternion!r}: must be non-zero (it is normalised)")
    parts[1] = parts[1] / norm
    return np.concatenate(parts)


def _element_transforms(beam: BeamProperties, strains: NDArray, rates: NDArray, frac: NDArray) -> NDArray:
    """``[G, Ġ, G̈/2]`` (..., 3, 4, 4) of ``exp(σ ℓ ξ^)`` along ``ε + t ε̇``: the first block row of one block
    exponential each (module doc; the block matrix is upper-triangular Toeplitz, exponentiated block by block:
    :func:`flexsim.structure._strain_kernels.expm_toeplitz_batch`)."""
    ell = beam.element_length_m * frac
    x = np.zeros(frac.shape + (3, 4, 4))  # first block row [A, E, 0]
    a, e = x[..., 0, :, :], x[..., 1, :, :]
    a[..., :3, :3] = _hat(ell[..., None] * strains[..., 1:])
    a[..., 0, 3] = frac * (1.0 + strains[..., 0])  # translations per unit element length: a small norm for the
    e[..., :3, :3] = _hat(ell[..., None] * rates[..., 1:])  # Padé approximant; they scale back below (linear in ρ)
    e[..., 0, 3] = frac * rates[..., 0]
    out = np.empty_like(x)
    _kern.expm_toeplitz_batch(x.reshape(-1, 3, 4, 4), out.reshape(-1, 3, 4, 4))
    out[..., 0:3, 3] *= beam.element_length_m
    return out


def beam_relative_motion(beam: BeamProperties, q: ArrayLike, qdot: ArrayLike, points_element: NDArray,
                         points_fraction: NDArray) -> tuple[NDArray, ...]:
    """Frames and their first two time derivatives at points of a beam moving along ``q + t q̇`` (body axes).

    Parameters
    ----------
    beam : BeamProperties
    q, qdot : array_like, shape (n,)
        Strains [-, 1/m] and strain rates [1/s, 1/(m s)].
    points_element : ndarray of int, shape (P,)
    points_fraction : ndarray, shape (P,)
        Element and fraction of its length (0-1) of each point.

    Returns
    -------
    p, pdot, pddot : ndarray, shape (P, 3)
        Reference-axis position [m], velocity ``J_p q̇`` [m/s] and acceleration at ``q̈ = 0``, ``J̇_p q̇`` [m/s²].
    rot, rotdot, rotddot : ndarray, shape (P, 3, 3)
        Section frame ``R`` and its first and second time derivatives at ``q̈ = 0``.
    """
    strains = beam.full_strains(q)
    rates = beam.full_strains(qdot)
    elements = _element_transforms(beam, strains, rates, np.ones(beam.n_elements))
    e = np.ascontiguousarray(points_element, dtype=np.int64)
    points = _element_transforms(beam, strains[e], rates[e], np.asarray(points_fraction, dtype=float))
    root = np.zeros((3, 4, 4))
    root[0, :3, :3], root[0, :3, 3], root[0, 3, 3] = beam.root_rotation, beam.root_position_m, 1.0
    out = np.empty_like(points)  # the product rule along the chain T_(j+1) = T_j G_j, then T_e H_p at each point
    _kern.chain_toeplitz(root, elements, e, points, out)
    pt, ptd, ptdd = out[:, 0], out[:, 1], 2.0 * out[:, 2]
    return (pt[:, :3, 3], ptd[:, :3, 3], ptdd[:, :3, 3], pt[:, :3, :3], ptd[:, :3, :3], ptdd[:, :3, :3])


@dataclass(frozen=True, eq=False)
class _Points:
    """Quadrature points of all beams (body axes): weights × mass, positions, Jacobians over all of V, motion."""

    mass: NDArray         # (P,) [kg] (m × weight)
    inertia: NDArray      # (P, 3, 3) [kg m²] R I Rᵀ × weight
    r: NDArray            # (P, 3) mass-centre positions [m]
    jac_c: NDArray        # (P, 3, 6 + n): L (mass-centre velocity per V)
    jac_w: NDArray        # (P, 3, 6 + n): A (section angular velocity per V)
    rdot: NDArray | None       # (P, 3) J_c ε̇ (the four: None when ε̇ = 0)
    rddot: NDArray | None      # (P, 3) J̇_c ε̇
    w_rel: NDArray | None      # (P, 3) J_θ ε̇
    alpha_rel: NDArray | None  # (P, 3) J̇_θ ε̇


def _points(structure: FreeFlexibleStructure, eps: NDArray, epsdot: NDArray | None,
            kinematics: list | None = None) -> _Points:
    """The quadrature points of all beams at ``eps`` (``kinematics``: the beams' kinematics there, if known)."""
    nv = structure.n_velocities
    blocks = []
    slices = structure.strain_slices()
    if kinematics is None:
        kinematics = [beam_kinematics(beam, eps[s]) for beam, s in zip(structure.beams, slices)]
    for beam, s, kin in zip(structure.beams, slices, kinematics):
        pts = mass_points(beam, kin)
        n_p = pts.mass.size
        lc = np.zeros((n_p, 3, nv))
        lw = np.zeros((n_p, 3, nv))
        lc[:, :, :3] = np.eye(3)
        lc[:, :, 3:6] = -_hat(pts.r)
        lc[:, :, 6 + s.start:6 + s.stop] = pts.jac_c
        lw[:, :, 3:6] = np.eye(3)
        lw[:, :, 6 + s.start:6 + s.stop] = pts.jac_rotation
        inertia = pts.rotations @ pts.inertia_section @ np.swapaxes(pts.rotations, 1, 2)
        motion = []
        if epsdot is not None:
            _, pd, pdd, rot, rd, rdd = beam_relative_motion(beam, eps[s], epsdot[s], pts.element, pts.fraction)
            rdot = pd + np.einsum("pij,pj->pi", rd, pts.offset)
            rddot = pdd + np.einsum("pij,pj->pi", rdd, pts.offset)
            w_rel = _vee(rd @ np.swapaxes(rot, 1, 2))
            alpha_rel = _vee(rdd @ np.swapaxes(rot, 1, 2) + rd @ np.swapaxes(rd, 1, 2))
            motion = [rdot, rddot, w_rel, alpha_rel]
        blocks.append((pts.mass, inertia, pts.r, lc, lw, *motion))
    if not blocks:
        z3, zj = np.zeros((0, 3)), np.zeros((0, 3, nv))
        return _Points(np.zeros(0), np.zeros((0, 3, 3)), z3, zj, zj, z3, z3, z3, z3)
    parts = [np.concatenate(arrays) for arrays in zip(*blocks)]
    return _Points(*parts) if epsdot is not None else _Points(*parts, None, None, None, None)


def _rigid_mass(body: RigidBody, nv: int) -> NDArray:
    m = np.zeros((nv, nv))
    c = _hat(body.cg_m)
    m[:3, :3] = body.mass_kg * np.eye(3)
    m[:3, 3:6] = -body.mass_kg * c
    m[3:6, :3] = body.mass_kg * c
    m[3:6, 3:6] = body.inertia_kg_m2 - body.mass_kg * c @ c
    return m


def _mass_from_points(structure: FreeFlexibleStructure, pts: _Points) -> NDArray:
    out = _rigid_mass(structure.body, structure.n_velocities)
    nv = out.shape[0]
    jc, jw = pts.jac_c.reshape(-1, nv), pts.jac_w.reshape(-1, nv)  # (3P, nv): one product each (BLAS)
    out += (pts.mass[:, None, None] * pts.jac_c).reshape(-1, nv).T @ jc
    out += jw.T @ (pts.inertia @ pts.jac_w).reshape(-1, nv)
    return 0.5 * (out + out.T)


def generalized_mass_matrix(structure: FreeFlexibleStructure, eps: ArrayLike) -> NDArray[np.float64]:
    """``M(ε)`` [kg, kg m, kg m²], shape (6 + n, 6 + n): ``T = ½ Vᵀ M V`` (Shearer & Cesnik 2007 eq. 12).

    Its strain block equals :func:`flexsim.structure.strain_beam.mass_matrix` of each beam; its rigid block is
    the mass and inertia about ``o`` of the body and the (deformed) beams.
    """
    eps = np.asarray(eps, dtype=float)
    return _mass_from_points(structure, _points(structure, eps, None))


def _split(structure: FreeFlexibleStructure, y: ArrayLike):
    y = np.asarray(y, dtype=float)
    if y.shape != (structure.n_states,):
        raise ValueError(f"state has shape {y.shape}: must be ({structure.n_states},) = [X (3), quaternion (4), "
                         f"strains ({structure.n_strains}), v (3), omega (3), strain rates ({structure.n_strains})]")
    n = structure.n_strains
    return y[:3], y[3:7], y[7:7 + n], y[7 + n:]


def _generalized_force(structure: FreeFlexibleStructure, pts: _Points, quat: NDArray, eps: NDArray, vel: NDArray,
                       gravity_m_s2: ArrayLike) -> NDArray:
    """The right-hand side of eq. (1), ``Q − Σ ∫ [Lᵀ m b + Aᵀ β] ds − (rigid body's terms)``, shape (6 + n,)."""
    v, om = vel[:3], vel[3:6]
    body = structure.body
    g_body = quaternion_matrix(quat).T @ np.asarray(gravity_m_s2, dtype=float)
    q = np.zeros(structure.n_velocities)
    q[6:] = -structure._stiffness @ eps
    if structure._damping is not None:
        q[6:] -= structure._damping @ vel[6:]
    # rigid body: bias ω × (m u_b) and ω × I_b ω, and its weight
    u_b = v + _cross(om, body.cg_m)
    f_b = body.mass_kg * (g_body - _cross(om, u_b))
    q[:3] += f_b
    q[3:6] += _cross(body.cg_m, f_b) - _cross(om, body.inertia_kg_m2 @ om)
    if pts.mass.size:
        nv = q.size
        u = (pts.jac_c.reshape(-1, nv) @ vel).reshape(-1, 3)
        if pts.w_rel is None:  # ε̇ = 0: no relative motion (the same terms, their zeros left out)
            b = _cross(om, u)
            tau = -_cross(om, pts.inertia @ om)
        else:
            w = om + pts.w_rel
            b = _cross(om, pts.rdot) + pts.rddot + _cross(om, u)
            iw = (pts.inertia @ w[:, :, None])[:, :, 0]
            tau = -((pts.inertia @ (pts.alpha_rel + _cross(om, w))[:, :, None])[:, :, 0] + _cross(w, iw))
        f = pts.mass[:, None] * (g_body - b)
        q += f.reshape(-1) @ pts.jac_c.reshape(-1, nv) + tau.reshape(-1) @ pts.jac_w.reshape(-1, nv)
    return q


def steady_generalized_force(structure: FreeFlexibleStructure, quat: ArrayLike, eps: ArrayLike, rigid_velocity: ArrayLike,
                             gravity_m_s2: ArrayLike, *, kinematics: list | None = None) -> NDArray[np.float64]:
    """The right-hand side of eq. (1) at ``ε̇ = 0``: ``M(ε) V̇`` of a state whose strains are momentarily at rest.

    Parameters
    ----------
    structure : FreeFlexibleStructure
    quat : array_like, shape (4,)
        Body→inertial quaternion (scalar first).
    eps : array_like, shape (n,)
    rigid_velocity : array_like, shape (6,)
        ``[v [m/s], ω [rad/s]]``, body axes.
    gravity_m_s2 : array_like, shape (3,)
        Inertial (north-east-down) components [m/s²].
    kinematics : list of BeamKinematics, optional
        The beams' kinematics at ``eps`` (:func:`~flexsim.structure.strain_beam.beam_kinematics`) when the caller
        has them already; default: computed here.

    Returns
    -------
    ndarray, shape (6 + n,)
        Zero exactly in a steady state (``V̇ = 0``, ``ε̇ = 0``): force [N], moment about o [N m], strain forces.
    """
    eps = np.asarray(eps, dtype=float)
    vel = np.concatenate([np.asarray(rigid_velocity, dtype=float), np.zeros(structure.n_strains)])
    return _generalized_force(structure, _points(structure, eps, None, kinematics), np.asarray(quat, float), eps,
                              vel, gravity_m_s2)


def free_flight_rhs(structure: FreeFlexibleStructure, t: float, y: ArrayLike,
                    external_force: ArrayLike | None = None) -> NDArray[np.float64]:
    """``dy/dt`` of the free-flying structure in vacuum (eq. 1 of the module doc; the paper's eq. 2).

    Parameters
    ----------
    structure : FreeFlexibleStructure
    t : float
        Time [s] (the equations are autonomous).
    y : array_like, shape (n_states,)
        ``[X [m] (inertial), quaternion (body→inertial), ε, v [m/s], ω [rad/s] (body axes), ε̇]``.
    external_force : array_like, shape (6 + n,), optional
        Generalized external force added to ``Q`` (e.g. airloads): force [N] and moment about o [N m] in body
        axes, strain forces; default none (vacuum).

    Returns
    -------
    ndarray, shape (n_states,)
        ``[C v, ½ q ⊗ (0, ω), ε̇, V̇]``.
    """
    _, quat, eps, vel = _split(structure, y)
    om, epsdot = vel[3:6], vel[6:]
    pts = _points(structure, eps, epsdot)
    mass = _mass_from_points(structure, pts)
    q = _generalized_force(structure, pts, quat, eps, vel, structure.gravity_m_s2)
    if external_force is not None:
        q = q + np.asarray(external_force, dtype=float)
    vdot = cho_solve(cho_factor(mass), q)
    q0, qv = quat[0], quat[1:]
    quat_dot = 0.5 * np.concatenate([[-qv @ om], q0 * om + _cross(qv, om)])
    return np.concatenate([quaternion_matrix(quat) @ vel[:3], quat_dot, epsdot, vdot])


@dataclass(frozen=True)
class Conserved:
    """Energy and momenta of a state (inertial components, SI).

    Attributes
    ----------
    kinetic_j, strain_j, gravity_j, energy_j : float
        ``½ Vᵀ M V``, ``½ εᵀ K ε``, ``−Σ m g·x`` and their sum [J].
    linear_momentum : ndarray, shape (3,)
        [kg m/s].
    angular_momentum_cg : ndarray, shape (3,)
        About the instantaneous mass centre of the whole structure [kg m²/s].
    cg_m : ndarray, shape (3,)
        Inertial position of the mass centre [m].
    """

    kinetic_j: float
    strain_j: float
    gravity_j: float
    energy_j: float
    linear_momentum: NDArray
    angular_momentum_cg: NDArray
    cg_m: NDArray


def conserved_quantities(structure: FreeFlexibleStructure, y: ArrayLike) -> Conserved:
    """Energy, linear momentum and angular momentum about the mass centre of state ``y`` (see :class:`Conserved`)."""
    x, quat, eps, vel = _split(structure, y)
    pts = _points(structure, eps, None)
    mass = _mass_from_points(structure, pts)
    body = structure.body
    rot = quaternion_matrix(quat)
    om = vel[3:6]
    u = pts.jac_c @ vel
    w = pts.jac_w @ vel
    m_tot = body.mass_kg + pts.mass.sum()
    cg = (body.mass_kg * body.cg_m + pts.mass @ pts.r) / m_tot
    u_b = vel[:3] + np.cross(om, body.cg_m)
    p_body = body.mass_kg * u_b + pts.mass @ u
    h = (body.mass_kg * np.cross(body.cg_m - cg, u_b) + body.inertia_kg_m2 @ om
         + np.sum(pts.mass[:, None] * np.cross(pts.r - cg, u), 0) + np.einsum("pij,pj->i", pts.inertia, w))
    kin = 0.5 * vel @ mass @ vel
    strain = 0.5 * eps @ structure.stiffness() @ eps
    cg_inertial = x + rot @ cg
    grav = -m_tot * structure.gravity_m_s2 @ cg_inertial
    return Conserved(float(kin), float(strain), float(grav), float(kin + strain + grav), rot @ p_body, rot @ h,
                     cg_inertial)


def free_free_frequencies(structure: FreeFlexibleStructure) -> NDArray[np.float64]:
    """Elastic natural frequencies [rad/s] of the free structure linearised about the undeformed state.

    About ``ε = 0, V = 0`` without gravity the velocity terms of eq. (1) are quadratic and drop out, leaving
    ``M(0) V̇ + [0; K ε] = 0``; eliminating the rigid-body accelerations (six zero-frequency modes) gives
    ``K ε = ω² (M_εε − M_εr M_rr⁻¹ M_rε) ε`` (Meirovitch & Tuzcu's free-free modes with the body's
    participation; the paper's eq. 2 linearised).

    Returns
    -------
    ndarray, shape (n,)
        Ascending.
    """
    if structure.n_strains == 0:
        return np.zeros(0)
    mass = generalized_mass_matrix(structure, np.zeros(structure.n_strains))
    mrr, mre, mee = mass[:6, :6], mass[:6, 6:], mass[6:, 6:]
    reduced = mee - mre.T @ np.linalg.solve(mrr, mre)
    lam = eigh(structure.stiffness(), 0.5 * (reduced + reduced.T), eigvals_only=True)
    return np.sqrt(np.clip(lam, 0.0, None))
