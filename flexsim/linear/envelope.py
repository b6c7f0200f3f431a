"""Where a flutter search looks: the aircraft's own flight envelope at an altitude.

A flutter search scans the Mach number of a steady manoeuvre at a fixed altitude (:mod:`flexsim.linear.flutter`).
The range comes from the aircraft file's ``[envelope]`` table (docs/aircraft-format.md, :class:`~flexsim.aircraft.definition.Envelope`):
the larger of its lower limits and the smaller of its upper limits, equivalent airspeeds converted to Mach at the
altitude (V_TAS = V_EAS sqrt(rho_0 / rho), ISA). A limit the file does not give is derived:

* lower end: the stall speed of the manoeuvre, estimated from the linear lift curve and the file's
  ``[aero] max_alpha_deg``. Two quasi-steady trims of the manoeuvre (limits not enforced) at dynamic pressures
  q_1 and q_2 give alpha(q) = alpha_0 + k / q (lift L = q S C_L_alpha (alpha - alpha_0) = n W, hence k = n W /
  (S C_L_alpha); Anderson, *Introduction to Flight*, 7th ed., 2012, sec. 5.4 and 6.7); the stall speed is where
  alpha reaches max_alpha_deg, q_s = k / (alpha_max - alpha_0). The elastic deflection and the large-angle
  geometry make alpha(q) depart from this form, so the fit is repeated through the latest two trims, the newest at
  the last estimate (a secant iteration, to 1e-3 in Mach); the result names it an estimate;
* upper end: M = 0.95, where the strips' Prandtl-Glauert factor is capped (docs/aircraft-format.md, ``[aero]
  compressibility``): beyond it the aerodynamic model is outside its range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from flexsim.aircraft.definition import Aircraft
from flexsim.atmosphere import isa_density, speed_of_sound
from flexsim.model.aircraft_model import AircraftModel

__all__ = ["SearchRange", "search_range", "CruisePoint", "cruise_point", "flutter_altitudes", "MODEL_MAX_MACH", "RHO_0",
           "CRUISE_SPEED_MARGIN", "DIVE_TO_CRUISE", "DERIVED_CRUISE_ALTITUDE_M", "FLUTTER_ALTITUDE_LEVELS"]

#: Largest Mach number the strip aerodynamics cover: the Prandtl-Glauert factor is capped there [-].
MODEL_MAX_MACH = 0.95
#: ISA sea-level density [kg/m^3] (EAS to TAS).
RHO_0 = 1.225
#: A cruise speed derived from the lower end of the envelope (the stall speed) is this multiple of it: the classical
#: margin of 1.3 V_S of the reference approach speed (14 CFR 25.125 before amendment 25-108; Raymer, *Aircraft Design:
#: A Conceptual Approach*, 6th ed., 2018, sec. 17.7) [-].
CRUISE_SPEED_MARGIN = 1.3
#: A cruise speed derived from the upper end of the envelope the file gives (its dive speed) is that end divided by
#: this: the design dive speed is at least 1.25 times the design cruise speed (CS-25.335(b)(1), 14 CFR 25.335) [-].
DIVE_TO_CRUISE = 1.25
#: Altitude of a cruise point the file does not give [m]: low, but clear of the ground so that a simulation from it is not
#: ended at once by ground contact (altitude <= 0).
DERIVED_CRUISE_ALTITUDE_M = 1000.0
#: Altitudes of a flutter search without given ones: this many, equally spaced from sea level to the file's
#: ``envelope.max_altitude_m`` (four: the paper's 0, 3048, 6096, 9144 m for the GTM's 9144 m).
FLUTTER_ALTITUDE_LEVELS = 4
#: Secant steps of the stall estimate at most (each one trim).
_STALL_ITERATIONS = 6


@dataclass(frozen=True)
class SearchRange:
    """The Mach range of a flutter search at one altitude, and where each end came from.

    Attributes
    ----------
    mach_min, mach_max : float
        Ends of the searched range [-].
    altitude_m : float
        Altitude of the search [m].
    lower_source, upper_source : str
        Where each end came from, e.g. ``"envelope.min_mach"``, ``"stall estimate (max_alpha_deg = 11)"``,
        ``"given"``.
    """

    mach_min: float
    mach_max: float
    altitude_m: float
    lower_source: str
    upper_source: str

    @property
    def speeds_m_s(self) -> tuple[float, float]:
        """The range as true airspeeds [m/s]."""
        a = speed_of_sound(self.altitude_m)
        return self.mach_min * a, self.mach_max * a

    def describe(self) -> str:
        """One line, e.g. ``"M 0.060-0.200 (V 20.4-68.1 m/s TAS) at H = 1000 m; lower end: ..., upper end: ..."``."""
        v_lo, v_hi = self.speeds_m_s
        return (f"M {self.mach_min:.3f}-{self.mach_max:.3f} (V {v_lo:.1f}-{v_hi:.1f} m/s TAS) at H = {self.altitude_m:.0f} m; "
                f"lower end: {self.lower_source}, upper end: {self.upper_source}")


def _eas_to_mach(eas_m_s: float, altitude_m: float) -> float:
    return eas_m_s * math.sqrt(RHO_0 / float(isa_density(altitude_m))) / speed_of_sound(altitude_m)


def search_range(model: AircraftModel | Aircraft | str | Path, manoeuvre, *, mach_min: float | None = None,
                 mach_max: float | None = None) -> SearchRange:
    """The Mach range of a flutter search of ``manoeuvre`` (its altitude and kind; its speed is not used).

    Parameters
    ----------
    model : AircraftModel, Aircraft, str or Path
        A free model with aerodynamics, an aircraft, or an aircraft file (bundled name or path: only its
        ``[envelope]`` is read unless the stall estimate is needed); the stall estimate (only when needed) trims the
        model's quasi-steady sibling, or ``AircraftModel(aircraft, aero="quasi-steady")`` (module docstring).
    manoeuvre : SteadyManoeuvre
    mach_min, mach_max : float, optional
        Ends given by the caller; they override the file and the derivation.

    Returns
    -------
    SearchRange

    Raises
    ------
    ValueError
        When the resulting range is empty (lower end >= upper end), naming both ends and their sources.
    """
    h = float(manoeuvre.altitude_m)
    if isinstance(model, (str, Path)):
        from flexsim.aircraft.toml_loader import load_aircraft, load_envelope

        env, source = load_envelope(model), model
        aircraft = None
    else:
        aircraft = model if isinstance(model, Aircraft) else model.aircraft
        env = aircraft.envelope
    lows: list[tuple[float, str]] = []
    highs: list[tuple[float, str]] = []
    if env is not None:
        if env.min_mach is not None:
            lows.append((env.min_mach, f"envelope.min_mach = {env.min_mach:g}"))
        if env.min_speed_eas_m_s is not None:
            lows.append((_eas_to_mach(env.min_speed_eas_m_s, h), f"envelope.min_speed_eas_m_s = {env.min_speed_eas_m_s:g}"))
        if env.max_mach is not None:
            highs.append((env.max_mach, f"envelope.max_mach = {env.max_mach:g}"))
        if env.max_speed_eas_m_s is not None:
            highs.append((_eas_to_mach(env.max_speed_eas_m_s, h), f"envelope.max_speed_eas_m_s = {env.max_speed_eas_m_s:g}"))
    if mach_min is not None:
        lo = (float(mach_min), "given")
    elif lows:
        lo = max(lows)
    else:
        if aircraft is None:
            aircraft = load_aircraft(source)
        lo = _stall_mach(model if isinstance(model, AircraftModel) else AircraftModel(aircraft, aero="quasi-steady"), manoeuvre)
    if mach_max is not None:
        hi = (float(mach_max), "given")
    elif highs:
        hi = min(highs)
    else:
        hi = (MODEL_MAX_MACH, f"M {MODEL_MAX_MACH:g}, the limit of the strips' compressibility correction")
    if not 0.0 < lo[0] < hi[0] < 1.0:
        raise ValueError(f"flutter search range at H = {h:.0f} m is empty or not subsonic: lower end M {lo[0]:.4f} "
                         f"({lo[1]}), upper end M {hi[0]:.4f} ({hi[1]}); must satisfy 0 < lower < upper < 1")
    return SearchRange(float(lo[0]), float(hi[0]), h, lo[1], hi[1])


def _stall_mach(model: AircraftModel, manoeuvre) -> tuple[float, str]:
    """(Mach, source) of the stall estimate of the module docstring: two quasi-steady trims, limits not enforced."""
    from dataclasses import replace

    from flexsim.trimming import TrimError, trim

    qs = model
    if model.aero.options.model != "quasi-steady":
        # the model's own terms (gravity, damping, density, compressibility, ...) with quasi-steady strips
        qs = model.replace(aero=replace(model.terms.aero, model="quasi-steady"))
    h = float(manoeuvre.altitude_m)
    a = speed_of_sound(h)
    rho = float(isa_density(h))
    alpha_max = model.aircraft.aero_settings.max_alpha_rad

    def alpha_at(mach: float) -> tuple[float, float]:
        try:
            point = trim(qs, manoeuvre.with_speed(mach * a), check_limits=False)
        except TrimError as exc:
            raise ValueError(f"{model.aircraft.name}: the stall speed (lower end of the flutter search) is estimated from "
                             f"trims, and the trim at M {mach:.3f} failed ({exc}); give the file an [envelope] table "
                             "(docs/aircraft-format.md) or the search range") from None
        return 0.5 * rho * (mach * a) ** 2, point.alpha

    pts = [alpha_at(0.3), alpha_at(0.6)]
    mach = math.nan
    for _ in range(_STALL_ITERATIONS):  # secant on alpha(1/q): refit through the two latest trims
        (q1, a1), (q2, a2) = pts[-2:]
        k = (a1 - a2) / (1.0 / q1 - 1.0 / q2)
        alpha_0 = a1 - k / q1
        if not (k > 0.0 and alpha_0 < alpha_max):
            raise ValueError(f"{model.aircraft.name}: cannot estimate the stall speed at H = {h:.0f} m (trim angles of "
                             f"attack {math.degrees(a1):.2f} and {math.degrees(a2):.2f} deg at V = {math.sqrt(2 * q1 / rho):.1f} "
                             f"and {math.sqrt(2 * q2 / rho):.1f} m/s do not fall with speed); give the file an [envelope] "
                             "table (docs/aircraft-format.md) or the search range")
        # an extrapolation beyond the bounds (far from the two trims it fits) is clamped and refitted there
        new = min(max(math.sqrt(2.0 * k / (alpha_max - alpha_0) / rho) / a, 0.01), 0.95)
        if abs(new - mach) < 1e-3:
            mach = new
            break
        mach = new
        pts.append(alpha_at(mach))
    deg = math.degrees(alpha_max)
    return mach, f"stall estimate (alpha reaches [aero] max_alpha_deg = {deg:g} deg)"


@dataclass(frozen=True)
class CruisePoint:
    """The flight condition a command flies when none is given: altitude and speed, and where each came from.

    Attributes
    ----------
    altitude_m : float
        Altitude [m].
    mach : float
        Mach number [-].
    altitude_source, speed_source : str
        E.g. ``"envelope.cruise_altitude_m = 20000"``, ``"given"``, or the derivation when the file gives none.
    """

    altitude_m: float
    mach: float
    altitude_source: str
    speed_source: str

    @property
    def speed_m_s(self) -> float:
        """True airspeed [m/s]."""
        return self.mach * speed_of_sound(self.altitude_m)

    @property
    def derived(self) -> bool:
        """True when the altitude or the speed was neither given nor read from the aircraft file."""
        return not all(src == "given" or src.startswith("envelope.") for src in (self.altitude_source, self.speed_source))

    def describe(self) -> str:
        """One line, e.g. ``"H = 9144 m (envelope.cruise_altitude_m = 9144), M 0.7800 = 236.52 m/s TAS (given)"``."""
        return (f"H = {self.altitude_m:.0f} m ({self.altitude_source}), M {self.mach:.4f} = {self.speed_m_s:.2f} m/s TAS "
                f"({self.speed_source})")


def cruise_point(model: AircraftModel | Aircraft | str | Path, *, altitude_m: float | None = None,
                 mach: float | None = None, speed_m_s: float | None = None) -> CruisePoint:
    """The flight condition of a trim, linearisation or simulation: the given values, else the aircraft's own.

    Altitude: ``altitude_m``, else the file's ``envelope.cruise_altitude_m``, else :data:`DERIVED_CRUISE_ALTITUDE_M`
    (stated). Speed: ``mach``
    or ``speed_m_s`` (true airspeed [m/s], at most one), else the file's ``envelope.cruise_mach`` or
    ``envelope.cruise_speed_m_s``, else derived and stated: the upper end of the envelope the file gives (its dive
    speed) divided by :data:`DIVE_TO_CRUISE`, or, without one or when that is slower, :data:`CRUISE_SPEED_MARGIN`
    times the lower end (:func:`search_range` of level flight at that altitude: the file's lower limits or the stall
    estimate); the middle of the envelope when that would reach its upper end.

    Parameters
    ----------
    model : AircraftModel, Aircraft, str or Path
        As for :func:`search_range`.
    altitude_m, mach, speed_m_s : float, optional
        Given values [m], [-], [m/s]; they override the aircraft's.

    Returns
    -------
    CruisePoint

    Raises
    ------
    ValueError
        For both ``mach`` and ``speed_m_s``, a value out of range (named, with the range), or an envelope from which
        no speed can be derived (the message says which ``[envelope]`` key to give).
    """
    from flexsim.atmosphere import isa
    from flexsim.trimming import SteadyManoeuvre

    if mach is not None and speed_m_s is not None:
        raise ValueError(f"mach = {mach!r} and speed_m_s = {speed_m_s!r}: give the speed once")
    if isinstance(model, (str, Path)):
        from flexsim.aircraft.toml_loader import load_envelope

        env = load_envelope(model)
    else:
        env = (model if isinstance(model, Aircraft) else model.aircraft).envelope
    if altitude_m is not None:
        h, h_src = altitude_m, "given"
    elif env is not None and env.cruise_altitude_m is not None:
        h, h_src = env.cruise_altitude_m, f"envelope.cruise_altitude_m = {env.cruise_altitude_m:g}"
    else:
        h, h_src = DERIVED_CRUISE_ALTITUDE_M, (f"{DERIVED_CRUISE_ALTITUDE_M:g} m, clear of the ground: the aircraft file "
                                               "gives no envelope.cruise_altitude_m")
    if isinstance(h, bool) or not isinstance(h, (int, float)) or not math.isfinite(h):
        raise ValueError(f"altitude_m = {h!r}: must be a finite number [m]")
    isa(float(h))  # the ISA range, named in its message
    h = float(h)
    a = speed_of_sound(h)
    for name, value, hi in (("mach", mach, 1.0), ("speed_m_s", speed_m_s, a)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))
                                  or not (math.isfinite(value) and 0.0 < value < hi)):
            raise ValueError(f"{name} = {value!r}: must be in (0, {hi:.6g}) (subsonic at H = {h:.0f} m)")
    if mach is not None:
        m, m_src = float(mach), "given"
    elif speed_m_s is not None:
        m, m_src = float(speed_m_s) / a, "given"
    elif env is not None and env.cruise_mach is not None:
        m, m_src = env.cruise_mach, f"envelope.cruise_mach = {env.cruise_mach:g}"
    elif env is not None and env.cruise_speed_m_s is not None:
        if not env.cruise_speed_m_s < a:
            raise ValueError(f"envelope.cruise_speed_m_s = {env.cruise_speed_m_s:g}: must be subsonic, below "
                             f"{a:.2f} m/s at H = {h:.0f} m")
        m, m_src = env.cruise_speed_m_s / a, f"envelope.cruise_speed_m_s = {env.cruise_speed_m_s:g}"
    else:
        try:
            rng = search_range(model, SteadyManoeuvre(float(0.5 * a), h))
        except ValueError as exc:
            raise ValueError(f"no cruise speed: the aircraft file gives no envelope.cruise_mach nor "
                             f"envelope.cruise_speed_m_s, and it cannot be derived from the envelope ({exc}); give one "
                             "of them, or the speed") from None
        stall = CRUISE_SPEED_MARGIN * rng.mach_min
        if rng.upper_source.startswith("envelope.") and rng.mach_max / DIVE_TO_CRUISE > stall:
            m = rng.mach_max / DIVE_TO_CRUISE
            m_src = (f"derived: the envelope's upper end M {rng.mach_max:.4f} ({rng.upper_source}) / {DIVE_TO_CRUISE:g}, "
                     "the file gives no envelope.cruise_mach")
        else:
            m = stall
            m_src = (f"derived: {CRUISE_SPEED_MARGIN:g} x the envelope's lower end M {rng.mach_min:.4f} "
                     f"({rng.lower_source}), the file gives no envelope.cruise_mach")
        if not m < rng.mach_max:
            m = 0.5 * (rng.mach_min + rng.mach_max)
            m_src = (f"derived: the middle of the envelope M {rng.mach_min:.4f}-{rng.mach_max:.4f}, the file gives no "
                     "envelope.cruise_mach")
    return CruisePoint(h, float(m), h_src, m_src)


def flutter_altitudes(model: AircraftModel | Aircraft | str | Path) -> tuple[list[float], str]:
    """The altitudes of a flutter search when none is given [m], and where they came from.

    :data:`FLUTTER_ALTITUDE_LEVELS` altitudes equally spaced from sea level to the file's ``envelope.max_altitude_m``
    (else its ``envelope.cruise_altitude_m``); sea level alone when the file gives neither.
    """
    if isinstance(model, (str, Path)):
        from flexsim.aircraft.toml_loader import load_envelope

        env = load_envelope(model)
    else:
        env = (model if isinstance(model, Aircraft) else model.aircraft).envelope
    for key in ("max_altitude_m", "cruise_altitude_m"):
        top = getattr(env, key, None) if env is not None else None
        if top:
            n = FLUTTER_ALTITUDE_LEVELS
            return [top * i / (n - 1) for i in range(n)], f"sea level to envelope.{key} = {top:g} in {n} levels"
    return [0.0], "sea level: the aircraft file gives no envelope.max_altitude_m"
