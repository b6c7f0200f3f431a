"""The measurements of flexsim.sim.measurements (one implementation of the air data) against independent values.

Checks:
* :func:`air_data` against closed forms: V = |v_a|, alpha = atan(w_a / u_a), beta = asin(v_a / V) for velocities
  chosen so that the angles are known (45 deg, 30 deg, +-90 deg sideslip, 0 at zero airspeed; 1e-15);
  ``outputs.air_angles`` returns the same for (3,) and (N, 3) input.
* The heading rate of a level turn (phi = 30 deg, theta = 0, q = Omega sin phi, r = Omega cos phi) is Omega
  (1e-15 relative), for one state and for rows.
* :func:`measure_rows` of off-trim states in a Dryden field: attitude, rates and altitude copied from the state;
  the air data with the wind packed (compiled wind) equal those of the wind asked in Python
  (``OutputMaps.air_velocity_body``, then the air data) to 1e-12; Mach = V / ``flexsim.atmosphere.speed_of_sound``
  (an independent ISA implementation) to 1e-12; the structural outputs equal the ``ComponentSensor`` rows to 1e-12
  (a different summation); NaN Mach above the ISA range.
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.atmosphere import speed_of_sound
from flexsim.sim.disturbances import DrydenTurbulence
from flexsim.sim.measurements import air_data
from flexsim.sim.outputs import air_angles, heading_rate
from flexsim.sim.periods import SENSOR_COMPONENTS, ActuatorRates, FlightDynamics, IntegratorSettings
from flexsim.trimming import SteadyManoeuvre


def _close(a, b, rtol=1e-12):
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert np.all(np.abs(a - b) <= rtol * np.maximum(np.abs(b), 1e-300) + 1e-300), (a, b)


def test_air_data_closed_forms():
    cases = [((100.0, 0.0, 100.0), (100.0 * math.sqrt(2.0), math.pi / 4, 0.0)),
             ((math.sqrt(3.0) * 50.0, 0.0, 50.0), (100.0, math.pi / 6, 0.0)),
             ((0.0, 80.0, 0.0), (80.0, 0.0, math.pi / 2)),
             ((0.0, -80.0, 0.0), (80.0, 0.0, -math.pi / 2)),
             ((60.0, 80.0, 0.0), (100.0, 0.0, math.asin(0.8))),
             ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))]
    for v, expected in cases:
        got = air_data(*v)
        assert got == pytest.approx(expected, rel=1e-15, abs=1e-15), (v, got)
        assert air_angles(np.array(v)) == pytest.approx(expected, rel=1e-15, abs=1e-15)
    rows = air_angles(np.array([c[0] for c in cases]))
    _close(np.array(rows).T, [c[1] for c in cases], rtol=1e-15)


def test_heading_rate_of_a_level_turn():
    omega, phi = 0.05, math.radians(30.0)
    velocity = np.array([230.0, 0.0, 0.0, 0.0, omega * math.sin(phi), omega * math.cos(phi)])
    assert heading_rate(np.array([phi, 0.0, 1.0]), velocity) == pytest.approx(omega, rel=1e-15)
    many = heading_rate(np.array([[phi, 0.0, 0.0]] * 3), np.array([velocity] * 3))
    _close(many, [omega] * 3, rtol=1e-15)


@pytest.fixture(scope="module")
def flying():
    """The GTM's level-flight trim at 9144 m, 12 states spread around it, and a moderate Dryden field."""
    dyn = FlightDynamics(AircraftModel(load_aircraft("gtm"), aero="unsteady"), IntegratorSettings(), ActuatorRates(), 0.02)
    point = dyn.trim(SteadyManoeuvre(speed_m_s=230.0, altitude_m=9144.0))
    rng = np.random.default_rng(0)
    lay = dyn.layout
    x = np.repeat(point.x[None, :], 12, axis=0)
    x[:, lay.euler] += rng.uniform(-1.2, 1.2, (12, 3))
    x[:, lay.omega] += rng.uniform(-0.5, 0.5, (12, 3))
    x[:, lay.v] *= rng.uniform(0.5, 1.5, (12, 3))
    x[:, lay.position] += rng.uniform(-300.0, 300.0, (12, 3))
    x[:, lay.q] += rng.uniform(-0.3, 0.3, (12, lay.nq))
    x[:, lay.s] += rng.uniform(-1.0, 1.0, (12, lay.nq))
    x[:, lay.xi] += rng.uniform(-0.02, 0.02, (12, lay.nxi))
    x[:, lay.eta] += rng.uniform(-0.5, 0.5, (12, lay.nxi))
    wind = DrydenTurbulence.mil_f_8785c(9144.0, "moderate", seed=3, heading_rad=0.0, origin_ned_m=point.x[lay.position],
                                        n_points=16384)
    return dyn, x, wind


def test_measurements_of_off_trim_states(flying):
    dyn, x, wind = flying
    lay = dyn.layout
    winds = [wind] * len(x)
    packed = dyn.measure_batch(x, np.full(len(x), 0.2), winds, dyn.model.pack_winds(winds))
    given = dyn.measure_batch(x, np.full(len(x), 0.2), winds)  # the wind asked in Python, per row
    for name in ("airspeed_m_s", "alpha_rad", "beta_rad", "mach"):
        _close(getattr(packed, name), getattr(given, name))
    _close(packed.euler_rad, x[:, lay.euler], rtol=0.0)
    _close(packed.body_rates_rad_s, x[:, lay.omega], rtol=0.0)
    _close(packed.altitude_m, -x[:, lay.position.start + 2], rtol=0.0)
    for i, xi in enumerate(x):
        _close(packed.mach[i], packed.airspeed_m_s[i] / speed_of_sound(-xi[lay.position.start + 2]))
        for c in SENSOR_COMPONENTS:
            sensor = dyn.sensors[c]
            for name in ("tip_deflection_m", "tip_deflection_rate_m_s", "tip_twist_rad", "tip_twist_rate_rad_s"):
                _close(getattr(packed, name)[c][i], getattr(sensor, name)(xi))
            if c != "vtail":
                _close(packed.root_bending_moment_n_m[c][i], sensor.root_bending_moment_n_m(xi))
    still = dyn.measure_batch(x, np.zeros(len(x)))
    speed, alpha, beta = air_angles(x[:, lay.v])
    _close(still.airspeed_m_s, speed)
    _close(still.alpha_rad, alpha)
    _close(still.beta_rad, beta)


def test_mach_outside_the_isa_range_is_nan(flying):
    dyn, x, _ = flying
    x = x[:2].copy()
    x[0, dyn.layout.position.start + 2] = -30_000.0  # 30 km: above the ISA model's 20 km
    meas = dyn.measure_batch(x, np.zeros(2))
    assert math.isnan(meas.mach[0]) and math.isfinite(meas.mach[1])
