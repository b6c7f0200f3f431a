"""The compiled ETD2RK step (flexsim.sim._step_kernels.etd2rk_rows via ETD2RK.run / advance_rows, and its stages via
ETD2RK.step) against the numpy transcription of the method (tests/sim/etd2rk_reference.py) with the model's right-hand side.

Invariant: the same arithmetic (two right-hand sides and the matrix-vector products of ETD2RK.step per step), so the
compiled steps equal the Python steps to rounding: 1e-11 relative to the largest magnitude of each group of the state
layout (positions, Euler angles, bending, torsion, velocities, rates, inflow) over 100 steps of 10 ms of the GTM
(252 states) through a 1-cos gust with a linear elevator ramp (measured: states 1.4e-12, derivatives 4.4e-12, in
the torsion rates; the compiled products sum in another (vectorised) order than BLAS, and the stiff inflow and
structural terms amplify that rounding; 0.0 while both called BLAS. Per entry, the lateral states of this symmetric
case are rounding noise, ~1e-11 m, whose digits depend on that order). A run with the dense output takes the same steps bit for bit and its
mean second derivatives equal step_accelerations' to 1e-12 of their largest magnitude (measured 3e-15). Rows of advance_rows
(the products of the run) equal the reference step row by row (own controls and winds; 1e-12, absolute below 1 SI unit) and
FlightDynamics' semantics for the ground (linear interpolation within the step), a non-finite state (the state
before the step) and a model error (altitude outside the ISA range: the state at which rhs fails).

simulate(method="ETD2RK") by the compiled steps equals the same run by ETD2RKSolver from Python (forced by a wind
callable that is not a disturbance field) to 1e-9 relative to each state group's largest magnitude — samples, events,
status — with a gust, a control schedule, a feedback controller and a terminal event; the difference is the
rounding of the control interpolation (u_a + (t - a) du/dt against np.interp), amplified over the run (measured
<= 3e-10 over 3 s of aileron roll, 1e-17 with constant controls). A pull-up that loses more than
RELINEARISE_DRIFT of its speed is re-linearised (njev > 1) and stays within 0.1 % of the speed of Radau at rtol 1e-6.
"""

import math

import numpy as np
import pytest

from flexsim.sim import _step_kernels as _sk
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.kinematics import dcm_321
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.jacobian import jacobian
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim.sim import ControlSchedule, SimEvent
from flexsim.sim.fixed_step import ETD2RK, step_accelerations
from flexsim.sim.run_settings import EventSettings, OutputSettings
from flexsim.sim.simulate import RELINEARISE_DRIFT, IntegratorSettings, simulate
from flexsim.trimming import SteadyManoeuvre, trim
from tests.sim.etd2rk_reference import reference_step


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


def _close(a, b, floor=1e-300):
    """Largest |a - b| relative to each entry's largest |b|, floored at ``floor`` (SI units)."""
    scale = np.maximum(np.abs(b).max(axis=0), floor)
    return float((np.abs(a - b) / scale).max())


def _close_groups(a, b, layout):
    """Largest |a - b| relative to the largest |b| of each group of the state layout (columns)."""
    worst = 0.0
    for sl in (layout.position, layout.euler, layout.q, layout.xi, layout.v, layout.omega, layout.s, layout.eta,
               layout.inflow):
        if sl.stop > sl.start:
            worst = max(worst, float(np.abs(a[:, sl] - b[:, sl]).max() / max(np.abs(b[:, sl]).max(), 1e-300)))
    return worst


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
        x = reference_step(stepper, lambda tt, xx: model.rhs(tt, xx, u_of(tt), gust), t, x, k1=k1)
        t += h
        k1 = model.rhs(t, x, u_of(t), gust)
        xs.append(x), fs.append(k1), ts.append(t)
    np.testing.assert_array_equal(run.t, ts)
    assert _close_groups(run.x, np.array(xs), model.layout) <= 1e-11
    assert _close_groups(run.f, np.array(fs), model.layout) <= 1e-11
    assert np.abs(run.x[:, model.layout.inflow]).max() > 0.1  # the gust was flown through
    dense = stepper.run(model, 0.0, point.x, f0, 10.0, n, (0.0, point.u, du_dt), gust.wind_data, dense=True)
    np.testing.assert_array_equal(dense.x, run.x)
    np.testing.assert_array_equal(dense.f, run.f)
    mean, _ = step_accelerations(h, np.diff(run.x, axis=0), run.f[:-1], run.f[1:], jac, difference=False)
    assert dense.mean.shape == (n, point.x.size)
    assert np.abs(dense.mean - mean).max() <= 1e-12 * np.abs(mean).max()


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
    assert out.status.tolist() == [_sk.ROW_RUNNING, _sk.ROW_RUNNING, _sk.ROW_GROUND, _sk.ROW_MODEL_ERROR, _sk.ROW_MODEL_ERROR]
    for r in (0, 1):
        xr = x[r]
        for i in range(k):
            xr = reference_step(stepper, model.rhs, 1.0 + i * h, xr, (u[r], winds[r]))
        # the run's products (another summation order than numpy's): rounding only, 1e-12 relative above 1 SI unit and
        # absolute below (at the trim most entries are rounding noise of ~1e-16)
        assert _close(out.x[r][None, :], xr[None, :], floor=1.0) <= 1e-12
        assert out.t[r] == 1.0 + k * h and out.steps[r] == k
    xr, t = x[2], 1.0
    for i in range(1, k + 1):
        x_next = reference_step(stepper, model.rhs, t, xr, (u[2], None))
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


