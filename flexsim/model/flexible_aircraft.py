"""A free-flying aircraft whose flexible components are geometrically exact beams, with strip airloads.

The structure is :class:`flexsim.structure.free_flexible.FreeFlexibleStructure`: a rigid body (the rigid
components and the lumped masses and engines they carry) with strain-based beams (Su & Cesnik 2011) clamped to it —
one beam per flexible component, rooted where the component is rooted, in body axes (x forward, y right, z down,
origin o), carrying its component's lumped masses and engines as point masses at their stations (the paper's eq. 6:
an engine moves with its wing). A flexible fuselage carrying the other components is refused: the beams are clamped
to the rigid body, not to the fuselage's bending (the linear model's topology, paper eq. 6).
Each beam's frame ``[e1, e2, e3]`` has ``e1`` along the component's axis, ``e2`` along the streamwise chord
towards the leading edge (body +x for an unswept wing) and ``e3 = e1 × e2`` (up on the right wing, down on the
left: the section theory is the same in either orientation, and the mass-centre offsets keep their meaning).

Aerodynamics (:func:`flexsim.model.beam_aero.section_loads`, the one implementation shared with the wind-tunnel
wing): quasi-steady Peters-Johnson strip loads (reference §1.3-1.4 with the inflow at zero) on

* the strips of a flexible component, at its beam's quadrature points, following the deformed sections (their
  dihedral, twist and sweep enter through the section frame and the strip's own air velocity
  ``V_a = −(v + ω × p)`` at ``ε̇ = 0``);
* the strips of a rigid component, fixed in the body at the linear model's strip stations
  (:class:`flexsim.model.strips.StripSet`: same stations, widths, chords, axes, lift slopes, incidences, cd0).

Control surfaces act through the thin-airfoil lift effectiveness of a plain flap, an equivalent incidence
``τ δ`` with ``τ = 1 − (φ_h − sin φ_h)/π``, ``cos φ_h`` = the hinge position (Glauert 1927; the first entry of
the linear model's flap weights ``[φ_h/π, 2 sin φ_h/π, …]``, :mod:`flexsim.model.strips`); the flap's own
zero-lift moment is neglected. Incidences and deflections are streamwise angles (the linear model's strips are
streamwise); on a swept component they enter the section normal to the beam as ``α / cos Λ``, which gives the
normal velocity ``U α`` of the streamwise strip. With the model's Prandtl-Glauert correction the circulatory loads
carry ``1/β``, ``β = √(1 − M²)`` at the Mach number of the trim (:meth:`FlexibleAircraft.held_at_mach`; held, like the
density, through a simulation or a linearisation about it; the linear strips' factor, Glauert 1928), the apparent
mass and the profile drag do not. Thrust acts at the engines along body x. The generalized forces are the virtual
work of these loads, ``Q = Σ w (L_pᵀ F + Aᵀ M)`` with ``L_p = [I, −p^, J_p]`` and ``A = [0, I, J_θ]`` over the
generalized velocities ``V = [v, ω, ε̇]`` (Shearer & Cesnik 2007 eq. 9; Su & Cesnik 2011 eq. 13).

Mass: the rigid body is the linear structural model's rigid block ``M0[:6, :6]`` (the whole undeformed aircraft,
paper eq. 8) less the beams' share at ``ε = 0``, so both models carry the same mass, centre of gravity and inertia
(up to the beams' element quadrature, O(1/N²) in the inertia). Structural damping: the model's modal damping ratio
(``terms.structural_damping``, else the file's ``structural_damping_ratio``) on every mode of the beams with the body
clamped, as the linear model applies it (:meth:`FreeFlexibleStructure.damping`). Units SI, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from flexsim._kernels.strips import compressibility_factor
from flexsim.model.aircraft_model import check_model
from flexsim.model.beam_aero import WingAero, section_loads
from flexsim.model.terms import NonlinearBeams, Terms
from flexsim.structure.beam_sections import beam_from_sections
from flexsim.structure.free_flexible import (FreeFlexibleStructure, RigidBody, _cross, free_flight_rhs,
                                             generalized_mass_matrix, steady_generalized_force)
from flexsim.structure.strain_beam import PointMass, beam_kinematics

__all__ = ["FlexibleAircraft", "flexible_aircraft"]


def _hat(v: NDArray) -> NDArray:
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def _flap_effectiveness(hinge_d: float) -> float:
    """Thin-airfoil lift effectiveness of a plain flap, ``τ = (φ_h + sin φ_h)/π``, ``φ_h = acos(hinge_d)``.

    Glauert's ``τ = 1 − (θ_h − sin θ_h)/π`` with the hinge angle from the leading edge ``θ_h = π − φ_h`` (``hinge_d``
    semichords aft of mid-chord; e.g. a 25 % chord flap, ``hinge_d = 0.5``: τ = 0.609).
    """
    phi = np.arccos(hinge_d)
    return float((phi + np.sin(phi)) / np.pi)


def _normal_sign(comp) -> float:
    """+1 when the frame's ``e3`` is the linear model's upward strip normal ``−z_i``, −1 when it is ``+z_i``.

    Incidences and flap deflections are nose-up / trailing-edge-down in the linear model's sense
    (:mod:`flexsim.model.strips`: plunge ``n = z_i``, pitch axis ``d × n``); a section whose ``e3`` points along
    ``+z_i`` (the left wing's) sees them with the opposite sign in its own frame.
    """
    return -float(np.sign(_beam_frame(comp)[:, 2] @ comp.axes_in_body[:, 2]) or 1.0)


@dataclass(frozen=True, eq=False)
class _RigidStrips:
    """Strips fixed in the body (arrays over the S strips, body axes)."""

    position: NDArray    # (S, 3) reference-axis point [m]
    rotations: NDArray   # (S, 3, 3) [e1, e2, e3]
    b: NDArray
    a: NDArray
    width: NDArray       # [m]
    scale: NDArray       # lift slope / 2π
    cd0: NDArray
    incidence: NDArray   # [rad]
    flap: NDArray        # (S, 4): incidence per control u (τ × sign on its channel)


@dataclass(frozen=True, eq=False)
class _BeamStrips:
    """Aerodynamics of one beam: its section data per element and its controls (element-wise)."""

    aero: WingAero
    cd0: NDArray         # (N,)
    incidence: NDArray   # (N,) [rad]
    flap: NDArray        # (N, 4): incidence per control u


@dataclass(frozen=True, eq=False)
class FlexibleAircraft:
    """The geometrically nonlinear free-flying aircraft of a model (module docstring).

    Attributes
    ----------
    name : str
    structure : FreeFlexibleStructure
        Rigid body and beams (body axes); gravity is applied by the callers through the attitude.
    beam_components : tuple of str
        The component of each beam.
    beam_strips : tuple
        Per beam, its aerodynamic sections.
    rigid_strips : _RigidStrips
    engine_position_m : ndarray, shape (E, 3)
        Engines (thrust shared equally, along body x) [m].
    terms : dict
        The terms of the model it was built from, with the nonlinear beams it uses
        (:meth:`flexsim.model.terms.Terms.record`; ``nonlinear_beams.elements_per_beam`` the element count).
    prandtl_glauert : bool
        Whether the strips' circulatory lift slope carries the Prandtl-Glauert factor ``1/β`` (the model's
        compressibility correction, :class:`flexsim.model.coupling.AeroOptions`).
    mach : float
        The Mach number at which ``β`` is held (as the density is held at the trim's altitude): the trim's
        (:meth:`held_at_mach`), or the model's frozen ``terms.compressibility_mach``; 0 before a trim.
    mach_frozen : bool
        True when ``mach`` is the model's ``terms.compressibility_mach`` (a trim does not change it).
    unmodelled : tuple of str
        The model's aerodynamic terms present on this aircraft that the nonlinear strips do not have (its tail's
        downwash, its parasite-drag items, its slender bodies' moments); the results that use it say so.
    """

    name: str
    structure: FreeFlexibleStructure
    beam_components: tuple
    beam_strips: tuple
    rigid_strips: _RigidStrips
    engine_position_m: NDArray
    terms: dict = field(default_factory=dict)
    prandtl_glauert: bool = False
    mach: float = 0.0
    mach_frozen: bool = False
    unmodelled: tuple = ()

    @cached_property
    def compressibility_beta(self) -> float:
        """``β = √(1 − min(M, 0.95)²)`` at :attr:`mach` with the Prandtl-Glauert correction, else 1
        (:func:`flexsim._kernels.strips.compressibility_factor`, the linear strips' own)."""
        return float(compressibility_factor(self.prandtl_glauert, float(self.mach)))

    def held_at_mach(self, mach: float) -> "FlexibleAircraft":
        """This aircraft with its compressibility factor held at ``mach`` (itself when the factor does not depend on
        the Mach number: no correction, or a frozen Mach number)."""
        if not self.prandtl_glauert or self.mach_frozen or float(mach) == self.mach:
            return self
        return replace(self, mach=float(mach))

    @property
    def n_strains(self) -> int:
        """Number of strain coordinates ``n``."""
        return self.structure.n_strains

    def beam_index(self, component: str) -> int:
        """Index of the beam of ``component``."""
        if component not in self.beam_components:
            raise ValueError(f"component = {component!r}: not a flexible component of {self.name!r} "
                             f"(flexible: {', '.join(self.beam_components) or 'none'})")
        return self.beam_components.index(component)

    def kinematics(self, eps: NDArray) -> list:
        """:class:`~flexsim.structure.strain_beam.BeamKinematics` of every beam at strains ``eps`` (n,)."""
        return [beam_kinematics(b, eps[s]) for b, s in zip(self.structure.beams, self.structure.strain_slices())]

    def tip_positions(self, eps: NDArray) -> NDArray:
        """Tip reference-axis positions [m] of the beams, body axes, shape (B, 3)."""
        return np.array([k.tip_position for k in self.kinematics(np.asarray(eps, float))]).reshape(-1, 3)

    @cached_property
    def undeformed_tips(self) -> NDArray:
        """Tip positions at ``ε = 0`` [m], shape (B, 3)."""
        return self.tip_positions(np.zeros(self.n_strains))

    @cached_property
    def beam_lengths_m(self) -> NDArray:
        """Length of each beam [m], shape (B,)."""
        return np.array([b.length_m for b in self.structure.beams])

    def tip_heights_m(self, eps: NDArray) -> NDArray:
        """Each beam tip's displacement from its undeformed position along body −z (up positive) [m], shape (B,)."""
        return -(self.tip_positions(eps) - self.undeformed_tips)[:, 2]

    def tip_twists_rad(self, eps: NDArray) -> NDArray:
        """Each beam's twist strain integrated root to tip, ``Σ κ1 ℓ`` [rad] (nose up on the right wing), shape (B,)."""
        eps = np.asarray(eps, float)
        return np.array([b.full_strains(eps[s])[:, 1].sum() * b.element_length_m
                         for b, s in zip(self.structure.beams, self.structure.strain_slices())])

    def root_bending_moments_n_m(self, eps: NDArray) -> NDArray:
        """Each beam's flapwise bending moment at the root, ``EI_flap κ2`` of its root element [N m], shape (B,)."""
        eps = np.asarray(eps, float)
        return np.array([b.ei_flap_nm2[0] * b.full_strains(eps[s])[0, 2]
                         for b, s in zip(self.structure.beams, self.structure.strain_slices())])

    def airloads(self, eps: NDArray, v: NDArray, omega: NDArray, u: NDArray, rho: float,
                 wind: NDArray | None = None, epsdot: NDArray | None = None) -> NDArray:
        """Generalized aerodynamic and thrust force ``Q`` (6 + n) at strains ``eps`` (module docstring).

        Quasi-steady: each strip sees the air velocity relative to its reference axis, ``−(v + ω × p + J_p ε̇)``
        plus the wind, and pitches at ``e1 · (ω + J_θ ε̇)`` (``epsdot`` None: ``ε̇ = 0``); no apparent mass and
        no wake (Peters' inflow at zero).

        Parameters
        ----------
        eps : ndarray, shape (n,)
        v, omega : ndarray, shape (3,)
            Velocity of o [m/s] and angular velocity [rad/s], body axes.
        u : ndarray, shape (4,)
            ``[T [N], δa, δe, δr [rad]]``.
        rho : float
            Air density [kg/m³].
        wind : ndarray, shape (3,), or callable, optional
            Uniform wind velocity in body axes [m/s], or the wind at points of the aircraft: a function of their
            body-axis positions (k, 3) [m] returning the wind there in body axes (k, 3) [m/s]
            (:func:`flexsim.sim.flexible_step.strip_wind`: each strip sees the gust where it is).
        epsdot : ndarray, shape (n,), optional
            Strain rates.

        Returns
        -------
        ndarray, shape (6 + n,)
            Force [N] (body), moment about o [N m] (body), strain forces.
        """
        return self._airloads(eps, v, omega, u, rho, wind, epsdot, self.kinematics(eps))

    def free_structure(self, gravity_m_s2: float) -> FreeFlexibleStructure:
        """This aircraft's structure with gravity ``gravity_m_s2`` [m/s²] along NED down, as the free-flight equations
        (:func:`~flexsim.structure.free_flexible.free_flight_rhs`) take it."""
        return FreeFlexibleStructure(self.structure.body, self.structure.beams,
                                     np.array([0.0, 0.0, float(gravity_m_s2)]), self.structure.damping_ratio)

    def free_flight_rate(self, structure: FreeFlexibleStructure, t: float, y: NDArray, u: NDArray, rho: float,
                         wind: NDArray | None = None) -> NDArray:
        """``dy/dt`` of the free aircraft with quasi-steady strip airloads: :func:`free_flight_rhs` (Su & Cesnik
        2011, eq. 2 in Kane's form) with :meth:`airloads` (at the state's ``ε``, ``v``, ``ω``, ``ε̇``) as ``Q``.

        The one combination integrated by :func:`flexsim.sim.flexible_run.simulate_flexible` and linearised by
        :func:`flexsim.linear.flexible_stability.free_aircraft_spectrum`.

        Parameters
        ----------
        structure : FreeFlexibleStructure
            This aircraft's structure with its gravity (NED) [m/s²].
        t : float
            Time [s].
        y : ndarray, shape (7 + 2 n + 6,)
            ``[X (3, NED) [m], quaternion (4, body→NED), ε (n), v (3) [m/s], ω (3) [rad/s], ε̇ (n)]``, body axes.
        u : ndarray, shape (4,)
            ``[T [N], δa, δe, δr [rad]]``.
        rho : float
            Air density [kg/m³].
        wind : ndarray, shape (3,), or callable, optional
            Uniform wind velocity, body axes [m/s], or the wind at points of the aircraft (:meth:`airloads`).

        Returns
        -------
        ndarray, shape like ``y``
        """
        n = structure.n_strains
        eps, vel = y[7:7 + n], y[7 + n:]
        q = self.airloads(eps, vel[:3], vel[3:6], u, rho, wind=wind, epsdot=vel[6:])
        return free_flight_rhs(structure, t, y, q)

    def free_flight_jacobian(self, structure: FreeFlexibleStructure, y: NDArray, u: NDArray, rho: float,
                             columns: slice = slice(3, None)) -> NDArray:
        """``∂(dy/dt)/∂y`` of :meth:`free_flight_rate` at ``y`` (no wind), by central differences with steps
        ``1e-6 max(1, |y_j|)``, for the state columns ``columns`` (default all but the position ``X``, on which the rate
        does not depend at a held density).

        Returns
        -------
        ndarray, shape (7 + 2 n + 6, k)
            Column ``j`` the derivative with respect to ``y[columns][j]``.
        """
        y = np.asarray(y, float)
        cols = np.arange(y.size)[columns]
        out = np.zeros((y.size, cols.size))
        for j, col in enumerate(cols):
            h = 1e-6 * max(1.0, abs(y[col]))
            up, down = y.copy(), y.copy()
            up[col] += h
            down[col] -= h
            out[:, j] = (self.free_flight_rate(structure, 0.0, up, u, rho)
                         - self.free_flight_rate(structure, 0.0, down, u, rho)) / (2.0 * h)
        return out

    @cached_property
    def strip_constants(self) -> tuple:
        """Per beam, its strips' constants at the quadrature points: ``b``, ``a``, ``lift_slope/2π`` (incompressible),
        incidence, flap rows (P, 4) and cd0 (they depend on the element of each point only, not on the strains)."""
        out = []
        for beam, strips in zip(self.structure.beams, self.beam_strips):
            kin = beam_kinematics(beam, np.zeros(beam.n_coordinates))
            b, a = strips.aero.strips(beam, kin)
            e = kin.points_element
            out.append((b, a, strips.aero.density_scale(beam, kin), strips.incidence[e], strips.flap[e],
                        strips.cd0[e]))
        return tuple(out)

    def _airloads(self, eps, v, omega, u, rho, wind, epsdot, kinematics) -> NDArray:
        """:meth:`airloads` with the beams' kinematics at ``eps`` given (one list per evaluation of the equations)."""
        nv = self.structure.n_velocities
        out = np.zeros(nv)
        wind_at = wind if callable(wind) else None
        w_air = np.zeros(3) if wind is None or wind_at is not None else np.asarray(wind, float)
        beta = self.compressibility_beta
        for s, kin, (b, a, scale, incidence, flap, cd0) in zip(self.structure.strain_slices(), kinematics,
                                                              self.strip_constants):
            p = kin.positions
            va = (w_air if wind_at is None else wind_at(p)) - (v + _cross(omega, p))
            rate = kin.rotations[:, :, 0] @ omega
            if epsdot is not None:
                va = va - kin.jac_position @ epsdot[s]
                rate = rate + np.einsum("pi,pi->p", kin.rotations[:, :, 0], kin.jac_rotation @ epsdot[s])
            force, moment = section_loads(kin.rotations, b, a, va, rho, rate_e1=rate, incidence=incidence + flap @ u,
                                          cd0=cd0, induced=(1.0 - scale) / beta, lift_scale=scale / beta)
            wt = kin.points_weight
            f, m = wt[:, None] * force, wt[:, None] * moment
            out[:3] += f.sum(0)
            out[3:6] += (_cross(p, f) + m).sum(0)
            out[6 + s.start:6 + s.stop] += (np.einsum("pik,pi->k", kin.jac_position, f)
                                            + np.einsum("pik,pi->k", kin.jac_rotation, m))
        r = self.rigid_strips
        if r.b.size:
            va = (w_air if wind_at is None else wind_at(r.position)) - (v + _cross(omega, r.position))
            force, moment = section_loads(r.rotations, r.b, r.a, va, rho, rate_e1=r.rotations[:, :, 0] @ omega,
                                          incidence=r.incidence + r.flap @ u, cd0=r.cd0,
                                          induced=(1.0 - r.scale) / beta, lift_scale=r.scale / beta)
            f, m = r.width[:, None] * force, r.width[:, None] * moment
            out[:3] += f.sum(0)
            out[3:6] += (_cross(r.position, f) + m).sum(0)
        n_eng = self.engine_position_m.shape[0]
        if n_eng:
            thrust = np.array([u[0] / n_eng, 0.0, 0.0])
            out[:3] += u[0] * np.array([1.0, 0.0, 0.0])
            out[3:6] += _cross(self.engine_position_m, thrust).sum(0)
        return out

    def max_strip_alpha_deg(self, eps: NDArray, v: NDArray, omega: NDArray, u: NDArray) -> float:
        """Largest ``|atan2(w, u0)|`` over all lifting strips, incidence and flap angle included [deg] (``ε̇ = 0``);
        a beam without strips (a fuselage: zero lift slope) has no angle of attack to check."""
        worst = 0.0
        groups = []
        for beam, strips, kin in zip(self.structure.beams, self.beam_strips, self.kinematics(eps)):
            if not np.any(np.asarray(strips.aero.lift_slope_per_rad) != 0.0):
                continue
            e = kin.points_element
            groups.append((kin.rotations, kin.positions, strips.incidence[e] + strips.flap[e] @ u))
        r = self.rigid_strips
        groups.append((r.rotations, r.position, r.incidence + r.flap @ u))
        for rot, pos, inc in groups:
            if not len(pos):
                continue
            va = -(v + np.cross(omega, pos))
            u0 = -np.einsum("pi,pi->p", rot[:, :, 1], va)
            wn = np.einsum("pi,pi->p", rot[:, :, 2], va)
            worst = max(worst, float(np.degrees(np.abs(np.arctan2(wn, u0) + inc)).max()))
        return worst

    def steady_residual(self, eps: NDArray, attitude: NDArray, v: NDArray, omega: NDArray, u: NDArray,
                        rho: float, gravity_m_s2: float) -> NDArray:
        """``Q_total`` (6 + n) of a steady state (``V̇ = 0`` and ``ε̇ = 0`` exactly when it vanishes).

        The inertial, elastic and gravity terms are those of the free-flying structure's equations
        (:func:`flexsim.structure.free_flexible.steady_generalized_force`), the airloads :meth:`airloads`.
        ``attitude`` is the body→NED quaternion [q0, q1, q2, q3].
        """
        kinematics = self.kinematics(eps)  # built once, shared by the structure's and the air's forces
        q = steady_generalized_force(self.structure, attitude, eps, np.concatenate([v, omega]),
                                     np.array([0.0, 0.0, gravity_m_s2]), kinematics=kinematics)
        return q + self._airloads(eps, v, omega, u, rho, None, None, kinematics)


def _beam_frame(comp) -> NDArray:
    """``[e1, e2, e3]`` in body axes: along the axis, towards the leading edge, ``e1 × e2``. A component whose chord
    lies along its axis (a fuselage: no leading edge across it) bends "flapwise" in the body's vertical plane:
    ``e3`` up (body −z) normal to the axis, ``e2 = e3 × e1``."""
    axes = comp.axes_in_body
    e1 = axes[:, 0]
    e2 = -(axes @ comp.chord_direction)
    e2 = e2 - (e2 @ e1) * e1
    if np.linalg.norm(e2) < 1e-9:
        e3 = np.array([0.0, 0.0, -1.0]) - (-e1[2]) * e1
        e3 /= np.linalg.norm(e3)
        return np.column_stack([e1, np.cross(e3, e1), e3])
    e2 /= np.linalg.norm(e2)
    return np.column_stack([e1, e2, np.cross(e1, e2)])


def _point_masses(aircraft, comp) -> tuple:
    """The lumped masses and engines of the file on flexible component ``comp``, as point masses of its beam: at the
    station nearest each (as the linear model places them, :func:`flexsim.structure.sections.mass_points`), offset and
    inertia in the beam's section frame (paper eq. 6, ``v_e = v_w(r_we)``: an engine moves with its wing)."""
    frame = _beam_frame(comp)
    out = []
    for item in (*aircraft.lumped_masses, *aircraft.engines):
        if item.component != comp.name:
            continue
        x = float(np.clip(comp.station_of(item.position_m), 0.0, comp.length_m))
        offset = frame.T @ (item.position_m - comp.root_m) - np.array([x, 0.0, 0.0])
        out.append(PointMass(x, item.mass_kg, offset, frame.T @ item.inertia_kg_m2 @ frame,
                             name=f"{item.where}.{item.name}"))
    return tuple(out)


#: The fields of :class:`~flexsim.model.terms.Terms` the nonlinear aircraft evaluates; any other field must keep its
#: default (refused by name otherwise: an option is honoured or refused, never dropped).
HONOURED_TERMS = ("aero", "gravity_m_s2", "structural_damping", "compressibility_mach", "nonlinear_beams")


def _check_terms(model) -> tuple:
    """Refuse the model's terms the nonlinear aircraft cannot evaluate, naming the field (a Terms field off its default
    outside :data:`HONOURED_TERMS`, the paper's force resolution); return the aerodynamic terms present on the aircraft
    that its strips do not have (:attr:`FlexibleAircraft.unmodelled`)."""
    default = Terms()
    for f in fields(Terms):
        value = getattr(model.terms, f.name)
        if f.name not in HONOURED_TERMS and value != getattr(default, f.name):
            raise ValueError(f"{f.name} = {value!r}: not available with the geometrically nonlinear beams (their "
                             f"aircraft evaluates the terms {', '.join(HONOURED_TERMS)}); leave it at its default, "
                             f"{getattr(default, f.name)!r}")
    if model.aero.formulation != "physical":
        raise ValueError(f"formulation = {model.aero.formulation!r}: the nonlinear strips resolve the physical force "
                         "(paper eq. 28 with the flow angle); not available with nonlinear_beams")
    out = []
    if model.aero.downwash_gradient:
        out.append("the tail's downwash ([aero] downwash_gradient)")
    if model.parasite_drag is not None:
        out.append("the parasite-drag items ([[aero.drag]])")
    if model.bodies is not None:
        out.append("the slender bodies' Munk moments ([[aero.body]])")
    return tuple(out)


def _check_topology(aircraft) -> None:
    """Refuse a flexible fuselage that carries other components: the nonlinear structure clamps every beam to the
    rigid body, whereas the linear model (paper eq. 6) attaches them to the fuselage's bending and torsion; the GTM's
    fuselage bending would be a 4.9 rad/s cantilever instead of its 27 rad/s mode carrying the wings."""
    names = [c.name for c in aircraft.components]
    if "fuselage" in names and aircraft.component("fuselage").is_flexible and len(names) > 1:
        raise ValueError("components.fuselage is flexible: the geometrically nonlinear structure clamps the wings and "
                         "stabilizers to the rigid body, not to a bending fuselage; set components.fuselage.rigid = "
                         "true to use it (the fuselage's flexibility is in the linear model only)")


def _streamwise_to_section(comp) -> float:
    """``1 / cos Λ``: the factor from a streamwise angle of incidence (the aircraft file's ``incidence_deg`` and control
    deflections, on the linear model's streamwise strips) to the angle of the section normal to the beam, whose
    chordwise speed is ``U cos Λ``: ``u0 α_n = U α_s`` keeps the normal velocity ``U α_s`` the streamwise strip sees
    (Λ the angle between the streamwise chord and ``e2``, the sweep; 1 for an unswept component or a fuselage)."""
    axes = comp.axes_in_body
    stream = -(axes @ comp.chord_direction)
    e2 = _beam_frame(comp)[:, 1]
    cos_sweep = abs(float(stream @ e2)) / max(float(np.linalg.norm(stream)), 1e-12)
    return 1.0 / cos_sweep if cos_sweep > 1e-3 else 1.0


def _flap_rows(comp, stations: NDArray) -> NDArray:
    """(k, 4) incidence per control at the given stations (0 outside the surface)."""
    from flexsim.model.strips import FLAP_KINDS

    rows = np.zeros((stations.size, 4))
    cs = comp.control_surface
    if cs is not None:
        inside = (stations >= cs.start_m) & (stations <= cs.end_m)
        sign = -1.0 if comp.name == "left_wing" else 1.0
        rows[inside, 1 + FLAP_KINDS.index(cs.kind)] = (sign * _normal_sign(comp) * _flap_effectiveness(cs.hinge_d)
                                                       * _streamwise_to_section(comp))
    return rows


def flexible_aircraft(model, elements_per_beam: int | None = None) -> FlexibleAircraft:
    """The :class:`FlexibleAircraft` of ``model`` (an :class:`~flexsim.model.aircraft_model.AircraftModel`).

    Parameters
    ----------
    model : AircraftModel
        Its aircraft, strips (lift slopes as the linear model resolves them) and structural model (mass).
    elements_per_beam : int, optional
        Equal elements of each flexible component's beam, 1-64; default the model's
        ``terms.nonlinear_beams.elements_per_beam``, or :class:`~flexsim.model.terms.NonlinearBeams`'s default (8) for a
        model of the linear structure.

    Raises
    ------
    ValueError
        A flexible component without ``sections.ei_chord_nm2`` (the beam bends in both planes), a flexible
        component without strips that is not the fuselage, or a bad element count.
    """
    check_model(model, nonlinear=True)
    beams_option = model.terms.nonlinear_beams or NonlinearBeams()
    if elements_per_beam is None:
        elements_per_beam = beams_option.elements_per_beam
    if isinstance(elements_per_beam, bool) or not isinstance(elements_per_beam, (int, np.integer)) \
            or not 1 <= elements_per_beam <= 64:
        raise ValueError(f"elements_per_beam = {elements_per_beam!r}: must be an integer in 1-64")
    terms = replace(model.terms, nonlinear_beams=replace(beams_option, elements_per_beam=int(elements_per_beam))).record()
    aircraft = model.aircraft
    if model.aero is None:
        raise ValueError("the model has no aerodynamics (Terms(aero=None)): the flexible aircraft needs its strips")
    unmodelled = _check_terms(model)
    strips = model.aero.strips
    beams, names, beam_strips = [], [], []
    for comp in aircraft.components:
        if not comp.is_flexible:
            continue
        if comp.sections.ei_chord_nm2 is None:
            option = "" if model.terms.nonlinear_beams is None else f"nonlinear_beams = {model.terms.nonlinear_beams!r}: "
            raise ValueError(f"{option}components.{comp.name}.sections.ei_chord_nm2 is not given: the geometrically "
                             "nonlinear structure needs the chordwise bending stiffness of every flexible "
                             "component [N m^2] (or set rigid = true)")
        beam = beam_from_sections(comp.sections, int(elements_per_beam), root_position_m=comp.root_m,
                                  root_rotation=_beam_frame(comp))
        carried = _point_masses(aircraft, comp)
        if carried:
            beam = replace(beam, point_masses=carried)
        n = beam.n_elements
        mid = (np.arange(n) + 0.5) * beam.element_length_m
        if comp.aero is None:
            aero = _BeamStrips(WingAero(chord_m=1.0, lift_slope_per_rad=0.0), np.zeros(n), np.zeros(n),
                               np.zeros((n, 4)))
        else:
            rows = [i for i, c in enumerate(strips.component) if c == comp.name]
            slope = np.interp(mid, strips.station_m[rows], strips.lift_slope0[rows])
            aero = _BeamStrips(WingAero(chord_m=comp.sections.at("chord_m", mid),
                                        axis_fraction=comp.sections.at("ea_fraction", mid),
                                        lift_slope_per_rad=slope),
                               np.full(n, comp.aero.cd0),
                               np.full(n, _normal_sign(comp) * comp.aero.incidence_rad * _streamwise_to_section(comp)),
                               _flap_rows(comp, mid))
        beams.append(beam), names.append(comp.name), beam_strips.append(aero)
    _check_topology(aircraft)
    probe = FreeFlexibleStructure(RigidBody(0.0), tuple(beams))
    m_beams = generalized_mass_matrix(probe, np.zeros(probe.n_strains))[:6, :6]
    m_rigid = model.structure.inertia.m0[:6, :6] - m_beams
    mass = float(m_rigid[0, 0])
    first = np.array([m_rigid[1, 5], m_rigid[2, 3], m_rigid[0, 4]])  # m c (M_v,ω = −m c^)
    cg = first / mass
    j_cg = m_rigid[3:6, 3:6] + mass * _hat(cg) @ _hat(cg)
    j_cg = 0.5 * (j_cg + j_cg.T)
    if mass <= 0.0 or np.linalg.eigvalsh(j_cg).min() < -1e-9 * max(float(np.abs(j_cg).max()), 1.0):
        raise ValueError(f"elements_per_beam = {elements_per_beam}: the beams' mass at this element count (each element's "
                         "mean section) exceeds the linear model's in some direction, leaving the rigid body a mass "
                         f"{mass:.6g} kg and inertia eigenvalues {np.round(np.linalg.eigvalsh(j_cg), 1).tolist()} kg m^2; "
                         "use more elements per beam")
    body = RigidBody(mass, cg, j_cg)
    rigid_rows = [i for i, c in enumerate(strips.component) if not aircraft.component(c).is_flexible]
    r = np.asarray(rigid_rows, dtype=int)
    frames = []
    flap = np.zeros((r.size, 4))
    normal = np.ones(r.size)
    for k, i in enumerate(r):
        comp = aircraft.component(strips.component[i])
        frames.append(_beam_frame(comp))
        normal[k] = _normal_sign(comp) * _streamwise_to_section(comp)
        flap[k] = _flap_rows(comp, np.array([strips.station_m[i]]))[0]
    rigid = _RigidStrips(position=strips.position_body_m[r], rotations=np.array(frames).reshape(-1, 3, 3),
                         b=strips.semichord_m[r], a=strips.a[r], width=strips.width_m[r],
                         scale=strips.lift_slope0[r] / (2.0 * np.pi), cd0=strips.cd0[r],
                         incidence=normal * strips.incidence_rad[r], flap=flap)
    engines = np.array([e.position_m for e in aircraft.engines]).reshape(-1, 3)
    frozen = model.terms.compressibility_mach
    structure = FreeFlexibleStructure(body, tuple(beams), damping_ratio=model.structural_damping_ratio)
    return FlexibleAircraft(name=aircraft.name, structure=structure,
                            beam_components=tuple(names), beam_strips=tuple(beam_strips), rigid_strips=rigid,
                            engine_position_m=engines, terms=terms,
                            prandtl_glauert=model.aero.compressibility == "prandtl-glauert",
                            mach=0.0 if frozen is None else float(frozen), mach_frozen=frozen is not None,
                            unmodelled=unmodelled)
