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

__all__ = ["SearchRange", "search_range", "MODEL_MAX_MACH", "RHO_0"]

#: Largest Mach number the strip aerodynamics cover: the Prandtl-Glauert factor is capped there [-].
MODEL_MAX_MACH = 0.95
#: ISA sea-level density [kg/m^3] (EAS to TAS).
RHO_0 = 1.225
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

    from flexsim.trim import TrimError, trim

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
