"""Strip airloads on the strain-based beam and the linear aeroelastic system about a deformed equilibrium.

The coupling of :mod:`flexsim.structure.strain_beam` (geometrically exact beam) with flexsim's 2-D aerodynamics
(:mod:`flexsim.aero.peters`: Peters-Johnson airloads of a rigid section in the downwash form, reference §1.3-1.4;
:mod:`flexsim.aero.inflow`: Peters' finite-state inflow, Peters, Karunamoorthy & Cao 1995, reference §2.1), for a
wing clamped in a wind tunnel. Strips sit at the beam's quadrature points and follow the deformed sections: each
strip's chordwise speed ``u0 = −V_a·e2`` and normal ``w = V_a·e3`` come from its own frame ``[e1, e2, e3]`` (so
dihedral, twist and sweep of the deformed wing all enter), the spanwise component of the flow is ignored (strip
theory). Thin-airfoil lift slope 2π (no tip loss) or a given spanwise lift slope (:class:`WingAero`), no drag
but the leading-edge suction of the Peters model (the resultant of a steady strip is normal to the wind: lift
2πρbU² sin α, no drag).

Frames and units: global frame of the tunnel (the beam's), free stream ``V_a = U d`` [m/s] along the unit vector
``d`` (default ``−y``: from the leading edge of an unpitched wing whose ``e2 = y``); loads per unit length: force
[N/m] in global components at the reference axis, moment [N] (N m/m) about it. Reference-axis position in the
chord: ``a`` semichords aft of mid-chord, ``a = 2 × axis_fraction − 1``.

Linearisation about a static equilibrium ``q0`` (rates zero, inflow zero), exact to first order:
``M(q0) δq̈ + K_T δq = δQ_a(δq̇, δq̈, λ)`` with ``K_T = K − ∂Q_ext/∂q − ∂Q_steady/∂q`` (the preload's geometric
stiffness and the steady airloads' stiffness of the deformed strips, by central differences; the steady loads are
``U²`` times those at unit speed) and the unsteady loads linear in the strip motions:
``δw0 = −(e3ᵀJ_p + a b e1ᵀJ_θ) δq̇``, ``δw1 = b e1ᵀJ_θ δq̇``, ``δu0 = e2ᵀJ_p δq̇``, ``δẇ0 = −(e3ᵀJ_p + a b e1ᵀJ_θ) δq̈
+ (e3 × V_a)ᵀJ_θ δq̇``, ``δẇ1 = b e1ᵀJ_θ δq̈``; ``{L} = πρ{b²[M]{ẇ} + b u0([B]{w} − {S}λ0)}`` (reference §1.3);
``[L, M_EA] = diag(1, −1) Tᵀ{L}`` (paper eq. 26); suction ``2πρ b (w0 − λ0)²`` forward along ``e2``;
``[A]λ̇ + (u0/b)λ = {c}(ẇ0 + ẇ1/2)`` per strip.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from numba import njit
from numpy.typing import ArrayLike, NDArray

from flexsim._arrays import frozen_array
from flexsim.aero.inflow import inflow_coefficients
from flexsim.aero.peters import peters_matrices
from flexsim.structure.beam_statics import LoadModel, load_stiffness
from flexsim.structure.strain_beam import (BeamKinematics, BeamProperties, beam_kinematics, mass_matrix,
                                           stiffness_matrix)

__all__ = ["WingAero", "TunnelFlow", "section_loads", "StripAirloads", "LoadSum", "AeroelasticSystem", "aeroelastic_system",
           "static_stiffness", "peters_strip_terms", "inflow_columns", "set_inflow_rows"]


@dataclass(frozen=True)
class WingAero:
    """Strip aerodynamics of a beam (validated, frozen).

    Parameters
    ----------
    chord_m : float or array of shape (N,)
        Chord per element [m].
    axis_fraction : float or array of shape (N,)
        Reference (elastic) axis position aft of the leading edge, as a fraction of the chord, in (0, 1).
    inflow_states : int
        Peters finite-state inflow states per strip, 1-10 (default 6).
    lift_slope_per_rad : float or array of shape (N,)
        Sectional lift slope per element [1/rad], in [0, 4π] (default 2π: thin airfoil). A spanwise distribution
        (e.g. one falling to 0 at the tip: tip loss) scales each strip's airloads, steady and unsteady, by
        ``lift_slope / 2π`` — as if the strip's air density were scaled — so that the strip keeps thin-airfoil
        theory's centre of pressure and unsteady behaviour (the usual strip-theory correction, e.g. Riso & Cesnik,
        J. Aircraft 2023, doi 10.2514/1.C036869).
    compressibility_beta : float
        Prandtl-Glauert's ``β = √(1 − M²)`` in (0, 1] (Glauert 1928; default 1: incompressible): the circulatory
        airloads (lift, moment, suction and the wake's) scale by ``1/β`` further, the apparent mass does not (the linear
        strips' correction, :func:`flexsim._kernels.strips.circulatory`).
    """

    chord_m: ArrayLike
    axis_fraction: ArrayLike = 0.5
    inflow_states: int = 6
    lift_slope_per_rad: ArrayLike = 2.0 * np.pi
    compressibility_beta: float = 1.0

    def __post_init__(self) -> None:
        chord = np.atleast_1d(np.array(self.chord_m, dtype=float))
        if not np.all(np.isfinite(chord) & (chord > 0)):
            raise ValueError(f"chord_m = {self.chord_m!r}: must be finite numbers > 0 [m]")
        frac = np.atleast_1d(np.array(self.axis_fraction, dtype=float))
        if not np.all(np.isfinite(frac) & (frac > 0) & (frac < 1)):
            raise ValueError(f"axis_fraction = {self.axis_fraction!r}: must be numbers in (0, 1) (of the chord, "
                             "from the leading edge)")
        object.__setattr__(self, "chord_m", frozen_array(chord))
        object.__setattr__(self, "axis_fraction", frozen_array(frac))
        inflow_coefficients(self.inflow_states)  # validates 1-10 with a message naming n_states
        slope = np.atleast_1d(np.array(self.lift_slope_per_rad, dtype=float))
        if not np.all(np.isfinite(slope) & (slope >= 0) & (slope <= 4.0 * np.pi)):
            raise ValueError(f"lift_slope_per_rad = {self.lift_slope_per_rad!r}: must be numbers in [0, 4π] "
                             "[1/rad]")
        object.__setattr__(self, "lift_slope_per_rad", frozen_array(slope))
        beta = self.compressibility_beta
        if isinstance(beta, bool) or not isinstance(beta, (int, float, np.floating)) or not 0.0 < beta <= 1.0:
            raise ValueError(f"compressibility_beta = {beta!r}: must be a number in (0, 1] (sqrt(1 - M^2))")
        object.__setattr__(self, "compressibility_beta", float(beta))

    def strips(self, beam: BeamProperties, kin: BeamKinematics) -> tuple[NDArray, NDArray]:
        """Semichord ``b`` [m] and axis position ``a`` [semichords aft of mid-chord] at the quadrature points."""
        n = beam.n_elements
        for name, arr in (("chord_m", self.chord_m), ("axis_fraction", self.axis_fraction),
                          ("lift_slope_per_rad", self.lift_slope_per_rad)):
            if arr.size not in (1, n):
                raise ValueError(f"{name} has {arr.size} values: must be one or one per element ({n})")
        e = kin.points_element
        return 0.5 * _at_points(self.chord_m, n, e), 2.0 * _at_points(self.axis_fraction, n, e) - 1.0

    def density_scale(self, beam: BeamProperties, kin: BeamKinematics) -> NDArray:
        """``lift_slope / (2π β)`` at the quadrature points (the factor on each strip's circulatory airloads; the
        apparent mass's is ``lift_slope / 2π``)."""
        return (_at_points(self.lift_slope_per_rad, beam.n_elements, kin.points_element)
                / (2.0 * np.pi * self.compressibility_beta))


def _at_points(values: NDArray, n: int, element: NDArray) -> NDArray:
    """Per-element ``values`` (one, or one per element of n) at points on the elements ``element``."""
    return values[element] if values.size == n else np.full(element.shape, values[0])


@dataclass(frozen=True)
class TunnelFlow:
    """Free stream of a wind tunnel (validated, frozen).

    Parameters
    ----------
    speed_m_s : float
        ``U`` >= 0 [m/s].
    density_kg_m3 : float
        ``ρ`` > 0 [kg/m³].
    direction : array_like, shape (3,)
        Unit vector of the free stream in the global frame (default ``(0, −1, 0)``).
    """

    speed_m_s: float
    density_kg_m3: float
    direction: ArrayLike = field(default_factory=lambda: np.array([0.0, -1.0, 0.0]))

    def __post_init__(self) -> None:
        for name, allow_zero in (("speed_m_s", True), ("density_kg_m3", False)):
            v = getattr(self, name)
            ok = isinstance(v, (int, float, np.floating)) and not isinstance(v, bool) and np.isfinite(v)
            if not ok or v < 0 or (v == 0 and not allow_zero):
                raise ValueError(f"{name} = {v!r}: must be a finite number {'>=' if allow_zero else '>'} 0")
        d = np.array(self.direction, dtype=float)
        if d.shape != (3,) or not np.all(np.isfinite(d)) or abs(np.linalg.norm(d) - 1.0) > 1e-9:
            raise ValueError(f"direction = {self.direction!r}: must be a unit vector of 3 numbers")
        object.__setattr__(self, "direction", frozen_array(d))

    @property
    def velocity_m_s(self) -> NDArray:
        """``V_a = U d`` [m/s], shape (3,)."""
        return self.speed_m_s * self.direction


@lru_cache(maxsize=4)
def _section_matrices():
    """Peters-Johnson [M], [B], {S} of a rigid section (2 Chebyshev terms: exact rows 0, 1; reference §1.4)."""
    m = peters_matrices(2)
    return m.mass, m.circulatory, m.inflow


def section_loads(rotations: NDArray, b: NDArray, a: NDArray, air_velocity: NDArray, rho: NDArray | float, *,
                  rate_e1: NDArray | float = 0.0, incidence: NDArray | float = 0.0,
                  cd0: NDArray | float = 0.0, induced: NDArray | float = 0.0,
                  lift_scale: NDArray | float = 1.0) -> tuple[NDArray, NDArray]:
    """Quasi-steady strip loads per unit span (inflow zero) of sections in a flow (module docstring).

    Peters-Johnson airloads of a rigid section (reference §1.3-1.4, ``{L} = πρ b u0 [B]{w}`` with the inflow
    ``λ0 = 0``), resolved as in the module docstring: lift along ``e3``, leading-edge suction along ``e2`` (with an
    incidence, the suction that keeps the steady resultant normal to the wind: :func:`_section_loads_kernel`), moment
    about the reference axis along ``e1``; plus, when ``cd0`` is given, a profile drag ``½ρ|V|² 2b cd0`` along the
    in-section air velocity (the linear model's physical force resolution, paper eq. 28 with
    ``docs/design.md`` "Force resolution").

    Parameters
    ----------
    rotations : ndarray, shape (P, 3, 3)
        Section frames ``[e1, e2, e3]`` (columns): span, towards the leading edge, normal (``e3 = e1 × e2``).
    b, a : ndarray, shape (P,)
        Semichord [m]; reference-axis position [semichords aft of mid-chord].
    air_velocity : ndarray, shape (P, 3) or (3,)
        Air velocity relative to the section's reference axis [m/s], in the frames' components.
    rho : float or ndarray, shape (P,)
        Air density [kg/m³].
    rate_e1 : float or ndarray, shape (P,)
        Section angular velocity about ``e1`` [rad/s] (pitch rate: ``w1 = b Ω1``, ``w0`` at mid-chord ``−a b Ω1``).
    incidence : float or ndarray, shape (P,)
        Nose-up incidence added to the section [rad] (rigging, or a flap's equivalent angle ``τ δ``).
    cd0 : float or ndarray, shape (P,)
        Profile drag coefficient [-].
    induced : float or ndarray, shape (P,)
        ``(1 − Cl_α0/2π)/β`` of a strip whose lift slope is a finite wing's: its induced drag ``L α_e (1 − Cl_α0/2π)/β``
        along the in-section air velocity (``α_e = w0/u0``), the linear model's (:mod:`flexsim._kernels.strips`,
        ``circulatory``, physical formulation); 0 (default) for none.
    lift_scale : float or ndarray, shape (P,)
        ``Cl_α / 2π`` of the circulatory loads (lift, moment and suction): a corrected lift slope
        (:meth:`WingAero.density_scale`) over the compressibility factor ``β`` (Prandtl-Glauert, Glauert 1928); the
        profile drag is not scaled. Default 1.

    Returns
    -------
    force, moment : ndarray, shape (P, 3)
        [N/m] and [N m/m] in the frames' components.
    """
    _, bm, _ = _section_matrices()
    rotations = np.asarray(rotations, dtype=float)
    p = rotations.shape[0]
    force, moment = np.empty((p, 3)), np.empty((p, 3))
    _section_loads_kernel(_strip_array(rotations, (p, 3, 3)), _strip_array(b, (p,)), _strip_array(a, (p,)),
                          _strip_array(air_velocity, (p, 3)), _strip_array(rho, (p,)), _strip_array(rate_e1, (p,)),
                          _strip_array(incidence, (p,)), _strip_array(cd0, (p,)), _strip_array(induced, (p,)),
                          _strip_array(lift_scale, (p,)), bm, force, moment)
    return force, moment


def _strip_array(value, shape: tuple) -> NDArray:
    """``value`` broadcast to ``shape`` as a C-contiguous float array (no copy when it already is one)."""
    arr = np.asarray(value, dtype=float)
    if arr.shape == shape and arr.flags.c_contiguous:
        return arr
    out = np.empty(shape)
    out[...] = arr
    return out


@njit(cache=True, nogil=True)
def _section_loads_kernel(rotations, b, a, va, rho, rate, incidence, cd0, induced, lift_scale, bm, force, moment):
    """The loads of :func:`section_loads` strip by strip (compiled; arguments broadcast to P strips).

    ``u0 = −e2·V_a``, ``w_n = e3·V_a``, ``w1 = b Ω1``, ``w0 = w_n + u0 α_i − a w1``; ``{L} = πρ s b u0 [B]{w}``
    (``s`` the lift scale); lift ``L0`` along e3, moment ``a b L0 − b L1`` along e1, suction
    ``2πρ s b w0 (w0 − u0 α_i)`` along e2, profile
    drag ``ρ b cd0 |V_in| V_in`` and induced drag ``L0 (w0/u0) (1 − Cl_α/2π)`` along the in-section air velocity
    ``V_in = w_n e3 − u0 e2``. The incidence ``α_i``
    (rigging or a flap's equivalent angle) changes the circulation, not the direction of the resultant: a steady
    strip's lift and suction add to ``2πρ b w0 (w_n e2 + u0 e3)``, normal to ``V_in`` (Kutta-Joukowski: no force
    along the wind without drag), where ``w0²`` would tilt it by ``α_i`` and make a flap produce thrust.
    """
    for k in range(rotations.shape[0]):
        r = rotations[k]
        u0 = -(r[0, 1] * va[k, 0] + r[1, 1] * va[k, 1] + r[2, 1] * va[k, 2])
        wn = r[0, 2] * va[k, 0] + r[1, 2] * va[k, 1] + r[2, 2] * va[k, 2]
        w1 = b[k] * rate[k]
        w0 = wn + u0 * incidence[k] - a[k] * w1
        scale = np.pi * rho[k] * lift_scale[k] * b[k] * u0
        gen0 = scale * (bm[0, 0] * w0 + bm[0, 1] * w1)
        gen1 = scale * (bm[1, 0] * w0 + bm[1, 1] * w1)
        mom = a[k] * b[k] * gen0 - b[k] * gen1
        suction = 2.0 * np.pi * rho[k] * lift_scale[k] * b[k] * w0 * (w0 - u0 * incidence[k])
        drag = 0.0
        if cd0[k] != 0.0 or induced[k] != 0.0:
            speed = np.sqrt(wn * wn + u0 * u0)
            if cd0[k] != 0.0:
                drag = rho[k] * b[k] * cd0[k] * speed
            if induced[k] != 0.0 and u0 != 0.0 and speed > 0.0:
                drag += gen0 * (w0 / u0) * induced[k] / speed  # L alpha_e (1 - Cl_a/2 pi) along V_in / |V_in|
        for i in range(3):
            force[k, i] = gen0 * r[i, 2] + suction * r[i, 1] + drag * (wn * r[i, 2] - u0 * r[i, 1])
            moment[k, i] = mom * r[i, 0]


def _steady_section_loads(kin, b, a, flow, scale=1.0):
    """Steady strip force [N/m] (P, 3) and moment [N] (P, 3) in global components (inflow zero, no rates).

    ``scale``: ``lift_slope / 2π`` per strip, shape (P,) or scalar (:meth:`WingAero.density_scale`).
    """
    return section_loads(kin.rotations, b, a, flow.velocity_m_s, flow.density_kg_m3, lift_scale=scale)


@dataclass(frozen=True)
class StripAirloads:
    """Steady strip airloads following the deformed strips (a :class:`~flexsim.structure.beam_statics.LoadModel`).

    Parameters
    ----------
    aero : WingAero
    flow : TunnelFlow
    """

    aero: WingAero
    flow: TunnelFlow

    def generalized_force(self, beam: BeamProperties, kin: BeamKinematics) -> NDArray[np.float64]:
        """``Q = Σ w (J_pᵀ F + J_θᵀ M)`` of the steady strip loads (virtual work; Su & Cesnik 2011 eq. 13)."""
        b, a = self.aero.strips(beam, kin)
        force, moment = _steady_section_loads(kin, b, a, self.flow, self.aero.density_scale(beam, kin))
        w = kin.points_weight[:, None]
        n = kin.jac_position.shape[-1]
        return ((w * force).reshape(-1) @ kin.jac_position.reshape(-1, n)
                + (w * moment).reshape(-1) @ kin.jac_rotation.reshape(-1, n))


@dataclass(frozen=True)
class LoadSum:
    """The sum of several load models (each a :class:`~flexsim.structure.beam_statics.LoadModel`)."""

    parts: tuple

    def generalized_force(self, beam: BeamProperties, kin: BeamKinematics) -> NDArray[np.float64]:
        """``Σ Q_i``, shape (n,)."""
        return sum(part.generalized_force(beam, kin) for part in self.parts)


@dataclass(frozen=True, eq=False)
class AeroelasticSystem:
    """Linear aeroelastic system about a static equilibrium, ``ẋ = A x`` with ``x = [δq, δq̇, λ]``.

    Attributes
    ----------
    state_matrix : ndarray, shape (2n + P N_λ, 2n + P N_λ)
        ``A`` [1/s and mixed units]; ``λ`` stacks the inflow states of the P strips [m/s].
    n_structural : int
        ``n``.
    tangent_stiffness : ndarray, shape (n, n)
        ``K_T`` including the preload's and the steady airloads' stiffness.
    mass : ndarray, shape (n, n)
        ``M(q0)``.
    """

    state_matrix: NDArray
    n_structural: int
    tangent_stiffness: NDArray
    mass: NDArray


def peters_strip_terms(weight: NDArray, pn: NDArray, pc: NDArray, a1: NDArray, w0v: NDArray, w1v: NDArray,
                       rate0: NDArray, rate1: NDArray, b: NDArray, a: NDArray, rho: NDArray, u0: NDArray,
                       suction_per_lambda0: NDArray, rho_apparent: NDArray | None = None
                       ) -> tuple[NDArray, NDArray, NDArray]:
    """The apparent-mass and inflow parts of Peters' strip loads (module docstring) in generalized coordinates.

    Per strip ``p`` (weight ``w``), the rows over the generalized velocities (shape (P, n)): ``pn = e3ᵀL`` and
    ``pc = e2ᵀL`` (the strip point's velocity normal and chordwise), ``a1 = e1ᵀA`` (its section's rate about the
    span), ``δw0 = w0v``, ``δw1 = w1v`` per velocity, and the velocity terms ``rate0``, ``rate1`` of ``ẇ0``, ``ẇ1``.
    ``{L} = πρ b² [M]{ẇ}`` and ``−πρ b u0 {S} λ0`` are resolved as lift along ``e3`` and moment ``a b L0 − b L1``
    along ``e1``; the suction's change per ``λ0`` is ``suction_per_lambda0`` along ``e2``. ``rho`` (P,) is the
    circulatory loads' density (times the lift scale), ``rho_apparent`` (P,) the apparent mass's (default ``rho``).

    Returns
    -------
    ma, ca : ndarray, shape (n, n)
        ``δQ = −ma δq̈ − ca δq̇`` of the apparent mass (its acceleration and velocity terms).
    g0 : ndarray, shape (n, P)
        ``δQ`` per strip ``λ0``.
    """
    mm, _, sv = _section_matrices()
    am = np.pi * ((rho if rho_apparent is None else rho_apparent) * b**2)[:, None, None]
    acc = am * np.einsum("ij,pjk->pik", mm, np.stack([w0v, w1v], 1))
    rate = am * np.einsum("ij,pjk->pik", mm, np.stack([rate0, rate1], 1))
    lam = -np.pi * (rho * b * u0)[:, None] * sv[None, :]
    mom_acc = (a * b)[:, None] * acc[:, 0] - b[:, None] * acc[:, 1]
    mom_rate = (a * b)[:, None] * rate[:, 0] - b[:, None] * rate[:, 1]
    mom_lam = a * b * lam[:, 0] - b * lam[:, 1]
    ma = -(np.einsum("p,pk,pl->kl", weight, pn, acc[:, 0]) + np.einsum("p,pk,pl->kl", weight, a1, mom_acc))
    ca = -(np.einsum("p,pk,pl->kl", weight, pn, rate[:, 0]) + np.einsum("p,pk,pl->kl", weight, a1, mom_rate))
    g0 = (weight[:, None] * (pn * lam[:, 0][:, None] + a1 * mom_lam[:, None]
                             + pc * suction_per_lambda0[:, None])).T
    return ma, ca, g0


def inflow_columns(g0: NDArray, coefficients) -> NDArray:
    """``δQ`` per inflow state, shape (n, P N): ``g0`` (per strip ``λ0``) times ``λ0 = ½ bᵀλ`` of each strip."""
    nl = coefficients.n_states
    out = np.zeros((g0.shape[0], g0.shape[1] * nl))
    for i in range(g0.shape[1]):
        out[:, i * nl:(i + 1) * nl] = np.outer(g0[:, i], 0.5 * coefficients.b)
    return out


def set_inflow_rows(out: NDArray, start: int, coefficients, forcing_rows: NDArray, u0: NDArray, b: NDArray) -> None:
    """Write the inflow states' rows of a state matrix in place: strip ``i``'s ``N`` states from ``start + i N``,
    ``[A]λ̇ + (u0/b)λ = {c} f`` with ``f = forcing_rows[i] @ state`` (``ẇ0 + ẇ1/2`` per state)."""
    nl = coefficients.n_states
    for i in range(forcing_rows.shape[0]):
        rows = slice(start + i * nl, start + (i + 1) * nl)
        out[rows] = np.outer(coefficients.A_inv_c, forcing_rows[i])
        out[rows, rows] -= (u0[i] / b[i]) * coefficients.A_inv


def aeroelastic_system(beam: BeamProperties, aero: WingAero, flow: TunnelFlow, q0: ArrayLike,
                       stiffness: NDArray, damping: NDArray | None = None) -> AeroelasticSystem:
    """Linear aeroelastic state matrix about the equilibrium ``q0`` (module docstring).

    Parameters
    ----------
    beam, aero, flow
    q0 : array_like, shape (n,)
        Static equilibrium under the flow (and any other loads).
    stiffness : ndarray, shape (n, n)
        ``K_T`` at ``q0``: elastic, geometric and steady-aero stiffness (:func:`static_stiffness`).
    damping : ndarray, shape (n, n), optional
        Structural damping ``C`` (generalized force ``−C q̇``), e.g. the beam's block of
        :meth:`flexsim.structure.free_flexible.FreeFlexibleStructure.damping`; default none.

    Returns
    -------
    AeroelasticSystem
    """
    q0 = np.asarray(q0, dtype=float)
    kin = beam_kinematics(beam, q0)
    n = beam.n_coordinates
    b, a = aero.strips(beam, kin)
    coef = inflow_coefficients(aero.inflow_states)
    nl = coef.n_states
    _, bm, _ = _section_matrices()
    rho, va, w = flow.density_kg_m3 * aero.density_scale(beam, kin), flow.velocity_m_s, kin.points_weight
    e1, e2, e3 = kin.rotations[:, :, 0], kin.rotations[:, :, 1], kin.rotations[:, :, 2]
    jp, jt = kin.jac_position, kin.jac_rotation
    u0, w0s = -(e2 @ va), e3 @ va
    pn, pc = np.einsum("pi,pik->pk", e3, jp), np.einsum("pi,pik->pk", e2, jp)
    a1 = np.einsum("pi,pik->pk", e1, jt)
    rn = np.einsum("pi,pik->pk", np.cross(e3, va), jt)
    w0v = -pn - (a * b)[:, None] * a1  # δw0 per δq̇ and δẇ0 per δq̈
    w1v = b[:, None] * a1
    suc = 4.0 * np.pi * rho * b * w0s  # δS = suc (δw0 − λ0)
    # apparent mass (δẇ = [w0v, w1v] δq̈ + [rn, 0] δq̇) and inflow
    ma, ca, g0 = peters_strip_terms(w, pn, pc, a1, w0v, w1v, rn, np.zeros_like(rn), b, a, rho, u0, -suc,
                                    rho * aero.compressibility_beta)
    # the quasi-steady velocity terms πρ{b δu0 [B]{w_s} + b u0 [B]{δw}}, resolved the same way, and the suction's
    # change with δw0
    vel = np.pi * rho[:, None, None] * ((b * w0s)[:, None, None] * bm[:, 0][None, :, None] * pc[:, None, :]
                                        + (b * u0)[:, None, None]
                                        * np.einsum("ij,pjk->pik", bm, np.stack([w0v, w1v], 1)))
    mom_vel = (a * b)[:, None] * vel[:, 0] - b[:, None] * vel[:, 1]
    ca = ca - (np.einsum("p,pk,pl->kl", w, pn, vel[:, 0]) + np.einsum("p,pk,pl->kl", w, a1, mom_vel)
               + np.einsum("p,pk,pl->kl", w * suc, pc, w0v))
    p = b.size
    g_lam = inflow_columns(g0, coef)
    m = mass_matrix(beam, kin)
    h = np.linalg.inv(m + ma)
    size = 2 * n + p * nl
    out = np.zeros((size, size))
    out[:n, n:2 * n] = np.eye(n)
    qdd_q, qdd_v, qdd_l = -h @ stiffness, -h @ (ca if damping is None else ca + damping), h @ g_lam
    out[n:2 * n, :n], out[n:2 * n, n:2 * n], out[n:2 * n, 2 * n:] = qdd_q, qdd_v, qdd_l
    # [A]λ̇ + (u0/b)λ = {c}(ẇ0 + ẇ1/2),  ẇ0 + ẇ1/2 = (w0v + w1v/2) δq̈ + rn δq̇
    f_rows = (w0v + 0.5 * w1v) @ out[n:2 * n]  # (P, size): ẇ0 + ẇ1/2 of each strip per state, through δq̈
    f_rows[:, n:2 * n] += rn
    set_inflow_rows(out, 2 * n, coef, f_rows, u0, b)
    return AeroelasticSystem(state_matrix=out, n_structural=n, tangent_stiffness=stiffness, mass=m)


def static_stiffness(beam: BeamProperties, q0: ArrayLike, loads: LoadModel | None, aero: WingAero,
                     flow: TunnelFlow, step: float = 1e-6) -> NDArray:
    """``K_T = K − ∂(Q_loads + Q_steady)/∂q`` at ``q0`` (central differences of their sum, step in q units; one
    kinematics per perturbed configuration serves both; ``Q_steady`` is ``U²`` times the loads at unit speed)."""
    parts = () if loads is None else (loads,)
    if flow.speed_m_s > 0:
        parts += (StripAirloads(aero, flow),)  # U² × the loads at unit speed: the steady loads at U
    if not parts:
        return stiffness_matrix(beam)
    # one kinematics per perturbed configuration for all loads
    return stiffness_matrix(beam) - load_stiffness(beam, parts[0] if len(parts) == 1 else LoadSum(parts), q0, step)
