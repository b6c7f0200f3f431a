"""The control periods of flexsim.sim.periods: rate limits, ground contact, one compiled call against separate calls.

Checks:
* :func:`rate_limit_rows` (the one implementation of the actuator rate limits): a command within reach is
  reached, one beyond it moves by exactly rate * period towards it (closed form, exact).
* :func:`ground_crossing` (the one implementation of the ground contact): a step from 1 m above to 1 m below the
  ground over [0, 0.02] s crosses at its middle (t = 0.01 s, the state the mean of the two; exact), also when the
  result overwrites the start state; a step that stays above, or starts below, returns -inf.
* :func:`advance_period` of 3 aircraft about one trim in one compiled call equals, bit for bit, the same period
  by the separate calls (rate limits, :func:`advance_rows`, measurements), row by row and as matrix products
  over the rows (the latter to 1e-12: other rounding of the products).
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim import periods
from flexsim.sim._step_kernels import ground_crossing, rate_limit_rows
from flexsim.sim.periods import ActuatorRates, FlightDynamics, IntegratorSettings, advance_period, advance_rows
from flexsim.trimming import SteadyManoeuvre


def test_rate_limits_closed_form():
    applied = np.array([[1000.0, 0.0, 0.1, -0.1], [0.0, 0.0, 0.0, 0.0]])
    command = np.array([[1500.0, 0.05, -0.5, 0.4], [-10.0, -1.0, 1.0, 0.0]])
    step = np.array([200.0, 0.02, 0.3, 0.6])
    out = np.empty_like(applied)
    rate_limit_rows(applied, command, step, out)
    np.testing.assert_array_equal(out, [[1200.0, 0.02, 0.1 - 0.3, 0.4], [-10.0, -0.02, 0.3, 0.0]])


def test_ground_crossing_closed_form():
    x = np.array([5.0, 0.0, -1.0, 2.0])
    x_new = np.array([7.0, 1.0, 1.0, 2.0])
    out = np.full(4, np.nan)
    assert ground_crossing(x, x_new, 0.0, 0.02, 2, out) == 0.01
    np.testing.assert_array_equal(out, [6.0, 0.5, 0.0, 2.0])
    same = x.copy()
    assert ground_crossing(same, x_new, 0.0, 0.02, 2, same) == 0.01 and same.tolist() == [6.0, 0.5, 0.0, 2.0]
    out[:] = 3.0
    assert ground_crossing(x, np.array([7.0, 1.0, -0.5, 2.0]), 0.0, 0.02, 2, out) == -math.inf
    assert ground_crossing(np.array([0.0, 0.0, 0.5, 0.0]), x_new, 0.0, 0.02, 2, out) == -math.inf
    assert out.tolist() == [3.0] * 4


@pytest.fixture(scope="module")
def three():
    dyn = FlightDynamics(AircraftModel(load_aircraft("gtm"), aero="unsteady"), IntegratorSettings(), ActuatorRates(), 0.02)
    manoeuvre = SteadyManoeuvre(speed_m_s=230.0, altitude_m=9144.0)
    point = dyn.trim(manoeuvre)
    dyns = [dyn] * 3
    states = [dyn.start(manoeuvre) for _ in range(3)]
    rng = np.random.default_rng(1)
    x = np.repeat(point.x[None, :], 3, axis=0)
    x[:, dyn.layout.omega] += rng.uniform(-0.02, 0.02, (3, 3))
    applied = np.repeat(point.u[None, :], 3, axis=0)
    command = applied * (1.0 + rng.uniform(-0.5, 0.5, (3, 4)))
    return dyns, states, x, applied, command


@pytest.mark.parametrize("rows_below", [periods.COMPILED_ROWS_BELOW, 2])
def test_one_compiled_call_equals_the_separate_calls(three, rows_below, monkeypatch):
    monkeypatch.setattr(periods, "COMPILED_ROWS_BELOW", rows_below)
    dyns, states, x, applied, command = three
    dyn = dyns[0]
    k = np.full(3, 20)  # the period [0.4, 0.42] s
    t0, t1 = k * dyn.dt, (k + 1) * dyn.dt
    winds = [None] * 3
    one = advance_period(dyns, states, x, applied, command, k, winds, dyn.model.pack_winds(winds))
    u = dyn.rate_limit(applied, command)
    np.testing.assert_array_equal(one.u, u)
    separate = advance_rows(dyns, states, x, u, t0, t1, winds)
    meas = dyn.measure_batch(separate.x, separate.time_s, winds)
    tol = 0.0 if rows_below > 3 else 1e-12
    np.testing.assert_allclose(one.outcome.x, separate.x, rtol=tol, atol=0.0)
    np.testing.assert_array_equal(one.outcome.time_s, separate.time_s)
    np.testing.assert_allclose(one.meas.matrix, meas.matrix, rtol=tol, atol=tol)
    assert not one.outcome.crashed.any() and list(one.outcome.failure) == [""] * 3 and one.outcome.nfev.tolist() == [2] * 3
