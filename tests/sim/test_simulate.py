"""simulate(): trim holding, a steady turn's circle, controls, events and bad input.

Sources and tolerances:
* (a) From a level-flight trim (GTM, unsteady N = 6, 9144 m, M 0.75) 60 s of flight: |speed drift| < 0.1 m/s
  and |altitude drift| < 1 m (the trim residual is ~1e-13, so the drift measures the
  integrator).
* (b) From a level-turn trim (R = 8000 m) the body origin flies a circle (paper eqs. 36-37,
  R = V cos(gamma) / Omega): the radius fitted to 60 s of the horizontal track is R within 0.5 %.
* (f) Events stop the run with the right status: ground contact (altitude 0 within 1e-6 m), structural
  limit (|tip deflection| = bound within 1e-6 m), gimbal lock (|theta| = 89 deg within 1e-9), non-finite
  state; user events (SimEvent) located on the dense output to 1e-6 s against a closed form.
* HoldingRadau takes exactly scipy Radau's steps (same evaluations, results to 1e-10) with fewer LU
  decompositions when the step is held at max_step.
"""

import math

import numpy as np
import pytest
from scipy.integrate import Radau

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.result import SimulationResult
from flexsim.sim.simulate import (HOLDING_RADAU_SCIPY, ControlSchedule, HoldingRadau, IntegratorSettings, SimEvent, radau_class,
                                  simulate, state_scales)
from flexsim.trimming import SteadyManoeuvre, trim
from flexsim.sim.run_settings import EventSettings, OutputSettings

H, MACH = 9144.0, 0.75


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


@pytest.fixture(scope="module")
def unsteady(gtm):
    return AircraftModel(gtm, aero="unsteady")


@pytest.fixture(scope="module")
def quasi_steady(gtm):
    return AircraftModel(gtm, aero="quasi-steady")


@pytest.fixture(scope="module")
def vacuum(gtm):
    return AircraftModel(gtm, aero=None)


def test_level_trim_held_for_60_s(unsteady):
    point = trim(unsteady, SteadyManoeuvre.level(H, mach=MACH))
    result = simulate(unsteady, point, 60.0, output=OutputSettings(rate_hz=10.0))
    assert isinstance(result, SimulationResult) and result.status == "completed" and result.t[-1] == 60.0
    speed_drift = np.abs(result.airspeed_m_s - point.manoeuvre.speed_m_s).max()
    altitude_drift = np.abs(result.altitude_m - H).max()
    assert speed_drift < 0.1 and altitude_drift < 1.0, (speed_drift, altitude_drift)
    assert result.method == "ETD2RK" and result.reason.startswith("reached t_end")  # the default with aerodynamics


def test_level_turn_flies_a_circle_of_the_trim_radius(unsteady):
    radius = 8000.0
    point = trim(unsteady, SteadyManoeuvre.turn(H, radius, mach=MACH))
    result = simulate(unsteady, point, 60.0, output=OutputSettings(rate_hz=5.0))
    north, east = result.position_ned_m[:, 0], result.position_ned_m[:, 1]
    # algebraic (Kasa) circle fit: x^2 + y^2 + D x + E y + F = 0
    a = np.column_stack([north, east, np.ones_like(north)])
    d, e, f = np.linalg.lstsq(a, -(north**2 + east**2), rcond=None)[0]
    fitted = math.sqrt(d * d / 4 + e * e / 4 - f)
    assert fitted == pytest.approx(radius, rel=5e-3)
    assert np.abs(result.altitude_m - H).max() < 1.0
    # heading advances at Omega = V / R (quarter of a turn in ~55 s)
    assert result.euler_rad[-1, 2] == pytest.approx(point.manoeuvre.turn_rate(0.0) * 60.0, rel=5e-3)


def test_schedule_is_interpolated_and_held(quasi_steady):
    point = trim(quasi_steady, SteadyManoeuvre.level(H, mach=MACH))
    u0 = point.u
    sched = ControlSchedule([0.0, 0.2, 0.3], [u0, u0, u0 + [0, 0, math.radians(1.0), 0]])
    np.testing.assert_allclose(sched(0.25), u0 + [0, 0, math.radians(0.5), 0])
    np.testing.assert_allclose(sched(5.0), sched(0.3))
    result = simulate(quasi_steady, point, 0.4, controls=sched, output=OutputSettings(rate_hz=50.0))
    np.testing.assert_allclose(result.u, sched.at(result.t), atol=1e-15)
    assert result.signal("elevator_rad")[-1] == pytest.approx(u0[2] + math.radians(1.0))
    assert result.signal("theta_rad")[-1] != pytest.approx(result.signal("theta_rad")[0], abs=1e-8)  # it responds


