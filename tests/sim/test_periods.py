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
* A row stopped by a model error stays in the compiled call and reads the model's own message: above the ISA range
  at the start of the period (``model.rhs`` raises there; the state and time are the start, 2 right-hand sides
  begun), and 1 cm below its top climbing at 50 m/s, where the right-hand side is evaluated at the start but not at
  the stage state of the first step, 1 m higher (the message of ``model.rhs`` there, state and time the start).
* ``FlightDynamics.advance`` with ETD2RK in a Dryden field is the compiled step of one row: equal to the steps around
  ``model.rhs`` (the compiled stages with a Python right-hand side) over 20 periods with changing controls, to 1e-12
  relative (two compiled right-hand sides, ``model.rhs``'s and the step's: rounding only; bit for bit when measured);
  rows about two different trims (no shared stepper) give each row's own ``advance``, bit for bit (one kernel).
* Rows about two trims in one :func:`advance_period` (one compiled call per trim) equal, bit for bit, the separate
  calls (rate limits, each row's ``advance``, measurements).
* A Python wind callable takes the steps around ``model.rhs``: the same Dryden field passed as a plain callable gives
  the compiled step's states over 20 periods to 1e-12 relative (the wind evaluated by numpy instead of the compiled
  kernel: rounding only; equal bit for bit when measured), with the same nfev and no failure.
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim import periods
from flexsim.sim._step_kernels import ground_crossing, rate_limit_rows
from flexsim.sim.disturbances import DrydenTurbulence
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


def test_model_error_named_in_the_compiled_call(three):
    dyns, states, x, applied, command = three
    dyn = dyns[0]
    lo, hi = dyn.model.altitude_range_m
    z, w = dyn.layout.position.start + 2, dyn.layout.v.start + 2
    x = x.copy()
    x[1, z] = -(hi + 100.0)  # above the ISA range: rhs fails at the start
    x[2, z] = -(hi - 0.01)  # 1 cm below the top, climbing 50 m/s (body axes, level attitude): fails at the stage state
    x[2, dyn.layout.euler] = 0.0
    x[2, w] = -50.0
    k = np.zeros(3, np.int64)
    winds = [None] * 3
    one = advance_period(dyns, states, x, applied, command, k, winds, dyn.model.pack_winds(winds))
    out = one.outcome
    assert out.failure[0] == "" and out.failed.tolist() == [False, True, True]
    for r in (1, 2):
        np.testing.assert_array_equal(out.x[r], x[r])
        assert out.time_s[r] == 0.0 and out.nfev[r] == 2
    with pytest.raises(ValueError) as at_start:
        dyn.model.rhs(0.0, x[1], one.u[1])
    assert out.failure[1] == f"model error: {at_start.value}"
    dyn.model.rhs(0.0, x[2], one.u[2])  # evaluated at the start ...
    stage = x[2] + states[2].stepper.h_phi1 @ dyn.model.rhs(0.0, x[2], one.u[2])
    with pytest.raises(ValueError) as at_stage:  # ... not at the stage state
        dyn.model.rhs(dyn.dt, stage, one.u[2])
    assert out.failure[2] == f"model error: {at_stage.value}" and "ISA range" in out.failure[2]


def test_advance_is_the_compiled_step_of_one_row(three):
    dyns, states, x, applied, _ = three
    dyn, state = dyns[0], states[0]
    wind = DrydenTurbulence.mil_f_8785c(9144.0, "moderate", seed=2)
    xa = xb = x[0]
    for k in range(20):
        u = applied[0] * (1.0 + 0.05 * math.sin(k))
        a = dyn.advance(state, xa, u, k * dyn.dt, (k + 1) * dyn.dt, wind)
        b = dyn._advance_fixed(state, xb, u, k * dyn.dt, (k + 1) * dyn.dt, wind)  # the steps around model.rhs
        assert (a.failure, a.crashed, a.nfev, a.time_s) == (b.failure, b.crashed, b.nfev, b.time_s) == ("", False, 2, (k + 1) * dyn.dt)
        scale = np.maximum(np.abs(b.x), 1e-6 * np.abs(b.x).max())
        assert np.max(np.abs(a.x - b.x) / scale) <= 1e-12
        xa, xb = a.x, b.x
    other = dyn.start(SteadyManoeuvre(speed_m_s=220.0, altitude_m=9144.0))  # another trim: no shared stepper
    two = [state, other]
    winds = [wind, None]
    rows = advance_rows([dyn, dyn], two, x[:2], applied[:2], np.zeros(2), np.full(2, dyn.dt), winds, dyn.model.pack_winds(winds))
    for i in range(2):
        alone = dyn.advance(two[i], x[i], applied[i], 0.0, dyn.dt, winds[i])
        np.testing.assert_array_equal(rows.x[i], alone.x)
        assert (rows.failure[i], rows.nfev[i]) == (alone.failure, alone.nfev)


