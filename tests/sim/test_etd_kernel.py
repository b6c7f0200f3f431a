"""The compiled ETD2RK steps (flexsim._kernels.etd2rk_run / etd2rk_rows via ETD2RK.run / advance_rows) against the
numpy ETD2RK.step with the model's right-hand side.

Invariant: the same arithmetic (two right-hand sides and the matrix-vector products of ETD2RK.step per step), so the
compiled steps equal the Python steps to rounding: 1e-12 relative to each state entry's largest magnitude over
100 steps of 10 ms of the GTM (252 states) through a 1-cos gust with a linear elevator ramp (measured: 0.0, the
products are the same BLAS calls). Rows of advance_rows equal ETD2RK.step row by row (own controls and winds) and
FlightDynamics' semantics for the ground (linear interpolation within the step), a non-finite state (the state
before the step) and a model error (altitude outside the ISA range: the state at which rhs fails).
"""

import math

import numpy as np
import pytest

from flexsim import _kernels as _k
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.kinematics import dcm_321
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.jacobian import jacobian
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim.sim.fixed_step import ETD2RK
from flexsim.trim import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def gtm():
    model = AircraftModel(load_aircraft("gtm"), aero="unsteady")
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))
    jac = jacobian(model, point.x, point.u, controls=False)[0]
    lay = model.layout
    velocity_ned = dcm_321(*point.x[lay.euler]).T @ point.x[lay.v]
    gust = OneMinusCosineGust.encounter(3.0, 20.0, position_ned_m=point.x[lay.position], velocity_ned_m_s=velocity_ned,
                                        start_time_s=0.2)
    return model, point, jac, gust


def _close(a, b):
    scale = np.maximum(np.abs(b).max(axis=0), 1e-300)
    return float((np.abs(a - b) / scale).max())


def test_compiled_run_equals_the_numpy_steps(gtm):
    model, point, jac, gust = gtm
    h, n = 0.01, 100
    stepper = ETD2RK(jac, h)
    du_dt = np.array([0.0, 0.0, math.radians(2.0), 0.0])  # 2 deg/s of elevator from t = 0

    def u_of(t):
        return point.u + t * du_dt

    f0 = model.rhs(0.0, point.x, u_of(0.0), gust)
    run = stepper.run(model, 0.0, point.x, f0, 10.0, n, (0.0, point.u, du_dt), gust.wind_data)
    assert run.x.shape == (n + 1, point.x.size)
    x, t, k1 = point.x.copy(), 0.0, f0
    xs, fs, ts = [x], [f0], [0.0]
    for _ in range(n):
        x = stepper.step(lambda tt, xx: model.rhs(tt, xx, u_of(tt), gust), t, x, k1=k1)
        t += h
        k1 = model.rhs(t, x, u_of(t), gust)
        xs.append(x), fs.append(k1), ts.append(t)
    np.testing.assert_array_equal(run.t, ts)
    assert _close(run.x, np.array(xs)) <= 1e-12
    assert _close(run.f, np.array(fs)) <= 1e-12
    assert np.abs(run.x[:, model.layout.inflow]).max() > 0.1  # the gust was flown through


def test_compiled_run_stops_at_t_bound_and_lands(gtm):
    model, point, jac, _ = gtm
    stepper = ETD2RK(jac, 0.02)
    f0 = model.rhs(0.0, point.x, point.u)
    controls = (0.0, point.u, np.zeros(4))
    run = stepper.run(model, 0.0, point.x, f0, 0.05, 100, controls)
    assert run.t.tolist() == [0.0, 0.02, 0.04]  # 0.05 - 0.04 <= h: the short last step is the caller's
    last = ETD2RK(jac, 0.01).run(model, run.t[-1], run.x[-1], run.f[-1], 0.05, 1, controls, land=True)
    assert last.t.tolist() == [0.04, 0.05]


