"""The task and the flight limits of an environment flown with an aircraft other than the bundled GTM.

The task classes' defaults (``LevelHoldTask()``: 9144 m, M 0.75; ``FlightLimits()``: 5.5 m wing-tip deflection, 60 m/s
lowest airspeed ...) are the notional GTM's. With ``aircraft=`` another aircraft and ``task=None`` / ``limits=None``,
the environment derives them from that aircraft instead (docs/environments.md, "Any aircraft"):

* the task's altitude and Mach number: the aircraft's cruise point (:func:`flexsim.linear.envelope.cruise_point`: the
  file's ``[envelope]`` ``cruise_altitude_m`` and ``cruise_mach``/``cruise_speed_m_s``, else derived from its envelope);
  a turn task's radii are those of the GTM task's bank angles at this speed (tan(mu) = V^2 / (g R), so R scales with
  V^2), from 100 m at least (the steady manoeuvres' tightest turn); a gust task's amplitudes are those of the GTM task's gust angles of attack (U_ds / V, so U_ds scales with V);
  a flutter-margin task searches the aircraft's flutter point over its envelope at the task's altitude (its target is
  that point plus the task's Mach margin);
* the limits: the wing-tip deflection bound 0.3 x the wing's length (the GTM's 5.5 m of its 18.25 m wing) beyond the
  trim's own deflection (a flexible aircraft whose trim bends its wing further still flies); the lowest airspeed and the
  highest Mach number the ends of the aircraft's flight envelope at the task's altitude
  (:func:`flexsim.linear.envelope.search_range`); the other bounds as ``FlightLimits()``.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from flexsim.aircraft.definition import Aircraft
from flexsim.atmosphere import speed_of_sound
from flexsim.trimming import SteadyManoeuvre

from flexsim.envs.config import FlightLimits

__all__ = ["is_bundled_gtm", "task_for_aircraft", "limits_for_aircraft", "limits_about", "WING_DEFLECTION_FRACTION"]

#: The bundled aircraft files the task and limit defaults were written for.
_GTM_FILES = ("gtm.toml", "gtm_paper.toml", "gtm_uncalibrated.toml")
#: Tightest turn radius of a steady manoeuvre (:class:`flexsim.trimming.SteadyManoeuvre`) [m]: a slow aircraft's turn task
#: keeps the ratio of its radii from there, at smaller bank angles than the GTM task's.
MIN_TURN_RADIUS_M = 100.0
#: Wing-tip deflection bound beyond the trim's, as a fraction of the wing's length: the GTM's 5.5 m of 18.25 m [-].
WING_DEFLECTION_FRACTION = 0.3


def is_bundled_gtm(aircraft: Aircraft) -> bool:
    """True for an aircraft loaded from one of the bundled GTM files (the defaults' own aircraft)."""
    from importlib import resources

    data = Path(str(resources.files("flexsim.aircraft") / "data")).resolve()
    source = Path(str(aircraft.source))
    return source.name in _GTM_FILES and source.resolve().parent == data


def task_for_aircraft(task, aircraft: Aircraft):
    """``task`` (a task class's default) at the aircraft's cruise point, scaled as the module docstring says; the task
    itself for the GTM or a task without a flight condition of its own (the flutter-margin tasks)."""
    from flexsim.linear.envelope import cruise_point

    names = {f.name for f in dataclasses.fields(task)}
    if is_bundled_gtm(aircraft):
        return task
    if "flutter_mach_range" in names:  # the flutter point searched over the aircraft's envelope at the task's altitude
        from flexsim.linear.envelope import search_range

        rng = search_range(aircraft, SteadyManoeuvre.level(task.altitude_m, mach=0.5))
        return dataclasses.replace(task, flutter_mach_range=(rng.mach_min, rng.mach_max))
    if not {"altitude_m", "mach"} <= names:
        return task
    point = cruise_point(aircraft)
    v_ref = task.mach * speed_of_sound(task.altitude_m)
    ratio = point.speed_m_s / v_ref
    changes: dict = {"altitude_m": point.altitude_m, "mach": point.mach}
    if "radius_range_m" in names:  # the same bank angles: R ~ V^2, no tighter than a steady manoeuvre allows
        lo, hi = (r * ratio**2 for r in task.radius_range_m)
        if lo < MIN_TURN_RADIUS_M:
            lo, hi = MIN_TURN_RADIUS_M, MIN_TURN_RADIUS_M * hi / lo
        changes["radius_range_m"] = (lo, hi)
    if "gust_amplitude_range_m_s" in names:  # the same gust angles of attack: U_ds ~ V
        changes["gust_amplitude_range_m_s"] = tuple(u * ratio for u in task.gust_amplitude_range_m_s)
    return dataclasses.replace(task, **changes)


def limits_for_aircraft(aircraft: Aircraft, dynamics, task) -> FlightLimits:
    """``FlightLimits()`` for the GTM; for another aircraft the bounds of the module docstring, about the trim of the
    task's level flight (``dynamics.trim``)."""
    names = {f.name for f in dataclasses.fields(task)}
    if is_bundled_gtm(aircraft) or "altitude_m" not in names:
        return FlightLimits()
    from flexsim.trimming import TrimError

    try:
        point = dynamics.trim(_level(task)[0])
    except TrimError:  # no episode can start there: reset() says why; the bound is then measured from the jig shape
        point = None
    tip = abs(float(point.tip_deflection_m)) if point is not None else 0.0
    return limits_about(aircraft, dynamics.model, task, tip)


def _level(task) -> tuple[SteadyManoeuvre, float]:
    """The task's level flight and its Mach number: the task's, or for a flutter-margin task the middle of its
    flutter search (its target is found later)."""
    names = {f.name for f in dataclasses.fields(task)}
    mach = task.mach if "mach" in names else 0.5 * sum(task.flutter_mach_range)
    return SteadyManoeuvre.level(task.altitude_m, mach=mach), mach


def limits_about(aircraft: Aircraft, model, task, trim_tip_deflection_m: float) -> FlightLimits:
    """The bounds of the module docstring for an aircraft that is not the GTM, about a trim whose wing tip is
    ``trim_tip_deflection_m`` [m] (its magnitude) from the jig shape; ``model`` a linear model of the aircraft
    (the envelope's speed bounds, :func:`flexsim.linear.envelope.search_range`)."""
    from flexsim.linear.envelope import MODEL_MAX_MACH, search_range

    level, mach = _level(task)
    changes: dict = {}
    if "right_wing" in aircraft.component_names:
        changes["wing_tip_deflection_m"] = (abs(float(trim_tip_deflection_m))
                                            + WING_DEFLECTION_FRACTION * aircraft.component("right_wing").length_m)
    try:
        rng = search_range(model, level)
    except ValueError:  # no envelope and no stall estimate: the GTM's speed bounds do not fit; half the task's speed
        changes["min_airspeed_m_s"] = 0.5 * level.speed_m_s
    else:
        low, _ = rng.speeds_m_s
        changes["min_airspeed_m_s"] = min(low, 0.9 * level.speed_m_s)
        # the envelope's end, with room for a flutter-margin task's target just beyond its flutter point
        changes["max_mach"] = min(MODEL_MAX_MACH, max(rng.mach_max, 1.1 * mach) + 0.05)
    return dataclasses.replace(FlightLimits(), **changes)