def test_a_wind_callable_equals_the_compiled_step(three):
    dyns, states, x, applied, _ = three
    dyn, state = dyns[0], states[0]
    field = DrydenTurbulence.mil_f_8785c(9144.0, "severe", seed=2)
    plain = lambda t, positions: field(t, positions)  # not packable: the steps around model.rhs
    assert dyn._packed_wind(plain) is None and dyn._packed_wind(field) is not None
    xa = xb = x[0]
    for k in range(20):
        u = applied[0] * (1.0 + 0.05 * math.sin(k))
        a = dyn.advance(state, xa, u, k * dyn.dt, (k + 1) * dyn.dt, field)
        b = dyn.advance(state, xb, u, k * dyn.dt, (k + 1) * dyn.dt, plain)
        assert (a.failure, a.nfev, a.time_s) == (b.failure, b.nfev, b.time_s) == ("", 2, (k + 1) * dyn.dt)
        scale = np.maximum(np.abs(a.x), 1e-6 * np.abs(a.x).max())
        assert np.max(np.abs(a.x - b.x) / scale) <= 1e-12
        xa, xb = a.x, b.x


def test_rows_about_two_trims(three):
    dyns, states, x, applied, command = three
    dyn = dyns[0]
    other = dyn.start(SteadyManoeuvre(speed_m_s=220.0, altitude_m=9144.0))
    mixed = [states[0], other, states[2]]
    winds = [None, DrydenTurbulence.mil_f_8785c(9144.0, "moderate", seed=4), None]
    k = np.array([3, 7, 5])
    one = advance_period(dyns, mixed, x, applied, command, k, winds, dyn.model.pack_winds(winds))
    u = dyn.rate_limit(applied, command)
    np.testing.assert_array_equal(one.u, u)
    for i in range(3):
        alone = dyn.advance(mixed[i], x[i], u[i], k[i] * dyn.dt, (k[i] + 1) * dyn.dt, winds[i])
        np.testing.assert_array_equal(one.outcome.x[i], alone.x)
        assert (one.outcome.time_s[i], one.outcome.failure[i], one.outcome.nfev[i]) == (alone.time_s, "", 2)
        meas = dyn.measure_batch(alone.x[None, :], np.array([alone.time_s]), [winds[i]], dyn.model.pack_winds([winds[i]]))
        np.testing.assert_array_equal(one.meas.matrix[i], meas.matrix[0])


def test_a_wind_callable_row_leaves_the_others_compiled(three):
    """One route with two paths per row: in a period whose row 1 flies a Python wind callable (which the kernels cannot
    evaluate), rows 0 and 2 still take the compiled period and equal, bit for bit, the same rows without row 1 (one
    kernel; the rows are independent); row 1 equals its own ``advance`` (the compiled stages around ``model.rhs``) with
    the rate limits and measurements of the separate calls, bit for bit."""
    dyns, states, x, applied, command = three
    dyn = dyns[0]
    field = DrydenTurbulence.mil_f_8785c(9144.0, "moderate", seed=3)
    plain = lambda t, positions: field(t, positions)
    winds = [field, plain, None]
    k = np.array([4, 4, 9])
    packed, python = periods.pack_period_winds(dyns, winds)
    assert python.tolist() == [False, True, False]
    one = advance_period(dyns, states, x, applied, command, k, winds, packed, python)
    kept = np.array([0, 2])
    alone = advance_period([dyn] * 2, [states[i] for i in kept], x[kept], applied[kept], command[kept], k[kept],
                           [winds[i] for i in kept], dyn.model.pack_winds([winds[i] for i in kept]))
    np.testing.assert_array_equal(one.outcome.x[kept], alone.outcome.x)
    np.testing.assert_array_equal(one.meas.matrix[kept], alone.meas.matrix)
    u = dyn.rate_limit(applied, command)
    np.testing.assert_array_equal(one.u, u)
    own = dyn.advance(states[1], x[1], u[1], k[1] * dyn.dt, (k[1] + 1) * dyn.dt, plain)
    np.testing.assert_array_equal(one.outcome.x[1], own.x)
    meas = dyn.measure_batch(own.x[None, :], np.array([own.time_s]), [plain])
    np.testing.assert_array_equal(one.meas.matrix[1], meas.matrix[0])
    assert one.outcome.failure.tolist() == ["", "", ""] and one.outcome.nfev.tolist() == [2, 2, 2]
    assert [s is t for s, t in zip(one.outcome.states, states)] == [True] * 3


def test_solve_ivp_rows_take_the_python_path(three):
    """DOP853, which the kernels do not run, flies each row by its own ``advance`` inside :func:`advance_period`
    (bit for bit), with the compiled rate limits and the packed winds' measurements."""
    dyns, _, x, applied, command = three
    dop = FlightDynamics(dyns[0].model, IntegratorSettings(method="DOP853"), ActuatorRates(), 0.02)
    manoeuvre = SteadyManoeuvre(speed_m_s=230.0, altitude_m=9144.0)
    states = [dop.start(manoeuvre) for _ in range(2)]
    winds = [DrydenTurbulence.mil_f_8785c(9144.0, "light", seed=5), None]
    packed, python = periods.pack_period_winds([dop] * 2, winds)
    k = np.array([0, 1])
    one = advance_period([dop] * 2, states, x[:2], applied[:2], command[:2], k, winds, packed, python)
    u = dop.rate_limit(applied[:2], command[:2])
    for i in range(2):
        own = dop.advance(states[i], x[i], u[i], k[i] * dop.dt, (k[i] + 1) * dop.dt, winds[i])
        np.testing.assert_array_equal(one.outcome.x[i], own.x)
        assert one.outcome.nfev[i] == own.nfev and one.outcome.states[i].first_step_s == own.state.first_step_s
    meas = dop.measure_batch(one.outcome.x, one.outcome.time_s, winds, packed)
    np.testing.assert_array_equal(one.meas.matrix, meas.matrix)