def test_rows_as_matrix_products_equal_the_rows_one_by_one(gtm):
    """etd2rk_rows with over_rows (products as GEMMs over the rows: the batched environments) gives the status, steps
    and times of the products row by row exactly and its states to rounding of the products (1e-12 of each
    column's largest entry), for normal rows, a gust, a ground crossing and two model errors."""
    model, point, jac, gust = gtm
    h, k = 0.005, 4
    stepper = ETD2RK(jac, h)
    z = model.layout.position.start + 2
    x = np.array([point.x] * 6)
    u = np.array([point.u] * 6)
    u[1, 1] = math.radians(-2.0)
    x[2, z] = -0.5  # crosses the ground within the period
    x[2, model.layout.euler.start + 1] = math.radians(-20.0)
    x[3, model.layout.inflow.start] = math.nan  # model error in the second step's stage
    x[4, z] = -1e6  # model error at the start
    x[5, model.layout.omega.start] = 0.05
    winds = model.pack_winds([None, gust, None, None, gust, None])
    outs = []
    for over_rows in (False, True):
        res = stepper.advance_rows(model, x, u, np.full(6, 1.0), np.full(6, 1.0 + k * h), k, winds, over_rows=over_rows)
        outs.append((res.x, res.t, res.status, res.steps))
    (xa, ta, sa, na), (xb, tb, sb, nb) = outs
    assert sa.tolist() == sb.tolist() == [_sk.ROW_RUNNING] * 2 + [_sk.ROW_GROUND] + [_sk.ROW_MODEL_ERROR] * 2 + [_sk.ROW_RUNNING]
    assert na.tolist() == nb.tolist()
    np.testing.assert_array_equal(ta[sa != _sk.ROW_GROUND], tb[sb != _sk.ROW_GROUND])
    assert tb[2] == pytest.approx(ta[2], rel=1e-12)
    np.testing.assert_array_equal(xb[3:5], x[3:5])
    keep = [0, 1, 2, 4, 5]  # row 3 holds its NaN
    assert _close(xb[keep], xa[keep]) <= 1e-12


def test_compiled_rows_report_a_non_finite_state():
    model = AircraftModel(load_aircraft("gtm"), aero=None)  # no altitude range: NaN reaches the state
    assert model.altitude_range_m == (-math.inf, math.inf)
    x = model.pack(position_m=[0.0, 0.0, -1000.0], velocity=np.r_[[200.0, 0.0, 5.0], np.zeros(model.structure.dofs.n_v - 3)])
    u = np.array([40e3, 0.0, 0.0, 0.0])
    stepper = ETD2RK(jacobian(model, x, u, controls=False)[0], 0.01)
    bad = x.copy()
    bad[model.layout.v.start] = math.nan
    out = stepper.advance_rows(model, np.array([x, bad]), u, 0.0, 0.03, 3)
    assert out.status.tolist() == [_sk.ROW_RUNNING, _sk.ROW_NON_FINITE]
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


def _python_wind(wind):
    """The same wind as a plain callable: simulate then steps ETD2RK from Python (ETD2RKSolver)."""
    return None if wind is None else (lambda t, p: wind(t, p))


def _same_run(a, b, rel=1e-9):
    assert (a.status, a.reason, [name for _, name in a.events]) == (b.status, b.reason, [name for _, name in b.events])
    np.testing.assert_allclose([t for t, _ in a.events], [t for t, _ in b.events], rtol=1e-12, atol=0.0)  # located on rounding-different dense outputs
    np.testing.assert_allclose(a.t, b.t, rtol=1e-12, atol=0.0)  # the last sample: at the event
    np.testing.assert_array_equal(a.u, b.u)
    # relative to each group of the layout: entries that stay within ~1e-10 of zero (antisymmetric states in symmetric
    # flight) carry rounding only, whose digits depend on the order of the sums (the compiled products against BLAS)
    assert _close_groups(a.x, b.x, a.model.layout) <= rel
    assert a.nfev == b.nfev if a.completed else a.nfev >= b.nfev  # a stop: the compiled chunk went on past it


