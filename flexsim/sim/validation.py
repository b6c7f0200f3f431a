"""Verification cases against published values and closed forms: ``flexsim validate``.

Each case computes one or more quantities with flexsim and compares them with a reference value taken from a
publication or a closed form, within a stated relative (or, for invariants, absolute) tolerance. The
built-in cases (``docs/validation.md`` gives the sources and the measured errors):

* ``goland-flutter-*`` — Goland wing clamped in a wind tunnel (Goland 1945; SI data of Patil, Hodges &
  Cesnik 2001): flutter speed and frequency, Theodorsen p-k and Peters N = 6, incompressible, at
  1.225 kg/m^3 (Goland's 137.2 m/s, 70.7 rad/s) and at 1.02 kg/m^3 with Prandtl-Glauert (Palacios &
  Epureanu 2011: 141 m/s, 69.8 rad/s, as quoted by the Aeroelasticity.jl documentation's Goland example).
* ``goland-divergence-*`` — divergence speed against the strip-theory closed form for a uniform clamped
  wing, q_D = pi^2 GJ / (4 L^2 e c Cl_alpha) (Hodges & Pierce 2011, ch. 4), at both densities.
* ``typical-section-*`` — the Hodges & Pierce typical section (a = -1/5, e = -1/10, mu = 20, r^2 = 6/25,
  sigma = 2/5): flutter speed U_F/(b omega_theta) 2.1839 (Theodorsen) and 2.1654 (Peters N = 6), and the
  quasi-steady model's divergence speed sqrt(mu r^2 / (2 (1/2 + a))) = 2.8284.
* ``free-flight-conservation`` — the free GTM tumbling in vacuum without gravity conserves energy, linear
  momentum and angular momentum about O (a consequence of eq. 33): relative drifts below 1e-9.
* ``phugoid-lanchester`` — phugoid of the quasi-rigid GTM (incompressible, 6000 m, M 0.6, with its parasite
  drag, without the fuselage/nacelle moments and the tail downwash: Lanchester's constant angle of attack is the
  stiff-pitch limit) against Lanchester's sqrt(2) g / V (5 %) and D / (sqrt(2) L) (20 %) (Lanchester 1908;
  Etkin & Reid 1996, sec. 6.4).
* ``coordinated-turn-load-factor`` — load factor of the coordinated level turn at 9144 m, M 0.78,
  R = 5 km against sqrt(1 + (V^2/gR)^2) and against 1/cos(mu), mu the wind-axis bank (the bank of the lift about
  the velocity, which the point-mass relation n = 1/cos(mu) means; the Euler roll angle phi differs from it when
  the body is pitched: sin(mu) = sin(phi) cos(theta) at zero sideslip), and mu against atan(V^2/gR).

A user case is a TOML file (:func:`load_case`) naming an aircraft file and the reference values.
"""

from __future__ import annotations

import math
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

__all__ = ["Check", "CaseResult", "PhugoidPoint", "ValidationCase", "builtin_cases", "load_case", "phugoid_point", "run_case",
           "case_names"]


@dataclass(frozen=True)
class Check:
    """One compared quantity: reference, flexsim's value, error and tolerance.

    ``error`` is relative, (value - reference) / |reference|, unless ``absolute`` (invariants whose
    reference is 0), and the check passes when |error| <= tolerance.
    """

    quantity: str
    unit: str
    reference: float
    value: float
    tolerance: float
    source: str
    absolute: bool = False

    @property
    def error(self) -> float:
        """Relative (or absolute) error of ``value``."""
        if self.absolute:
            return self.value - self.reference
        return (self.value - self.reference) / abs(self.reference)

    @property
    def passed(self) -> bool:
        """|error| <= tolerance (a non-finite value fails)."""
        return bool(np.isfinite(self.value) and abs(self.error) <= self.tolerance)

    def as_dict(self) -> dict:
        """JSON-ready row."""
        return {"quantity": self.quantity, "unit": self.unit, "reference": self.reference, "flexsim": self.value,
                "error": self.error, "error_kind": "absolute" if self.absolute else "relative",
                "tolerance": self.tolerance, "pass": self.passed, "source": self.source}


@dataclass(frozen=True)
class CaseResult:
    """The checks of one case, its wall time and its CPU time (this process) [s]."""

    name: str
    description: str
    checks: tuple[Check, ...]
    seconds: float
    error: str = ""
    cpu_seconds: float = 0.0

    @property
    def passed(self) -> bool:
        """Every check passed and the case ran."""
        return not self.error and all(c.passed for c in self.checks)


