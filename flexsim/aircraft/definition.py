"""Aircraft definition: validated, frozen dataclasses for the paper's topology.

The aircraft is the flexible multibody system of Tuzcu & Nguyen (2014), "Modeling Flexible Aircraft":
a fuselage beam clamped at the body origin o, and right/left wing, right/left horizontal stabilizer and
vertical stabilizer beams clamped to the fuselage at their roots. Every beam carries one bending
displacement along z_i and one torsion about x_i (its elastic axis). Lumped masses (engines, fuel, gear,
payload) ride on a component at a station.

All quantities are SI and expressed in **body axes** (x forward, y right, z down, origin o); the TOML
loader (:mod:`flexsim.aircraft.toml_loader`) converts other input frames. Validation happens on
construction: a malformed definition raises :class:`~flexsim.errors.AircraftDefinitionError` naming the
field, the value and what is allowed.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field, fields, replace
from typing import Iterable

import numpy as np

from flexsim.aircraft.checks import MAX_STATIONS, PLAUSIBLE, _check_scalar, _fail, _frozen_array, _in_plausible  # noqa: F401 (re-exported)
from flexsim.aircraft.content import ContentKey, feed_digest
from flexsim.aircraft.sections import SectionTable
from flexsim.kinematics import dcm_321

__all__ = [
    "COMPONENT_NAMES",
    "MAX_MODES",
    "ContentKey",
    "SectionTable",
    "StripAero",
    "AeroSettings",
    "Envelope",
    "DragItem",
    "BodyItem",
    "COMPRESSIBILITY",
    "DEFAULT_MAX_ALPHA_DEG",
    "ControlSurface",
    "Component",
    "LumpedMass",
    "Engine",
    "Aircraft",
]

#: Largest number of bending or torsion shape functions per component accepted by flexsim.
MAX_MODES = 10

#: The paper's components, in the order of the global velocity vector (eq. 9).
COMPONENT_NAMES = ("fuselage", "right_wing", "left_wing", "right_htail", "left_htail", "vtail")

#: Resolutions of the strip airloads (docs/design.md, "Force resolution"): the default first.
FORMULATIONS = ("physical", "paper")

#: Control surface kind allowed on each component (paper: ailerons antisymmetric, elevator symmetric).
_SURFACE_KIND = {
    "right_wing": "aileron",
    "left_wing": "aileron",
    "right_htail": "elevator",
    "left_htail": "elevator",
    "vtail": "rudder",
}


@dataclass(frozen=True)
class StripAero:
    """Aerodynamic strips of a lifting component (paper: N_w, N_h spanwise locations, Fig. 5).

    Attributes
    ----------
    strips : int
        Number of equal-width streamwise strips along the elastic axis, 1..200.
    lift_slope : str or float
        Sectional lift-curve slope Cl_alpha: ``"vlm"`` (vortex lattice of wing + horizontal stabilizer,
        the paper's choice; wings and stabilizers only), ``"2pi"`` (thin-airfoil value), or a number
        [1/rad] in (0, 2 pi]. The Prandtl-Glauert factor 1/sqrt(1 - M^2) is applied on top. An aircraft file
        that gives none sets ``"vlm"`` on wings and stabilizers and ``"2pi"`` on the fin.
    cd0 : float
        Section parasite-drag coefficient [-] (not in the paper; default 0).
    incidence_rad : float
        Rigging angle of the strips' chords relative to the component's x_i y_i plane, nose up [rad]
        (not in the paper's Table 1, whose angles fix the elastic axis; default 0).
    """

    strips: int = 8
    lift_slope: str | float = "vlm"
    cd0: float = 0.0
    incidence_rad: float = 0.0

    def check(self, where: str, component: str) -> None:
        """Validate against the owning component (raises AircraftDefinitionError)."""
        if isinstance(self.strips, bool) or not isinstance(self.strips, (int, np.integer)) or not 1 <= self.strips <= 200:
            _fail(f"{where}.strips", self.strips, "must be an integer in [1, 200]")
        if isinstance(self.lift_slope, str):
            if self.lift_slope not in ("vlm", "2pi"):
                _fail(f"{where}.lift_slope", self.lift_slope, 'must be "vlm", "2pi" or a number in (0, 2 pi] [1/rad]')
            if self.lift_slope == "vlm" and component == "vtail":
                _fail(f"{where}.lift_slope", self.lift_slope, 'the vortex lattice covers wing and horizontal stabilizer only (paper); give "2pi" or a number for the fin')
        else:
            _check_scalar(f"{where}.lift_slope", self.lift_slope, 0.0, 2 * np.pi, lo_open=True)
        _check_scalar(f"{where}.cd0", self.cd0, 0.0, 1.0)
        _check_scalar(f"{where}.incidence", self.incidence_rad, -np.deg2rad(15.0), np.deg2rad(15.0))


#: Compressibility corrections of the sectional lift-curve slope (aircraft file ``[aero] compressibility``).
COMPRESSIBILITY = ("prandtl-glauert", "none")

#: Default validity limit of the linear aerodynamics, |alpha| of the CG [deg] (aircraft file ``[aero] max_alpha_deg``):
#: the NASA GTM's. Its wind-tunnel database (``flexsim/aircraft/data/sources/t2_aero_basic_beta0.csv``, NASA
#: GTM_DesignSim's T2 polynomial aerodynamic database at beta = 0) has a normal-force coefficient CN = -CZ within 10 %
#: of its straight line over alpha = 0-6 deg up to alpha = 11 deg (-8.2 %) and 12.6 % below it at 12 deg, where the
#: lift curve breaks (slope 38 % of the linear one between 11 and 12 deg): beyond 11 deg the strip theory's linear
#: lift is more than 10 % too high (:func:`flexsim.aircraft.t2_data.t2_linear_alpha_limit_deg`).
DEFAULT_MAX_ALPHA_DEG = 11.0
#: Largest accepted ``max_alpha_deg`` [deg]: a plausibility bound on the input, as for the other fields.
MAX_ALPHA_LIMIT_DEG = 30.0


@dataclass(frozen=True, eq=False)
class DragItem:
    """A parasite-drag item: a body in the flow with drag area f = C_D0 S (not in the paper).

    Attributes
    ----------
    name : str
    component : str
        The component it is attached to (its drag loads that component's structure).
    position_m : ndarray, shape (3,)
        Point where the drag acts, body axes [m] (e.g. a nacelle's centre, a fuselage's centre of area).
    drag_area_m2 : float
        f = C_D0 S_ref-contribution [m^2], in [0, 100]: the drag is 1/2 rho |v|^2 f along the local air velocity.
    """

    name: str
    component: str
    position_m: np.ndarray
    drag_area_m2: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "position_m", _frozen_array(f"aero.drag.{self.name}.position_m", self.position_m, (3,)))
        object.__setattr__(self, "drag_area_m2", _check_scalar(f"aero.drag.{self.name}.drag_area_m2", self.drag_area_m2, 0.0, 100.0))


@dataclass(frozen=True, eq=False)
class BodyItem:
    """A slender body in the flow (fuselage, nacelle) carrying Munk's moment (not in the paper).

    Its axis is parallel to the body x axis (a transport's fuselage and nacelles); its apparent masses
    are those of the prolate spheroid of the same fineness ratio (:mod:`flexsim.model.bodies`).

    Attributes
    ----------
    name : str
    component : str
        The component it is attached to (its moment loads that component's structure).
    position_m : ndarray, shape (3,)
        Reference point, body axes [m] (the centroid of its volume): where its velocity is taken.
    length_m, diameter_m : float
        Length l and maximum diameter d [m], 0 < d < l (fineness ratio l/d > 1).
    volume_m3 : float
        Volume [m^3], at most that of the cylinder pi d^2 l / 4.
    """

    name: str
    component: str
    position_m: np.ndarray
    length_m: float
    diameter_m: float
    volume_m3: float

    def __post_init__(self) -> None:
        w = f"aero.body.{self.name}"
        object.__setattr__(self, "position_m", _frozen_array(f"{w}.position_m", self.position_m, (3,)))
        object.__setattr__(self, "length_m", _check_scalar(f"{w}.length_m", self.length_m, 0.0, 200.0, lo_open=True))
        object.__setattr__(self, "diameter_m", _check_scalar(f"{w}.diameter_m", self.diameter_m, 0.0, 50.0, lo_open=True))
        if not self.diameter_m < self.length_m:
            _fail(f"{w}.diameter_m", self.diameter_m, f"must be smaller than length_m = {self.length_m:.6g} m (a slender body, fineness ratio > 1)")
        cylinder = 0.25 * np.pi * self.diameter_m**2 * self.length_m
        object.__setattr__(self, "volume_m3", _check_scalar(f"{w}.volume_m3", self.volume_m3, 0.0, cylinder, lo_open=True))


@dataclass(frozen=True)
class AeroSettings:
    """Aircraft-wide aerodynamic settings (the file's top-level ``[aero]`` table).

    Attributes
    ----------
    compressibility : {"prandtl-glauert", "none"}
        Correction of the circulatory lift-curve slope for the flight Mach number M:
        ``"prandtl-glauert"`` (default, the paper's "Numerical Model": Cl_alpha / sqrt(1 - M^2), M capped
        at 0.95) or ``"none"`` (incompressible strip theory, as in the classical Goland and typical-section
        benchmarks). Models take it unless :class:`~flexsim.model.coupling.AeroOptions` overrides it.
    drag : tuple of DragItem
        Parasite-drag items (zero-lift drag of fuselage, nacelles, tails, wing profile; not in the paper,
        default none). Models apply them unless ``AeroOptions(parasite_drag=False)``.
    bending_incidence : bool
        Swept-wing bending-incidence coupling (default False, the paper's model): the strips' streamwise
        pitch includes sin(Lambda) times the bending slope (docs/options.md).
    bodies : tuple of BodyItem
        Slender bodies carrying Munk's moment (fuselage, nacelles; not in the paper, default none). Models
        apply them unless ``AeroOptions(body_moments=False)``.
    downwash_gradient : float
        d(epsilon)/d(alpha) of the wing's downwash at the horizontal tail in incompressible flow, in [0, 1)
        (not in the paper, whose tail sees the free stream: default 0). The tail strips see the downwash
        epsilon = gradient x (wing lift) / (its incompressible lift per radian) (:mod:`flexsim.model.coupling`).
    max_alpha_rad : float
        Validity limit of the linear (no-stall) aerodynamics: the largest |angle of attack| of the centre of
        gravity at which a trim is accepted [rad], in (0, 30 deg] (file: ``max_alpha_deg``). Default
        :data:`DEFAULT_MAX_ALPHA_DEG`, the NASA GTM's measured linear range (its wind-tunnel database, see the
        constant); another aircraft should give its own. :func:`flexsim.trimming.trim` raises beyond it unless
        ``check_limits=False``.
    """

    compressibility: str = "prandtl-glauert"
    drag: tuple = ()
    bending_incidence: bool = False
    bodies: tuple = ()
    downwash_gradient: float = 0.0
    max_alpha_rad: float = float(np.deg2rad(DEFAULT_MAX_ALPHA_DEG))

    def __post_init__(self) -> None:
        if self.compressibility not in COMPRESSIBILITY:
            _fail("aero.compressibility", self.compressibility, f"must be one of {', '.join(repr(c) for c in COMPRESSIBILITY)}")
        if not isinstance(self.bending_incidence, bool):
            _fail("aero.bending_incidence", self.bending_incidence, "must be true or false")
        object.__setattr__(self, "drag", tuple(self.drag))
        names = [d.name for d in self.drag]
        if len(set(names)) != len(names):
            _fail("aero.drag names", names, "must be unique")
        object.__setattr__(self, "bodies", tuple(self.bodies))
        gradient = _check_scalar("aero.downwash_gradient", self.downwash_gradient, 0.0, 1.0)
        if gradient == 1.0:
            _fail("aero.downwash_gradient", self.downwash_gradient, "must be in [0, 1): at 1 the tail would not see the angle of attack")
        object.__setattr__(self, "downwash_gradient", gradient)
        object.__setattr__(self, "max_alpha_rad", _check_scalar("aero.max_alpha_rad", self.max_alpha_rad, 0.0, np.deg2rad(MAX_ALPHA_LIMIT_DEG), lo_open=True))
        names = [b.name for b in self.bodies]
        if len(set(names)) != len(names):
            _fail("aero.body names", names, "must be unique")


@dataclass(frozen=True, eq=False)
class ControlSurface:
    """A trailing-edge control surface on a lifting component (paper Fig. 2, eq. 26).

    Attributes
    ----------
    kind : {"aileron", "elevator", "rudder"}
    hinge_fraction : float
        Hinge line aft of the leading edge as a fraction of the chord, in (0, 1); Peters' d = 2 f - 1.
    start_m, end_m : float
        Spanwise extent along the elastic axis [m], 0 <= start < end <= length.
    max_deflection_rad : float
        Deflection limit, +-, used by trim and the environments [rad] (default 25 deg).
    """

    kind: str
    hinge_fraction: float
    start_m: float
    end_m: float
    max_deflection_rad: float = float(np.deg2rad(25.0))

    @property
    def hinge_d(self) -> float:
        """Hinge position in semichords from mid-chord, d = 2 hinge_fraction - 1 (docs/reference/aero-kinematics.md §1.6)."""
        return 2.0 * self.hinge_fraction - 1.0


@dataclass(frozen=True, eq=False)
class Component:
    """One beam of the aircraft, clamped at its root (paper eqs. 1, 5-6, Table 1).

    Attributes
    ----------
    name : str
        One of :data:`COMPONENT_NAMES`.
    root_m : ndarray, shape (3,)
        Root (origin o_i of x_i y_i z_i) in body axes [m]; the fuselage root is the body origin.
    euler_rad : ndarray, shape (3,)
        3-2-1 angles (phi, theta, psi) from body axes to component axes [rad] (paper Table 1).
    sections : SectionTable
    bending_modes, torsion_modes : int
        Numbers m and n of shape functions (0..10); both 0 when ``rigid``.
    rigid : bool
        True for a component carried rigidly (mass and aerodynamics, no elastic coordinates).
    section_inertia : {"chordwise", "axisymmetric"}
        How the torsional inertia splits into the section's rotary inertias: chordwise (airfoil,
        J_yy = 0, J_zz = I_theta) or axisymmetric (fuselage, J_yy = J_zz = I_theta / 2).
    control_surface : ControlSurface or None
    aero : StripAero or None
        Aerodynamic strips; None for a component without aerodynamics (the fuselage, paper).
    sweep_rad : float or None
        Sweep of the elastic axis Lambda_i [rad] (paper, text after eq. 27) when given explicitly;
        None derives it from the orientation (see :attr:`sweep`).
    """

    name: str
    root_m: np.ndarray
    euler_rad: np.ndarray
    sections: SectionTable
    bending_modes: int = 2
    torsion_modes: int = 2
    rigid: bool = False
    section_inertia: str = "chordwise"
    control_surface: ControlSurface | None = None
    aero: StripAero | None = None
    sweep_rad: float | None = None

    def __post_init__(self) -> None:
        w = f"components.{self.name}"
        if self.name not in COMPONENT_NAMES:
            _fail("components", self.name, f"unknown component; allowed: {', '.join(COMPONENT_NAMES)}")
        object.__setattr__(self, "root_m", _frozen_array(f"{w}.root_m", self.root_m, (3,)))
        object.__setattr__(self, "euler_rad", _frozen_array(f"{w}.euler", self.euler_rad, (3,)))
        _in_plausible(f"{w}.root_m", self.root_m, "position_m")
        _in_plausible(f"{w}.euler", self.euler_rad, "euler_rad")
        for attr in ("bending_modes", "torsion_modes"):
            v = getattr(self, attr)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not 0 <= v <= MAX_MODES:
                _fail(f"{w}.{attr}", v, f"must be an integer in [0, {MAX_MODES}]")
        if not isinstance(self.rigid, bool):
            _fail(f"{w}.rigid", self.rigid, "must be true or false")
        if self.rigid:
            object.__setattr__(self, "bending_modes", 0)
            object.__setattr__(self, "torsion_modes", 0)
        sec = self.sections
        if self.bending_modes and not np.any(sec.mass_kg_per_m > 0.0):
            _fail(f"{w}.sections.mass_kg_per_m", sec.mass_kg_per_m.tolist(), "a beam with bending modes needs mass (all entries are 0); set rigid = true or give the mass")
        if self.torsion_modes and not np.any(sec.torsional_inertia_kg_m > 0.0):
            _fail(f"{w}.sections.torsional_inertia_kg_m", sec.torsional_inertia_kg_m.tolist(), "a beam with torsion modes needs torsional inertia (all entries are 0)")
        if self.section_inertia not in ("chordwise", "axisymmetric"):
            _fail(f"{w}.section_inertia", self.section_inertia, 'must be "chordwise" or "axisymmetric"')
        if self.section_inertia == "chordwise" and abs(self.chord_direction[0]) > np.sin(np.deg2rad(80.0)):
            _fail(f"{w}.euler_deg", np.rad2deg(self.euler_rad).round(6).tolist(),
                  'points the beam within 10 deg of the flow (x_i along body x), which a "chordwise" section cannot '
                  'have (angles are in degrees; for a fuselage-like beam set section_inertia = "axisymmetric")')
        cs = self.control_surface
        if cs is not None:
            allowed = _SURFACE_KIND.get(self.name)
            if allowed is None or cs.kind != allowed:
                _fail(f"{w}.control_surface.kind", cs.kind, f"must be {allowed!r} on {self.name}" if allowed else f"{self.name} carries no control surface")
            _check_scalar(f"{w}.control_surface.hinge_fraction", cs.hinge_fraction, 0.0, 1.0, lo_open=True)
            if cs.hinge_fraction >= 1.0:
                _fail(f"{w}.control_surface.hinge_fraction", cs.hinge_fraction, "must be in (0, 1)")
            _check_scalar(f"{w}.control_surface.max_deflection", cs.max_deflection_rad, 0.0, np.deg2rad(60.0), lo_open=True)
            length = self.sections.length_m
            if not (0.0 <= cs.start_m < cs.end_m <= length * (1 + 1e-12)):
                _fail(f"{w}.control_surface.[start_m, end_m]", [cs.start_m, cs.end_m], f"must satisfy 0 <= start_m < end_m <= length_m = {length}")
        if self.aero is not None:
            if self.name == "fuselage":
                _fail(f"{w}.aero", "table", "the fuselage carries no aerodynamic strips (paper: wing and stabilizers only)")
            self.aero.check(f"{w}.aero", self.name)
            if np.any(self.sections.chord_m <= 0.0):
                i = int(np.flatnonzero(self.sections.chord_m <= 0.0)[0])
                _fail(f"{w}.sections.chord_m[{i}]", float(self.sections.chord_m[i]), "must be > 0 on a component with aerodynamic strips")
        if self.sweep_rad is not None:
            _check_scalar(f"{w}.sweep", self.sweep_rad, -np.pi / 2, np.pi / 2, lo_open=True)
            object.__setattr__(self, "sweep_rad", float(self.sweep_rad))

    @property
    def length_m(self) -> float:
        """Beam length L_i [m]."""
        return self.sections.length_m

    @property
    def sweep(self) -> float:
        """Sweep Lambda_i of the elastic axis [rad]: the given ``sweep_rad``, else asin(-x_i . x_body)."""
        if self.sweep_rad is not None:
            return self.sweep_rad
        return float(np.arcsin(np.clip(-self.axes_in_body[0, 0], -1.0, 1.0)))

    @property
    def dcm(self) -> np.ndarray:
        """C_i, shape (3, 3): body components -> component components (paper eq. 6, Table 1)."""
        return dcm_321(*self.euler_rad)

    @property
    def axes_in_body(self) -> np.ndarray:
        """Unit vectors x_i, y_i, z_i as the columns of a (3, 3) array in body components (C_i^T)."""
        return self.dcm.T

    @property
    def is_flexible(self) -> bool:
        """True when the component has at least one elastic coordinate."""
        return self.bending_modes + self.torsion_modes > 0

    @property
    def chord_direction(self) -> np.ndarray:
        """Unit vector along the streamwise chord towards the trailing edge, component axes, shape (3,).

        The aerodynamic strips are streamwise (the paper's "horizontal lines on the wing", Fig. 5), so
        chords, chordwise mass offsets and the airfoil coordinate run along body -x projected onto the
        component's x_i y_i plane. For a swept beam it has a spanwise component sin(Lambda) along x_i;
        unswept, it is +-y_i.
        """
        aft = -self.dcm[:, 0]  # body -x in component axes
        d = np.array([aft[0], aft[1], 0.0])
        norm = np.linalg.norm(d)
        return d / norm if norm > 1e-9 else np.array([0.0, 1.0, 0.0])

    def station_of(self, point_m: np.ndarray) -> float:
        """Projection of a body-axes point [m] onto the elastic axis: station x_i [m]."""
        return float((np.asarray(point_m, float) - self.root_m) @ self.axes_in_body[:, 0])


@dataclass(frozen=True, eq=False)
class LumpedMass:
    """A point mass with its own inertia, attached rigidly to a component at the nearest station.

    Attributes
    ----------
    name : str
    component : str
    position_m : ndarray, shape (3,)
        Centre of mass in body axes [m].
    mass_kg : float
        [kg], >= 0; 0 only with a nonzero ``inertia_kg_m2`` (a pure rotary inertia, as a NASTRAN CONM2 of zero mass).
    inertia_kg_m2 : ndarray, shape (3, 3)
        Inertia tensor about its own centre of mass, body axes [kg m^2].
    """

    name: str
    component: str
    position_m: np.ndarray
    mass_kg: float
    inertia_kg_m2: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))
    where: str = field(default="lumped_masses", repr=False)

    def __post_init__(self) -> None:
        w = f"{self.where}.{self.name}"
        object.__setattr__(self, "position_m", _frozen_array(f"{w}.position_m", self.position_m, (3,)))
        _in_plausible(f"{w}.position_m", self.position_m, "position_m")
        zero = not isinstance(self.mass_kg, bool) and isinstance(self.mass_kg, (int, float, np.number)) and self.mass_kg == 0
        try:
            rotary = bool(np.any(np.nan_to_num(np.asarray(self.inertia_kg_m2, dtype=float))))
        except (TypeError, ValueError):
            rotary = True  # a malformed inertia: named by its own check below
        if zero and not rotary:
            _fail(f"{w}.mass_kg", self.mass_kg, "must be in (0.0, inf], or 0 with a nonzero inertia_kg_m2 (a pure rotary "
                                                "inertia, as a NASTRAN CONM2 of zero mass)")
        if not zero:
            _check_scalar(f"{w}.mass_kg", self.mass_kg, 0.0, np.inf, lo_open=True)
            _in_plausible(f"{w}.mass_kg", self.mass_kg, "mass_kg", lo_open=True)
        object.__setattr__(self, "mass_kg", float(self.mass_kg))
        inertia = np.array(self.inertia_kg_m2, dtype=float) if np.ndim(self.inertia_kg_m2) else None
        if inertia is not None and inertia.shape == (3,):
            inertia = np.diag(inertia)
        inertia = _frozen_array(f"{w}.inertia_kg_m2", inertia if inertia is not None else self.inertia_kg_m2, (3, 3))
        if not np.allclose(inertia, inertia.T) or np.linalg.eigvalsh(inertia).min() < -1e-9 * max(1.0, np.abs(inertia).max()):
            _fail(f"{w}.inertia_kg_m2", inertia.tolist(), "must be a symmetric positive semi-definite tensor")
        _in_plausible(f"{w}.inertia_kg_m2", np.abs(inertia), "inertia_kg_m2")
        object.__setattr__(self, "inertia_kg_m2", inertia)


@dataclass(frozen=True, eq=False)
class Engine(LumpedMass):
    """An engine: a lumped mass that also carries thrust along body x (paper eqs. 17, 20-24).

    Attributes
    ----------
    max_thrust_n : float
        Maximum thrust of this engine [N]; the total thrust T_e is shared equally by the engines.
    """

    max_thrust_n: float = 0.0

    def __post_init__(self) -> None:
        super().__post_init__()
        _check_scalar(f"{self.where}.{self.name}.mass_kg", self.mass_kg, 0.0, np.inf, lo_open=True)
        _check_scalar(f"{self.where}.{self.name}.max_thrust_n", self.max_thrust_n, 0.0, np.inf, lo_open=True)
        _in_plausible(f"{self.where}.{self.name}.max_thrust_n", self.max_thrust_n, "max_thrust_n", lo_open=True)
        object.__setattr__(self, "max_thrust_n", float(self.max_thrust_n))


#: How far from the beam it rides on a component's root (from the fuselage's elastic axis) or a lumped mass (from its
#: component's) may lie: this fraction of that beam's length plus :data:`ROOT_REACH_M`. The bundled and example aircraft
#: stay within 0.18 of it (a T-tail's root on top of the sailplane's fin, 1.25 m on a 6.8 m fuselage; the GTM's engines
#: 3.2 m from its 18.25 m wing); a root or mass further out is not carried by the beam the model clamps it to [-].
ROOT_REACH_FRACTION = 0.2
#: The constant part of the reach, for short beams (a 1 m model fuselage) [m].
ROOT_REACH_M = 1.0


@dataclass(frozen=True)
class Envelope:
    """Where the aircraft flies, as far as a flutter search needs it (the file's ``[envelope]`` table).

    Every limit is optional; a search runs from the larger of the given lower limits to the smaller of the given
    upper limits at its altitude (:func:`flexsim.linear.envelope.search_range`). Equivalent airspeeds (EAS) are
    converted to Mach at the altitude with the ISA density and speed of sound.

    Attributes
    ----------
    min_mach, max_mach : float or None
        Mach limits [-], 0 < min_mach < max_mach <= 0.99 (subsonic strip theory).
    min_speed_eas_m_s, max_speed_eas_m_s : float or None
        Equivalent-airspeed limits [m/s] (e.g. the stall speed and the dive speed with its flutter margin), in
        (0, 400] m/s.
    cruise_altitude_m : float or None
        Altitude of the cruise point [m], in [0, 20000] (the ISA range of :mod:`flexsim.atmosphere`): where ``flexsim
        trim``, ``linearize``, ``simulate`` and the environments fly the aircraft when no altitude is given.
    cruise_mach, cruise_speed_m_s : float or None
        Speed of the cruise point, as a Mach number in (0, 0.99] or a true airspeed [m/s] in (0, 400] (at most one).
    max_altitude_m : float or None
        Highest altitude the aircraft flies [m], in (0, 20000]: ``flexsim flutter`` searches four altitudes from sea
        level to it when none is given.
    """

    min_mach: float | None = None
    max_mach: float | None = None
    min_speed_eas_m_s: float | None = None
    max_speed_eas_m_s: float | None = None
    cruise_altitude_m: float | None = None
    cruise_mach: float | None = None
    cruise_speed_m_s: float | None = None
    max_altitude_m: float | None = None

    def __post_init__(self) -> None:
        for name, lo, hi, lo_open in (("min_mach", 0.0, 0.99, True), ("max_mach", 0.0, 0.99, True),
                                      ("min_speed_eas_m_s", 0.0, 400.0, True), ("max_speed_eas_m_s", 0.0, 400.0, True),
                                      ("cruise_altitude_m", 0.0, 20000.0, False), ("cruise_mach", 0.0, 0.99, True),
                                      ("cruise_speed_m_s", 0.0, 400.0, True), ("max_altitude_m", 0.0, 20000.0, True)):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _check_scalar(f"envelope.{name}", value, lo, hi, lo_open=lo_open))
        if self.cruise_mach is not None and self.cruise_speed_m_s is not None:
            _fail("envelope.cruise_speed_m_s", self.cruise_speed_m_s,
                  f"give the cruise speed once: envelope.cruise_mach = {self.cruise_mach!r} is given too")
        if (self.cruise_altitude_m is not None and self.max_altitude_m is not None
                and self.cruise_altitude_m > self.max_altitude_m):
            _fail("envelope.cruise_altitude_m", self.cruise_altitude_m,
                  f"must not exceed envelope.max_altitude_m = {self.max_altitude_m!r}")
        for lo, hi in (("min_mach", "max_mach"), ("min_speed_eas_m_s", "max_speed_eas_m_s")):
            a, b = getattr(self, lo), getattr(self, hi)
            if a is not None and b is not None and not a < b:
                _fail(f"envelope.{lo}", a, f"must be below envelope.{hi} = {b!r}")


@dataclass(frozen=True, eq=False)
class Aircraft:
    """A whole aircraft definition: components, lumped masses and engines (body axes, SI).

    Attributes
    ----------
    name : str
    components : tuple of Component
        In :data:`COMPONENT_NAMES` order; any component may be omitted.
    lumped_masses : tuple of LumpedMass
    engines : tuple of Engine
    description : str
    source : str
        Where the definition came from (file path or "<python>"); used in error messages.
    design_origin_m : ndarray, shape (3,), or None
        For files written in a design frame (x aft, y right, z up): the body origin o in that frame
        [m], so that results can be reported back in the file's axes.
    structural_damping_ratio : float
        Modal damping ratio zeta [-] of every clamped elastic mode (``StructuralModel.damping``), in
        [0, 0.1]; 0 (the paper's undamped structure) unless the file sets it. Models built on the aircraft
        use it unless given another value.
    formulation : {"physical", "paper"}
        Resolution of the strip airloads (eq. 28; docs/design.md "Force resolution"): ``physical``
        (default: lift normal and drag along the local relative wind) or ``paper`` (the paper's eq. 28
        with no net body-x component, as its trims imply: T_e = W sin(theta)). Models built on the
        aircraft use it unless their :class:`~flexsim.model.coupling.AeroOptions` say otherwise.
    aero_settings : AeroSettings
        Aircraft-wide aerodynamic settings (the file's ``[aero]`` table).
    envelope : Envelope or None
        The flight envelope of the flutter search (the file's ``[envelope]`` table); None: derived
        (:func:`flexsim.linear.envelope.search_range`).
    """

    name: str
    components: tuple[Component, ...]
    lumped_masses: tuple[LumpedMass, ...] = ()
    engines: tuple[Engine, ...] = ()
    description: str = ""
    source: str = "<python>"
    design_origin_m: np.ndarray | None = None
    structural_damping_ratio: float = 0.0
    formulation: str = "physical"
    aero_settings: AeroSettings = field(default_factory=AeroSettings)
    envelope: Envelope | None = None

    def to_design_frame(self, point_m: np.ndarray) -> np.ndarray:
        """A body-axes point [m] in the file's design frame (x aft, y right, z up) [m]."""
        if self.design_origin_m is None:
            raise ValueError(f"aircraft {self.name!r} was not defined in a design frame")
        return self.design_origin_m + np.array([-1.0, 1.0, -1.0]) * np.asarray(point_m, float)

    def __post_init__(self) -> None:
        object.__setattr__(self, "structural_damping_ratio", _check_scalar("structural_damping_ratio", self.structural_damping_ratio, 0.0, 0.1))
        if self.formulation not in FORMULATIONS:
            _fail("formulation", self.formulation, f"must be one of {', '.join(repr(f) for f in FORMULATIONS)}")
        if not isinstance(self.aero_settings, AeroSettings):
            _fail("aero", self.aero_settings, "must be an AeroSettings")
        comps = tuple(self.components)
        names = [c.name for c in comps]
        if not comps:
            _fail("components", [], "at least one component is required")
        if len(set(names)) != len(names):
            _fail("components", names, "each component may appear once")
        comps = tuple(sorted(comps, key=lambda c: COMPONENT_NAMES.index(c.name)))
        object.__setattr__(self, "components", comps)
        object.__setattr__(self, "lumped_masses", tuple(self.lumped_masses))
        object.__setattr__(self, "engines", tuple(self.engines))
        fus = self.component("fuselage") if "fuselage" in names else None
        if fus is not None:
            if np.any(fus.root_m != 0.0):
                where = "components.fuselage.root_m" + ("" if self.design_origin_m is None else f" (design frame: {self.to_design_frame(fus.root_m).tolist()})")
                _fail(where, fus.root_m.tolist(), "must be [0, 0, 0] in body axes: the fuselage is clamped at the body origin o (paper: x_f y_f z_f coincides with xyz)")
            if np.any(fus.euler_rad != 0.0):
                _fail("components.fuselage.euler", fus.euler_rad.tolist(), "must be [0, 0, 0] (paper Table 1)")
            for c in comps:
                if c.name == "fuselage":
                    continue
                s = fus.station_of(c.root_m)
                if not -1e-9 <= s <= fus.length_m * (1 + 1e-9):
                    _fail(f"components.{c.name}.root_m", c.root_m.tolist(), f"root lies at fuselage station {s:.4g} m, off the fuselage (0 to {fus.length_m:.4g} m)")
                side = float(np.linalg.norm(c.root_m - fus.root_m - s * fus.axes_in_body[:, 0]))
                reach = ROOT_REACH_FRACTION * fus.length_m + ROOT_REACH_M
                if side > reach:
                    _fail(f"components.{c.name}.root_m", c.root_m.tolist(),
                          f"root lies {side:.4g} m from the fuselage's elastic axis: a component is clamped to the "
                          f"fuselage, at most {ROOT_REACH_FRACTION:g} x its length + {ROOT_REACH_M:g} m = {reach:.4g} m away")
        all_names = [m.name for m in self.lumped_masses] + [e.name for e in self.engines]
        if len(set(all_names)) != len(all_names):
            _fail("lumped_masses/engines names", all_names, "names must be unique")
        for item in (*self.lumped_masses, *self.engines):
            w = f"{item.where}.{item.name}"
            if item.component not in names:
                _fail(f"{w}.component", item.component, f"must be one of the defined components: {', '.join(names)}")
            comp = self.component(item.component)
            s = comp.station_of(item.position_m)
            if not -1e-9 * comp.length_m <= s <= comp.length_m * (1 + 1e-9):
                _fail(f"{w}.position_m", item.position_m.tolist(), f"projects to station {s:.4g} m, off component {comp.name} (0 to {comp.length_m:.4g} m)")
            off = float(np.linalg.norm(item.position_m - comp.root_m - s * comp.axes_in_body[:, 0]))
            reach = ROOT_REACH_FRACTION * comp.length_m + ROOT_REACH_M
            if off > reach:
                _fail(f"{w}.position_m", item.position_m.tolist(), f"lies {off:.4g} m from the elastic axis of {comp.name}: "
                      f"a lumped mass rides on its component, at most {ROOT_REACH_FRACTION:g} x its length + "
                      f"{ROOT_REACH_M:g} m = {reach:.4g} m away")
        total = sum(float(np.trapezoid(c.sections.mass_kg_per_m, c.sections.station_m)) for c in comps)
        total += sum(m.mass_kg for m in (*self.lumped_masses, *self.engines))
        if not total > 0.0:
            _fail("total mass", total, "must be > 0 kg (every mass_kg_per_m is 0 and there are no lumped masses)")
        _in_plausible("total mass", total, "total_mass_kg", lo_open=True)
        for d in self.aero_settings.drag:
            w = f"aero.drag.{d.name}"
            if d.component not in names:
                _fail(f"{w}.component", d.component, f"must be one of the defined components: {', '.join(names)}")
            comp = self.component(d.component)
            s = comp.station_of(d.position_m)
            if not -0.05 * comp.length_m <= s <= comp.length_m * 1.05:
                _fail(f"{w}.position_m", d.position_m.tolist(), f"projects to station {s:.4g} m, off component {comp.name} (0 to {comp.length_m:.4g} m)")
        for b in self.aero_settings.bodies:
            w = f"aero.body.{b.name}"
            if b.component not in names:
                _fail(f"{w}.component", b.component, f"must be one of the defined components: {', '.join(names)}")
            comp = self.component(b.component)
            s = comp.station_of(b.position_m)
            if not -0.05 * comp.length_m <= s <= comp.length_m * 1.05:
                _fail(f"{w}.position_m", b.position_m.tolist(), f"projects to station {s:.4g} m, off component {comp.name} (0 to {comp.length_m:.4g} m)")

    def content_digest(self) -> str:
        """SHA-256 (hex) of everything that defines the aircraft, all fields except ``source``.

        The key for caches of results computed from an aircraft (flutter points, modes): two definitions
        with the same content share it whatever file they came from, and any change (a scaled stiffness,
        other modes, an edited file) gives another key. Floats enter by their exact ``repr``, arrays by
        dtype, shape and bytes. Computed once per instance (the definition is immutable: frozen dataclasses,
        read-only arrays); every eigen-analysis asks for it (0.65 ms).
        """
        known = self.__dict__.get("_content_digest")
        if known is not None:
            return known
        digest = hashlib.sha256()
        feed_digest(digest, {f.name: getattr(self, f.name) for f in fields(self) if f.name != "source"})
        object.__setattr__(self, "_content_digest", digest.hexdigest())
        return self._content_digest

    def content_key(self) -> "ContentKey":
        """This aircraft as a hashable cache key, equal for equal content (:meth:`content_digest`)."""
        return ContentKey(self)

    def component(self, name: str) -> Component:
        """The component called ``name`` (KeyError listing the available ones otherwise)."""
        for c in self.components:
            if c.name == name:
                return c
        raise KeyError(f"component {name!r} not in aircraft {self.name!r}; available: {[c.name for c in self.components]}")

    @property
    def max_thrust_n(self) -> float:
        """Total maximum thrust of all engines [N] (0 without engines)."""
        return float(sum(e.max_thrust_n for e in self.engines))

    def control_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper limits of u = [T_e (N), delta_a, delta_e, delta_r (rad)], shape (4,) each.

        Thrust: 0 .. sum of the engines' maximum thrust; a surface absent from the aircraft has limits 0.
        """
        hi = np.zeros(4)
        hi[0] = self.max_thrust_n
        kinds = {"aileron": 1, "elevator": 2, "rudder": 3}
        for c in self.components:
            if c.control_surface is not None:
                k = kinds[c.control_surface.kind]
                hi[k] = max(hi[k], c.control_surface.max_deflection_rad)
        lo = -hi
        lo[0] = 0.0
        return lo, hi

    @property
    def nonlinear_beam_fields(self) -> tuple[str, ...]:
        """Section fields given in the file that only the geometrically nonlinear beam uses, as
        ``components.<name>.sections.<field>`` (:data:`flexsim.aircraft.sections.NONLINEAR_BEAM_FIELDS`); the
        linear structure (the paper's) has no use for them. Empty for a file of the paper's fields only."""
        return tuple(f"components.{c.name}.sections.{name}" for c in self.components
                     for name in c.sections.nonlinear_beam_fields)

    @property
    def component_names(self) -> tuple[str, ...]:
        """Names of the components present, in the order of the global velocity vector (eq. 9)."""
        return tuple(c.name for c in self.components)

    def subset(self, names: Iterable[str]) -> "Aircraft":
        """A new aircraft keeping only the components ``names`` and the masses they carry.

        Without the fuselage, the remaining components are clamped directly to the body axes (e.g. a
        single wing clamped at its root, paper "individual flexible components" model).
        """
        keep = tuple(names)
        for n in keep:
            self.component(n)
        return replace(
            self,
            components=tuple(c for c in self.components if c.name in keep),
            lumped_masses=tuple(m for m in self.lumped_masses if m.component in keep),
            engines=tuple(e for e in self.engines if e.component in keep),
            aero_settings=replace(self.aero_settings, drag=tuple(d for d in self.aero_settings.drag if d.component in keep),
                                  bodies=tuple(b for b in self.aero_settings.bodies if b.component in keep)),
            name=f"{self.name}[{','.join(keep)}]",
        )

    def with_modes(self, bending_modes: int, torsion_modes: int) -> "Aircraft":
        """A copy with every flexible component using m = ``bending_modes`` and n = ``torsion_modes``."""
        comps = tuple(
            c if c.rigid else replace(c, bending_modes=bending_modes, torsion_modes=torsion_modes)
            for c in self.components
        )
        return replace(self, components=comps)
