"""Named manoeuvres flown by the geometrically nonlinear aircraft (``flexsim simulate ... --nonlinear-beams``).

The same manoeuvres as :mod:`flexsim.sim.manoeuvres` (their pulses, gust and durations are defined there once:
``ELEVATOR_DOUBLET``, ``AILERON_ROLL``, ``GUST_ENCOUNTER``) from the *nonlinear* level trim of the aircraft at its
cruise point, flown by :func:`flexsim.sim.flexible_run.simulate_flexible`. The manoeuvres that need the linear model's
state layout (the turn entry's bank controller), a second trim (the climb) or a wind tunnel (the flutter onset) are
not available and are refused by name.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.aircraft.definition import Aircraft
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.errors import positive_number
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.terms import NonlinearBeams, Terms
from flexsim.sim.controls import ControlSchedule
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim.sim.flexible_run import FlexibleRun, simulate_flexible
from flexsim.sim.manoeuvres import AILERON_ROLL, ELEVATOR_DOUBLET, GUST_DESCRIPTION, GUST_ENCOUNTER
from flexsim.structure.free_flexible import quaternion_matrix
from flexsim.trimming import SteadyManoeuvre, trim
from flexsim.trimming.flexible_trim import FlexibleTrimPoint

__all__ = ["FlexibleManoeuvre", "build_flexible_manoeuvre", "FLEXIBLE_MANOEUVRES"]

#: The named manoeuvres the nonlinear aircraft flies.
FLEXIBLE_MANOEUVRES = ("elevator-doublet", "aileron-roll", "gust-encounter")


@dataclass(frozen=True, eq=False)
class FlexibleManoeuvre:
    """A named manoeuvre of the nonlinear aircraft, ready to fly (:meth:`fly`).

    Attributes
    ----------
    name, description : str
    model : AircraftModel
        With ``terms.nonlinear_beams``.
    point : FlexibleTrimPoint
        The nonlinear level trim it starts from.
    controls : ControlSchedule
    wind : OneMinusCosineGust or None
    duration_s : float
    """

    name: str
    description: str
    model: AircraftModel
    point: FlexibleTrimPoint
    controls: ControlSchedule
    wind: OneMinusCosineGust | None
    duration_s: float

    def fly(self, *, step_s: float | None = 0.01, rtol: float = 1e-6, sample_dt_s: float = 0.02) -> FlexibleRun:
        """:func:`simulate_flexible` of this manoeuvre: fixed ROS2 steps of ``step_s`` [s], or with ``step_s=None``
        the error-controlled BDF method at ``rtol`` (``atol = 1e-2 rtol``)."""
        return simulate_flexible(self.model, self.point, self.duration_s, controls=self.controls, wind=self.wind,
                                 sample_dt_s=sample_dt_s, step_s=step_s, rtol=rtol, atol=1e-2 * rtol)


def build_flexible_manoeuvre(name: str, aircraft: Aircraft | str, *, beams: NonlinearBeams = NonlinearBeams(),
                             altitude_m: float | None = None, mach: float | None = None,
                             speed_m_s: float | None = None, duration_s: float | None = None) -> FlexibleManoeuvre:
    """The named manoeuvre ``name`` (one of :data:`FLEXIBLE_MANOEUVRES`) of ``aircraft`` with the nonlinear beams
    ``beams``, from its level trim at the cruise point (:func:`flexsim.linear.envelope.cruise_point`, or the
    altitude [m] and Mach number or true airspeed [m/s] given); ``duration_s`` [s] instead of the manoeuvre's."""
    from flexsim.linear.envelope import cruise_point

    if name not in FLEXIBLE_MANOEUVRES:
        raise ValueError(f"manoeuvre = {name!r}: not flown with the nonlinear beams; available: "
                         f"{', '.join(FLEXIBLE_MANOEUVRES)}")
    craft = aircraft if isinstance(aircraft, Aircraft) else load_aircraft(aircraft)
    cruise = cruise_point(craft, altitude_m=altitude_m, mach=mach, speed_m_s=speed_m_s)
    model = AircraftModel(craft, terms=Terms(nonlinear_beams=beams))
    point = trim(model, SteadyManoeuvre.level(cruise.altitude_m, speed_m_s=cruise.speed_m_s))
    wind = None
    if name == "gust-encounter":
        g = GUST_ENCOUNTER
        y0 = point.state()
        wind = OneMinusCosineGust.encounter(g["amplitude_m_s"], g["length_m"], position_ned_m=y0[:3],
                                            velocity_ned_m_s=quaternion_matrix(y0[3:7]) @ point.velocity_m_s,
                                            start_time_s=g["start_s"])
        description, duration, controls = GUST_DESCRIPTION, g["duration_s"], ControlSchedule.constant(point.controls)
    else:
        pulse = ELEVATOR_DOUBLET if name == "elevator-doublet" else AILERON_ROLL
        description, duration, controls = pulse.description, pulse.duration_s, pulse.schedule(np.asarray(point.controls))
    if duration_s is not None:
        duration = float(positive_number("duration_s", duration_s, "s"))
    return FlexibleManoeuvre(name, f"{craft.name}: {description}; nonlinear level trim at {cruise.describe()}", model,
                             point, controls, wind, duration)
