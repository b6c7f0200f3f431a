"""Aeroelastic coupling: strip airloads as generalized forces, apparent mass and inflow states.

Sources: Tuzcu & Nguyen (2014) eqs. (25)-(31); Peters-Johnson rigid-strip loads as written in
``docs/reference/aero-kinematics.md`` sections 1.3-1.6 (pi rho normalisation); Peters, Karunamoorthy &
Cao (1995) finite-state inflow (reference section 2.1).

For every strip (see :mod:`flexsim.model.strips`) the Chebyshev downwash coefficients follow from the
kinematic map of its elastic-axis point, in strip axes (chord direction d, plunge direction n, pitch axis p)::

    u0 = -d^T A(q) V                             chordwise air speed [m/s]
    w_EA = n^T A(q) V + u0 (alpha_el + alpha_r)  normal velocity relative to the air, down [m/s]
    alpha_dot = p^T B V                          pitch rate [rad/s]

with alpha_el the elastic pitch of the strip (phi cos(Lambda) for the component's own torsion, plus the
fuselage's rotation at the attachment) and alpha_r the rigging incidence.
    w0 = w_EA - a b alpha_dot + u0 beta f0,   w1 = b alpha_dot + u0 beta f1,   w2 = u0 beta f2

and the loads per unit span are (Cl_alpha replaces 2 pi in the circulatory terms, as in the paper)::

    L   = Cl_a rho b u0 (w0 + w1/2 - lambda0) + pi rho b^2 w0_dot
    M_EA = (Cl_a/2) rho b^2 u0 (w0 - lambda0 - w2/2) + (b^4 terms) + a b L

The circulatory lift acts normal to the local relative wind and the drag along it (eq. 28, with the
local flow angle a0 = (w0 + w1/2 - lambda0)/u0 - alpha_chord relative to the component axes instead of
the body's W/U): f = L (-n - a0 d) + D (d - a0 n) (formulation "physical", the default). Formulation
"paper" (the paper's eq. 28 with one alpha_i0 = W/U and the drag d = l alpha_i0, which its Tables 2-3
imply through T_e = W sin(theta)): on wing and stabilizer strips f = -L n + L (n_x / d_x) d, the lift
along -n plus the chordwise part that cancels the body-x component (n_x, d_x: body-x components of n
and d); the fin keeps the physical resolution (eq. 31, no load in symmetric flight). The drag is the induced drag of the strip,
L alpha_e (1 - Cl_a0/2 pi) with alpha_e = (w0 + w1/2 - lambda0)/u0 the effective angle of attack (the lift
tilted by the 3-D induced angle implied by the vortex-lattice slope; zero in 2-D, as Peters' drag is in
steady flow), plus an optional parasite drag. Each strip's force and moment enter the equations of motion as
width * G^T [f; M_EA p] (eqs. 17-24).

The apparent-mass terms and the inflow forcing w0_dot + w1_dot/2 contain the accelerations V_dot: the
coupling returns the added-mass matrix M_a (moved to the left-hand side, E(x) x_dot = f(x)) and the
explicit parts, so that the model solves for the accelerations inside the right-hand side and then
evaluates the inflow rates with those accelerations. No acceleration is lagged.

The per-call arithmetic is the compiled kernels :func:`flexsim._kernels.strip_kinematics`,
:func:`~flexsim._kernels.circulatory`, :func:`~flexsim._kernels.aero_evaluate` and
:func:`~flexsim._kernels.inflow_rate` (numba; :attr:`AeroCoupling.kernel_data` is their frozen data); this
class builds the data and wraps them.

Simplifications (documented in docs/design.md): control-surface rates and the u0_dot terms of Peters'
[G] matrix are neglected; the fin is quasi-steady (lambda0 = 0, paper eqs. 29-31) with apparent mass.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from flexsim._immutable import Immutable
from flexsim import _kernels as _k
from flexsim._arrays import kernel_arg as _arr
from flexsim.aero.inflow import inflow_coefficients
from flexsim.aircraft.definition import COMPRESSIBILITY, FORMULATIONS
from flexsim.model.strips import StripSet
from flexsim.structure.model import StructuralModel

if TYPE_CHECKING:
    from flexsim.model.terms import Terms

__all__ = ["AeroOptions", "AeroCoupling", "AERO_MODELS", "StripLoads", "StripKinematics", "tail_downwash"]

#: Aerodynamic models by name (the "theodorsen" frequency-domain model is for linear flutter analysis).
AERO_MODELS = ("quasi-steady", "unsteady", "theodorsen")
_MACH_CAP = 0.95


@dataclass(frozen=True)
class AeroOptions:
    """Choice of aerodynamic model.

    Attributes
    ----------
    model : {"quasi-steady", "unsteady", "theodorsen"}
        ``quasi-steady``: lambda0 = 0 (paper "QS"); ``unsteady``: Peters finite-state inflow with
        ``n_inflow`` states per wing/stabilizer strip (time domain and state space); ``theodorsen``:
        frequency-domain C(k), valid for linear flutter analysis only (its time-domain limit k = 0 is
        the quasi-steady model, which is what trim uses).
    n_inflow : int
        Inflow states per strip, 1..10 (default 6).
    lift_slope : {"file", "vlm", "2pi"}
        Where the sectional Cl_alpha comes from: each component's file setting, or an override.
    formulation : {"physical", "paper"} or None
        Resolution of the strip force (module docstring, docs/design.md "Force resolution"); None (default)
        takes the aircraft file's ``formulation`` (itself "physical" unless the file says otherwise).
    compressibility : {"file", "prandtl-glauert", "none"}
        Mach correction of the circulatory Cl_alpha: the aircraft file's ``[aero] compressibility``
        (``"file"``, default; the file's own default is Prandtl-Glauert, the paper's), Prandtl-Glauert
        1/sqrt(1 - M^2) with M capped at 0.95, or none (incompressible strip theory).
    parasite_drag : bool
        Apply the aircraft file's parasite-drag items (``[[aero.drag]]``, :mod:`flexsim.model.drag`;
        default True; an aircraft without items has none).
    bending_incidence : bool or None
        Swept-wing bending-incidence coupling: the strips' pitch includes the streamwise rotation of the
        bending slope, (p . -y_i) U_i'(x) q_i = sin(Lambda) w' (:func:`_bending_slope_pitch`). None (default)
        takes the aircraft file's ``[aero] bending_incidence`` (itself False: the paper's model).
    downwash : bool
        The horizontal tail sees the wing's downwash with the aircraft file's ``[aero] downwash_gradient``
        (:func:`tail_downwash`; default True; the file's default gradient 0 means none). Physical formulation
        only, like the parasite drag.
    body_moments : bool
        Apply Munk's moment of the aircraft file's slender bodies (``[[aero.body]]``: fuselage, nacelles;
        :mod:`flexsim.model.bodies`; default True; an aircraft without items has none). Like the parasite
        drag they belong to the physical formulation and are not applied with the paper's.
    """

    model: str = "unsteady"
    n_inflow: int = 6
    lift_slope: str = "file"
    formulation: str | None = None
    compressibility: str = "file"
    parasite_drag: bool = True
    bending_incidence: bool | None = None
    downwash: bool = True
    body_moments: bool = True

    def __post_init__(self) -> None:
        if self.model not in AERO_MODELS:
            raise ValueError(f"aero model = {self.model!r}: must be one of {', '.join(AERO_MODELS)}")
        inflow_coefficients(self.n_inflow)  # validates 1..10 with a clear message
        if self.lift_slope not in ("file", "vlm", "2pi"):
            raise ValueError(f"lift_slope = {self.lift_slope!r}: must be \"file\", \"vlm\" or \"2pi\"")
        if self.formulation is not None and self.formulation not in FORMULATIONS:
            raise ValueError(f"formulation = {self.formulation!r}: must be one of {', '.join(FORMULATIONS)} (or None: the aircraft file's)")
        if self.compressibility not in ("file", *COMPRESSIBILITY):
            raise ValueError(f"compressibility = {self.compressibility!r}: must be \"file\", \"prandtl-glauert\" or \"none\"")
        if self.bending_incidence is not None and not isinstance(self.bending_incidence, bool):
            raise ValueError(f"bending_incidence = {self.bending_incidence!r}: must be True, False or None (the file's)")
        if not isinstance(self.parasite_drag, bool):
            raise ValueError(f"parasite_drag = {self.parasite_drag!r}: must be True or False")
        if not isinstance(self.downwash, bool):
            raise ValueError(f"downwash = {self.downwash!r}: must be True or False")
        if not isinstance(self.body_moments, bool):
            raise ValueError(f"body_moments = {self.body_moments!r}: must be True or False")


def _bending_slope_pitch(structure: StructuralModel, strips: StripSet) -> np.ndarray:
    """Strip pitch rate per unit V from the own bending slope, shape (n_s, n_v) (not in the paper).

    The Euler-Bernoulli section of a bent beam rotates by the slope, Omega = -y_i U_i'(x) s_i (the rotation
    eq. 6 applies to the fuselage's bending at the attachment, here for the component's own bending). Its
    component along the strip's pitch axis p pitches the streamwise section: alpha_b = (p . -y_i) U_i'(x) q_i.
    For a wing swept by Lambda, p = (cos Lambda, -sin Lambda, 0) in component axes, so alpha_b = sin(Lambda) w'
    with w' the slope in z_i: upward bending of a swept-back wing washes the tips out (Bisplinghoff, Ashley &
    Halfman, *Aeroelasticity*, 1955, sec. 8-4; Hodges & Pierce 2011, sec. 4.3). Zero for unswept surfaces.
    The same map gives the pitch rate and, by virtual work, the strip moment's generalized force on q.
    """
    from flexsim.structure.shapes import bending_shapes

    out = np.zeros((strips.n_strips, structure.dofs.n_v))
    comps = np.array(strips.component)
    for name in dict.fromkeys(strips.component):
        comp = structure.aircraft.component(name)
        if not comp.bending_modes:
            continue
        idx = np.flatnonzero(comps == name)
        slope = bending_shapes(strips.station_m[idx], comp.length_m, comp.bending_modes, derivative=1)  # (k, m) [1/m]
        out[np.ix_(idx, np.arange(structure.dofs.n_v)[structure.dofs.v_bending(name)])] = -strips.p[idx, 1][:, None] * slope
    return out


def tail_downwash(wing_weight: np.ndarray, u0: np.ndarray, wc: np.ndarray, speed: float, beta: float, gradient: float) -> float:
    """Downwash angle epsilon [rad] of the wing at the horizontal tail (not in the paper).

    epsilon = (d epsilon / d alpha)_0 L_w / L_alpha0,w: the wing's circulatory lift over its incompressible
    lift per radian, L_w = sum Cl_a0/beta rho b u0 (w0 + w1/2 - lambda0) w, L_alpha0,w = rho V^2 sum Cl_a0 b w.
    At M -> 0 and a uniform angle of attack this is (d epsilon/d alpha)_0 alpha; at Mach M it grows with the
    wing's lift slope, the compressibility scaling of the USAF DATCOM (sec. 4.4.1: d epsilon/d alpha at M is
    the incompressible value times CL_alpha,w(M)/CL_alpha,w(0); Hoak et al. 1978); the downwash follows the
    circulation the wing actually carries (flexible twist, flaps, unsteady lag). Quasi-steady: the wake's
    travel time to the tail is neglected (no downwash lag, no Cm_alpha_dot from it).

    Parameters
    ----------
    wing_weight : ndarray, shape (n_s,)
        Cl_a0 b w of each wing strip over the sum of Cl_a0 b w over the wing strips; 0 on other strips [-].
    u0, wc : ndarray, shape (n_s,)
        Chordwise speed and w0 + w1/2 - lambda0 of every strip [m/s].
    speed : float
        Flight speed V [m/s].
    beta : float
        Compressibility factor of the strips' lift slope [-].
    gradient : float
        (d epsilon / d alpha) at M -> 0 [-].

    The compiled kernel :func:`flexsim._kernels.tail_downwash`.
    """
    return _k.tail_downwash(_arr(wing_weight), _arr(u0), _arr(wc), float(speed), float(beta), float(gradient))


class StripKinematics(NamedTuple):
    """Strip velocities and downwash at one state (module docstring); arrays of shape (n_s,) unless noted."""

    p_mat: np.ndarray  #: n^T A(q), shape (n_s, n_v)
    d_mat: np.ndarray  #: d^T A(q), shape (n_s, n_v)
    alpha_el: np.ndarray  #: elastic pitch + rigging [rad]
    u0: np.ndarray  #: chordwise air speed [m/s]
    w_ea: np.ndarray  #: normal velocity of the elastic axis relative to the air, down [m/s]
    w34: np.ndarray  #: w0 + w1/2, three-quarter-chord downwash [m/s]
    wc: np.ndarray  #: w0 + w1/2 - lambda0 [m/s]
    w_moment: np.ndarray  #: w0 - lambda0 - w2/2 [m/s]
    alpha_chord: np.ndarray  #: pitch of the chord (elastic + rigging) plus the flap's camber angle [rad]


@dataclass(frozen=True, eq=False)
class StripLoads:
    """Per-strip aerodynamic quantities at one state (outputs for logging and tests).

    Attributes
    ----------
    u0_m_s, w_ea_m_s, lift_n_m, moment_n, drag_n_m, alpha0_rad : ndarray, shape (n_s,)
        Chordwise speed, normal velocity, circulatory lift per span, moment about the
        elastic axis per span (nose up), drag per span, flow angle relative to the component axes
        (the tilt of the lift in eq. 28).
    """

    u0_m_s: np.ndarray
    w_ea_m_s: np.ndarray
    lift_n_m: np.ndarray
    moment_n: np.ndarray
    drag_n_m: np.ndarray
    alpha0_rad: np.ndarray


class _StripsOf(NamedTuple):
    """What the strips' term data classes read of a model (their ``fields_of``): its coupling and structure."""

    aero: "AeroCoupling"
    structure: StructuralModel


