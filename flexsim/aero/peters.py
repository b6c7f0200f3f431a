"""Peters–Johnson finite-state generalized airloads for a deformable thin airfoil.

Implements the 2-D airloads of Tuzcu & Nguyen, *Flutter of Maneuvering Aircraft* (paper eqs. 25–26),
which take them from Peters & Johnson (1994), with the matrices derived from thin-airfoil theory in
``docs/reference/aero-kinematics.md`` §1 ("reference §1.x") and verified against Theodorsen.

Conventions (fixed once for the whole module)
---------------------------------------------
* Chord ``x ∈ [-b, b]``, leading edge (LE) at ``-b``, trailing edge (TE) at ``+b``; ``ξ = x/b = cos φ``.
* Deformation ``h(x, t)`` positive **down**, expanded in Chebyshev polynomials ``h = Σ h_n T_n(ξ)``
  (Glauert expansion); ``h_n`` in metres.
* Downwash ``w = ∂h/∂t + u0 ∂h/∂x = Σ w_n T_n`` [m/s]; positive ``w`` gives positive lift.
* ``λ0`` is the uniform wake-induced inflow [m/s], positive down: it reduces the effective downwash.
* ``L_n = ∫ Δp T_n(x/b) dx`` [N/m] with ``Δp = p_lower - p_upper`` (lift-positive projections).
  The generalized force conjugate to ``h_n`` is ``-L_n``.
* **Normalisation: πρ.** ``{L} = πρ{b²[M]{ḧ} + b u0[C]{ḣ} + u0²[K]{h} + b u̇0[G]{h} - b u0{S}λ0}``
  (reference §1.4). Peters' 2πρ form (paper eq. 25) has every matrix halved and the overall sign flipped
  (his ``L_n`` are the forces conjugate to ``h_n``).
* Rigid section with plunge ``h`` (down, at the elastic axis ``x = a b``), pitch ``α`` (nose up) and a
  rigid trailing-edge flap ``β`` (TE down) hinged at ``x = d b``: ``h_n = T [h, α, β]ᵀ`` (paper eq. 26).
* Section loads ``[L, M_EA, H]``: lift per span positive up, moment about the elastic axis nose up,
  flap hinge moment TE down; ``[L, M_EA, H] = diag(1, -1, -1) Tᵀ{L}`` (paper: ``[L Mα Mβ]ᵀ = TᵀL_n``
  with Peters' sign).

All functions are vectorised: leading axes ``(...)`` (e.g. strips) broadcast; the last axis is ``n``.
Matrix builders return ``(N, N)`` arrays (``{S}``: ``(N,)``), dimensionless.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flexsim._arrays import readonly

_LOAD_SIGNS = np.array([1.0, -1.0, -1.0])


def _check_n_terms(n_terms: object, minimum: int = 1) -> int:
    """Validate an expansion size: an ``int`` (not bool) ``>= minimum``."""
    if isinstance(n_terms, bool) or not isinstance(n_terms, (int, np.integer)) or n_terms < minimum:
        raise ValueError(f"n_terms must be an integer >= {minimum}; got {n_terms!r}")
    return int(n_terms)


def _col(x: ArrayLike) -> NDArray:
    """Append a trailing axis so a per-section scalar broadcasts against ``(..., n)`` vectors."""
    return np.asarray(x)[..., None]


def chebyshev_derivative_matrix(n_terms: int) -> NDArray[np.float64]:
    """Chebyshev derivative matrix [D], ``dT_m/dξ = Σ_n D_nm T_n`` (reference §1.2).

    ``D_0m = m`` for odd ``m``; ``D_nm = 2m`` for ``1 <= n < m`` with ``m - n`` odd; else 0. Strictly upper
    triangular, so truncation is exact. Gives ``{w} = {ḣ} + (u0/b)[D]{h}``.
    """
    n = _check_n_terms(n_terms)
    row, col = np.indices((n, n))
    odd_above = ((col - row) % 2 == 1) & (row < col)
    return np.where(odd_above, np.where(row == 0, col, 2 * col), 0).astype(float)


def apparent_mass_matrix(n_terms: int) -> NDArray[np.float64]:
    """Apparent-mass matrix [M], symmetric, multiplying ``πρb²{ḧ}`` (reference §1.4).

    ``M00 = 1``, ``M02 = M20 = -1/2``, ``M11 = 1/8``; ``M_nn = n/(2(n² - 1))`` for ``n >= 2``;
    ``M_{n,n+2} = M_{n+2,n} = -1/(4(n+1))`` for ``n >= 1``.
    """
    n = _check_n_terms(n_terms)
    idx = np.arange(n, dtype=float)
    diag = np.empty(n)
    diag[0] = 1.0
    diag[1:2] = 0.125
    diag[2:] = idx[2:] / (2.0 * (idx[2:] ** 2 - 1.0))
    mass = np.diag(diag)
    if n > 2:
        off = -1.0 / (4.0 * (idx[: n - 2] + 1.0))
        off[0] = -0.5
        mass += np.diag(off, 2) + np.diag(off, -2)
    return mass


def circulatory_matrix(n_terms: int) -> NDArray[np.float64]:
    """Circulatory matrix [B] multiplying ``πρ b u0{w}`` (reference §1.4).

    Row 0 = ``[2, 1, 0, ...]``; row 1 = ``[-1, 0, 1/2, 0, ...]``; row ``n >= 2``: ``-1/2`` at column
    ``n - 1`` and ``+1/2`` at column ``n + 1``.
    """
    n = _check_n_terms(n_terms)
    circ = np.diag(np.full(n - 1, 0.5), 1) + np.diag(np.full(n - 1, -0.5), -1)
    circ[0, 0] = 2.0
    if n > 1:
        circ[0, 1] = 1.0
        circ[1, 0] = -1.0
    return circ


def damping_matrix(n_terms: int) -> NDArray[np.float64]:
    """``[C] = [M][D] + [B]`` multiplying ``πρ b u0{ḣ}``.

    Reference §1.4: ``C00 = C01 = 2``, ``C10 = -1``, ``C12 = 1``, ``C_{n,n±1} = ±1`` (n >= 2).
    """
    return apparent_mass_matrix(n_terms) @ chebyshev_derivative_matrix(n_terms) + circulatory_matrix(n_terms)


def stiffness_matrix(n_terms: int) -> NDArray[np.float64]:
    """``[K] = [B][D]`` multiplying ``πρ u0²{h}`` (reference §1.4: ``K_0m = 2m``, ``K_nn = -n``)."""
    return circulatory_matrix(n_terms) @ chebyshev_derivative_matrix(n_terms)


def speed_rate_matrix(n_terms: int) -> NDArray[np.float64]:
    """``[G] = [M][D]`` multiplying ``πρ b u̇0{h}``.

    Reference §1.4: ``G01 = 1``, ``G12 = 1/2``, ``G_{n,n±1} = ±1/2`` (n >= 2).
    """
    return apparent_mass_matrix(n_terms) @ chebyshev_derivative_matrix(n_terms)


def inflow_load_vector(n_terms: int) -> NDArray[np.float64]:
    """``{S} = [2, -1, 0, ...]``; ``{L}`` contains ``-πρ b u0{S}λ0`` (reference §1.4; column 0 of [C])."""
    n = _check_n_terms(n_terms)
    vec = np.zeros(n)
    vec[0] = 2.0
    vec[1:2] = -1.0
    return vec


@dataclass(frozen=True, eq=False)
class PetersMatrices:
    """Read-only Peters–Johnson matrices of size ``n_terms`` (πρ normalisation, reference §1.2–1.4).

    Attributes
    ----------
    n_terms : int
    derivative, mass, circulatory, damping, stiffness, speed_rate : ndarray, shape (N, N)
        [D], [M], [B], [C], [K], [G].
    inflow : ndarray, shape (N,)
        {S}.
    """

    n_terms: int
    derivative: NDArray[np.float64]
    mass: NDArray[np.float64]
    circulatory: NDArray[np.float64]
    damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    speed_rate: NDArray[np.float64]
    inflow: NDArray[np.float64]


@lru_cache(maxsize=32)
def _build_matrices(n: int) -> PetersMatrices:
    builders = (
        chebyshev_derivative_matrix,
        apparent_mass_matrix,
        circulatory_matrix,
        damping_matrix,
        stiffness_matrix,
        speed_rate_matrix,
        inflow_load_vector,
    )
    return PetersMatrices(n, *(readonly(build(n)) for build in builders))


def peters_matrices(n_terms: int) -> PetersMatrices:
    """Cached :class:`PetersMatrices` of size ``n_terms >= 1`` (reference §1.4); ``ValueError`` otherwise."""
    return _build_matrices(_check_n_terms(n_terms))


def downwash(
    matrices: PetersMatrices, h: ArrayLike, h_dot: ArrayLike, u0: ArrayLike, b: ArrayLike
) -> NDArray:
    """Downwash coefficients ``{w} = {ḣ} + (u0/b)[D]{h}`` (reference §1.2).

    Parameters
    ----------
    matrices : PetersMatrices
    h, h_dot : array_like, shape (..., N)
        Deformation coefficients [m] (positive down) and their rates [m/s].
    u0, b : array_like, shape (...)
        Chordwise free-stream speed [m/s], semichord [m].

    Returns
    -------
    ndarray, shape (..., N)
        ``w_n`` [m/s].
    """
    return np.asarray(h_dot) + _col(np.asarray(u0) / np.asarray(b)) * (np.asarray(h) @ matrices.derivative.T)


def circulatory_downwash(w: ArrayLike) -> NDArray:
    """``w0 + w1/2`` (..., from ``w`` of shape (..., N >= 2)): drives circulation and the inflow model.

    Source: reference §1.2–1.3, §2.1 (Theodorsen's 3/4-chord downwash for a rigid section, paper eq. 27).
    Units of ``w`` (m/s, or m/s² for rates).
    """
    w = np.asarray(w)
    return w[..., 0] + 0.5 * w[..., 1]


def generalized_loads(
    matrices: PetersMatrices,
    h: ArrayLike,
    h_dot: ArrayLike,
    h_ddot: ArrayLike,
    u0: ArrayLike,
    u0_dot: ArrayLike,
    lambda0: ArrayLike,
    rho: ArrayLike,
    b: ArrayLike,
) -> NDArray:
    """Peters–Johnson generalized airloads (paper eq. 25, reference §1.4, πρ normalisation).

    ``{L} = πρ{b²[M]{ḧ} + b u0[C]{ḣ} + u0²[K]{h} + b u̇0[G]{h} - b u0{S}λ0}``.
    Rows ``0..N-1`` are exact for an ``N``-term deformation; ``L_N`` and ``L_{N+1}`` are non-zero too
    (pad ``h`` with two zeros to get them, as :class:`FlappedSection` does). Linear, so complex harmonic
    amplitudes may be passed.

    Parameters
    ----------
    matrices : PetersMatrices
    h, h_dot, h_ddot : array_like, shape (..., N)
        Deformation coefficients [m] (positive down) and their first and second time derivatives.
    u0, u0_dot : array_like, shape (...)
        Chordwise free-stream speed [m/s] and its rate [m/s²].
    lambda0, rho, b : array_like, shape (...)
        Inflow [m/s] (positive down), density [kg/m³], semichord [m].

    Returns
    -------
    ndarray, shape (..., N)
        ``L_n`` [N/m].
    """
    u0c, bc, h = _col(u0), _col(b), np.asarray(h)
    loads = (
        bc**2 * (np.asarray(h_ddot) @ matrices.mass.T)
        + bc * u0c * (np.asarray(h_dot) @ matrices.damping.T)
        + u0c**2 * (h @ matrices.stiffness.T)
        + bc * _col(u0_dot) * (h @ matrices.speed_rate.T)
        - bc * u0c * _col(lambda0) * matrices.inflow
    )
    return np.pi * _col(rho) * loads


def generalized_loads_from_downwash(
    matrices: PetersMatrices,
    w: ArrayLike,
    w_dot: ArrayLike,
    u0: ArrayLike,
    lambda0: ArrayLike,
    rho: ArrayLike,
    b: ArrayLike,
) -> NDArray:
    """Generalized airloads in downwash form, ``{L} = πρ{b²[M]{ẇ} + b u0([B]{w} - {S}λ0)}``.

    Source: reference §1.3 (closed form).

    Identical to :func:`generalized_loads` when ``{w} = {ḣ} + (u0/b)[D]{h}``; convenient when rigid-body
    velocities are added to the downwash (paper eq. 25: ``ḣ_n + v_n``).

    Parameters
    ----------
    matrices : PetersMatrices
    w, w_dot : array_like, shape (..., N)
        Downwash coefficients [m/s] and their rates [m/s²].
    u0, lambda0, rho, b : array_like, shape (...)
        Free-stream speed [m/s], inflow [m/s] (positive down), density [kg/m³], semichord [m].

    Returns
    -------
    ndarray, shape (..., N)
        ``L_n`` [N/m].
    """
    u0c, bc = _col(u0), _col(b)
    loads = bc**2 * (np.asarray(w_dot) @ matrices.mass.T) + bc * u0c * (
        np.asarray(w) @ matrices.circulatory.T - _col(lambda0) * matrices.inflow
    )
    return np.pi * _col(rho) * loads


def peters_drag(
    matrices: PetersMatrices,
    h: ArrayLike,
    w: ArrayLike,
    loads: ArrayLike,
    lambda0: ArrayLike,
    rho: ArrayLike,
    b: ArrayLike,
) -> NDArray:
    """Chordwise (drag) force per span of the deformable airfoil, positive aft (along the free stream).

    **Derived here**, not transcribed: Peters & Johnson's (1994) drag matrices [S], [H] of paper eq. 25
    were not available. Drag = pressure on the slope of the deformed camber line minus leading-edge
    suction, ``D = (1/b)([D]{h})ᵀ{L} - 2πρ b (w0 - λ0)²``. The first term is ``∫Δp ∂h/∂x dx`` with
    ``∂h/∂x = (1/b)Σ([D]h)_n T_n``. The suction ``(πρb/8)s²`` comes from the leading-edge singularity
    ``s/sin φ`` of the bound vorticity, ``s = 4(w0 - λ0)`` in the Peters model (reference §1.3 step 1
    with downwash ``w - λ0``); with ``λ0 = (1 - C)(w0 + w1/2)`` it equals the value
    ``s = 2[2C(k)(w0 + w1/2) - w1]`` obtained from Theodorsen's wake vortices. Tested: zero drag in
    steady flow for any camber or flap (d'Alembert) and Garrick's (NACA Rep. 567) mean plunge thrust
    ``πρbω²h̄²|C(k)|²``. No skin friction.

    Parameters
    ----------
    matrices : PetersMatrices
    h, w, loads : array_like, shape (..., N)
        Deformation [m], downwash [m/s] and ``L_n`` [N/m] (from :func:`generalized_loads`).
    lambda0, rho, b : array_like, shape (...)
        Inflow [m/s], density [kg/m³], semichord [m].

    Returns
    -------
    ndarray, shape (...)
        Drag per unit span [N/m] along the reference chord; negative values are thrust.
    """
    slope = np.asarray(h) @ matrices.derivative.T
    pressure = np.sum(slope * np.asarray(loads), axis=-1) / np.asarray(b)
    effective = np.asarray(w)[..., 0] - np.asarray(lambda0)
    suction = 2.0 * np.pi * np.asarray(rho) * np.asarray(b) * effective**2
    return pressure - suction


def flap_shape_coefficients(n_terms: int, d: ArrayLike) -> NDArray[np.float64]:
    """Chebyshev coefficients ``F_n`` of a unit rigid trailing-edge flap rotation.

    Source: reference §1.6, paper eq. 26. For a flap rotation ``β`` (TE down) hinged at ``x = d b``:
    ``h(x) = β(x - d b)`` for ``x >= d b`` and ``h_n = b β F_n``; with ``φ_h = acos d``:
    ``F_0 = (sin φ_h - d φ_h)/π``, ``F_1 = (φ_h - d sin φ_h)/π``,
    ``F_n = [sin((n-1)φ_h)/(n-1) - sin((n+1)φ_h)/(n+1)]/(πn)`` for ``n >= 2``.

    Parameters
    ----------
    n_terms : int
        Number of coefficients ``N >= 1``.
    d : array_like, shape (...)
        Hinge position in semichords from mid-chord, ``-1 < d < 1``.

    Returns
    -------
    ndarray, shape (..., N)
        Dimensionless.
    """
    n = _check_n_terms(n_terms)
    d = np.asarray(d, dtype=float)
    if not np.all((d > -1.0) & (d < 1.0)):
        raise ValueError(f"flap hinge position d must satisfy -1 < d < 1 (semichords); got {d!r}")
    d = d[..., None]
    phi = np.arccos(d)
    order = np.arange(n, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        lower = np.sin((order - 1) * phi) / (order - 1)
        coeffs = (lower - np.sin((order + 1) * phi) / (order + 1)) / (np.pi * order)
    coeffs[..., 0:1] = (np.sin(phi) - d * phi) / np.pi
    if n > 1:
        coeffs[..., 1:2] = (phi - d * np.sin(phi)) / np.pi
    return coeffs


def transformation_matrix(n_terms: int, a: ArrayLike, d: ArrayLike, b: ArrayLike) -> NDArray[np.float64]:
    """Transformation ``T``, ``h_n = T[h, α, β]ᵀ`` (paper eq. 26; reference §1.2, §1.6).

    Columns: ``h`` (plunge at the EA, down) ``[1, 0, ...]``; ``α`` (nose up) ``[-ab, b, 0, ...]``;
    ``β`` (flap, TE down) ``b F_n``.

    Parameters
    ----------
    n_terms : int
        Expansion size ``N >= 2``.
    a, d : array_like, shape (...)
        Elastic axis and hinge, semichords from mid-chord (aft positive), ``-1 < d < 1``.
    b : array_like, shape (...)
        Semichord [m].

    Returns
    -------
    ndarray, shape (..., N, 3)
        [m/m, m/rad, m/rad].
    """
    n = _check_n_terms(n_terms, minimum=2)
    a, d, b = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (a, d, b)))
    transform = np.zeros(a.shape + (n, 3))
    transform[..., 0, 0] = 1.0
    transform[..., 0, 1] = -a * b
    transform[..., 1, 1] = b
    transform[..., :, 2] = b[..., None] * flap_shape_coefficients(n, d)
    return transform


@dataclass(frozen=True, eq=False)
class FlappedSection:
    """Section with plunge, pitch and a rigid flap, ``q = [h, α, β]`` (paper eqs. 25–26).

    Built by :func:`flapped_section`.

    The deformation is truncated at ``n_terms`` coefficients; loads are carried to ``n_terms + 2`` rows
    so the hinge moment is the exact virtual work of the truncated deformation's pressure. Geometry may
    be per strip (``a, d, b`` of shape (S,)); then ``q`` is (..., S, 3) and the outputs (..., S, ...).

    Method arguments: ``q, q_dot, q_ddot`` shape (..., 3) = ``[h (m, down at the EA), α (rad, nose up),
    β (rad, TE down)]`` and time derivatives; ``u0, u0_dot, lambda0, rho`` shape (...) = free-stream
    speed [m/s] and rate [m/s²], inflow [m/s] (positive down), density [kg/m³].

    Attributes
    ----------
    n_terms : int
    a, d, b : ndarray, shape () or (S,)
        Elastic axis and hinge [semichords], semichord [m].
    deformation : ndarray, shape ([S,] N + 2, 3)
        ``T`` with rows ``>= N`` zeroed: ``h_n = deformation @ q``.
    projection : ndarray, shape ([S,] N + 2, 3)
        Full ``T`` for ``[L, M_EA, H] = diag(1, -1, -1) projectionᵀ{L}``.
    matrices : PetersMatrices
        Size ``N + 2``.
    """

    n_terms: int
    a: NDArray[np.float64]
    d: NDArray[np.float64]
    b: NDArray[np.float64]
    deformation: NDArray[np.float64]
    projection: NDArray[np.float64]
    matrices: PetersMatrices

    def _h(self, q: ArrayLike) -> NDArray:
        return np.einsum("...k,...nk->...n", np.asarray(q), self.deformation)

    def downwash(self, q: ArrayLike, q_dot: ArrayLike, u0: ArrayLike) -> NDArray:
        """``w_n`` (..., N + 2) [m/s] (reference §1.2); ``circulatory_downwash`` of it enters eq. 27."""
        return downwash(self.matrices, self._h(q), self._h(q_dot), u0, self.b)

    def generalized_loads(
        self,
        q: ArrayLike,
        q_dot: ArrayLike,
        q_ddot: ArrayLike,
        u0: ArrayLike,
        u0_dot: ArrayLike,
        lambda0: ArrayLike,
        rho: ArrayLike,
    ) -> NDArray:
        """All non-zero ``L_n`` (..., N + 2) [N/m] (paper eq. 25 with ``h_n = Tq``)."""
        h, hd, hdd = self._h(q), self._h(q_dot), self._h(q_ddot)
        return generalized_loads(self.matrices, h, hd, hdd, u0, u0_dot, lambda0, rho, self.b)

    def loads(
        self,
        q: ArrayLike,
        q_dot: ArrayLike,
        q_ddot: ArrayLike,
        u0: ArrayLike,
        u0_dot: ArrayLike,
        lambda0: ArrayLike,
        rho: ArrayLike,
    ) -> NDArray:
        """``[L, M_EA, H]`` (..., 3) (reference §1.5).

        Lift [N/m] up, moment about the EA [N] nose up, hinge moment [N] TE down. Linear: complex
        harmonic amplitudes with ``λ0 = (1 - C(k))(w0 + w1/2)`` give the paper's eq. 27 model.
        """
        loads = self.generalized_loads(q, q_dot, q_ddot, u0, u0_dot, lambda0, rho)
        return np.einsum("...n,...nk->...k", loads, self.projection) * _LOAD_SIGNS

    def drag(
        self,
        q: ArrayLike,
        q_dot: ArrayLike,
        q_ddot: ArrayLike,
        u0: ArrayLike,
        u0_dot: ArrayLike,
        lambda0: ArrayLike,
        rho: ArrayLike,
    ) -> NDArray:
        """Drag (...) [N/m], positive aft along the reference chord; see :func:`peters_drag` (real inputs)."""
        loads = self.generalized_loads(q, q_dot, q_ddot, u0, u0_dot, lambda0, rho)
        w = self.downwash(q, q_dot, u0)
        return peters_drag(self.matrices, self._h(q), w, loads, lambda0, rho, self.b)


def flapped_section(n_terms: int, a: ArrayLike, d: ArrayLike, b: ArrayLike) -> FlappedSection:
    """Precompute a :class:`FlappedSection` (paper eqs. 25–26), one section or one per strip.

    Parameters
    ----------
    n_terms : int
        Deformation expansion size ``N >= 2``; the flap loads converge as ``O(1/N)`` (reference §1.7),
        plunge/pitch loads are exact for any ``N``.
    a, d : float or array_like, shape (S,)
        Elastic axis and hinge [semichords from mid-chord, aft positive].
    b : float or array_like, shape (S,)
        Semichord [m].

    Returns
    -------
    FlappedSection
    """
    n = _check_n_terms(n_terms, minimum=2)
    geometry = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (a, d, b)))
    a, d, b = (readonly(x.copy()) for x in geometry)
    projection = transformation_matrix(n + 2, a, d, b)
    deformation = projection.copy()
    deformation[..., n:, :] = 0.0
    return FlappedSection(n, a, d, b, readonly(deformation), readonly(projection), peters_matrices(n + 2))
