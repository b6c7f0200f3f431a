"""The physical terms a model is built with: one frozen, validated options object, :class:`Terms`.

Every term of the equations of motion (paper eq. 33) is on by default, and each can be switched off or modified when
the model is built; the compiled right-hand side then evaluates exactly that model (trim, linearisation, simulation
and the environments alike). The switches serve studies of which term causes an effect (e.g.
``studies/manoeuvre_decomposition.py``: what makes flutter depend on the manoeuvre) and the paper-replication settings
of docs/flutter.md. A model records its terms (:attr:`flexsim.model.aircraft_model.AircraftModel.terms`;
:meth:`Terms.record` gives them as a JSON-ready dict for result rows and log headers). A model that differs only in some
terms is ``model.replace(field=value, ...)`` (:meth:`~flexsim.model.aircraft_model.AircraftModel.replace`), the way every
analysis builds the siblings it needs, so that each evaluates the terms of the model it was given.

Example::

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.model.coupling import AeroOptions
    from flexsim.model.terms import Terms

    gtm = load_aircraft("gtm")
    model = AircraftModel(gtm, terms=Terms(aero=AeroOptions("quasi-steady"), gravity_m_s2=0.0,
                                           compressibility_mach=0.8))
    print(model.terms.record()["compressibility_mach"])  # 0.8
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field, fields

import flexsim._kernels  # noqa: F401  (imports every term module, which registers its data class in TERMS)
from flexsim._kernels.layout import TERMS
from flexsim.atmosphere import G0
from flexsim.model.coupling import AeroOptions

__all__ = ["Terms", "NonlinearBeams", "FORCE_RESOLUTIONS", "NONLINEAR_ANALYSES", "aero_term_options"]

#: Metadata of a :class:`Terms` field that switches an aerodynamic term: with ``aero=None`` it must keep its default.
_AERODYNAMIC = {"aerodynamic": True}
#: Values of :attr:`Terms.force_resolution`.
FORCE_RESOLUTIONS = ("full", "normal", "fin-normal")


def _finite_tuple(name: str, value, length: int | None = None) -> tuple[float, ...] | None:
    if value is None:
        return None
    try:
        out = tuple(float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be a sequence of numbers (or None)") from None
    if not all(math.isfinite(v) for v in out):
        raise ValueError(f"{name} = {value!r}: every entry must be finite")
    if length is not None and len(out) != length:
        raise ValueError(f"{name} = {value!r}: must have {length} entries")
    return out


def aero_term_options() -> tuple[type, ...]:
    """The options classes of the optional aerodynamic terms, the values :attr:`Terms.aero_terms` takes: each declared in
    its term's module of :mod:`flexsim._kernels` beside the data class that names it (``options``), in the order the
    terms are registered (e.g. :class:`flexsim._kernels.downwash_lag.DownwashLag`)."""
    return tuple(t.options for t in TERMS if getattr(t, "options", None) is not None)


#: The analyses that evaluate a model with :attr:`Terms.nonlinear_beams`; every other analysis refuses such a model
#: (:func:`flexsim.model.aircraft_model.check_model`).
NONLINEAR_ANALYSES = ("fs.trim, fs.flutter, fs.vg_diagram, fs.linear_system, fs.state_space, fs.flexible_aircraft, "
                      "fs.trim_flexible, fs.flexible_flutter, fs.simulate_flexible (time-domain flight)")


#: The structures the nonlinear beams' flutter search can linearise about a trim.
STABILITY_STRUCTURES = ("clamped-wing", "free-aircraft")


@dataclass(frozen=True)
class NonlinearBeams:
    """The geometrically nonlinear structure: each flexible component a strain-based beam (Su & Cesnik 2011, J.
    Aircraft 48(1) eqs. 1-17; :mod:`flexsim.structure.strain_beam`) on the free-flying rigid body, instead of the
    paper's linear beams (Tuzcu & Nguyen 2014 eqs. 1, 14). docs/nonlinear-beams.md; docs/design.md gives the choice.

    Attributes
    ----------
    elements_per_beam : int
        Elements of each flexible component's beam, 1-64 (default 8: the HALE wing's first modes and its flutter
        within 1 % of 16 elements, docs/nonlinear-beams.md).
    stability : {"clamped-wing", "free-aircraft"}
        What the flutter search linearises about each nonlinear trim: the wing clamped at its trimmed root (default)
        or the whole free aircraft with Peters' strips on every lifting strip
        (:func:`flexsim.linear.flexible_flutter.flexible_flutter`'s ``structure``).
    """

    elements_per_beam: int = 8
    stability: str = "clamped-wing"

    def __post_init__(self) -> None:
        n = self.elements_per_beam
        if isinstance(n, bool) or not isinstance(n, numbers.Integral) or not 1 <= n <= 64:
            raise ValueError(f"nonlinear_beams.elements_per_beam = {n!r}: must be an integer in 1-64")
        object.__setattr__(self, "elements_per_beam", int(n))
        if self.stability not in STABILITY_STRUCTURES:
            raise ValueError(f"nonlinear_beams.stability = {self.stability!r}: must be one of "
                             f"{', '.join(STABILITY_STRUCTURES)}")


@dataclass(frozen=True)
class Terms:
    """Physical terms of the equations of motion (paper eq. 33), chosen at model construction.

    The defaults are the full model (every term on, true density, the flight's Mach number); each field switches one
    term off or modifies it. Validated on construction (a clear error names the field, the value and the allowed
    range); shapes that depend on the aircraft (``inertia_q_offset_m``) are checked when a model is built.

    Attributes
    ----------
    aero : AeroOptions or None
        The aerodynamic terms: strip airloads (eqs. 25-31), Peters finite-state inflow (``model="unsteady"``) or
        quasi-steady strips, and the switches of :class:`~flexsim.model.coupling.AeroOptions` (parasite drag, slender
        bodies, tail downwash, compressibility, force resolution of the paper or the physical one). None: vacuum
        (no aerodynamic term). Default ``AeroOptions()`` (unsteady, every aerodynamic term on).
    gravity_m_s2 : float
        g of the gravity term Q_g = M(q) [C [0, 0, g]; 0] (eq. 32) [m/s^2], >= 0 (0: no gravity). Default 9.80665.
    structural_damping : float or None
        Modal damping ratio zeta of every clamped elastic mode, in [0, 1) (the term -C_el [s; eta]); None (default):
        the aircraft file's ``structural_damping_ratio`` (0 unless it sets one: the paper's structure is undamped).
    aero_density_kg_m3 : float or None
        Air density of the aerodynamic terms [kg/m^3], in (0, 2), instead of the ISA density at the aircraft's
        altitude (None, default). The paper-replication setting of the *linearised* aerodynamics of a flutter search
        (docs/flutter.md); Mach number and compressibility keep the true altitude.
    compressibility_mach : float or None
        Mach number at which the strips' compressibility factor beta (Prandtl-Glauert, Glauert 1928; also the
        downwash's DATCOM scaling) is frozen, in [0, 1); None (default): the flight Mach number of every state.
        Without a compressibility correction (``AeroOptions(compressibility="none")``) it has no effect.
    force_resolution : {"full", "normal", "fin-normal"}
        Terms of the strip force resolution (eq. 28) that depend on the section's flow angle: ``"full"`` (default)
        f = L (-n - a0 d) + D (d - a0 n); ``"normal"``: on every strip the lift along -n only, without its tilt by the
        flow angle a0 and without drag (c_n = -L, c_d = 0; the trim-angle terms of the resolution removed);
        ``"fin-normal"``: the same on the fin's strips only (the strips without inflow states), which bounds any
        resolution of the fin's lift (eq. 31).
    fin_drag_per_lift : float or None
        kappa = C_Dav / C_Lav of the paper's fin drag law (eq. 30, d_v = q c_v C_Dav a_v = kappa l_v, section drag
        linear in the fin's angle; the paper gives no value), replacing the drag of the fin's strips (those without
        inflow states); resolved like every strip force (eq. 31 with the fin's flow angle). Finite, |kappa| <= 1.
        None (default): the fin's own induced and profile drag.
    thrust_follows_deflection : bool
        True (default): the thrust's generalized force T_e (t0 + t1 q) follows the bending of the engines' mounts
        (eqs. 17-24); False: T_e t0, the thrust line of the undeformed aircraft (no thrust stiffness).
    engine_angular_momentum : tuple of float or None
        h_e (3,) [kg m^2/s], body axes: the angular momentum of the engines' rotors, whose gyroscopic moment
        -omega x h_e enters the moment equations (:mod:`flexsim._kernels.gyroscopic`; Etkin & Reid 1996, ch. 4). None
        (default): no gyroscopic term (the paper has none).
    inertia_q_offset_m : tuple of float or None
        dq (nq,) [m]: the inertia term (M(q), dT/dq and M_dot V, eqs. 8-10, 33, and the gravity that acts through
        M(q)) evaluated at q + dq instead of q, the rest of the model at q. E.g. the level flight's static deflection
        minus a manoeuvre's: the static deflection's effect on M(q). None (default): dq = 0.
    aero_velocity_offset_m_s : tuple of float or None
        dv (3,) [m/s], body axes, added to the body velocity v that the strip aerodynamics see (kinematics, loads,
        apparent mass, inflow forcing and downwash; not the Mach number, the parasite drag or the bodies). E.g. the
        level flight's body velocity minus a manoeuvre's at the same speed: the aerodynamics at the level angle of
        attack and sideslip. None (default): dv = 0.
    aero_terms : tuple
        The optional aerodynamic terms the model has, each given by its options object, declared in the term's own
        module (:func:`aero_term_options`), at most one of each; e.g. ``(fs.DownwashLag(),)``
        (:class:`flexsim._kernels.downwash_lag.DownwashLag`): the horizontal tail's downwash lag, the tail's alpha-dot
        derivatives (Etkin & Reid 1996 ch. 5, USAF DATCOM sec. 7.4.4), which needs the wing's downwash at the tail.
        Default ``()``: none (the paper has none).
    nonlinear_beams : NonlinearBeams or None
        The structure: None (default) the paper's linear beams (eqs. 1, 14; the small-deflection limit, valid to a
        tip deflection of 14 % of a beam's length, :mod:`flexsim.model.linear_range`); a :class:`NonlinearBeams`:
        geometrically exact strain-based beams with strip airloads on the deformed strips. A model with it is
        evaluated by the analyses of :data:`NONLINEAR_ANALYSES` (trim of symmetric flight, flutter about that trim)
        and refused by the others with a message naming this field.
    """

    aero: AeroOptions | None = AeroOptions()
    gravity_m_s2: float = G0
    structural_damping: float | None = None
    aero_density_kg_m3: float | None = field(default=None, metadata=_AERODYNAMIC)
    compressibility_mach: float | None = field(default=None, metadata=_AERODYNAMIC)
    force_resolution: str = field(default="full", metadata=_AERODYNAMIC)
    fin_drag_per_lift: float | None = field(default=None, metadata=_AERODYNAMIC)
    thrust_follows_deflection: bool = True
    engine_angular_momentum: tuple[float, float, float] | None = None
    inertia_q_offset_m: tuple[float, ...] | None = None
    aero_velocity_offset_m_s: tuple[float, float, float] | None = field(default=None, metadata=_AERODYNAMIC)
    aero_terms: tuple = field(default=(), metadata=_AERODYNAMIC)
    nonlinear_beams: NonlinearBeams | None = None

    def __post_init__(self) -> None:
        if self.aero is not None and not isinstance(self.aero, AeroOptions):
            raise ValueError(f"aero = {self.aero!r}: must be an AeroOptions or None (vacuum)")
        g = self.gravity_m_s2
        if isinstance(g, bool) or not isinstance(g, numbers.Real) or not math.isfinite(g) or g < 0:
            raise ValueError(f"gravity_m_s2 = {g!r}: must be a finite number >= 0")
        object.__setattr__(self, "gravity_m_s2", float(g))
        z = self.structural_damping
        if z is not None:
            if isinstance(z, bool) or not isinstance(z, numbers.Real) or not (math.isfinite(z) and 0.0 <= z < 1.0):
                raise ValueError(f"structural_damping = {z!r}: must be a damping ratio in [0, 1) (or None: the aircraft's)")
            object.__setattr__(self, "structural_damping", float(z))
        rho = self.aero_density_kg_m3
        if rho is not None:
            if isinstance(rho, bool) or not isinstance(rho, numbers.Real) or not (math.isfinite(rho) and 0.0 < rho < 2.0):
                raise ValueError(f"aero_density_kg_m3 = {rho!r}: must be an air density in (0, 2) kg/m^3 (or None: the ISA density)")
            object.__setattr__(self, "aero_density_kg_m3", float(rho))
        m = self.compressibility_mach
        if m is not None:
            if isinstance(m, bool) or not isinstance(m, numbers.Real) or not (math.isfinite(m) and 0.0 <= m < 1.0):
                raise ValueError(f"compressibility_mach = {m!r}: must be a Mach number in [0, 1) (or None: the flight's)")
            object.__setattr__(self, "compressibility_mach", float(m))
        if self.force_resolution not in FORCE_RESOLUTIONS:
            raise ValueError(f"force_resolution = {self.force_resolution!r}: must be one of {', '.join(FORCE_RESOLUTIONS)}")
        k = self.fin_drag_per_lift
        if k is not None:
            if isinstance(k, bool) or not isinstance(k, numbers.Real) or not (math.isfinite(k) and abs(k) <= 1.0):
                raise ValueError(f"fin_drag_per_lift = {k!r}: must be a number in [-1, 1] (or None: the fin's own drag)")
            object.__setattr__(self, "fin_drag_per_lift", float(k))
        if not isinstance(self.thrust_follows_deflection, bool):
            raise ValueError(f"thrust_follows_deflection = {self.thrust_follows_deflection!r}: must be True or False")
        self._check_aero_terms()
        if self.nonlinear_beams is not None and not isinstance(self.nonlinear_beams, NonlinearBeams):
            raise ValueError(f"nonlinear_beams = {self.nonlinear_beams!r}: must be a NonlinearBeams (e.g. "
                             "NonlinearBeams(elements_per_beam=8)) or None (the paper's linear beams)")
        object.__setattr__(self, "engine_angular_momentum",
                           _finite_tuple("engine_angular_momentum", self.engine_angular_momentum, 3))
        object.__setattr__(self, "inertia_q_offset_m", _finite_tuple("inertia_q_offset_m", self.inertia_q_offset_m))
        object.__setattr__(self, "aero_velocity_offset_m_s",
                           _finite_tuple("aero_velocity_offset_m_s", self.aero_velocity_offset_m_s, 3))
        if self.aero is None:
            for f in fields(self):  # the aerodynamic terms' switches (metadata _AERODYNAMIC) keep their defaults
                if f.metadata.get("aerodynamic") and getattr(self, f.name) != f.default:
                    raise ValueError(f"{f.name} = {getattr(self, f.name)!r}: a model without aerodynamics (aero None) has "
                                     "no aerodynamic term to apply it to")

    def _check_aero_terms(self) -> None:
        """:attr:`aero_terms` as a tuple of options objects of distinct registered terms, else a ValueError."""
        given = self.aero_terms
        if isinstance(given, (str, bytes)) or not hasattr(given, "__iter__"):
            raise ValueError(f"aero_terms = {given!r}: must be a tuple of aerodynamic terms' options, e.g. (DownwashLag(),)")
        given = tuple(given)
        allowed = aero_term_options()
        for option in given:
            if type(option) not in allowed:
                raise ValueError(f"aero_terms = {given!r}: {option!r} is not the options of an aerodynamic term (one of "
                                 f"{', '.join(c.__name__ for c in allowed)})")
        kinds = [type(option) for option in given]
        if len(set(kinds)) != len(kinds):
            raise ValueError(f"aero_terms = {given!r}: each term at most once")
        object.__setattr__(self, "aero_terms", given)

    def aero_term(self, options: type):
        """The options object of class ``options`` in :attr:`aero_terms` (the term is on), or None (off)."""
        for option in self.aero_terms:
            if type(option) is options:
                return option
        return None

    def record(self) -> dict:
        """The terms as a JSON-ready dict (for result rows and log headers): every field by name, ``aero`` as the
        dict of its options (None: vacuum), offsets as lists, ``aero_terms`` as a list of dicts (``"term"``: the
        options class's name, then its options); :meth:`from_record` reads it back."""
        out = {}
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name in ("aero", "nonlinear_beams"):
                v = None if v is None else {g.name: getattr(v, g.name) for g in fields(v)}
            elif f.name == "aero_terms":  # each term by its options class's name and its options
                v = [{"term": type(t).__name__, **{g.name: getattr(t, g.name) for g in fields(t)}} for t in v]
            elif isinstance(v, tuple):
                v = list(v)
            out[f.name] = v
        return out

    @classmethod
    def from_record(cls, record: dict) -> Terms:
        """The terms of a :meth:`record` (also of earlier records: a ``downwash_lag`` flag, fields then absent)."""
        t = dict(record)
        t["aero"] = None if t.get("aero") is None else AeroOptions(**t["aero"])
        if t.get("nonlinear_beams") is not None:
            t["nonlinear_beams"] = NonlinearBeams(**t["nonlinear_beams"])
        options = {c.__name__: c for c in aero_term_options()}
        terms = []
        for entry in t.pop("aero_terms", ()):
            entry = dict(entry)
            name = entry.pop("term")
            if name not in options:
                raise ValueError(f"aero_terms: {name!r} is not an aerodynamic term of this flexsim (one of {', '.join(options)})")
            terms.append(options[name](**entry))
        if t.pop("downwash_lag", False):
            terms.append(options["DownwashLag"]())
        t["aero_terms"] = tuple(terms)
        return cls(**t)
