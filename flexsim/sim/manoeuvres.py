"""Named manoeuvres: each builds a model, an initial state, a control schedule and a duration.

``build_manoeuvre(name, aero=..., duration_s=...)`` returns a :class:`ManoeuvreSetup`;
``setup.simulate(output=OutputSettings(log_path=...))`` runs it with :func:`flexsim.sim.simulate.simulate`.
Registered names (:func:`manoeuvre_names`):

* ``level-turn-entry`` — GTM from level flight into a steady level turn of radius 10 km: a bank-angle
  feedback on the aileron (20 Hz, zero-order hold) follows a smooth bank command to the turn trim's bank
  while the other controls blend from the level to the turn trim (paper eqs. 36-37).
* ``climb`` — GTM from level flight, elevator and thrust ramped to the 3 deg climb trim (eqs. 38-39).
* ``elevator-doublet`` — GTM level trim, elevator +2 deg / -2 deg, 0.5 s each.
* ``aileron-roll`` — GTM level trim, aileron -3 deg (right wing trailing edge up: roll right) for 2 s.
* ``gust-encounter`` — GTM level trim flying into a 1-cos up-gust, U_ds = 10 m/s, H = 60 m (CS-25.341).
* ``flutter-onset`` — the Goland wing clamped in a wind tunnel (sea level) at 1.05 times its flutter
  speed with Peters' unsteady aerodynamics (found by :func:`goland_flutter_speed`, 136.2 m/s): the
  oscillation that starts from the static sag under gravity grows until the structural-limit event stops
  the run. With ``aero="quasi-steady"`` the same tunnel speed is used (that model flutters from 64.6 m/s).

The GTM runs are at 9144 m and M 0.75 (the paper's 30 000 ft cruise) with the notional GTM of
``flexsim/aircraft/data/gtm.md``.
``build_manoeuvre(name, aircraft=...)`` flies another aircraft instead (``flexsim simulate AIRCRAFT``,
``--aircraft``): the same inputs from its level trim at its cruise point
(:func:`flexsim.linear.envelope.cruise_point`), or ``flutter-onset`` in a sea-level tunnel at 1.05 times its own
flutter speed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np

from flexsim.aircraft.definition import Aircraft
from flexsim.errors import positive_number
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.flutter import wind_tunnel_flutter
from flexsim.model.aircraft_model import AircraftModel, Wind
from flexsim.model.coupling import AeroOptions
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim.sim.result import SimulationResult
from flexsim.sim.run_settings import EventSettings, OutputSettings
from flexsim.sim.simulate import ControlSchedule, IntegratorSettings, simulate
from flexsim.kinematics import dcm_321
from flexsim.trimming import SteadyManoeuvre, TrimPoint, trim

__all__ = ["ManoeuvreSetup", "build_manoeuvre", "manoeuvre_names", "goland_flutter_speed", "pulse_schedule",
           "BankController", "CRUISE_ALTITUDE_M", "CRUISE_MACH"]

CRUISE_ALTITUDE_M = 9144.0
CRUISE_MACH = 0.75
_AERO_CHOICES = ("unsteady", "quasi-steady")


@dataclass(frozen=True, eq=False)
class ManoeuvreSetup:
    """Everything :func:`~flexsim.sim.simulate.simulate` needs for one named manoeuvre.

    Attributes
    ----------
    name, description : str
    model : AircraftModel
    initial : TrimPoint or ndarray
        Initial state (a trim point where the manoeuvre starts from one).
    controls : ControlSchedule, ndarray (4,) or callable(t, x) -> u
    duration_s : float
        Default run length [s].
    control_rate_hz : float
        Rate of a feedback controller [Hz] (``simulate``'s and the environments' ``control_rate_hz``).
    wing_tip_deflection_m : float or None
        Bound of the structural-limit event [m] (None: simulate's default, 0.25 x wing length;
        :class:`~flexsim.sim.run_settings.EventSettings`).
    notes : tuple of (t [s], text)
        Informational events for the flight log.
    wind : callable or None
        The disturbance the manoeuvre is flown in (passed to ``simulate``), None for still air.
    metadata : dict of str to str
        Run metadata for the flight log.
    """

    name: str
    description: str
    model: AircraftModel
    initial: TrimPoint | np.ndarray
    controls: ControlSchedule | np.ndarray | Callable[[float, np.ndarray], np.ndarray]
    duration_s: float
    control_rate_hz: float = 50.0
    wing_tip_deflection_m: float | None = None
    notes: tuple[tuple[float, str], ...] = ()
    metadata: dict[str, str] = field(default_factory=dict)
    wind: Wind | None = None

    def simulate(self, t_end_s: float | None = None, *, integrator: IntegratorSettings = IntegratorSettings(),
                 events: EventSettings | None = None, output: OutputSettings = OutputSettings()) -> SimulationResult:
        """Run the manoeuvre with :func:`~flexsim.sim.simulate.simulate`: its controls, wind and control period, for
        ``t_end_s`` [s] (default its duration). ``integrator`` and ``output`` as simulate's (the output's notes and
        metadata are added to the manoeuvre's); ``events`` default: the built-in events with the manoeuvre's
        ``wing_tip_deflection_m``."""
        t_end = self.duration_s if t_end_s is None else t_end_s
        if events is None:
            events = EventSettings(wing_tip_deflection_m=self.wing_tip_deflection_m)
        meta = {"manoeuvre": self.name, "description": self.description, **self.metadata, **output.metadata}
        output = replace(output, notes=self.notes + output.notes, metadata=meta)
        return simulate(self.model, self.initial, t_end, controls=self.controls, control_rate_hz=self.control_rate_hz,
                        wind=self.wind, integrator=integrator, events=events, output=output)


def pulse_schedule(base_u: np.ndarray, pulses: list[tuple[int, float, float, float]], ramp_s: float = 0.05) -> ControlSchedule:
    """Trim controls plus trapezoidal pulses, as an exact piecewise-linear schedule.

    Parameters
    ----------
    base_u : ndarray, shape (4,)
        Controls held outside the pulses [N, rad].
    pulses : list of (control index, start [s], end [s], increment)
        Control ``index`` (0 thrust, 1 aileron, 2 elevator, 3 rudder) moves by ``increment`` [N or rad],
        ramping over ``ramp_s`` from ``start`` and back from ``end``.
    ramp_s : float
        Ramp time [s] > 0.
    """
    base = np.asarray(base_u, dtype=float)
    if not ramp_s > 0:
        raise ValueError(f"ramp_s = {ramp_s!r}: must be > 0 [s]")
    for j, start, end, _ in pulses:
        if not (0 <= j <= 3 and 0 <= start and end >= start + ramp_s):
            raise ValueError(f"pulse ({j}, {start}, {end}): needs a control index 0..3, start >= 0 and end >= start + ramp_s")
    knots = sorted({0.0} | {t for _, s, e, _ in pulses for t in (s, s + ramp_s, e, e + ramp_s)})

    def value(t: float) -> np.ndarray:
        u = base.copy()
        for j, s, e, d in pulses:
            u[j] += d * float(np.interp(t, [s, s + ramp_s, e, e + ramp_s], [0.0, 1.0, 1.0, 0.0]))
        return u

    return ControlSchedule(np.array(knots), np.array([value(t) for t in knots]))


@dataclass(frozen=True, eq=False)
class BankController:
    """Turn entry: bank-angle feedback on the aileron plus a feed-forward blend of two trims.

    With the blend f(t) = smoothstep((t - start_s) / ramp_s) in [0, 1], the controls are
    ``u = (1 - f) level.u + f turn.u`` and the aileron adds ``k_phi (phi - f phi_turn) + k_p p`` (delta_a > 0
    rolls left, so positive gains oppose a bank error), saturated at the aircraft's limits.

    Attributes
    ----------
    level, turn : TrimPoint
    start_s, ramp_s : float
        Start and duration of the blend [s].
    k_phi, k_p : float
        Gains [rad/rad], [rad/(rad/s)].
    lower, upper : ndarray, shape (4,)
        Control limits.
    euler_index, omega_index : int
        Positions of phi and of the roll rate p in the state vector (``model.layout``).
    """

    level: TrimPoint
    turn: TrimPoint
    start_s: float
    ramp_s: float
    k_phi: float
    k_p: float
    lower: np.ndarray
    upper: np.ndarray
    euler_index: int
    omega_index: int

    def blend(self, t: float) -> float:
        """f(t) in [0, 1] (smoothstep, continuous slope)."""
        s = min(max((t - self.start_s) / self.ramp_s, 0.0), 1.0)
        return s * s * (3.0 - 2.0 * s)

    def __call__(self, t: float, x: np.ndarray) -> np.ndarray:
        f = self.blend(t)
        u = (1.0 - f) * self.level.u + f * self.turn.u
        phi, p = x[self.euler_index], x[self.omega_index]
        u[1] += self.k_phi * (phi - f * self.turn.phi) + self.k_p * p
        return np.clip(u, self.lower, self.upper)


# ---------------------------------------------------------------------------------------------- flight
@dataclass(frozen=True)
class _Flight:
    """The aircraft a manoeuvre flies and its level trim condition: the GTM at :data:`CRUISE_ALTITUDE_M`,
    :data:`CRUISE_MACH` by default, else the given aircraft at its cruise point
    (:func:`flexsim.linear.envelope.cruise_point`: the given altitude and speed, or the file's, or derived)."""

    aircraft: Aircraft | None
    altitude_m: float
    mach: float
    condition: str = ""


def _model(flight: _Flight, aero: AeroOptions) -> AircraftModel:
    return AircraftModel(load_aircraft("gtm") if flight.aircraft is None else flight.aircraft, aero=aero)


def _cruise(model: AircraftModel, flight: _Flight) -> TrimPoint:
    return trim(model, SteadyManoeuvre.level(flight.altitude_m, mach=flight.mach))


def _limit(model: AircraftModel, level: TrimPoint, flight: _Flight) -> float | None:
    """Structural limit of a manoeuvre of a given aircraft [m]: its wing tip's deflection in the level trim plus a
    quarter of the wing's length (simulate's default bound, 0.25 x wing length, measured from the trim: a flexible
    aircraft whose trim bends its wing beyond that bound still flies); None for the default GTM (simulate's default)."""
    if flight.aircraft is None or "right_wing" not in model.aircraft.component_names:
        return None
    tip = abs(float(level.summary().get("tip_deflection_m", 0.0)))
    return tip + 0.25 * model.aircraft.component("right_wing").length_m


def _setup(flight: _Flight, model: AircraftModel, level: TrimPoint, name: str, description: str, *args, **kw) -> ManoeuvreSetup:
    if flight.aircraft is not None:
        description = f"{model.aircraft.name}: {description}; {flight.condition}"
    return ManoeuvreSetup(name, description, model, level, *args, wing_tip_deflection_m=_limit(model, level, flight), **kw)


def _level_turn_entry(aero: AeroOptions, flight: _Flight) -> ManoeuvreSetup:
    model = _model(flight, aero)
    level = _cruise(model, flight)
    turn = trim(model, SteadyManoeuvre.turn(flight.altitude_m, 10_000.0, mach=flight.mach), guess=level)
    lo, hi = model.aircraft.control_limits()
    lay = model.layout
    ctrl = BankController(level, turn, start_s=1.0, ramp_s=4.0, k_phi=0.8, k_p=0.0, lower=lo, upper=hi,
                          euler_index=lay.euler.start, omega_index=lay.omega.start)
    return _setup(flight, model, level, "level-turn-entry",
                  f"level flight into a level turn of R = 10 km (bank {math.degrees(turn.phi):.1f} deg)",
                  ctrl, 10.0, control_rate_hz=20.0,
                  notes=((1.0, f"turn entry: bank command to {math.degrees(turn.phi):.1f} deg over 4 s"),))


def _climb(aero: AeroOptions, flight: _Flight) -> ManoeuvreSetup:
    model = _model(flight, aero)
    level = _cruise(model, flight)
    climb = trim(model, SteadyManoeuvre.climb(flight.altitude_m, math.radians(3.0), mach=flight.mach), guess=level)
    sched = ControlSchedule(np.array([0.0, 1.0, 3.0]), np.array([level.u, level.u, climb.u]))
    return _setup(flight, model, level, "climb", "level flight to the 3 deg climb trim's elevator and thrust (ramped over 2 s)",
                  sched, 10.0, notes=((1.0, "controls ramp to the 3 deg climb trim"),))


@dataclass(frozen=True)
class PulseManoeuvre:
    """A named manoeuvre made of control pulses from a level trim (:func:`pulse_schedule`), flown by the linear
    model's :func:`build_manoeuvre` and the nonlinear aircraft's
    :func:`flexsim.sim.flexible_manoeuvres.build_flexible_manoeuvre` alike."""

    name: str
    description: str
    pulses: tuple[tuple[int, float, float, float], ...]
    ramp_s: float
    duration_s: float
    note: tuple[float, str]

    def schedule(self, trim_u: np.ndarray) -> ControlSchedule:
        """The pulses about the trim's controls ``trim_u`` [N, rad]."""
        return pulse_schedule(trim_u, list(self.pulses), ramp_s=self.ramp_s)


#: The elevator doublet and the aileron roll.
ELEVATOR_DOUBLET = PulseManoeuvre("elevator-doublet", "elevator doublet +-2 deg, 0.5 s each, from level trim",
                                  ((2, 1.0, 1.5, math.radians(2.0)), (2, 1.5, 2.0, -math.radians(2.0))), 0.05, 6.0,
                                  (1.0, "elevator doublet"))
AILERON_ROLL = PulseManoeuvre("aileron-roll", "aileron -3 deg (roll right) for 2 s from level trim",
                              ((1, 1.0, 3.0, -math.radians(3.0)),), 0.1, 6.0, (1.0, "aileron input"))
#: The gust encounter: U_ds [m/s], H [m], the time the body origin reaches the front [s], duration [s].
GUST_ENCOUNTER = {"amplitude_m_s": 10.0, "length_m": 60.0, "start_s": 1.0, "duration_s": 5.0}
GUST_DESCRIPTION = "1-cos up-gust U_ds = 10 m/s, H = 60 m (CS-25.341) reached at t = 1 s"


def _pulses(manoeuvre: PulseManoeuvre, aero: AeroOptions, flight: _Flight) -> ManoeuvreSetup:
    model = _model(flight, aero)
    level = _cruise(model, flight)
    return _setup(flight, model, level, manoeuvre.name, manoeuvre.description, manoeuvre.schedule(level.u),
                  manoeuvre.duration_s, notes=(manoeuvre.note,))


def _elevator_doublet(aero: AeroOptions, flight: _Flight) -> ManoeuvreSetup:
    return _pulses(ELEVATOR_DOUBLET, aero, flight)


def _aileron_roll(aero: AeroOptions, flight: _Flight) -> ManoeuvreSetup:
    return _pulses(AILERON_ROLL, aero, flight)


def _gust_encounter(aero: AeroOptions, flight: _Flight) -> ManoeuvreSetup:
    model = _model(flight, aero)
    level = _cruise(model, flight)
    lay = model.layout
    velocity_ned = dcm_321(*level.x[lay.euler]).T @ level.x[lay.v]
    g = GUST_ENCOUNTER
    gust = OneMinusCosineGust.encounter(g["amplitude_m_s"], g["length_m"], position_ned_m=level.x[lay.position],
                                        velocity_ned_m_s=velocity_ned, start_time_s=g["start_s"])
    return _setup(flight, model, level, "gust-encounter", GUST_DESCRIPTION,
                  level.u, g["duration_s"], notes=((g["start_s"], "the body origin enters the 1-cos gust"),),
                  metadata={"gust": "1-cos, U_ds 10 m/s, H 60 m"}, wind=gust)


# ---------------------------------------------------------------------------------------------- Goland
def _goland_model(speed_m_s: float, aero: AeroOptions) -> AircraftModel:
    return AircraftModel(load_aircraft("goland_wing"), variant="restrained", restrained_velocity_m_s=[speed_m_s, 0.0, 0.0],
                         altitude_m=0.0, aero=aero)


@lru_cache(maxsize=4)
def goland_flutter_speed(aero: str = "unsteady") -> float:
    """Flutter speed of the clamped Goland wing at sea level [m/s] with this model
    (:func:`flexsim.linear.flutter.wind_tunnel_flutter`, cached).

    Literature: 137.2 m/s at 70.7 rad/s (Goland 1945; Patil, Hodges & Cesnik 2001), incompressible;
    flexsim's m = 3, n = 2 model (incompressible, as the bundled file sets) against it: the Goland rows of
    docs/validation.md's generated table (``flexsim validate``).
    """
    if aero not in _AERO_CHOICES:
        raise ValueError(f"aero = {aero!r}: must be one of {', '.join(_AERO_CHOICES)}")
    return wind_tunnel_flutter(load_aircraft("goland_wing"), aero_model=aero)[0]


def _flutter_onset(aero: AeroOptions, flight: _Flight) -> ManoeuvreSetup:
    if flight.aircraft is not None:
        return _tunnel_onset(aero, flight.aircraft)
    speed_f = goland_flutter_speed("unsteady")
    speed = 1.05 * speed_f
    model = _goland_model(speed, aero)
    note = "" if aero.model == "unsteady" else (f", simulated with quasi-steady aerodynamics (whose own flutter speed is "
                                          f"{goland_flutter_speed('quasi-steady'):.1f} m/s)")
    return ManoeuvreSetup("flutter-onset", f"Goland wing clamped in a sea-level wind tunnel at {speed:.1f} m/s = 1.05 x its "
                          f"flutter speed {speed_f:.1f} m/s (Peters unsteady aerodynamics){note}; "
                          "released undeformed under gravity",
                          model, model.layout.zeros(), np.zeros(4), 10.0,
                          notes=((0.0, f"tunnel speed {speed:.2f} m/s, flutter speed {speed_f:.2f} m/s"),),
                          metadata={"flutter_speed_m_s": f"{speed_f:.3f}", "tunnel_speed_m_s": f"{speed:.3f}"})


def _tunnel_onset(aero: AeroOptions, aircraft: Aircraft) -> ManoeuvreSetup:
    """flutter-onset of a given aircraft: clamped at its body origin in a sea-level tunnel at 1.05 x its flutter speed
    (Peters' unsteady aerodynamics, :func:`~flexsim.linear.flutter.wind_tunnel_flutter`)."""
    speed_f = wind_tunnel_flutter(aircraft, aero_model="unsteady")[0]
    speed = 1.05 * speed_f
    model = AircraftModel(aircraft, variant="restrained", restrained_velocity_m_s=[speed, 0.0, 0.0], altitude_m=0.0, aero=aero)
    return ManoeuvreSetup("flutter-onset", f"{aircraft.name} clamped in a sea-level wind tunnel at {speed:.1f} m/s = 1.05 x "
                          f"its flutter speed {speed_f:.1f} m/s (Peters unsteady aerodynamics); released undeformed under "
                          "gravity", model, model.layout.zeros(), np.zeros(4), 10.0,
                          notes=((0.0, f"tunnel speed {speed:.2f} m/s, flutter speed {speed_f:.2f} m/s"),),
                          metadata={"flutter_speed_m_s": f"{speed_f:.3f}", "tunnel_speed_m_s": f"{speed:.3f}"})


_REGISTRY: dict[str, Callable[[AeroOptions, _Flight], ManoeuvreSetup]] = {
    "level-turn-entry": _level_turn_entry,
    "climb": _climb,
    "elevator-doublet": _elevator_doublet,
    "aileron-roll": _aileron_roll,
    "gust-encounter": _gust_encounter,
    "flutter-onset": _flutter_onset,
}


def manoeuvre_names() -> tuple[str, ...]:
    """Names accepted by :func:`build_manoeuvre`."""
    return tuple(_REGISTRY)


def build_manoeuvre(name: str, *, aero: str = "unsteady", duration_s: float | None = None,
                    formulation: str | None = None, aircraft: Aircraft | str | None = None,
                    altitude_m: float | None = None, mach: float | None = None,
                    speed_m_s: float | None = None) -> ManoeuvreSetup:
    """Build a named manoeuvre (see the module docstring).

    Parameters
    ----------
    name : str
        One of :func:`manoeuvre_names`.
    aero : {"unsteady", "quasi-steady"}
        Aerodynamic model (default Peters finite-state, N = 6).
    duration_s : float, optional
        Run length [s] > 0 instead of the manoeuvre's default.
    formulation : {"physical", "paper"}, optional
        Resolution of the strip airloads (docs/design.md); default None: the aircraft file's.
    aircraft : Aircraft or str, optional
        The aircraft (loaded, bundled name or TOML path) instead of the GTM (the Goland wing for
        ``flutter-onset``); it flies from its level trim at its cruise point
        (:func:`flexsim.linear.envelope.cruise_point`), with a structural limit measured from that trim's wing-tip
        deflection (a quarter of the wing's length beyond it).
    altitude_m, mach, speed_m_s : float, optional
        The level trim's altitude [m] and Mach number or true airspeed [m/s] instead of the aircraft's cruise point
        (the GTM's default: 9144 m, M 0.75); not for ``flutter-onset`` (a wind tunnel at sea level).

    Raises
    ------
    ValueError
        Unknown name (the message lists the valid ones), aero model or duration.
    """
    if name not in _REGISTRY:
        raise ValueError(f"manoeuvre = {name!r}: unknown; valid manoeuvres: {', '.join(_REGISTRY)}")
    if aero not in _AERO_CHOICES:
        raise ValueError(f"aero = {aero!r}: must be one of {', '.join(_AERO_CHOICES)}")
    given = {k: v for k, v in (("altitude_m", altitude_m), ("mach", mach), ("speed_m_s", speed_m_s)) if v is not None}
    if name == "flutter-onset" and given:
        raise ValueError(f"{', '.join(given)}: flutter-onset is a wind tunnel at sea level at 1.05 x the flutter speed; "
                         "it takes no flight condition")
    if aircraft is None and not given:
        flight = _Flight(None, CRUISE_ALTITUDE_M, CRUISE_MACH)
    else:
        from flexsim.linear.envelope import cruise_point

        craft = load_aircraft("gtm" if aircraft is None else aircraft) if not isinstance(aircraft, Aircraft) else aircraft
        point = cruise_point(craft, altitude_m=altitude_m, mach=mach, speed_m_s=speed_m_s) if name != "flutter-onset" else None
        flight = _Flight(craft, point.altitude_m if point else 0.0, point.mach if point else 0.0,
                         f"level trim at {point.describe()}" if point else "")
    setup = _REGISTRY[name](AeroOptions(aero, formulation=formulation), flight)
    if duration_s is not None:
        duration_s = positive_number("duration_s", duration_s, "s")
        setup = replace(setup, duration_s=float(duration_s))  # every other field kept (the gust of gust-encounter)
    return setup