@dataclass(frozen=True)
class ValidationCase:
    """A named case: ``run()`` returns its checks."""

    name: str
    description: str
    run: Callable[[], list[Check]] = field(repr=False)


# ------------------------------------------------------------------------------------------- Goland
GOLAND_SOURCE = "Goland (1945), J. Appl. Mech. 12; SI data Patil, Hodges & Cesnik (2001), J. Aircraft 38(1)"
PALACIOS_SOURCE = ("Palacios & Epureanu (2011), AIAA 2011-1917, strip theory at 1.02 kg/m^3, as quoted by the "
                   "Aeroelasticity.jl documentation (Goland example, Prandtl-Glauert on)")
HODGES_PIERCE = "Hodges & Pierce (2011), Introduction to Structural Dynamics and Aeroelasticity, 2nd ed."


def goland_divergence_closed_form(rho: float, gj: float = 0.987e6, length: float = 6.096, chord: float = 1.8288,
                                  ea_fraction: float = 0.33, lift_slope: float = 2 * math.pi) -> float:
    """Divergence speed [m/s] of a uniform unswept clamped wing in incompressible strip theory.

    q_D = pi^2 GJ / (4 L^2 e c Cl_alpha) with e = (ea_fraction - 1/4) c the distance of the quarter chord
    ahead of the elastic axis (Hodges & Pierce 2011, ch. 4); U_D = sqrt(2 q_D / rho).
    """
    e = (ea_fraction - 0.25) * chord
    q_d = math.pi**2 * gj / (4.0 * length**2 * e * chord * lift_slope)
    return math.sqrt(2.0 * q_d / rho)


def _goland_flutter(aero_model: str, rho: float, compressibility: str, speed: float, freq: float, source: str,
                    speed_range: tuple[float, float]) -> Callable[[], list[Check]]:
    def run() -> list[Check]:
        from flexsim.aircraft.toml_loader import load_aircraft
        from flexsim.linear.flutter import wind_tunnel

        res = wind_tunnel(load_aircraft("goland_wing"), aero_model=aero_model, speed_range=speed_range, speed_step=10.0,
                          density_kg_m3=rho, compressibility=compressibility, divergence=False, tol_m_s=1e-2)
        u_f = np.nan if res.flutter_speed_m_s is None else res.flutter_speed_m_s
        w_f = np.nan if res.flutter_frequency_rad_s is None else res.flutter_frequency_rad_s
        return [Check("flutter speed", "m/s", speed, u_f, 0.02, source), Check("flutter frequency", "rad/s", freq, w_f, 0.02, source)]

    return run


def _goland_divergence(rho: float) -> Callable[[], list[Check]]:
    def run() -> list[Check]:
        from flexsim.aircraft.toml_loader import load_aircraft
        from flexsim.linear.flutter import wind_tunnel

        ref = goland_divergence_closed_form(rho)
        res = wind_tunnel(load_aircraft("goland_wing"), aero_model="quasi-steady", speed_range=(0.8 * ref, 1.2 * ref),
                          speed_step=0.1 * ref, density_kg_m3=rho, flutter=False, tol_m_s=1e-4)
        u_d = np.nan if res.divergence_speed_m_s is None else res.divergence_speed_m_s
        return [Check("divergence speed", "m/s", ref, u_d, 1e-4, f"closed form, {HODGES_PIERCE} ch. 4")]

    return run


# ------------------------------------------------------------------------------------- typical section
def _typical_section(model: str) -> Callable[[], list[Check]]:
    def run() -> list[Check]:
        from flexsim.aero.typical_section import TypicalSection, divergence_speed, flutter_analysis

        section = TypicalSection()
        if model == "quasi_steady":
            closed = math.sqrt(section.mu * section.r2 / (2.0 * (0.5 + section.a)))
            return [Check("divergence speed U_D/(b w_theta)", "-", closed, divergence_speed(section), 1e-6,
                          f"closed form sqrt(mu r^2 / (2 (1/2 + a))), {HODGES_PIERCE} ch. 4")]
        ref = {"theodorsen": (2.1839, 0.6490), "peters": (2.1654, 0.6545)}[model]
        src = (f"{HODGES_PIERCE} ch. 5 section with Theodorsen's C(k): g = 0 crossing of the exact flutter determinant "
               "(docs/validation.md)" if model == "theodorsen"
               else f"{HODGES_PIERCE} problems 5.5/5.7 with Peters N = 6 (AeroBeams.jl reference data: 2.166, 0.655)")
        res = flutter_analysis(section, model, 6, speed_max=3.0, speed_step=0.1)
        u_f = np.nan if res.flutter_speed is None else res.flutter_speed
        w_f = np.nan if res.flutter_frequency is None else res.flutter_frequency
        return [Check("flutter speed U_F/(b w_theta)", "-", ref[0], u_f, 5e-3, src),
                Check("flutter frequency w_F/w_theta", "-", ref[1], w_f, 5e-3, src)]

    return run