def test_constant_segments_skip_the_interpolation(quasi_steady, monkeypatch):
    """Segments where the schedule is constant hand the rhs the held vector: interpolated only at the
    segment ends, not per right-hand side, with results identical to the interpolated ones."""
    point = trim(quasi_steady, SteadyManoeuvre.level(H, mach=MACH))
    u0 = point.u
    sched = ControlSchedule([0.0, 0.2, 0.3], [u0, u0, u0 + [0, 0, math.radians(1.0), 0]])
    calls = []
    original = ControlSchedule.__call__
    monkeypatch.setattr(ControlSchedule, "__call__", lambda self, t: calls.append(t) or original(self, t))
    result = simulate(quasi_steady, point, 0.4, controls=sched, output=OutputSettings(rate_hz=50.0),
                      integrator=IntegratorSettings(method="Radau"))  # rhs from Python
    in_ramp = [t for t in calls if 0.2 < t < 0.3]
    outside = [t for t in calls if not 0.2 <= t <= 0.3]
    assert result.nfev > 50 and in_ramp  # the ramp segment interpolates per rhs
    assert len(outside) <= 4  # the constant segments [0, 0.2] and [0.3, 0.4]: their ends only
    np.testing.assert_allclose(result.u, sched.at(result.t), atol=0.0)


def test_etd2rk_option_is_second_order_near_trim(quasi_steady):
    """method="ETD2RK" (fixed steps of max_step, the initial Jacobian as linear part) after an elevator ramp
    of 0.5 deg: pitch within 1e-7 deg of DOP853 at rtol 1e-10 with 10 ms steps (measured 2.5e-8 over 1 s),
    and the error falls as h^2 (ratio 4 +- 0.6 from 10 ms to 5 ms; measured 3.9)."""
    point = trim(quasi_steady, SteadyManoeuvre.level(H, mach=MACH))
    u0 = point.u
    sched = ControlSchedule([0.0, 0.1, 0.2], [u0, u0, u0 + [0, 0, math.radians(0.5), 0]])
    ref = simulate(quasi_steady, point, 0.6, controls=sched, integrator=IntegratorSettings(method="DOP853", rtol=1e-10))
    errs = []
    for h in (0.01, 0.005):
        r = simulate(quasi_steady, point, 0.6, controls=sched,
                     integrator=IntegratorSettings(method="ETD2RK", max_step_s=h))
        assert r.completed and r.nfev == 3 + 2 * round(0.6 / h)  # one start per schedule segment, 2 per step
        errs.append(np.degrees(np.abs(r.signal("theta_rad") - ref.signal("theta_rad")).max()))
    assert errs[0] < 1e-7
    assert 3.4 < errs[0] / errs[1] < 4.6
    with pytest.raises(ValueError, match="max_step_s = inf: ETD2RK"):
        simulate(quasi_steady, point, 0.1, integrator=IntegratorSettings(method="ETD2RK", max_step_s=math.inf))


def test_feedback_controller_is_sampled_every_period_and_held(vacuum):
    x0 = vacuum.pack(position_m=[0, 0, -H], velocity=np.r_[200.0, 0.0, 0.0, np.zeros(vacuum.structure.dofs.n_v - 3)])
    calls = []

    def controller(t, x):
        calls.append(t)
        return np.array([1e4 * (1 + len(calls)), 0.0, 0.0, 0.0])

    result = simulate(vacuum, x0, 0.1, controls=controller, control_rate_hz=40.0,
                      output=OutputSettings(rate_hz=200.0))
    np.testing.assert_allclose(calls, [0.0, 0.025, 0.05, 0.075], atol=1e-12)
    held = 1e4 * (2 + np.minimum(np.floor(result.t / 0.025 + 1e-9), 3))  # u(t) = controller(t_k) on [t_k, t_k+1)
    np.testing.assert_allclose(result.u[:, 0], held)
    assert result.t.size == 21
    assert result.method == "DOP853"  # the default without aerodynamics