def test_compiled_rows_equal_the_numpy_steps_and_report_like_the_environments(gtm):
    model, point, jac, gust = gtm
    h, k = 0.005, 4
    stepper = ETD2RK(jac, h)
    z = model.layout.position.start + 2
    x = np.array([point.x] * 5)
    u = np.array([point.u] * 5)
    u[1, 1] = math.radians(-2.0)  # row 1: aileron
    winds = [None, gust, None, None, None]
    x[2, z] = -0.5  # row 2: 0.5 m above the ground, pitched 20 deg down: crosses within the period
    x[2, model.layout.euler.start + 1] = math.radians(-20.0)
    x[3, model.layout.inflow.start] = math.nan  # row 3: NaN inflow: the stage state's altitude is NaN, rhs refuses it
    x[4, z] = -1e6  # row 4: above the ISA range (rhs refuses it)
    out = stepper.advance_rows(model, x, u, np.full(5, 1.0), np.full(5, 1.0 + k * h), k, model.pack_winds(winds))
    assert out.status.tolist() == [_k.ROW_RUNNING, _k.ROW_RUNNING, _k.ROW_GROUND, _k.ROW_MODEL_ERROR, _k.ROW_MODEL_ERROR]
    for r in (0, 1):
        xr = x[r]
        for i in range(k):
            xr = stepper.step(model.rhs, 1.0 + i * h, xr, (u[r], winds[r]))
        assert _close(out.x[r][None, :], xr[None, :]) <= 1e-12
        assert out.t[r] == 1.0 + k * h and out.steps[r] == k
    xr, t = x[2], 1.0
    for i in range(1, k + 1):
        x_next = stepper.step(model.rhs, t, xr, (u[2], None))
        if x_next[z] >= 0.0 > xr[z]:
            s = xr[z] / (xr[z] - x_next[z])
            break
        xr, t = x_next, 1.0 + i * h
    assert out.steps[2] == i < k
    np.testing.assert_allclose(out.x[2], xr + s * (x_next - xr), rtol=1e-12, atol=1e-12)
    assert out.t[2] == pytest.approx(t + s * h, rel=1e-14)
    np.testing.assert_array_equal(out.x[3], x[3])
    assert out.steps[3] == 1 and out.t[3] == 1.0
    np.testing.assert_array_equal(out.x[4], x[4])
    with pytest.raises(ValueError, match="altitude"):
        model.rhs(1.0, out.x[4], u[4])


def test_compiled_rows_report_a_non_finite_state():
    model = AircraftModel(load_aircraft("gtm"), aero=None)  # no altitude range: NaN reaches the state
    assert model.altitude_range_m == (-math.inf, math.inf)
    x = model.pack(position_m=[0.0, 0.0, -1000.0], velocity=np.r_[[200.0, 0.0, 5.0], np.zeros(model.structure.dofs.n_v - 3)])
    u = np.array([40e3, 0.0, 0.0, 0.0])
    stepper = ETD2RK(jacobian(model, x, u, controls=False)[0], 0.01)
    bad = x.copy()
    bad[model.layout.v.start] = math.nan
    out = stepper.advance_rows(model, np.array([x, bad]), u, 0.0, 0.03, 3)
    assert out.status.tolist() == [_k.ROW_RUNNING, _k.ROW_NON_FINITE]
    assert out.steps.tolist() == [3, 1]
    np.testing.assert_array_equal(out.x[1], bad)


def test_invalid_rows_arguments_are_named(gtm):
    model, point, jac, _ = gtm
    stepper = ETD2RK(jac, 0.01)
    with pytest.raises(ValueError, match="x: expected shape"):
        stepper.advance_rows(model, np.zeros((2, 3)), point.u, 0.0, 0.01, 1)
    with pytest.raises(ValueError, match="n_steps = 0"):
        stepper.advance_rows(model, point.x, point.u, 0.0, 0.01, 0)
    with pytest.raises(ValueError, match="wind: expected None or a BatchWind of 1 rows"):
        stepper.advance_rows(model, point.x, point.u, 0.0, 0.01, 1, wind=[None])
