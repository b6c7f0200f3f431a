"""Trim of an aircraft without a rudder (the mAEWing1 flying wing): the heading offset (sideslip) balances yaw.

Invariant: an aircraft that is mirror-symmetric about its x-z plane trims in level flight with zero bank, aileron
and sideslip, to 1e-7 rad (the trim converges to a scaled residual of 1e-8 g, and the roll and yaw residuals change
by about 1-6 g per radian of aileron or sideslip: a few 1e-9 rad); the bundled mAEWing1, whose two wings differ in
stiffness (its FEM v5.2), needs an aileron (> 1e-4 rad) and a sideslip instead, and its rudder stays at zero.
A coordinated (zero-sideslip) manoeuvre cannot be trimmed without a rudder and is refused with a message saying so.
"""

from dataclasses import replace

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre, TrimError, trim

LEVEL = SteadyManoeuvre.level(0.0, speed_m_s=25.0)


def _mirrored(aircraft):
    """The aircraft with its right wing given the left wing's sections (the two then mirror each other)."""
    left = aircraft.component("left_wing")
    comps = tuple(replace(c, sections=left.sections) if c.name == "right_wing" else c for c in aircraft.components)
    return replace(aircraft, components=comps)


def test_symmetric_rudderless_aircraft_trims_without_sideslip():
    point = trim(AircraftModel(_mirrored(load_aircraft("maewing1")), aero="quasi-steady"), LEVEL)
    assert point.residual < 1e-8
    assert abs(point.phi) < 1e-7 and abs(point.u[1]) < 1e-7 and abs(point.heading_offset) < 1e-7
    assert point.u[3] == 0.0


def test_asymmetric_rudderless_aircraft_trims_in_sideslip():
    point = trim(AircraftModel(load_aircraft("maewing1"), aero="quasi-steady"), LEVEL)
    assert point.residual < 1e-8
    assert point.u[3] == 0.0
    assert abs(point.u[1]) > 1e-4
    assert 1e-7 < abs(point.heading_offset) < np.radians(1.0)


def test_coordinated_manoeuvre_without_rudder_is_refused():
    turn = SteadyManoeuvre.turn(0.0, 200.0, speed_m_s=25.0, coordinated=True)
    with pytest.raises(TrimError, match="no rudder"):
        trim(AircraftModel(load_aircraft("maewing1"), aero="quasi-steady"), turn)
