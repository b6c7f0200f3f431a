"""Fixed ROS2 steps of the nonlinear aircraft (flexsim.sim.flexible_step) against invariants and the BDF run.

* The nonlinear trim is a fixed point of the step: over 1 s at h = 10 ms the velocity drifts below 1e-8 m/s (the
  trim's residual is ~1e-10 scaled; ROS2 keeps any equilibrium of f exactly up to round-off, since f(y*) = 0 gives
  k1 = k2 = 0).
* The HALE's 1-cos gust (10 m/s, H 60 m, 4 elements per beam, 1.5 s) against ``simulate_flexible``'s error-controlled
  BDF (rtol 1e-6), each strip meeting the gust where it is: the tip deflection within 5 cm at h = 10 ms (measured
  3.94 cm; 7.93 cm at 20 ms, 1.94 cm at 5 ms, 0.93 cm at 2.5 ms: the error halves with h) and the peak within 0.4 %
  of the semispan (measured 0.25 %; slow: the BDF run takes ~20 s).
* The phugoid of the nonlinear run equals the linearisation's eigenvalue (3 % in damping, 0.5 % in frequency).
* Bad steps are refused by name.
* Each strip meets the wind where it is (``strip_wind``): a field uniform in space gives the uniform wind's airloads
  to round-off; an upward gust whose front lies between the wing (10 m ahead of the body origin) and the tail (at it)
  lifts the wing only, so the lift lies between none and the uniform gust's and the nose-up moment about the centre of
  gravity exceeds the uniform gust's (whose tail lift pitches the nose down).
"""

from __future__ import annotations

import numpy as np
import pytest

import flexsim as fs
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim.sim.flexible_step import FlexibleStepper, strip_wind
from flexsim.structure.free_flexible import quaternion_matrix
from flexsim.trimming.flexible_trim import trim_flexible

SEMISPAN_M = 16.0  # PHC 2001's wing half (flexsim/aircraft/data/phc_hale.md)


@pytest.fixture(scope="module")
def hale():
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    return model, trim_flexible(model, fs.SteadyManoeuvre.level(altitude_m=20000.0, speed_m_s=25.0), elements_per_beam=4)


def test_trim_is_a_fixed_point(hale):
    model, point = hale
    run = fs.simulate_flexible(model, point, 1.0, sample_dt_s=0.1, step_s=0.01)
    assert np.abs(run.velocity_m_s - point.velocity_m_s).max() < 1e-8
    assert np.abs(run.strains - point.strains).max() < 1e-8
    assert run.method.startswith("ROS2, h = 0.01 s")


@pytest.mark.parametrize("step_s", [0.0, 0.1, True, float("nan")])
def test_bad_step_is_refused(hale, step_s):
    model, point = hale
    flex = point.aircraft
    with pytest.raises(ValueError, match="step_s"):
        FlexibleStepper.about(flex, flex.free_structure(9.80665), point.state(), point.controls,
                              point.density_kg_m3, step_s)


def test_sample_spacing_must_be_whole_steps(hale):
    model, point = hale
    with pytest.raises(ValueError, match="sample_dt_s = 0.015: must be a whole number of steps"):
        fs.simulate_flexible(model, point, 0.1, sample_dt_s=0.015, step_s=0.01)


@pytest.mark.slow
def test_gust_against_bdf(hale):
    model, point = hale
    y0 = point.state()
    gust = OneMinusCosineGust.encounter(10.0, 60.0, position_ned_m=y0[:3],
                                        velocity_ned_m_s=quaternion_matrix(y0[3:7]) @ point.velocity_m_s,
                                        start_time_s=0.2)
    bdf = fs.simulate_flexible(model, point, 1.5, wind=gust, sample_dt_s=0.01)
    ros2 = fs.simulate_flexible(model, point, 1.5, wind=gust, sample_dt_s=0.01, step_s=0.01)
    diff = np.abs(ros2.tip_deflection_fraction - bdf.tip_deflection_fraction).max() * SEMISPAN_M
    print(f"tip deflection: ROS2 h = 10 ms within {diff:.4f} m of BDF; wall {ros2.wall_s:.2f} s against "
          f"{bdf.wall_s:.1f} s; peak {100 * ros2.tip_deflection_fraction.max():.2f} % against "
          f"{100 * bdf.tip_deflection_fraction.max():.2f} %")
    assert diff < 0.05
    assert abs(ros2.tip_deflection_fraction.max() - bdf.tip_deflection_fraction.max()) < 4e-3