# ------------------------------------------------------------------------------------- free flight
def _conservation() -> list[Check]:
    from scipy.integrate import solve_ivp

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel

    model = AircraftModel(load_aircraft("gtm"), aero=None, gravity_m_s2=0.0, structural_damping=0.0)
    lay = model.layout
    rng = np.random.default_rng(7)
    x0 = model.pack(position_m=[100.0, -50.0, -5000.0], euler_rad=[0.3, -0.2, 1.0],
                    q=0.1 * rng.standard_normal(lay.nq), xi=0.01 * rng.standard_normal(lay.nxi))
    vel = np.concatenate([[230.0, 4.0, -6.0, 0.35, -0.25, 0.30], 0.3 * rng.standard_normal(lay.nq + lay.nxi)])
    x0[lay.velocity] = vel
    sol = solve_ivp(lambda t, x: model.rhs(t, x, np.zeros(4)), (0.0, 2.0), x0, method="DOP853", rtol=1e-11, atol=1e-11)

    def invariants(x: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
        p, h = model.momentum_inertial(x)
        return model.kinetic_energy(x) + model.strain_energy(x), p, h

    e0, p0, h0 = invariants(x0)
    e1, p1, h1 = invariants(sol.y[:, -1])
    src = "exact invariants of eq. (33) without external forces (Tuzcu & Nguyen 2014; docs/design.md)"
    return [Check("energy drift |dE|/E0 over 2 s", "-", 0.0, abs(e1 - e0) / e0, 1e-9, src, absolute=True),
            Check("linear momentum drift |dP|/|P0|", "-", 0.0, float(np.linalg.norm(p1 - p0) / np.linalg.norm(p0)), 1e-9, src, absolute=True),
            Check("angular momentum drift |dH_O|/|H_O0|", "-", 0.0, float(np.linalg.norm(h1 - h0) / np.linalg.norm(h0)), 1e-9, src, absolute=True)]


@dataclass(frozen=True)
class PhugoidPoint:
    """The phugoid of the quasi-rigid GTM at one level-flight point (quasi-steady, incompressible) with
    Lanchester's closed forms beside it (Lanchester 1908; Etkin & Reid 1996, sec. 6.4)."""

    omega_rad_s: float  #: natural frequency |lambda| of the phugoid root [rad/s] (NaN if none in 0.02-0.3 rad/s)
    damping_ratio: float  #: its damping ratio [-]
    lanchester_omega_rad_s: float  #: sqrt(2) g / V [rad/s]
    lanchester_damping_ratio: float  #: D / (sqrt(2) L) of the trim [-]
    lift_to_drag: float  #: L / D of the trim [-]
    static_margin: float  #: neutral point behind the CG as a fraction of the mean aerodynamic chord [-]


def phugoid_point(altitude_m: float = 6000.0, mach: float = 0.6, *, body_moments: bool = False,
                  downwash: bool = False, parasite_drag: bool = True) -> PhugoidPoint:
    """Trim the quasi-rigid bundled GTM in level flight (quasi-steady, incompressible, with the given
    :class:`~flexsim.model.coupling.AeroOptions` switches) and return its phugoid against Lanchester's.

    The defaults are the ``phugoid-lanchester`` case: Lanchester's model is the limit of a stiff pitch (constant
    angle of attack), which the strips-only aircraft (no fuselage/nacelle moments, no tail downwash: the largest
    static margin) is closest to.
    """
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.stability import spectrum
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.model.coupling import AeroOptions
    from flexsim.trimming import SteadyManoeuvre, trim
    from flexsim.trimming.margin import static_margin

    options = AeroOptions("quasi-steady", compressibility="none", body_moments=body_moments, downwash=downwash,
                          parasite_drag=parasite_drag)
    model = AircraftModel(load_aircraft("gtm"), aero=options, variant="quasi-rigid")
    man = SteadyManoeuvre.level(altitude_m, mach=mach)
    point = trim(model, man)
    spec = spectrum(model, point.x, point.u, aero_model="quasi-steady")
    phugoid = [m for m in spec.of_kind("rigid") if 0.02 < m.frequency_rad_s < 0.3]
    omega = float(abs(phugoid[0].eigenvalue)) if phugoid else math.nan
    zeta = float(phugoid[0].damping_ratio) if phugoid else math.nan
    return PhugoidPoint(omega, zeta, math.sqrt(2.0) * model.terms.gravity_m_s2 / man.speed_m_s,
                        point.drag_n / (math.sqrt(2.0) * point.lift_n), point.lift_n / point.drag_n,
                        static_margin(model, point).fraction_of_mac)


def _phugoid() -> list[Check]:
    p = phugoid_point()
    src = "Lanchester (1908): omega = sqrt(2) g / V, zeta = D / (sqrt(2) L); Etkin & Reid (1996), Dynamics of Flight, sec. 6.4"
    return [Check("phugoid natural frequency", "rad/s", p.lanchester_omega_rad_s, p.omega_rad_s, 0.05, src),
            Check("phugoid damping ratio", "-", p.lanchester_damping_ratio, p.damping_ratio, 0.2, src)]


def _coordinated_turn() -> list[Check]:
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.trimming import SteadyManoeuvre, trim

    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    radius = 5000.0
    point = trim(model, SteadyManoeuvre.turn(9144.0, radius, mach=0.78, coordinated=True))
    ratio = point.manoeuvre.speed_m_s**2 / (model.terms.gravity_m_s2 * radius)
    src = "steady level coordinated turn: n = sqrt(1 + (V^2/gR)^2), tan(mu) = V^2/(gR) (Stevens & Lewis 2003, sec. 3.6)"
    bank = ("point-mass turn: n = L/W = 1/cos(mu), mu the bank of the lift about the velocity (wind axes); in Euler "
            "angles sin(mu) = sin(phi) cos(theta) at zero sideslip and climb: with beta = 0 the wind and body y axes coincide "
            "and their down components are sin(mu) cos(gamma) and sin(phi) cos(theta) (3-2-1 direction cosines, "
            "docs/reference/aero-kinematics.md sec. 6.1; Stevens & Lewis 2003, sec. 3.6)")
    return [Check("load factor |F|/W", "-", math.hypot(1.0, ratio), point.load_factor_total, 5e-3, src),
            Check("load factor |F|/W against 1/cos(mu)", "-", 1.0 / math.cos(point.bank_wind), point.load_factor_total, 5e-3, bank),
            Check("wind-axis bank angle", "deg", math.degrees(math.atan(ratio)), math.degrees(point.bank_wind), 5e-3, src),
            Check("sideslip at the CG", "deg", 0.0, math.degrees(point.sideslip_cg), 0.05, "coordinated: zero sideslip", absolute=True)]


def builtin_cases() -> dict[str, ValidationCase]:
    """The built-in cases by name, in run order."""
    cases = [
        ValidationCase("goland-flutter-theodorsen-1.225", "Goland wing, Theodorsen p-k, rho 1.225, incompressible",
                       _goland_flutter("theodorsen", 1.225, "none", 137.2, 70.7, GOLAND_SOURCE, (130.0, 150.0))),
        ValidationCase("goland-flutter-peters6-1.225", "Goland wing, Peters N = 6, rho 1.225, incompressible",
                       _goland_flutter("unsteady", 1.225, "none", 137.2, 70.7, GOLAND_SOURCE, (130.0, 150.0))),
        ValidationCase("goland-flutter-theodorsen-1.02", "Goland wing, Theodorsen p-k, rho 1.02, Prandtl-Glauert",
                       _goland_flutter("theodorsen", 1.02, "prandtl-glauert", 141.0, 69.8, PALACIOS_SOURCE, (130.0, 150.0))),
        ValidationCase("goland-flutter-peters6-1.02", "Goland wing, Peters N = 6, rho 1.02, Prandtl-Glauert",
                       _goland_flutter("unsteady", 1.02, "prandtl-glauert", 141.0, 69.8, PALACIOS_SOURCE, (130.0, 150.0))),
        ValidationCase("goland-divergence-1.225", "Goland wing divergence, rho 1.225", _goland_divergence(1.225)),
        ValidationCase("goland-divergence-1.02", "Goland wing divergence, rho 1.02", _goland_divergence(1.02)),
        ValidationCase("typical-section-theodorsen", "Hodges & Pierce typical section, Theodorsen", _typical_section("theodorsen")),
        ValidationCase("typical-section-peters6", "Hodges & Pierce typical section, Peters N = 6", _typical_section("peters")),
        ValidationCase("typical-section-quasi-steady", "Hodges & Pierce typical section, quasi-steady divergence",
                       _typical_section("quasi_steady")),
        ValidationCase("free-flight-conservation", "free GTM tumbling in vacuum, no gravity, DOP853 rtol 1e-11, 2 s", _conservation),
        ValidationCase("phugoid-lanchester", "quasi-rigid GTM, 6000 m M 0.6, incompressible, quasi-steady", _phugoid),
        ValidationCase("coordinated-turn-load-factor", "GTM coordinated turn R 5 km, 9144 m, M 0.78", _coordinated_turn),
    ]
    return {c.name: c for c in cases}


def case_names() -> tuple[str, ...]:
    """Names of the built-in cases."""
    return tuple(builtin_cases())


# ------------------------------------------------------------------------------------------ user cases
_CASE_KEYS = {"name", "description", "kind", "aircraft", "aero_model", "density_kg_m3", "altitude_m", "speed_range_m_s",
              "speed_step_m_s", "compressibility", "reference", "mach", "turn_radius_m", "coordinated"}
_REFERENCE_KEYS = {"wind-tunnel": {"flutter_speed_m_s": "m/s", "flutter_frequency_rad_s": "rad/s", "divergence_speed_m_s": "m/s"},
                   "trim": {"load_factor": "-", "load_factor_total": "-", "phi_deg": "deg", "bank_wind_deg": "deg",
                            "alpha_deg": "deg", "theta_deg": "deg", "thrust_kN": "kN", "elevator_deg": "deg",
                            "sideslip_deg": "deg", "tip_deflection_m": "m", "tip_twist_deg": "deg"}}


def _bad(path: Path, field_: str, value, allowed: str) -> ValueError:
    return ValueError(f"{path}: {field_} = {value!r}: {allowed}")


def load_case(path: str | Path) -> ValidationCase:
    """A user case from a TOML file: an aircraft file and reference values.

    Format (``docs/validation.md``)::

        name = "my wing"                 # optional (default: the file name)
        kind = "wind-tunnel"             # or "trim"
        aircraft = "my_wing.toml"        # bundled name or path, relative to the case file
        aero_model = "theodorsen"        # wind tunnel: "theodorsen", "unsteady", "quasi-steady"
        density_kg_m3 = 1.225            # wind tunnel: or altitude_m (ISA)
        speed_range_m_s = [100.0, 200.0]
        speed_step_m_s = 10.0
        compressibility = "none"         # optional: "file" (default), "prandtl-glauert", "none"
        # trim: altitude_m, mach, optional turn_radius_m and coordinated
        [reference.flutter_speed_m_s]    # one table per compared quantity
        value = 137.2
        tolerance = 0.02                 # relative
        source = "Goland (1945)"

    Raises
    ------
    ValueError
        Naming the file, the field, the value and what is allowed.
    """
    path = Path(path)
    try:
        doc = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: cannot be read: {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML: {exc}") from None
    for key in doc:
        if key not in _CASE_KEYS:
            raise ValueError(f"{path}: {key}: unknown key; allowed: {', '.join(sorted(_CASE_KEYS))}")
    kind = doc.get("kind", "wind-tunnel")
    if kind not in _REFERENCE_KEYS:
        raise _bad(path, "kind", kind, 'must be "wind-tunnel" or "trim"')
    if "aircraft" not in doc:
        raise ValueError(f"{path}: aircraft: missing required field (a bundled name or an aircraft file path)")
    refs = doc.get("reference")
    if not isinstance(refs, dict) or not refs:
        raise ValueError(f"{path}: reference: missing; give at least one [reference.<quantity>] table with value and tolerance")
    allowed = _REFERENCE_KEYS[kind]
    checks_spec = []
    for q, table in refs.items():
        if q not in allowed:
            raise _bad(path, f"reference.{q}", table, f"unknown quantity for kind {kind!r}; allowed: {', '.join(allowed)}")
        if not isinstance(table, dict) or set(table) - {"value", "tolerance", "source"} or "value" not in table or "tolerance" not in table:
            raise _bad(path, f"reference.{q}", table, "must be a table with value, tolerance (relative) and optional source")
        value, tol = table["value"], table["tolerance"]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value == 0:
            raise _bad(path, f"reference.{q}.value", value, "must be a finite non-zero number")
        if isinstance(tol, bool) or not isinstance(tol, (int, float)) or not 0 < tol <= 1:
            raise _bad(path, f"reference.{q}.tolerance", tol, "must be a relative tolerance in (0, 1]")
        checks_spec.append((q, allowed[q], float(value), float(tol), str(table.get("source", str(path)))))
    aircraft_ref = str(doc["aircraft"])
    candidate = path.parent / aircraft_ref
    aircraft_arg = str(candidate) if candidate.is_file() else aircraft_ref
    name = str(doc.get("name", path.stem))
    description = str(doc.get("description", f"user case {path}"))

    if kind == "wind-tunnel":
        rng = doc.get("speed_range_m_s")
        if not (isinstance(rng, list) and len(rng) == 2 and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in rng)):
            raise _bad(path, "speed_range_m_s", rng, "must be [low, high] in m/s")
        step = doc.get("speed_step_m_s", (rng[1] - rng[0]) / 10.0)
        kwargs = dict(aero_model=str(doc.get("aero_model", "unsteady")), speed_range=(float(rng[0]), float(rng[1])),
                      speed_step=float(step), compressibility=str(doc.get("compressibility", "file")),
                      density_kg_m3=doc.get("density_kg_m3"), altitude_m=float(doc.get("altitude_m", 0.0)),
                      divergence="divergence_speed_m_s" in refs, flutter=bool(set(refs) & {"flutter_speed_m_s", "flutter_frequency_rad_s"}))

        def run() -> list[Check]:
            from flexsim.aircraft.toml_loader import load_aircraft
            from flexsim.linear.flutter import wind_tunnel

            res = wind_tunnel(load_aircraft(aircraft_arg), **kwargs)
            got = {"flutter_speed_m_s": res.flutter_speed_m_s, "flutter_frequency_rad_s": res.flutter_frequency_rad_s,
                   "divergence_speed_m_s": res.divergence_speed_m_s}
            return [Check(q, unit, ref, np.nan if got[q] is None else float(got[q]), tol, src) for q, unit, ref, tol, src in checks_spec]
    else:
        for key in ("altitude_m", "mach"):
            if not isinstance(doc.get(key), (int, float)) or isinstance(doc.get(key), bool):
                raise _bad(path, key, doc.get(key), "must be a number (trim cases need altitude_m and mach)")
        alt, mach = float(doc["altitude_m"]), float(doc["mach"])
        radius = float(doc.get("turn_radius_m", math.inf))
        coordinated = bool(doc.get("coordinated", False))
        compressibility = str(doc.get("compressibility", "file"))

        def run() -> list[Check]:
            from flexsim.aircraft.toml_loader import load_aircraft
            from flexsim.model.aircraft_model import AircraftModel
            from flexsim.model.coupling import AeroOptions
            from flexsim.trimming import SteadyManoeuvre, trim

            model = AircraftModel(load_aircraft(aircraft_arg), aero=AeroOptions("quasi-steady", compressibility=compressibility))
            start = SteadyManoeuvre.level(alt, mach=mach)
            point = trim(model, SteadyManoeuvre(start.speed_m_s, alt, radius, 0.0, coordinated))
            summary = point.summary()
            return [Check(q, unit, ref, float(summary[q]), tol, src) for q, unit, ref, tol, src in checks_spec]

    return ValidationCase(name, description, run)


def run_case(case: ValidationCase) -> CaseResult:
    """Run one case; a failure to compute is reported in ``error`` (the case fails), never raised."""
    from flexsim.errors import FlexsimError

    start, cpu = time.perf_counter(), time.process_time()
    try:
        checks = tuple(case.run())
        err = ""
    except (FlexsimError, ValueError, RuntimeError, OSError, np.linalg.LinAlgError) as exc:
        checks, err = (), f"{type(exc).__name__}: {exc}"
    return CaseResult(case.name, case.description, checks, time.perf_counter() - start, err, time.process_time() - cpu)