#: The term data classes of the strips' own packed data (:attr:`AeroCoupling.kernel_data`).
_STRIP_TERMS = (_k.StripData, _k.PetersData, _k.DownwashData)


class AeroCoupling(Immutable):
    """Strip aerodynamics of a structural model (built once; :meth:`evaluate` per right-hand side).

    Parameters
    ----------
    structure : StructuralModel
    terms : Terms
        The model's terms (:class:`flexsim.model.terms.Terms`, validated there) with aerodynamics (``terms.aero`` an
        :class:`AeroOptions`); the strips use its aerodynamic switches: ``compressibility_mach`` (the Mach number of a
        frozen compressibility factor, None: the flight's), ``force_resolution`` (which strips lose the flow-angle
        terms of the force resolution: "full" none, "normal" all, "fin-normal" the fin's), ``fin_drag_per_lift``
        (kappa of the paper's fin drag law, eq. 30; None: the fin's own drag) and ``aero_velocity_offset_m_s`` (the
        body velocity offset the strips see [m/s]).

    Attributes
    ----------
    options : AeroOptions
    terms : Terms
    strips : StripSet
    tilt_scale, drag_scale, drag_per_lift : ndarray, shape (n_s,)
        Per strip: the scale of the lift's tilt by the flow angle and of the drag, and the drag per unit lift kappa
        (``force_resolution``, ``fin_drag_per_lift``).
    velocity_offset_m_s : ndarray, shape (3,)
        The body velocity offset the strips see [m/s] (zero unless ``aero_velocity_offset_m_s``).
    """

    def __init__(self, structure: StructuralModel, terms: "Terms") -> None:
        options = terms.aero
        if not isinstance(options, AeroOptions):
            raise ValueError(f"terms.aero = {options!r}: the strip aerodynamics need an AeroOptions")
        self.options = options
        #: The model's terms (:class:`flexsim.model.terms.Terms`) the strips were built with.
        self.terms = terms
        comp = options.compressibility
        #: The compressibility correction in force ("prandtl-glauert" or "none"), resolved from the file.
        self.compressibility = structure.aircraft.aero_settings.compressibility if comp == "file" else comp
        self.strips = s = StripSet.from_model(structure, options.lift_slope)
        self._nq = structure.dofs.nq
        self._ext_u = np.zeros(4)
        self._b = s.semichord_m
        self.ab = s.a * s.semichord_m
        self.k0 = s.lift_slope0 / (2 * np.pi)
        self.pr_w = np.pi * s.semichord_m**2 * s.width_m  # apparent mass per rho, all strips
        bend = options.bending_incidence
        #: Swept-wing bending-incidence coupling in force (the strips' pitch includes the bending slope).
        self.bending_incidence = structure.aircraft.aero_settings.bending_incidence if bend is None else bend
        self.proj_p = s.proj_p + (_bending_slope_pitch(structure, s) if self.bending_incidence else 0.0)
        self.rel = self.proj_p[:, 6:]  # elastic pitch per unit [q; xi] (B constant: angles = rates map)
        self.finite_state = options.model == "unsteady"
        self.inflow_idx = np.flatnonzero(s.unsteady) if self.finite_state else np.zeros(0, int)
        self.inflow = inflow_coefficients(options.n_inflow)
        self.n_inflow_states = self.inflow_idx.size * options.n_inflow
        #: Resolution of the strip force in use ("physical" or "paper"; module docstring).
        self.formulation = options.formulation or structure.aircraft.formulation
        # "paper": on the wing and stabilizer strips (those with inflow, i.e. not the fin) the force has no
        # body-x component: c_d = -c_n (n . x_b) / (d . x_b) with x_b the body x axis in component axes.
        x_b = (np.array([structure.aircraft.component(c).dcm[:, 0] for c in s.component]) if s.n_strips else np.zeros((0, 3)))
        self.paper_strips = s.unsteady.copy() if self.formulation == "paper" else np.zeros(s.n_strips, bool)
        d_x = np.einsum("sk,sk->s", s.d, x_b)
        if np.any(self.paper_strips & (np.abs(d_x) < 1e-3)):
            raise ValueError('formulation = "paper": a wing/stabilizer strip chord is normal to body x; the force cannot be resolved without a body-x component')
        # downwash of the wings at the horizontal tail (physical formulation; tail_downwash)
        gradient = structure.aircraft.aero_settings.downwash_gradient if (options.downwash and self.formulation == "physical") else 0.0
        comps = np.array(s.component)
        wing = np.isin(comps, ("right_wing", "left_wing"))
        tail = np.isin(comps, ("right_htail", "left_htail"))
        #: d(epsilon)/d(alpha) at M -> 0 in force (0: the tail sees the free stream, as in the paper).
        self.downwash_gradient = float(gradient) if wing.any() and tail.any() else 0.0
        weight = np.where(wing, s.lift_slope0 * s.semichord_m * s.width_m, 0.0)
        self.dw_wing_weight = weight / weight.sum() if wing.any() else weight
        z_b = np.array([structure.aircraft.component(c).dcm[:, 2] for c in s.component]) if s.n_strips else np.zeros((0, 3))
        self.dw_tail_nz = np.where(tail, np.einsum("sk,sk->s", s.n, z_b), 0.0)  # n . z_body of the tail strips
        self.n_over_d_x = np.where(self.paper_strips, np.einsum("sk,sk->s", s.n, x_b) / np.where(np.abs(d_x) < 1e-3, 1.0, d_x), 0.0)
        # the terms' switches (flexsim.model.terms.Terms): flow-angle terms of the resolution per strip, velocity offset
        fin = ~s.unsteady  # the fin's strips: those without inflow states (quasi-steady, eqs. 29-31)
        self.tilt_scale = {"full": np.ones(s.n_strips), "normal": np.zeros(s.n_strips),
                           "fin-normal": np.where(fin, 0.0, 1.0)}[terms.force_resolution]
        self.drag_scale, self.drag_per_lift = self.tilt_scale.copy(), np.zeros(s.n_strips)
        if terms.fin_drag_per_lift is not None:  # the paper's fin drag, eq. 30: d_v = q c C_Dav a_v = kappa l_v
            self.drag_scale[fin] = 0.0
            self.drag_per_lift[fin] = terms.fin_drag_per_lift
        dv = terms.aero_velocity_offset_m_s
        self.velocity_offset_m_s = np.zeros(3) if dv is None else np.asarray(dv, float)
        #: Mach number of the frozen compressibility factor (None: the flight's at every state).
        self.compressibility_mach = terms.compressibility_mach
        #: Component-to-body rotation of each strip (n_s, 3, 3).
        self.strip_dcm = (np.stack([structure.aircraft.component(c).dcm for c in s.component]) if s.n_strips
                          else np.zeros((0, 3, 3)))
        #: sum_j pi b^4 w / 8 (p^T B)^T (p^T B) (n_v, n_v) [m^4]: the apparent mass of the strips' pitch.
        self.apparent_pitch = np.einsum("s,si,sk->ik", self.pr_w * self._b**2 / 8.0, self.proj_p, self.proj_p)
        #: The strips' packed data (:class:`flexsim._kernels.KernelData`): the fields of their term data classes
        #: (strips, inflow, downwash), filled by those classes as for the model (:func:`flexsim._kernels.fields_of`).
        self.kernel_data = _k.pack_fields(_k.fields_of(_StripsOf(self, structure), _STRIP_TERMS))

    def kinematics(self, q, xi, vel, lam, u, wind_c=None) -> StripKinematics:
        """Strip velocities and Chebyshev downwash coefficients at a state (module docstring).

        ``wind_c`` (n_s, 3), optional: air velocity at each strip in its component axes [m/s]; the strip
        sees the air velocity relative to itself (gusts, turbulence).
        """
        has_wind = wind_c is not None
        wind = _arr(wind_c) if has_wind else np.zeros((self.strips.n_strips, 3))
        out = _k.strip_kinematics(*self.kernel_data, _arr(q), _arr(xi), _arr(vel), _arr(lam), _arr(u), wind, has_wind)
        return StripKinematics(*out[:9])

    def compressibility_factor(self, mach: float) -> float:
        """beta such that Cl_alpha(M) = Cl_alpha0 / beta [-].

        Prandtl-Glauert rule (H. Glauert, "The effect of compressibility on the lift of an aerofoil",
        Proc. R. Soc. Lond. A 118, 113-119, 1928):
        beta = sqrt(1 - M^2) with M capped at 0.95 (the paper's "Numerical Model"); 1 when the
        correction is switched off (``compressibility = "none"``).
        """
        if self.compressibility_mach is not None:
            mach = self.compressibility_mach
        return _k.compressibility_factor(self.compressibility == "prandtl-glauert", float(mach))

    def _with_downwash(self, kin: StripKinematics, vel: np.ndarray, mach: float) -> StripKinematics:
        """The tail strips' kinematics in the wing's downwash (:func:`tail_downwash`).

        The downwash is an air velocity epsilon V along body z (down) at the tail: the normal velocity of each
        tail strip relative to the air falls by epsilon V (n . z_b), and with it w0, w0 + w1/2 and the moment's
        downwash (like a wind, it does not force the inflow states or the apparent mass).
        """
        if not self.downwash_gradient:
            return kin
        shift = _k.downwash_shift(*self.kernel_data, _arr(vel), kin.u0, kin.wc, float(mach))
        return kin._replace(w_ea=kin.w_ea + shift, w34=kin.w34 + shift, wc=kin.wc + shift, w_moment=kin.w_moment + shift)

    def _circulatory(self, kin: StripKinematics, rho: float, mach: float):
        """Circulatory lift, moment about the EA, lift x flow angle and drag per unit span.

        The flow angle relative to the component axes is (w0 + w1/2 - lambda0)/u0 - alpha_chord: the
        effective angle of attack less the chord's own pitch and the flap camber. The products with the
        lift are formed without dividing by u0 (well defined in still air).
        """
        return _k.circulatory(*self.kernel_data, kin.u0, kin.wc, kin.w_moment, kin.alpha_chord, float(rho), float(mach))

    def evaluate(self, q, xi, vel, lam, u, rho, mach, wind_c=None):
        """Added mass, generalized aerodynamic force and inflow forcing at one state.

        Parameters
        ----------
        q, xi : ndarray, shapes (nq,), (nxi,)
            Elastic coordinates [m], [rad].
        vel : ndarray, shape (n_v,)
            Global velocity vector V (body axes).
        lam : ndarray, shape (n_inflow_states,)
            Inflow states [m/s], strip-major.
        u : ndarray, shape (4,)
            Controls [T_e, delta_a, delta_e, delta_r].
        rho : float
            Air density [kg/m^3].
        mach : float
            Flight Mach number (Prandtl-Glauert factor on Cl_alpha, capped at M = 0.95, unless the
            compressibility correction is off).
        wind_c : ndarray, shape (n_s, 3), optional
            Air velocity at the strips, component axes [m/s] (its time derivative is neglected in the
            apparent-mass and inflow terms).

        Returns
        -------
        m_a : ndarray, shape (n_v, n_v)
            Added-mass matrix (left-hand side).
        q_a : ndarray, shape (n_v,)
            Explicit generalized aerodynamic force.
        inflow : tuple
            Terms for :meth:`inflow_rate`.
        """
        has_wind = wind_c is not None
        wind = _arr(wind_c) if has_wind else np.zeros((self.strips.n_strips, 3))
        lam = _arr(lam)
        m_a, q_a, row0, w_ea_x, u0 = _k.aero_evaluate(*self.kernel_data, _arr(q), _arr(xi), _arr(vel), lam, _arr(u),
                                                      float(rho), float(mach), wind, has_wind)
        return m_a, q_a, (row0, w_ea_x, u0, lam)

    def inflow_rate(self, terms, vdot: np.ndarray) -> np.ndarray:
        """Finite-state inflow derivative lambda_dot (reference 2.1) with the solved accelerations.

        lambda_dot = A^-1 [c (w0_dot + w1_dot/2) - (u0/b) lambda] for every wing/stabilizer strip.
        """
        if not self.finite_state:
            return np.zeros(0)
        row0, w_ea_x, u0, lam = terms
        return _k.inflow_rate(*self.kernel_data, row0, w_ea_x, u0, lam, _arr(vdot))

    def strip_loads(self, q, xi, vel, lam, u, rho, mach, wind_c=None) -> StripLoads:
        """Per-strip circulatory loads at a state (no apparent mass), for outputs and tests."""
        kin = self._with_downwash(self.kinematics(q, xi, vel, lam, u, wind_c), vel, mach)
        lift, moment, _, drag, flow_angle = self._circulatory(kin, rho, mach)
        return StripLoads(kin.u0, kin.w_ea, lift, moment, drag, flow_angle)
