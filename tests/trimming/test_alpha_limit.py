"""The trim's angle-of-attack limit: the linear (no-stall) aerodynamics' range (reliability census).

A trim whose centre of gravity flies beyond the aircraft's ``[aero] max_alpha_deg`` (the GTM's 11 deg: the end of
the linear lift range of the NASA T2 wind-tunnel database, tests/aircraft/test_gtm_alpha_limit.py) is refused with a
TrimError naming the angle of attack, its value and the allowed range; ``check_limits=False`` returns it as asked.
The two cases are those ``studies/reliability_census.py trim`` found trimmed silently: 20000 m at M 0.78 trims at
alpha = 21.95 deg, a glide at M 0.3 and 3000 m at 18.8 deg.
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.errors import AircraftDefinitionError
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre, TrimError, trim

HIGH = SteadyManoeuvre.level(20000.0, mach=0.78)
SLOW_GLIDE = SteadyManoeuvre.glide(3000.0, mach=0.3)


@pytest.fixture(scope="module")
def model():
    return AircraftModel(load_aircraft("gtm"), aero="quasi-steady")


def _alpha_cg_deg(model, point) -> float:
    """atan(w_cg / u_cg) of v_cg = v + omega x r_cg (undeformed CG), independent of the solver's helper."""
    lay = model.layout
    v_cg = point.x[lay.v] + np.cross(point.x[lay.omega], model.structure.mass_properties.cg_m)
    return math.degrees(math.atan2(v_cg[2], v_cg[0]))


@pytest.mark.parametrize("manoeuvre, alpha_deg", [(HIGH, r"21\.9\d"), (SLOW_GLIDE, r"18\.8\d")])
def test_trim_beyond_the_linear_range_names_alpha_value_and_range(model, manoeuvre, alpha_deg):
    with pytest.raises(TrimError, match=rf"trim infeasible for .*H = {manoeuvre.altitude_m:.0f} m: angle of attack alpha = "
                                        rf"{alpha_deg} deg at the CG beyond the range of the linear \(no-stall\) aerodynamics, "
                                        r"\+-11 deg = \[aero\] max_alpha_deg of GTM-notional-A(; local angle of attack .*)? \(the "
                                        r"equations were solved"):
        trim(model, manoeuvre)


@pytest.mark.parametrize("manoeuvre", [HIGH, SLOW_GLIDE])
def test_no_limits_returns_the_solution_as_asked(model, manoeuvre):
    point = trim(model, manoeuvre, check_limits=False)
    assert point.residual < 1e-8
    assert _alpha_cg_deg(model, point) > 11.0
    # straight flight: no rotation, so the CG's angle of attack is the body origin's
    assert _alpha_cg_deg(model, point) == pytest.approx(math.degrees(point.alpha), abs=1e-12)


def test_the_limit_is_the_aircraft_field(model):
    """With a wider range on the same aircraft the 20000 m trim is accepted: its surfaces are within their limits
    (elevator about -16 deg of +-25), so the angle of attack alone refused it."""
    ac = model.aircraft
    wide = replace(ac, aero_settings=replace(ac.aero_settings, max_alpha_rad=math.radians(25.0)))
    point = trim(AircraftModel(wide, aero="quasi-steady"), HIGH)
    assert 11.0 < _alpha_cg_deg(model, point) < 25.0
    lo, hi = ac.control_limits()
    assert np.all(point.u[1:] > lo[1:]) and np.all(point.u[1:] < hi[1:])


def test_a_normal_trim_passes_within_the_range(model):
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.78))
    assert 0.0 < _alpha_cg_deg(model, point) < 11.0


def test_every_exceeded_limit_is_named(model):
    """M 0.3 at 9144 m (alpha about 38 deg, elevator about -33 deg of +-25): both are named, alpha first."""
    with pytest.raises(TrimError, match=r"angle of attack alpha = 3\d\.\d+ deg at the CG .*; elevator delta_e \[rad\] = "
                                        r"-0\.\d+ outside its limits \[-0\.43633, 0\.43633\]"):
        trim(model, SteadyManoeuvre.level(9144.0, mach=0.3))


@pytest.mark.parametrize("value", [0.0, -0.1, math.radians(31.0), float("nan"), float("inf")])
def test_bad_limit_is_refused_naming_the_field(value):
    ac = load_aircraft("gtm")
    with pytest.raises(AircraftDefinitionError, match=r"aero\.max_alpha_rad = .*must be in \(0"):
        replace(ac.aero_settings, max_alpha_rad=value)