def test_phugoid_in_time_matches_the_linearisation(hale):
    """The free aircraft's phugoid about the nonlinear trim, two ways: the eigenvalue of the linearisation
    (``free_aircraft_spectrum``) and a damped sinusoid fitted to the airspeed of the nonlinear run after a 0.25 m/s
    forward-speed disturbance (40 s, ROS2 h = 20 ms; t > 5 s, so the short period has died out; a decaying exponential
    for the rest). Measured: sigma -0.04545 against -0.04530 1/s (0.3 %), omega 0.31735 against 0.31750 rad/s
    (0.05 %); windows from t > 3 s to t > 8 s move them by 0.5 % and 0.16 %, h = 10 ms by < 0.01 %; tolerances 3 % and
    0.5 %."""
    from scipy.optimize import least_squares

    from flexsim.linear.flexible_stability import free_aircraft_spectrum

    model, point = hale
    phugoid = next(m.eigenvalue for m in free_aircraft_spectrum(model, point).modes if m.name == "phugoid")
    y0 = point.state()
    n = point.strains.size
    y0[7 + n] += 0.25
    run = fs.simulate_flexible(model, point, 40.0, sample_dt_s=0.1, step_s=0.02, initial_state=y0)
    dv = np.linalg.norm(run.velocity_m_s, axis=1) - np.linalg.norm(point.velocity_m_s)
    t, keep = run.t, run.t > 5.0

    def residual(p):
        a, s, w, ph, c, a2, s2 = p
        return (a * np.exp(s * t) * np.cos(w * t + ph) + c + a2 * np.exp(s2 * t) - dv)[keep]

    fit = least_squares(residual, [0.25, phugoid.real, phugoid.imag, 0.0, 0.0, 0.0, -0.5])
    sigma, omega = fit.x[1], fit.x[2]
    print(f"phugoid: time domain {sigma:.5f} +- {omega:.5f}j, linearisation {phugoid.real:.5f} +- {phugoid.imag:.5f}j")
    assert np.abs(fit.fun).max() < 1e-3 * 0.25  # the fitted form describes the response
    assert sigma == pytest.approx(phugoid.real, rel=0.03)
    assert omega == pytest.approx(phugoid.imag, rel=0.005)


def test_each_strip_meets_the_wind_where_it_is(hale):
    model, point = hale
    y = point.state()
    flex, n = point.aircraft, point.aircraft.n_strains
    eps, v, om, u, rho = y[7:7 + n], y[7 + n:10 + n], y[10 + n:13 + n], point.controls, point.density_kg_m3
    c = quaternion_matrix(y[3:7])
    up = np.array([0.0, 0.0, -5.0])  # NED: 5 m/s upward
    uniform = flex.airloads(eps, v, om, u, rho, wind=c.T @ up)
    field = flex.airloads(eps, v, om, u, rho, wind=strip_wind(lambda t, p: np.tile(up, (len(p), 1)), 0.0, y))
    assert np.abs(field - uniform).max() < 1e-12 * np.abs(uniform).max()
    forward = c[:, 0]  # the body x axis in NED: the front 5 m ahead of the tail (the body origin), behind the wing
    front = (y[:3] + 5.0 * forward) @ forward

    def gust(t, p):
        return np.where((np.asarray(p) @ forward > front)[:, None], up[None, :], 0.0)

    split = flex.airloads(eps, v, om, u, rho, wind=strip_wind(gust, 0.0, y))
    still = flex.airloads(eps, v, om, u, rho)
    assert -still[2] < -split[2] < -uniform[2]  # lift (body z down)
    cg = np.asarray(model.structure.mass_properties.cg_m)

    def pitch_about_cg(q):
        return q[4] - np.cross(cg, q[:3])[1]

    assert pitch_about_cg(split) > pitch_about_cg(uniform) + 0.01 * abs(pitch_about_cg(uniform) - pitch_about_cg(still))