def test_ground_contact_stops_the_run(quasi_steady):
    point = trim(quasi_steady, SteadyManoeuvre.level(H, mach=MACH))
    x0 = point.x.copy()
    lay = quasi_steady.layout
    x0[lay.position.start + 2] = -30.0  # 30 m above the ground
    x0[lay.v.start + 2] += 40.0  # and sinking
    # only the ground event: at 227 m/s in sea-level air the wings also reach the structural limit. Far from the
    # linearisation (a 9144 m trim at 30 m, structural rates ~100 m/s): the default's 20 ms steps leave the model's
    # range near t = 1.4 s and the chunk is repeated with 10 ms steps (compiled_run.HALVINGS); Radau at rtol 1e-6:
    # ground contact at 1.463 s, the default at 1.57 s (10 ms throughout: 1.467 s)
    result = simulate(quasi_steady, x0, 5.0, controls=point.u, events=EventSettings(["ground"]))
    assert result.status == "ground_contact" and "ground contact" in result.reason
    assert result.altitude_m[-1] == pytest.approx(0.0, abs=1e-6)
    assert 0.3 < result.t[-1] < 2.0
    assert result.events == ((result.t[-1], "ground"),)


def test_gimbal_lock_stops_the_run(vacuum):
    x0 = vacuum.pack(position_m=[0, 0, -H], euler_rad=[0, math.radians(88.0), 0],
                     velocity=np.r_[0.0, 0.0, 0.0, 0.0, 0.5, 0.0, np.zeros(vacuum.structure.dofs.n_v - 6)])
    result = simulate(vacuum, x0, 1.0, controls=np.zeros(4))
    assert result.status == "gimbal_lock" and "gimbal lock" in result.reason
    assert abs(result.euler_rad[-1, 1]) == pytest.approx(math.radians(89.0), abs=1e-9)


