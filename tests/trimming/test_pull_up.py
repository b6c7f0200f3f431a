"""Symmetric pull-up at load factor n: the quasi-steady bottom of the manoeuvre.

Closed forms at the bottom of a wings-level pull-up with a horizontal flight path (Stevens & Lewis, *Aircraft
Control and Simulation*, 2nd ed., 2003, sec. 3.6, pull-up constraint): pitch rate q = (n - 1) g / V about the body
y axis, and the resultant of aerodynamic force and thrust equal to n W (the normal-force equation
V gamma_dot = g (n - cos gamma) at gamma = 0). n = 1 is level flight.
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import STANDARD_GRAVITY, AircraftModel
from flexsim.kinematics import dcm_321
from flexsim.trimming import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def gtm():
    return AircraftModel(load_aircraft("gtm"), aero="quasi-steady")


def test_pitch_rate_is_the_closed_form_and_nose_up():
    man = SteadyManoeuvre.pull_up(9144.0, 2.5, mach=0.6)
    # q = (n - 1) g / V, positive: nose up about body y (x forward, y right, z down)
    assert man.pitch_rate == pytest.approx(1.5 * STANDARD_GRAVITY / man.speed_m_s, rel=1e-15)
    v, omega = man.body_rates(0.0, 0.05, 0.0)
    assert omega[1] > 0.0 and omega[0] == 0.0 and omega[2] == 0.0
    assert omega[1] == pytest.approx(man.pitch_rate, rel=1e-15)
    # the load factor is kept at another speed (flutter's speed scan) and q follows V
    faster = man.with_speed(2.0 * man.speed_m_s)
    assert faster.load_factor == 2.5 and faster.pitch_rate == pytest.approx(man.pitch_rate / 2.0, rel=1e-15)
    assert "pull-up (n = 2.5" in man.describe()


@pytest.mark.parametrize("bad", [0.5, 6.5, math.nan, math.inf, "2"])
def test_load_factor_outside_its_range_is_refused_by_name(bad):
    with pytest.raises(ValueError, match=r"load_factor = .*\[1, 6\]"):
        SteadyManoeuvre.pull_up(9144.0, bad, mach=0.6)


def test_pull_up_needs_straight_horizontal_flight():
    with pytest.raises(ValueError, match="load_factor = 2.0: a pull-up is symmetric"):
        SteadyManoeuvre(180.0, 9144.0, turn_radius_m=5000.0, load_factor=2.0)


def test_n_equal_one_is_level_flight(gtm):
    level = trim(gtm, SteadyManoeuvre.level(9144.0, mach=0.6))
    pull = trim(gtm, SteadyManoeuvre.pull_up(9144.0, 1.0, mach=0.6))
    # the same manoeuvre (n = 1 adds q = 0): equal to the solver's tolerance (residual ~1e-12)
    assert pull.theta == pytest.approx(level.theta, abs=1e-9)
    np.testing.assert_allclose(pull.u, level.u, rtol=1e-8, atol=1e-9)


@pytest.mark.parametrize("n", [1.5, 2.5])
def test_gtm_pull_up_lifts_n_times_the_weight(gtm, n):
    man = SteadyManoeuvre.pull_up(9144.0, n, mach=0.6)
    point = trim(gtm, man, check_limits=False)
    assert point.residual < 1e-8
    assert abs(point.phi) < 1e-9  # symmetric: wings level
    assert point.x[gtm.layout.omega][1] == pytest.approx((n - 1.0) * STANDARD_GRAVITY / man.speed_m_s, rel=1e-12)
    # resultant of aero force and thrust over weight = |a_cg - g| / g with the rigid-body CG acceleration
    # a_cg = omega x (v + omega x r_cg) (steady in body axes); 5e-4: the CG of the deformed structure moves from the
    # undeformed r_cg used here (measured 6e-5 at n = 2.5)
    lay = gtm.layout
    v, w, r = point.x[lay.v], point.x[lay.omega], gtm.structure.mass_properties.cg_m
    g_body = dcm_321(point.phi, point.theta, 0.0) @ np.array([0.0, 0.0, STANDARD_GRAVITY])
    closed = np.linalg.norm(np.cross(w, v + np.cross(w, r)) - g_body) / STANDARD_GRAVITY
    assert point.load_factor_total == pytest.approx(closed, rel=5e-4)
    # and = n to 0.5 %: n is the load factor at the body origin (q V); the CG, 22 m aft of the GTM's origin, adds the
    # centripetal q^2 r_cg (0.2 % at n = 2.5)
    assert point.load_factor_total == pytest.approx(n, rel=5e-3)
    level = trim(gtm, SteadyManoeuvre.level(9144.0, mach=0.6))
    assert point.theta > level.theta  # more lift needs a higher angle of attack (gamma = 0 in both)


def test_hale_pull_up_lifts_n_times_the_weight():
    hale = AircraftModel(load_aircraft("phc_hale"), aero="quasi-steady")
    man = SteadyManoeuvre.pull_up(20000.0, 1.5, speed_m_s=25.0)
    point = trim(hale, man, check_limits=False)
    assert point.residual < 1e-8
    # n at the body origin; 1e-2 covers the CG offset's centripetal term and the large static deflection's CG shift
    assert point.load_factor_total == pytest.approx(1.5, rel=1e-2)
