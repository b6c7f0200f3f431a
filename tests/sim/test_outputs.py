"""The outputs of many samples at once (flexsim.sim.outputs.OutputMaps, what a flight log's samples need).

Invariant: :meth:`OutputMaps.structure_series` and the load factor and wing lift of :meth:`OutputMaps.series` (one
compiled call over the samples, flexsim.sim._output_kernels) equal the sample-by-sample :meth:`OutputMaps.structure`
and :meth:`OutputMaps.load_factor_and_lift` bit for bit (the same kernels and BLAS calls with the same arguments), on
30 states of a GTM run through a 1-cos gust (elastic deflections, inflow and the tail in the wing's downwash), in the
gust, in still air and in a wind given as a plain callable (which takes the sample-by-sample path); likewise the air
data and heading rates of the series against :meth:`OutputMaps.air_velocity_body` and ``heading_rate`` of each sample.
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.kinematics import dcm_321
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim.atmosphere import speed_of_sound
from flexsim.sim.outputs import OutputMaps, air_angles, heading_rate
from flexsim.sim.simulate import simulate
from flexsim.trimming import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def gust_run():
    model = AircraftModel(load_aircraft("gtm"), aero="unsteady")
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))
    lay = model.layout
    velocity = dcm_321(*point.x[lay.euler]).T @ point.x[lay.v]
    gust = OneMinusCosineGust.encounter(3.0, 20.0, position_ned_m=point.x[lay.position], velocity_ned_m_s=velocity,
                                        start_time_s=0.1)
    result = simulate(model, point, 0.6, wind=gust)
    rows = np.linspace(0, result.t.size - 1, 30).astype(int)
    u = point.u + np.outer(np.sin(result.t[rows]), [1e3, 0.01, -0.01, 0.005])
    return OutputMaps(model), result.t[rows], result.x[rows], u, gust


def test_structure_series_equals_the_samples(gust_run):
    out, _, x, _, _ = gust_run
    series = out.structure_series(x)
    for k, xk in enumerate(x):
        for name, nodes in out.structure(xk).items():
            np.testing.assert_array_equal(series[name][k], nodes)


@pytest.mark.parametrize("wind_kind", ["gust", "still", "callable"])
def test_loads_of_the_series_equal_the_samples(gust_run, wind_kind):
    out, t, x, u, gust = gust_run
    wind = {"gust": gust, "still": None, "callable": lambda tt, p: gust(tt, p)}[wind_kind]
    cols = out.series(["load_factor", "wing_lift_N"], t, x, u, wind)
    one = np.array([out.load_factor_and_lift(float(tk), xk, uk, wind) for tk, xk, uk in zip(t, x, u)])
    np.testing.assert_array_equal(cols["load_factor"], one[:, 0])
    np.testing.assert_array_equal(cols["wing_lift_N"], one[:, 1])
    assert np.ptp(one[:, 0]) > 1e-3  # the gust and the controls moved the load factor


@pytest.mark.parametrize("wind_kind", ["gust", "still", "callable"])
def test_air_data_and_heading_rate_of_the_series_equal_the_samples(gust_run, wind_kind):
    """The air data of N samples (the wind of a disturbance field asked for all positions in one call) and their
    heading rates equal those of each sample alone (air_velocity_body, air_angles, the ISA speed of sound of its
    altitude; heading_rate of its unpacked state) bit for bit."""
    out, t, x, _, gust = gust_run
    wind = {"gust": gust, "still": None, "callable": lambda tt, p: gust(tt, p)}[wind_kind]
    air = out.air_data(t, x, wind)
    rates = out.heading_rate_rad_s(x)
    for k in range(len(t)):
        speed, alpha, beta = air_angles(out.air_velocity_body(float(t[k]), x[k], wind))
        assert (air.airspeed_m_s[k], air.alpha_rad[k], air.beta_rad[k]) == (speed, alpha, beta)
        assert air.mach[k] == speed / speed_of_sound(float(out.altitude_m(x[k])))
        _, euler, _, _, velocity = out.model.unpack(x[k])
        assert rates[k] == heading_rate(euler, velocity)