def test_structural_limit_stops_a_fluttering_wing():
    from flexsim.sim.manoeuvres import build_manoeuvre

    setup = build_manoeuvre("flutter-onset", aero="unsteady")
    result = setup.simulate(output=OutputSettings(rate_hz=50.0))
    assert result.status == "structural_limit" and "right_wing tip deflection" in result.reason
    length = setup.model.aircraft.component("right_wing").length_m
    assert abs(result.tip_deflection_m()[-1]) == pytest.approx(0.25 * length, abs=1e-6)
    assert 1.0 < result.t[-1] < 10.0
    tip = np.abs(result.tip_deflection_m())
    first, last = tip[: tip.size // 3].max(), tip[-tip.size // 3:].max()
    assert last > 20 * first  # the oscillation grew


def test_non_finite_state_stops_the_run(vacuum):
    class Broken(AircraftModel):
        def rhs(self, t, x, u, wind=None):
            dx = super().rhs(t, x, u, wind)
            return dx * np.nan if t > 0.05 else dx

    model = Broken(vacuum.aircraft, aero=None)
    x0 = model.pack(position_m=[0, 0, -H], velocity=np.r_[200.0, np.zeros(model.structure.dofs.n_v - 1)])
    result = simulate(model, x0, 1.0, controls=np.zeros(4))
    assert result.status == "non_finite" and "non-finite" in result.reason
    assert np.all(np.isfinite(result.x)) and result.t[-1] < 0.1


def test_user_events_are_located_on_the_dense_output(vacuum):
    # free fall from rest in vacuum: the body origin has dropped g t^2 / 2
    x0 = vacuum.pack(position_m=[0, 0, -H])
    g = vacuum.terms.gravity_m_s2
    drop = SimEvent("dropped 1 m", lambda t, x: x[2] - (-H + 1.0), direction=1, terminal=False)
    stop = SimEvent("dropped 5 m", lambda t, x: (-H + 5.0) - x[2])
    result = simulate(vacuum, x0, 3.0, controls=np.zeros(4), events=EventSettings(["ground", drop, stop]))
    assert result.status == "event" and "dropped 5 m" in result.reason
    (t1, n1), (t2, n2) = result.events
    assert (n1, n2) == ("dropped 1 m", "dropped 5 m")
    assert t1 == pytest.approx(math.sqrt(2 / g), abs=1e-6)
    assert t2 == pytest.approx(math.sqrt(10 / g), abs=1e-6)


def test_holding_radau_takes_scipys_steps_with_fewer_factorisations():
    rng = np.random.default_rng(2)
    n = 40
    q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    lam = np.concatenate([-rng.uniform(100, 2000, n // 2), -rng.uniform(0.1, 1.0, n // 2)])
    a = q @ np.diag(lam) @ q.T

    def fun(t, y):
        return a @ y + np.sin(3 * t)

    runs = {}
    for cls in (Radau, HoldingRadau):
        solver = cls(fun, 0.0, np.ones(n), 5.0, max_step=0.05, rtol=1e-4, atol=1e-7, jac=a)
        while solver.status == "running":
            solver.step()
        runs[cls] = solver
    plain, held = runs[Radau], runs[HoldingRadau]
    assert held.nfev == plain.nfev
    np.testing.assert_allclose(held.y, plain.y, rtol=1e-10, atol=1e-12)
    assert held.nlu < plain.nlu / 3


def test_holding_radau_only_with_the_scipy_versions_it_was_tested_with():
    import scipy

    lo, hi = HOLDING_RADAU_SCIPY
    assert radau_class() is HoldingRadau  # the installed scipy is one it was tested with (test above)
    assert lo <= tuple(int(p) for p in scipy.__version__.split(".")[:2]) <= hi
    assert radau_class(f"{hi[0]}.{hi[1] + 1}.0") is Radau and radau_class(f"{lo[0]}.{lo[1] - 1}.3") is Radau
    assert radau_class(f"{lo[0]}.{lo[1]}.0rc1") is HoldingRadau


def test_bad_arguments_are_rejected_with_clear_messages(quasi_steady, tmp_path):
    point = trim(quasi_steady, SteadyManoeuvre.level(H, mach=MACH))
    with pytest.raises(ValueError, match=r"t_end_s = -1.0: must be a finite number > 0"):
        simulate(quasi_steady, point, -1.0)
    with pytest.raises(ValueError, match=r"initial state: expected shape \(60,\)"):
        simulate(quasi_steady, np.zeros(5), 1.0, controls=np.zeros(4))
    with pytest.raises(ValueError, match="give the controls"):
        simulate(quasi_steady, point.x, 1.0)
    with pytest.raises(ValueError, match=r"method = 'Euler': must be 'auto' or one of"):
        simulate(quasi_steady, point, 1.0, integrator=IntegratorSettings(method="Euler"))
    with pytest.raises(ValueError, match=r"elevator delta_e \[rad\] = 0.7 at t = 0.5 s is outside the aircraft's limits"):
        simulate(quasi_steady, point, 1.0,
                 controls=ControlSchedule([0.0, 0.5], [point.u, point.u + [0, 0, 0.7 - point.u[2], 0]]))
    with pytest.raises(ValueError, match=r"control_rate_hz = 0.0: must be a finite number > 0 \[Hz\]"):
        simulate(quasi_steady, point, 1.0, controls=lambda t, x: point.u, control_rate_hz=0.0)
    with pytest.raises(ValueError, match="initial state already stops the run: structural limit"):
        simulate(quasi_steady, point, 1.0, events=EventSettings(wing_tip_deflection_m=0.5))
    with pytest.raises(ValueError, match=r"names: unknown event 'stall'"):
        simulate(quasi_steady, point, 1.0, events=EventSettings(["stall"]))
    with pytest.raises(ValueError, match=r"log_path = '.*run.txt': must end in .mcap"):
        simulate(quasi_steady, point, 1.0, output=OutputSettings(log_path=tmp_path / "run.txt"))
    with pytest.raises(FileNotFoundError, match="directory .*nowhere.* does not exist"):
        simulate(quasi_steady, point, 1.0, output=OutputSettings(log_path=tmp_path / "nowhere" / "run.mcap"))
    with pytest.raises(ValueError, match="is a directory"):
        simulate(quasi_steady, point, 1.0, output=OutputSettings(log_path=tmp_path))


def test_integration_settings_are_frozen_validated_and_resolved(quasi_steady):
    """The numerical settings of a run are one frozen, validated object (``_integrate`` took 18 arguments), the class
    the environments' control periods take too."""
    n = quasi_steady.layout.n_states
    s = IntegratorSettings().resolve(quasi_steady)
    assert (s.method, s.rtol, s.max_step_s, s.implicit, s.needs_jacobian) == ("ETD2RK", 1e-6, 0.02, False, True)
    assert IntegratorSettings().resolve(quasi_steady, lambda t, p: 0.0 * p).method == "Radau"  # a Python wind
    s = IntegratorSettings(method="Radau").resolve(quasi_steady)
    assert (s.method, s.rtol, s.max_step_s, s.implicit, s.needs_jacobian) == ("Radau", 1e-3, 0.05, True, True)
    np.testing.assert_array_equal(s.atol, 1e-3 * state_scales(quasi_steady))
    with pytest.raises(ValueError, match="read-only"):
        s.atol[0] = 1.0
    with pytest.raises(AttributeError):
        s.rtol = 1e-6  # type: ignore[misc]
    assert s == IntegratorSettings(method="Radau").resolve(quasi_steady) and hash(s) == hash(IntegratorSettings("Radau").resolve(quasi_steady))
    explicit = IntegratorSettings(method="DOP853", atol=1e-9).resolve(quasi_steady)
    assert explicit.rtol == 1e-6 and not explicit.needs_jacobian and explicit.atol.shape == (n,) and np.all(explicit.atol == 1e-9)
    assert IntegratorSettings(method="ETD2RK").resolve(quasi_steady).needs_jacobian
    assert IntegratorSettings(rtol=1e-4).resolve(quasi_steady, rtol=1e-3).rtol == 1e-4  # a caller's default only fills None
    for kwargs, match in [({"method": "Euler"}, r"method = 'Euler': must be 'auto' or one of"),
                          ({"rtol": 0.5}, r"rtol = 0.5: must be a number in \[1e-13, 0.1\]"),
                          ({"atol": -1.0}, r"atol = -1.0: must be positive and finite"),
                          ({"max_step_s": 0.0}, r"max_step_s = 0.0: must be a number > 0"),
                          ({"method": "ETD2RK", "max_step_s": math.inf}, r"max_step_s = inf: ETD2RK takes fixed steps")]:
        with pytest.raises(ValueError, match=match):
            IntegratorSettings(**kwargs)
    with pytest.raises(ValueError, match=r"atol = .*must be positive and finite \(a number or 60 numbers\)"):
        IntegratorSettings(atol=np.ones(3)).resolve(quasi_steady)
    with pytest.raises(ValueError, match=r"integrator = 'Radau': must be a IntegratorSettings"):  # one name per setting
        simulate(quasi_steady, np.zeros(n), 1.0, controls=np.zeros(4), integrator="Radau")
    with pytest.raises(TypeError, match="max_step"):  # no second name of the step beside IntegratorSettings.max_step_s
        simulate(quasi_steady, np.zeros(n), 1.0, controls=np.zeros(4), max_step=0.01)
    with pytest.raises(ValueError, match=r"t_end_s = nan: must be a finite number > 0"):
        simulate(quasi_steady, np.zeros(n), math.nan)


@pytest.mark.parametrize("times, values, match", [
    ([0.0, 1.0, 0.5], np.zeros((3, 4)), r"times_s\[2\] = 0.5: must be > times_s\[1\] = 1 \(times must increase strictly\)"),
    ([0.0, 1.0], np.zeros((2, 3)), r"values: expected shape \(k, 4\) = \(2, 4\) .* got shape \(2, 3\)"),
    ([0.0, 1.0], [[0, 0, 0, 0], [0, math.nan, 0, 0]], r"values\[1, 1\] \(aileron delta_a \[rad\] at t = 1.0 s\) = nan: must be finite"),
    ([0.0, math.inf], np.zeros((2, 4)), r"times_s\[1\] = inf: times must be finite"),
    ([], np.zeros((0, 4)), "expected a 1-D array of k >= 1 times"),
])
def test_control_schedule_rejects_bad_tables(times, values, match):
    with pytest.raises(ValueError, match=match):
        ControlSchedule(times, values)


def test_default_log_directory_is_created(quasi_steady, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    point = trim(quasi_steady, SteadyManoeuvre.level(H, mach=MACH))
    result = simulate(quasi_steady, point, 0.05, output=OutputSettings(log_path=True))
    assert result.log_path.parent.name == "logs" and (tmp_path / result.log_path).is_file()
    assert state_scales(quasi_steady).shape == (quasi_steady.layout.n_states,)


def test_ragged_or_non_numeric_controls_are_refused_naming_them(gtm, quasi_steady):
    """Ragged, non-numeric or NaN controls, constant or scheduled, and a definition where a model is expected: each
    refused naming the argument (before: numpy's "inhomogeneous shape" message, ``controls`` not named)."""
    from flexsim.sim.controls import ControlSchedule
    from flexsim.trimming import SteadyManoeuvre, trim

    point = trim(quasi_steady, SteadyManoeuvre.level(9144.0, mach=0.75))
    with pytest.raises(ValueError, match=r"controls = .*must be an array of numbers \[thrust N, aileron"):
        simulate(quasi_steady, point, 0.1, controls=[1e4, [0.0, 0.1], 0.0, 0.0])
    with pytest.raises(ValueError, match=r"controls = .*must have shape \(4,\)"):
        simulate(quasi_steady, point, 0.1, controls=[1e4, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"controls\[2\] = nan: must be finite"):
        simulate(quasi_steady, point, 0.1, controls=[1e4, 0.0, float("nan"), 0.0])
    with pytest.raises(ValueError, match=r"ControlSchedule.values = .*must be an array of numbers"):
        ControlSchedule([0.0, 1.0], [[1e4, 0.0, 0.0, 0.0], [1e4, 0.0, 0.0]])
    with pytest.raises(TypeError, match=r"model = .*must be an AircraftModel.*build the model with flexsim.AircraftModel"):
        simulate(gtm, point, 0.1)
