"""Geometrically exact strain-based beam: properties, kinematics from strains, mass and stiffness matrices.

Formulation: Su & Cesnik, *Strain-based geometrically nonlinear beam formulation for modeling very flexible
aircraft*, Int. J. Solids Struct. 48 (2011) 2349-2360 (eqs. 1-12), and Su & Cesnik, J. Aircraft 47(5) 2010; the
exponential map of SE(3) and its left Jacobian as in Barfoot, *State Estimation for Robotics* (2017) §7.1.4
(eqs. 7.80-7.86, 7.95). Design choice and alternatives: ``docs/design.md``, "Geometrically nonlinear beams".

Coordinates and frames
----------------------
* The beam of length ``L`` is divided into ``N`` elements of constant strain. Element ``j`` has the strain
  vector ``ε_j = [e, κ1, κ2, κ3]``: extension ``e`` [-], twist ``κ1``, flap (out-of-plane) curvature ``κ2`` and
  chordwise (in-plane) curvature ``κ3`` [1/m] (Su & Cesnik eq. 2). The generalized coordinates ``q`` are the
  free strains of all elements, element by element (``e`` is left out when the beam is inextensible).
* Each cross-section carries an orthonormal frame ``R = [e1, e2, e3]`` (columns, components in the global frame
  ``G``): ``e1`` along the reference (elastic) axis towards the tip, ``e2`` in the section plane towards the
  leading edge, ``e3 = e1 × e2`` (up for a wing). Along the element, ``dR/ds = R κ^`` and ``dp/ds = (1 + e) R e1``
  (Su & Cesnik eq. 1), so with constant strain the frame at arc length ``s`` from node ``j`` is
  ``T(s) = T_j exp(s ξ_j^)``, ``ξ_j = [(1 + e) e1, κ]`` — exact for any strain (a tip couple gives an exact
  circular arc with one element).
* ``T_0`` is the clamp: root position ``p0`` [m] and root rotation ``R0`` (any orientation).

Jacobians: the spatial twist of a variation, ``δT T⁻¹ = [[δθ^, δρ], [0, 0]]``, gives the virtual rotation
``δθ`` [rad] and the virtual displacement ``δp = δρ + δθ × p`` of any point. For ``T = T_k exp(ξ_k^) ...``,
``δT T⁻¹ = Σ_k Ad(T_k) 𝒥(ξ_k) δξ_k`` (𝒥: left Jacobian of SE(3)), so the point Jacobians ``J_p = ∂p/∂q``
[m per unit q] and ``J_θ`` (virtual rotation per unit q) are sums over the elements between the root and the
point. They map strain rates to the velocity of the point and the angular velocity of its section
(``v = J_p q̇``, ``ω = J_θ q̇``): the beam's kinematic map, the counterpart of ``G(q)`` in
:mod:`flexsim.structure.kinematic_map`, now nonlinear in ``q``.

Energies: strain energy ``U = ½ qᵀ K q`` with constant ``K = blockdiag(ℓ_j diag(EA, GJ, EI_flap, EI_chord))``
(Su & Cesnik eq. 6); kinetic energy ``T = ½ q̇ᵀ M(q) q̇``, ``M(q) = ∫ (m J_cᵀ J_c + J_θᵀ R I Rᵀ J_θ) ds``
(eq. 10 in strain form) with ``J_c`` the Jacobian of the section's mass centre, integrated by Gauss-Legendre
points along each element, plus the point masses carried by the beam (engines, stores: :class:`PointMass`), each a
rigid body fixed to the section at its station, ``m J_cᵀ J_c + J_θᵀ R I Rᵀ J_θ`` at its mass centre ``p + R o``
(Shearer & Cesnik 2007 eq. 12 with a concentrated mass; the paper's engines, eq. 6: ``v_e = v_w(r_we)``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flexsim._arrays import frozen_array
from flexsim.structure import _strain_kernels as _kern

__all__ = ["BeamProperties", "PointMass", "BeamKinematics", "MassPoints", "beam_kinematics", "mass_points",
           "station_kinematics", "stiffness_matrix", "mass_matrix", "se3_exp", "se3_left_jacobian", "STRAIN_NAMES"]

#: Names of the four strains of an element, in order.
STRAIN_NAMES = ("extension", "twist", "flap curvature", "chord curvature")


def _per_element(name: str, value, n: int, unit: str, *, allow_zero: bool = False) -> NDArray[np.float64]:
    """``value`` (scalar or length ``n``) as a read-only array of ``n`` finite numbers > 0 (>= 0 with allow_zero)."""
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be a number or {n} numbers [{unit}]") from None
    if arr.ndim == 0:
        arr = np.full(n, float(arr))
    if arr.shape != (n,):
        raise ValueError(f"{name} has shape {arr.shape}: must be a number or one value per element ({n}) [{unit}]")
    ok = np.isfinite(arr) & ((arr >= 0.0) if allow_zero else (arr > 0.0))
    if not np.all(ok):
        bad = float(arr[~ok][0])
        raise ValueError(f"{name} = {bad!r}: must be a finite number {'>=' if allow_zero else '>'} 0 [{unit}]")
    return frozen_array(arr)


@dataclass(frozen=True)
class PointMass:
    """A rigid mass fixed to a beam's section (an engine, a store, a tip body; validated, frozen).

    Parameters
    ----------
    station_m : float
        Undeformed arc length of the section it is fixed to [m], ``0 <= station_m <= L`` (checked by the beam).
    mass_kg : float
        Mass [kg], >= 0.
    offset_m : array_like, shape (3,)
        Its mass centre from the reference axis at the station, in the undeformed section frame ``[e1, e2, e3]``
        (along the span, towards the leading edge, normal) [m].
    inertia_kg_m2 : array_like, shape (3, 3)
        Inertia about its mass centre in the section frame [kg m²], symmetric.
    name : str
        Its name in messages.
    """

    station_m: float
    mass_kg: float
    offset_m: ArrayLike = field(default_factory=lambda: np.zeros(3))
    inertia_kg_m2: ArrayLike = field(default_factory=lambda: np.zeros((3, 3)))
    name: str = "point mass"

    def __post_init__(self) -> None:
        for attr, unit in (("station_m", "m"), ("mass_kg", "kg")):
            value = getattr(self, attr)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) \
                    or not np.isfinite(value) or value < 0.0:
                raise ValueError(f"{self.name}: {attr} = {value!r}: must be a finite number >= 0 [{unit}]")
            object.__setattr__(self, attr, float(value))
        offset = np.array(self.offset_m, dtype=float)
        if offset.shape != (3,) or not np.all(np.isfinite(offset)):
            raise ValueError(f"{self.name}: offset_m = {self.offset_m!r}: must be 3 finite numbers [m]")
        inertia = np.array(self.inertia_kg_m2, dtype=float)
        if inertia.shape != (3, 3) or not np.all(np.isfinite(inertia)) \
                or np.abs(inertia - inertia.T).max() > 1e-9 * max(1.0, np.abs(inertia).max()):
            raise ValueError(f"{self.name}: inertia_kg_m2 must be a finite symmetric 3 x 3 matrix [kg m^2]")
        object.__setattr__(self, "offset_m", frozen_array(offset))
        object.__setattr__(self, "inertia_kg_m2", frozen_array(0.5 * (inertia + inertia.T)))


@dataclass(frozen=True)
class BeamProperties:
    """A uniform-by-element, clamped, strain-based beam (validated, frozen).

    Parameters
    ----------
    length_m : float
        Undeformed length ``L`` [m].
    n_elements : int
        Number of constant-strain elements ``N`` (equal lengths ``L/N``).
    gj_nm2, ei_flap_nm2, ei_chord_nm2 : float or array of shape (N,)
        Torsional, flapwise (about ``e2``) and chordwise (about ``e3``) stiffness [N m²].
    mass_kg_per_m : float or array of shape (N,)
        Mass per unit length ``m`` [kg/m].
    ea_n : float or array of shape (N,) or None
        Axial stiffness [N]; None: inextensible (``e`` is not a coordinate).
    cg_offset_m : float or array of shape (N,)
        Mass centre ahead of the reference axis along ``e2`` (towards the leading edge) [m].
    torsion_inertia_kg_m, flap_inertia_kg_m, chord_inertia_kg_m : float or array of shape (N,)
        Section mass moments of inertia per length about the mass centre [kg m], about ``e1`` (torsion), ``e2``
        (rotary inertia of flapwise bending) and ``e3`` (of chordwise bending).
    root_position_m : array_like, shape (3,)
        Clamp position ``p0`` in the global frame [m].
    root_rotation : array_like, shape (3, 3)
        Clamp orientation ``R0`` (columns: ``e1, e2, e3`` of the root section in global components); orthonormal,
        right-handed.
    gauss_points : int
        Gauss-Legendre points per element for the mass matrix and distributed loads (1-6).
    point_masses : tuple of PointMass
        Rigid masses fixed to sections of the beam (default none).
    """

    length_m: float
    n_elements: int
    gj_nm2: ArrayLike
    ei_flap_nm2: ArrayLike
    ei_chord_nm2: ArrayLike
    mass_kg_per_m: ArrayLike
    ea_n: ArrayLike | None = None
    cg_offset_m: ArrayLike = 0.0
    torsion_inertia_kg_m: ArrayLike = 0.0
    flap_inertia_kg_m: ArrayLike = 0.0
    chord_inertia_kg_m: ArrayLike = 0.0
    root_position_m: ArrayLike = field(default_factory=lambda: np.zeros(3))
    root_rotation: ArrayLike = field(default_factory=lambda: np.eye(3))
    gauss_points: int = 3
    point_masses: tuple = ()

    def __post_init__(self) -> None:
        length = float(self.length_m) if isinstance(self.length_m, (int, float, np.floating)) else np.nan
        if not (np.isfinite(length) and length > 0.0):
            raise ValueError(f"length_m = {self.length_m!r}: must be a finite number > 0 [m]")
        object.__setattr__(self, "length_m", length)
        n = self.n_elements
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 1 <= n <= 1000:
            raise ValueError(f"n_elements = {n!r}: must be an integer in 1-1000")
        object.__setattr__(self, "n_elements", int(n))
        g = self.gauss_points
        if isinstance(g, bool) or not isinstance(g, (int, np.integer)) or not 1 <= g <= 6:
            raise ValueError(f"gauss_points = {g!r}: must be an integer in 1-6")
        for name, unit in (("gj_nm2", "N m^2"), ("ei_flap_nm2", "N m^2"), ("ei_chord_nm2", "N m^2"),
                           ("mass_kg_per_m", "kg/m")):
            object.__setattr__(self, name, _per_element(name, getattr(self, name), n, unit))
        if self.ea_n is not None:
            object.__setattr__(self, "ea_n", _per_element("ea_n", self.ea_n, n, "N"))
        for name in ("torsion_inertia_kg_m", "flap_inertia_kg_m", "chord_inertia_kg_m"):
            object.__setattr__(self, name, _per_element(name, getattr(self, name), n, "kg m", allow_zero=True))
        cg = np.array(self.cg_offset_m, dtype=float) * np.ones(n)
        if cg.shape != (n,) or not np.all(np.isfinite(cg)):
            raise ValueError(f"cg_offset_m = {self.cg_offset_m!r}: must be a finite number or {n} numbers [m]")
        object.__setattr__(self, "cg_offset_m", frozen_array(cg))
        p0 = np.array(self.root_position_m, dtype=float)
        if p0.shape != (3,) or not np.all(np.isfinite(p0)):
            raise ValueError(f"root_position_m = {self.root_position_m!r}: must be 3 finite numbers [m]")
        object.__setattr__(self, "root_position_m", frozen_array(p0))
        r0 = np.array(self.root_rotation, dtype=float)
        if r0.shape != (3, 3) or not np.all(np.isfinite(r0)):
            raise ValueError(f"root_rotation has shape {r0.shape}: must be a finite 3 x 3 rotation matrix")
        orth = np.abs(r0.T @ r0 - np.eye(3)).max()
        if orth > 1e-9 or np.linalg.det(r0) < 0.0:
            raise ValueError(f"root_rotation must be orthonormal and right-handed (|R^T R - I| = {orth:.2e}, "
                             f"det = {np.linalg.det(r0):.6f}; allowed: 1e-9 and +1)")
        object.__setattr__(self, "root_rotation", frozen_array(r0))
        masses = tuple(self.point_masses)
        for k, pm in enumerate(masses):
            if not isinstance(pm, PointMass):
                raise ValueError(f"point_masses[{k}] = {pm!r}: must be a PointMass")
            if pm.station_m > length * (1.0 + 1e-12):
                raise ValueError(f"point_masses[{k}] ({pm.name}): station_m = {pm.station_m!r}: must be within the "
                                 f"beam, 0-{length:g} [m]")
        object.__setattr__(self, "point_masses", masses)

    @property
    def extensible(self) -> bool:
        """True when the extension ``e`` of each element is a coordinate."""
        return self.ea_n is not None

    @property
    def strains_per_element(self) -> int:
        """4 (extensible) or 3."""
        return 4 if self.extensible else 3

    @property
    def n_coordinates(self) -> int:
        """Number of generalized coordinates ``n = N × strains_per_element``."""
        return self.n_elements * self.strains_per_element

    @property
    def element_length_m(self) -> float:
        """``ℓ = L/N`` [m]."""
        return self.length_m / self.n_elements

    def full_strains(self, q: ArrayLike) -> NDArray[np.float64]:
        """The strains ``[e, κ1, κ2, κ3]`` of every element, shape (N, 4), from ``q`` (``e = 0`` if inextensible)."""
        q = np.asarray(q, dtype=float)
        if q.shape != (self.n_coordinates,):
            raise ValueError(f"q has shape {q.shape}: must be ({self.n_coordinates},) for {self.n_elements} "
                             f"elements of {self.strains_per_element} strains")
        out = np.zeros((self.n_elements, 4))
        out[:, 4 - self.strains_per_element:] = q.reshape(self.n_elements, self.strains_per_element)
        return out

    def coordinate_name(self, index: int) -> str:
        """``"element j <strain>"`` for coordinate ``index`` (elements counted from 1 at the root)."""
        j, k = divmod(int(index), self.strains_per_element)
        return f"element {j + 1} {STRAIN_NAMES[k + 4 - self.strains_per_element]}"


def _hat(v: NDArray) -> NDArray:
    """Skew-symmetric matrices ``v^`` (``v^ w = v × w``), shape (..., 3, 3)."""
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def se3_exp(rho: ArrayLike, phi: ArrayLike) -> tuple[NDArray, NDArray]:
    """The exponential map of SE(3): ``exp([[φ^, ρ], [0, 0]]) = [[R, J(φ) ρ], [0, 1]]``.

    Source: Barfoot (2017) eqs. 7.80-7.83 (Rodrigues' formula and the SO(3) left Jacobian ``J``); compiled
    (:mod:`flexsim.structure._strain_kernels`).

    Parameters
    ----------
    rho, phi : array_like, shape (..., 3)
        Translation part [m] and rotation vector [rad].

    Returns
    -------
    R : ndarray, shape (..., 3, 3)
    p : ndarray, shape (..., 3)
        ``J(φ) ρ`` [m].
    """
    rho, phi = np.broadcast_arrays(np.asarray(rho, dtype=float), np.asarray(phi, dtype=float))
    shape = rho.shape[:-1]
    rot, pos = np.empty(shape + (3, 3)), np.empty(shape + (3,))
    _kern.se3_exp_batch(np.ascontiguousarray(rho.reshape(-1, 3)), np.ascontiguousarray(phi.reshape(-1, 3)),
                        rot.reshape(-1, 3, 3), pos.reshape(-1, 3))
    return rot, pos


def se3_left_jacobian(rho: ArrayLike, phi: ArrayLike) -> NDArray:
    """Left Jacobian 𝒥 of SE(3): ``exp((ξ + δξ)^) ≈ exp((𝒥 δξ)^) exp(ξ^)``, ξ = (ρ, φ).

    Source: Barfoot (2017) eqs. 7.85-7.86 (``𝒥 = [[J, Q], [0, J]]``; ``Q(ρ, φ)`` with the four θ-coefficients);
    checked against the Fréchet derivative of the matrix exponential (scipy.linalg.expm_frechet) in the tests.
    Compiled (:mod:`flexsim.structure._strain_kernels`).

    Parameters
    ----------
    rho, phi : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 6, 6)
        Ordering (translation, rotation) in rows and columns.
    """
    rho, phi = np.broadcast_arrays(np.asarray(rho, dtype=float), np.asarray(phi, dtype=float))
    out = np.empty(rho.shape[:-1] + (6, 6))
    _kern.se3_left_jacobian_batch(np.ascontiguousarray(rho.reshape(-1, 3)), np.ascontiguousarray(phi.reshape(-1, 3)),
                                  out.reshape(-1, 6, 6))
    return out


@dataclass(frozen=True, eq=False)
class BeamKinematics:
    """Frames and Jacobians of a beam at one set of strains (arrays in the global frame, SI).

    Attributes
    ----------
    q : ndarray, shape (n,)
        The strains evaluated.
    node_positions : ndarray, shape (N + 1, 3)
        Reference-axis positions of the nodes (root first) [m].
    node_rotations : ndarray, shape (N + 1, 3, 3)
        Section frames ``R`` at the nodes.
    points_s : ndarray, shape (P,)
        Undeformed arc length of the quadrature points [m] (``gauss_points`` per element, root to tip).
    points_weight : ndarray, shape (P,)
        Quadrature weights [m] (sum ``L``).
    points_element : ndarray of int, shape (P,)
    positions, rotations : ndarray, shapes (P, 3), (P, 3, 3)
        Reference-axis position [m] and section frame at the points.
    jac_position, jac_rotation : ndarray, shape (P, 3, n)
        ``∂p/∂q`` [m] and the virtual rotation per unit ``q`` at the points.
    tip_jac_position, tip_jac_rotation : ndarray, shape (3, n)
        The same at the tip node.
    """

    q: NDArray
    node_positions: NDArray
    node_rotations: NDArray
    points_s: NDArray
    points_weight: NDArray
    points_element: NDArray
    positions: NDArray
    rotations: NDArray
    jac_position: NDArray
    jac_rotation: NDArray
    tip_jac_position: NDArray
    tip_jac_rotation: NDArray

    @property
    def tip_position(self) -> NDArray:
        """Tip reference-axis position [m], shape (3,)."""
        return self.node_positions[-1]

    @property
    def tip_rotation(self) -> NDArray:
        """Tip section frame, shape (3, 3)."""
        return self.node_rotations[-1]


@lru_cache(maxsize=8)
def _gauss(n: int) -> tuple[NDArray, NDArray]:
    """Gauss-Legendre fractions of an element (0-1) and weights (sum 1) of ``n`` points (read-only; cached)."""
    x, w = np.polynomial.legendre.leggauss(n)
    return frozen_array(0.5 * (x + 1.0)), frozen_array(0.5 * w)


def beam_kinematics(beam: BeamProperties, q: ArrayLike) -> BeamKinematics:
    """Positions, rotations and Jacobians of the beam at strains ``q`` (Su & Cesnik 2011 eqs. 1-5, exact map).

    The chain of element transforms ``T_(j+1) = T_j exp(ℓ ξ_j^)`` and the point Jacobians (sums of the spatial
    twists ``Ad(T_k) 𝒥(ξ_k) ℓ B`` of the elements between the root and the point) are compiled
    (:func:`flexsim.structure._strain_kernels.beam_chain`).

    Parameters
    ----------
    beam : BeamProperties
    q : array_like, shape (n,)
        Element strains (``BeamProperties.full_strains`` order) [-, 1/m].

    Returns
    -------
    BeamKinematics
    """
    strains = beam.full_strains(q)
    n_el, ell, n = beam.n_elements, beam.element_length_m, beam.n_coordinates
    sigma, _ = _gauss(beam.gauss_points)
    n_points = n_el * sigma.size
    rots, poss = np.empty((n_el + 1, 3, 3)), np.empty((n_el + 1, 3))
    prot, ppos = np.empty((n_points, 3, 3)), np.empty((n_points, 3))
    jac_pos, jac_rot = np.empty((n_points, 3, n)), np.empty((n_points, 3, n))
    tip_pos, tip_rot = np.empty((3, n)), np.empty((3, n))
    _kern.beam_chain(strains, ell, beam.root_rotation, beam.root_position_m, sigma, 4 - beam.strains_per_element,
                     rots, poss, prot, ppos, jac_pos, jac_rot, tip_pos, tip_rot)
    elem, points_s, points_weight = _point_layout(n_el, beam.gauss_points, ell)
    return BeamKinematics(
        q=np.array(q, dtype=float), node_positions=poss, node_rotations=rots,
        points_s=points_s, points_weight=points_weight, points_element=elem,
        positions=ppos, rotations=prot, jac_position=jac_pos, jac_rotation=jac_rot,
        tip_jac_position=tip_pos, tip_jac_rotation=tip_rot)


@lru_cache(maxsize=64)
def _point_layout(n_el: int, n_gauss: int, ell: float) -> tuple[NDArray, NDArray, NDArray]:
    """Element index, arc length [m] and weight [m] of each quadrature point, root to tip (read-only; cached)."""
    sigma, weights = _gauss(n_gauss)
    elem = np.repeat(np.arange(n_el), n_gauss)
    return (frozen_array(elem, dtype=np.int64), frozen_array((elem + np.tile(sigma, n_el)) * ell),
            frozen_array(np.tile(weights, n_el) * ell))


def stiffness_matrix(beam: BeamProperties) -> NDArray[np.float64]:
    """Constant stiffness ``K = blockdiag(ℓ diag(EA, GJ, EI_flap, EI_chord))`` [N, N m²] × [m] (Su & Cesnik eq. 6).

    Returns
    -------
    ndarray, shape (n, n)
        Conjugate to ``q``: ``U = ½ qᵀ K q`` [J].
    """
    cols = [beam.gj_nm2, beam.ei_flap_nm2, beam.ei_chord_nm2]
    if beam.extensible:
        cols.insert(0, beam.ea_n)
    diag = np.stack(cols, axis=1).ravel() * beam.element_length_m
    return np.diag(diag)


@dataclass(frozen=True, eq=False)
class MassPoints:
    """The beam's masses as points (global components, SI): its sections' mass centres at the quadrature points
    (mass ``m w``, inertia ``diag(I_torsion, I_flap, I_chord) w``), then its point masses.

    Attributes
    ----------
    mass : ndarray, shape (Q,)
        [kg].
    r : ndarray, shape (Q, 3)
        Mass-centre positions [m].
    jac_c : ndarray, shape (Q, 3, n)
        ``∂r/∂q`` [m].
    rotations : ndarray, shape (Q, 3, 3)
        Frames of the sections carrying them.
    jac_rotation : ndarray, shape (Q, 3, n)
        Virtual rotation of those sections per unit ``q``.
    inertia_section : ndarray, shape (Q, 3, 3)
        Inertia about the mass centre in the section frame [kg m²].
    element : ndarray of int, shape (Q,)
    fraction : ndarray, shape (Q,)
        Element and fraction of its length (0-1) of each carrying section.
    offset : ndarray, shape (Q, 3)
        Mass centre from the reference axis, section frame [m].
    """

    mass: NDArray
    r: NDArray
    jac_c: NDArray
    rotations: NDArray
    jac_rotation: NDArray
    inertia_section: NDArray
    element: NDArray
    fraction: NDArray
    offset: NDArray


def station_kinematics(beam: BeamProperties, q: ArrayLike, stations_m: ArrayLike) -> tuple[NDArray, ...]:
    """Reference-axis positions (K, 3), section frames (K, 3, 3) and their Jacobians (K, 3, n) at stations along the
    beam [m] (the exact chain of :func:`beam_kinematics` evaluated at each station's element and fraction), plus the
    elements (K,) and fractions (K,)."""
    stations = np.atleast_1d(np.asarray(stations_m, dtype=float))
    strains = beam.full_strains(q)
    n_el, ell, n = beam.n_elements, beam.element_length_m, beam.n_coordinates
    k = stations.size
    pos, rot = np.empty((k, 3)), np.empty((k, 3, 3))
    jp, jr = np.empty((k, 3, n)), np.empty((k, 3, n))
    element = np.minimum((stations / ell).astype(np.int64), n_el - 1)
    fraction = np.clip(stations / ell - element, 0.0, 1.0)
    rots, poss = np.empty((n_el + 1, 3, 3)), np.empty((n_el + 1, 3))
    prot, ppos = np.empty((n_el, 3, 3)), np.empty((n_el, 3))
    jac_pos, jac_rot = np.empty((n_el, 3, n)), np.empty((n_el, 3, n))
    tip_pos, tip_rot = np.empty((3, n)), np.empty((3, n))
    for i in range(k):
        _kern.beam_chain(strains, ell, beam.root_rotation, beam.root_position_m, fraction[i:i + 1],
                         4 - beam.strains_per_element, rots, poss, prot, ppos, jac_pos, jac_rot, tip_pos, tip_rot)
        j = element[i]
        pos[i], rot[i], jp[i], jr[i] = ppos[j], prot[j], jac_pos[j], jac_rot[j]
    return pos, rot, jp, jr, element, fraction


def mass_points(beam: BeamProperties, kin: BeamKinematics) -> MassPoints:
    """The beam's sections (mass centre ``cg_offset_m`` ahead of the reference axis along e2) and point masses as
    mass points at the strains of ``kin`` (:class:`MassPoints`; ``J_c = J_p − (R o)^ J_θ``)."""
    e = kin.points_element
    w = kin.points_weight
    n_p = e.size
    offset = np.zeros((n_p, 3))
    offset[:, 1] = beam.cg_offset_m[e]
    inertia = np.zeros((n_p, 3, 3))
    inertia[:, 0, 0] = beam.torsion_inertia_kg_m[e] * w
    inertia[:, 1, 1] = beam.flap_inertia_kg_m[e] * w
    inertia[:, 2, 2] = beam.chord_inertia_kg_m[e] * w
    parts = [(beam.mass_kg_per_m[e] * w, kin.positions, kin.rotations, kin.jac_position, kin.jac_rotation, inertia,
              e, kin.points_s / beam.element_length_m - e, offset)]
    if beam.point_masses:
        pms = beam.point_masses
        pos, rot, jp, jr, el, fr = station_kinematics(beam, kin.q, [pm.station_m for pm in pms])
        parts.append((np.array([pm.mass_kg for pm in pms]), pos, rot, jp, jr,
                      np.array([pm.inertia_kg_m2 for pm in pms]), el, fr, np.array([pm.offset_m for pm in pms])))
    mass, p, rot, jp, jr, inertia, el, fr, offset = (np.concatenate(a) if len(parts) > 1 else a[0]
                                                      for a in zip(*parts))
    arm = np.einsum("pij,pj->pi", rot, offset)
    return MassPoints(mass, p + arm, jp - _hat(arm) @ jr, rot, jr, inertia, el, fr, offset)


def mass_matrix(beam: BeamProperties, kin: BeamKinematics) -> NDArray[np.float64]:
    """Mass matrix ``M(q) = ∫ (m J_cᵀ J_c + J_θᵀ R I Rᵀ J_θ) ds`` [kg, kg m, kg m²] (Su & Cesnik 2011 eq. 10),
    plus the point masses' ``m J_cᵀ J_c + J_θᵀ R I Rᵀ J_θ`` (:func:`mass_points`).

    Gauss-Legendre quadrature over each element (``beam.gauss_points`` points, exact kinematics at each).

    Returns
    -------
    ndarray, shape (n, n)
        Symmetric positive definite; ``T = ½ q̇ᵀ M q̇`` [J].
    """
    pts = mass_points(beam, kin)
    rt_j = np.einsum("pji,pjk->pik", pts.rotations, pts.jac_rotation)  # (Q, 3, n): ω in section axes
    trans = np.einsum("p,pji,pjk->ik", pts.mass, pts.jac_c, pts.jac_c)
    rotary = np.einsum("pji,pjl,plk->ik", rt_j, pts.inertia_section, rt_j)
    out = trans + rotary
    return 0.5 * (out + out.T)