def test_simulate_compiled_equals_the_python_steps(gtm):
    model, point, _, gust = gtm
    u0 = point.u
    sched = ControlSchedule([0.0, 0.3, 0.4, 0.7, 0.8], [u0, u0, u0 + [0, math.radians(-2), math.radians(1), 0],
                                                         u0 + [0, math.radians(-2), math.radians(1), 0], u0])
    up = SimEvent("climbing", lambda t, x: x[model.layout.v.start + 2], direction=0, terminal=False)
    etd = IntegratorSettings(method="ETD2RK")
    for kwargs in ({"wind": gust, "controls": sched, "events": EventSettings(("ground", up)), "integrator": etd},
                   {"controls": lambda t, x: u0 + [0, 0, 0.002 * x[model.layout.euler.start], 0], "control_rate_hz": 20.0,
                    "integrator": etd},
                   {"wind": gust, "integrator": IntegratorSettings(method="ETD2RK", max_step_s=0.02),
                    "output": OutputSettings(rate_hz=None, log_rate_hz=20.0)}):
        fast = simulate(model, point, 1.0, **kwargs)
        slow = simulate(model, point, 1.0, **{**kwargs, "wind": _python_wind(kwargs.get("wind"))})
        _same_run(fast, slow)
    assert fast.t.size == 50 + 1  # every step end and t = 0
    stop = SimEvent("pitch", lambda t, x: 0.01 - abs(x[model.layout.omega.start + 1]), terminal=True)
    fast = simulate(model, point, 1.0, integrator=IntegratorSettings(method="ETD2RK"), wind=gust,
                    events=EventSettings(("ground", stop)))
    slow = simulate(model, point, 1.0, integrator=IntegratorSettings(method="ETD2RK"), wind=_python_wind(gust),
                    events=EventSettings(("ground", stop)))
    _same_run(fast, slow)
    assert fast.status == "event" and 0.0 < fast.t[-1] < 1.0


def test_simulate_compiled_relinearises_when_the_speed_drifts():
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))
    u1 = point.u + [0.0, 0.0, math.radians(-6.0), 0.0]
    sched = ControlSchedule([0.0, 0.5], [point.u, u1])  # a sustained pull-up: 227 -> ~150 m/s in 20 s
    fast = simulate(model, point, 20.0, controls=sched, output=OutputSettings(rate_hz=2.0))
    ref = simulate(model, point, 20.0, controls=sched, output=OutputSettings(rate_hz=2.0),
                   integrator=IntegratorSettings(method="Radau", rtol=1e-6))
    assert fast.method == "ETD2RK" and fast.completed
    assert fast.airspeed_m_s[-1] < (1.0 - RELINEARISE_DRIFT) * fast.airspeed_m_s[0] and fast.njev >= 2
    np.testing.assert_allclose(fast.airspeed_m_s, ref.airspeed_m_s, rtol=1e-3)


def test_long_chunks_equal_chunks_of_the_check_interval(monkeypatch):
    """Calls of COMPILED_CHUNK_S (2 s) cut at the first CHECK_INTERVAL_S (0.5 s) boundary where the flight condition
    drifted, and keep the sub-chunks before a failed one, so they take the same steps, re-linearise and halve at
    the same times as calls of CHECK_INTERVAL_S (the chunks before 2026-12-02): bit for bit equal samples, on a
    pull-up that re-linearises and on a descent far from the linearisation whose steps leave the model's range and
    are halved (the cases of test_simulate_compiled_relinearises_when_the_speed_drifts and
    tests/sim/test_simulate.py::test_ground_contact_stops_the_run)."""
    from flexsim.sim import compiled_run

    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))
    sched = ControlSchedule([0.0, 0.5], [point.u, point.u + [0.0, 0.0, math.radians(-6.0), 0.0]])
    x0 = point.x.copy()
    x0[model.layout.position.start + 2] = -30.0
    x0[model.layout.v.start + 2] += 40.0
    runs = [dict(initial=point, t_end_s=20.0, controls=sched, output=OutputSettings(rate_hz=2.0)),
            dict(initial=x0, t_end_s=5.0, controls=point.u, events=EventSettings(("ground",)))]
    assert compiled_run.COMPILED_CHUNK_S > compiled_run.CHECK_INTERVAL_S
    long = [simulate(model, **kw) for kw in runs]
    monkeypatch.setattr(compiled_run, "COMPILED_CHUNK_S", compiled_run.CHECK_INTERVAL_S)
    short = [simulate(model, **kw) for kw in runs]
    assert long[0].njev >= 2 and long[1].status == "ground_contact"
    for a, b in zip(long, short):
        assert (a.status, a.reason, a.events, a.njev) == (b.status, b.reason, b.events, b.njev)
        np.testing.assert_array_equal(a.t, b.t)
        np.testing.assert_array_equal(a.x, b.x)
