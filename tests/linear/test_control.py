"""The linear model for control (flexsim.linear.control): python-control StateSpace, file, and agreement with the
eigen-analysis and with the nonlinear simulation.

* Poles: the StateSpace's poles are the eigenvalues of the eigen-analysis (flexsim.linear.stability.spectrum) of the
  same trim, quasi-steady and finite-state, to 1e-9 of |lambda| (one linearisation: they agree to round-off).
* Gust input: in a uniform wind the aerodynamic loads depend on the velocity relative to the air only (Galilean
  invariance), so with the loads that see the wind (the strips; the parasite drag and the slender-body moments
  neglect a gust's change by the model's documented assumptions, docs/options.md, and the tail downwash scales with
  the inertial speed, so those options are off here) the gust column of B equals A's body-velocity columns times
  C e_z (an up-gust w_g changes the relative velocity by w_g C e_z), to the central differences' error (measured
  2.4e-8 of the largest entry; asserted 1e-6).
* Steps: the linear response to du equals the nonlinear simulation's (DOP853, rtol 1e-10) up to the linearisation
  error, which is second order in du. Asserted: for elevator steps of 1e-3 and 2e-3 rad the error of each signal is
  below 1 % of its peak at 1e-3 rad (measured at most 0.46 %, the forward speed) and grows by a factor in [3.5, 4.5]
  when the step doubles (measured 3.98 to 4.00): the second-order scaling shows that the difference is the model's
  nonlinearity, not integration or differencing error (which would scale with du, a factor 2). The same for uniform
  up-gusts of 0.5 and 1 m/s given to the nonlinear model as its wind (below 2 %, measured at most 1.41 %; factors
  3.94 to 4.01). The flight is
  at 12 km, in the isothermal stratosphere (speed of sound constant), with the aerodynamics' density fixed at the trim
  altitude's: the linear model drops the altitude and freezes the density (flexsim.linear.linearize), so the
  nonlinear model is given the same density and the comparison measures the nonlinearity alone.
"""

import dataclasses
import math
import sys

import numpy as np
import pytest

control = pytest.importorskip("control")

from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.atmosphere import isa_density  # noqa: E402
from flexsim.kinematics import dcm_321  # noqa: E402
from flexsim.linear.control import (  # noqa: E402
    FILE_FORMAT, GUST_INPUT, INPUT_NAMES, LinearSystem, MissingDependencyError, linear_system, state_space)
from flexsim.linear.stability import spectrum  # noqa: E402
from flexsim.model.aircraft_model import AircraftModel  # noqa: E402
from flexsim.model.coupling import AeroOptions  # noqa: E402
from flexsim.model.sensors import structural_sensors  # noqa: E402
from flexsim.sim.simulate import IntegratorSettings, simulate  # noqa: E402
from flexsim.trimming import SteadyManoeuvre, trim  # noqa: E402
from flexsim.sim.run_settings import EventSettings, OutputSettings  # noqa: E402
import flexsim as fs  # noqa: E402

POLE_RTOL = 1e-9


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


@pytest.fixture(scope="module")
def level(gtm):
    model = AircraftModel(gtm, aero="quasi-steady")
    return model, trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))


def _assert_same_roots(poles, reference, rtol=POLE_RTOL):
    poles, reference = np.sort_complex(np.asarray(poles)), np.asarray(reference)
    assert poles.size == reference.size
    for lam in reference:
        k = int(np.argmin(np.abs(poles - lam)))
        assert abs(poles[k] - lam) <= rtol * max(abs(lam), 1.0), (lam, poles[k])
        poles = np.delete(poles, k)


def test_statespace_is_named_and_its_poles_are_the_eigen_analysis(level):
    model, point = level
    ss = state_space(model, point)
    system = linear_system(model, point)
    assert isinstance(ss, control.StateSpace)
    assert tuple(ss.state_labels) == system.state_names and len(system.state_names) == model.layout.n_states - 4
    assert tuple(ss.input_labels) == INPUT_NAMES == ("thrust_N", "aileron_rad", "elevator_rad", "rudder_rad", GUST_INPUT)
    assert tuple(ss.output_labels) == system.output_names
    assert "tip_deflection_right_wing_m" in system.output_names and "root_bending_moment_left_wing_N_m" in system.output_names
    spec = spectrum(model, point.x, point.u, aero_model="quasi-steady")
    _assert_same_roots(ss.poles(), [m.eigenvalue for m in spec.modes])
    np.testing.assert_array_equal(system.d, 0.0)


def test_finite_state_model_keeps_its_inflow_states_and_poles(gtm, level):
    _, point = level  # a quasi-steady trim: extended with the zero inflow of the steady wake
    model = AircraftModel(gtm, aero=AeroOptions("unsteady", 2))
    system = linear_system(model, point)
    assert sum(n.startswith("lambda_") for n in system.state_names) == model.layout.n_inflow > 0
    x = np.concatenate([point.x, np.zeros(model.layout.n_inflow)])
    spec = spectrum(model, x, point.u, aero_model="unsteady")
    _assert_same_roots(system.to_statespace().poles(), [m.eigenvalue for m in spec.modes])


def test_outputs_are_the_sensor_bank(level):
    model, point = level
    system = linear_system(model, point, state_outputs=True)
    rng = np.random.default_rng(1)
    dx = 1e-3 * rng.standard_normal(len(system.state_names))
    x = np.array(point.x)
    x[system.keep] += dx
    y = system.c @ dx
    for name, sensor in structural_sensors(model).items():
        for quantity, value in ((f"tip_deflection_{name}_m", sensor.tip_deflection_m),
                                (f"tip_twist_rate_{name}_rad_s", sensor.tip_twist_rate_rad_s),
                                (f"root_bending_moment_{name}_N_m", sensor.root_bending_moment_n_m)):
            if quantity in system.output_names:
                ref = float(value(x) - value(point.x))
                assert y[system.output_names.index(quantity)] == pytest.approx(ref, rel=1e-9, abs=1e-12 * max(1.0, abs(ref)))
    n_sensors = len(system.output_names) - len(system.state_names)
    np.testing.assert_array_equal(y[n_sensors:], dx)
    assert system.output_names[n_sensors:] == system.state_names


def test_gust_column_is_the_relative_velocity_column_of_a(gtm):
    model = AircraftModel(gtm, aero=AeroOptions("quasi-steady", parasite_drag=False, body_moments=False, downwash=False))
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))
    system = linear_system(model, point)
    lay = model.layout
    v_cols = [list(system.keep).index(i) for i in range(lay.velocity.start, lay.velocity.start + 3)]
    c_ez = dcm_321(*point.x[lay.euler]) @ np.array([0.0, 0.0, 1.0])
    gust = system.b[:, INPUT_NAMES.index(GUST_INPUT)]
    np.testing.assert_allclose(gust, system.a[:, v_cols] @ c_ez, rtol=0, atol=1e-6 * np.abs(gust).max())
    assert gust[system.state_names.index("v_z_m_s")] < 0.0  # an up-gust lifts: the body accelerates up (-z)


@pytest.fixture(scope="module")
def stratosphere(gtm):
    altitude = 12000.0
    model = AircraftModel(gtm, aero="quasi-steady", aero_density_kg_m3=float(isa_density(altitude)))
    point = trim(model, SteadyManoeuvre.level(altitude, mach=0.8))
    return model, point, linear_system(model, point, state_outputs=True)


def _uniform_up_gust(w_m_s: float):
    """The wind of the gust input: the air moving up at w [m/s] at every point (NED z negative)."""
    return lambda t, positions: np.tile([0.0, 0.0, -w_m_s], (len(positions), 1))


@pytest.mark.parametrize("input_name, steps, bound", [("elevator_rad", (1e-3, 2e-3), 0.01), (GUST_INPUT, (0.5, 1.0), 0.02)],
                         ids=["elevator", "gust"])
def test_step_response_matches_the_nonlinear_simulation(stratosphere, input_name, steps, bound):
    """Elevator steps of 1e-3 and 2e-3 rad (measured errors at most 0.46 % of the peaks, ratios 3.98-4.00) and uniform
    up-gusts of 0.5 and 1 m/s passed to the nonlinear model as its wind (at most 1.41 %, ratios 3.94-4.01)."""
    model, point, system = stratosphere
    ss = system.to_statespace()
    t_end, rate = 2.0, 100.0
    k = INPUT_NAMES.index(input_name)

    def run(du: float):
        controls, wind = np.array(point.u), None
        if input_name == GUST_INPUT:
            wind = _uniform_up_gust(du) if du else None
        else:
            controls[k] += du
        return simulate(model, point, t_end, controls=controls, wind=wind,
            integrator=IntegratorSettings(method="DOP853", rtol=1e-10, atol=1e-12),
            output=OutputSettings(rate_hz=rate), events=EventSettings(()))

    still = run(0.0)  # the trim's own drift (residual 1e-13) is taken out
    signals = ("v_x_m_s", "v_z_m_s", "theta_rad", "omega_y_rad_s", "tip_deflection_right_wing_m",
               "tip_twist_right_wing_rad", "root_bending_moment_right_wing_N_m")
    rows = [system.output_names.index(s) for s in signals]
    errors, peaks = {}, {}
    for du in steps:
        result = run(du)
        assert np.array_equal(result.t, still.t)
        dx = (result.x - still.x)[:, system.keep]
        u = np.zeros((len(INPUT_NAMES), result.t.size))
        u[k] = du
        linear = control.forced_response(ss, result.t, u).outputs[rows]
        nonlinear = system.c[rows] @ dx.T
        errors[du] = np.abs(nonlinear - linear).max(axis=1)
        peaks[du] = np.abs(linear).max(axis=1)
    small, large = steps
    relative = errors[small] / peaks[small]
    assert np.all(relative < bound), dict(zip(signals, relative))
    ratio = errors[large] / errors[small]
    assert np.all((3.5 < ratio) & (ratio < 4.5)), dict(zip(signals, ratio))
    assert peaks[small][signals.index("theta_rad")] > 1e-4  # a real response: more than 0.005 deg of pitch


def test_file_round_trip(tmp_path, gtm):
    model = AircraftModel(gtm, aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.turn(9144.0, 8000.0, mach=0.75, coordinated=True))
    system = linear_system(model, point)
    path = system.save(tmp_path / "turn.npz")
    back = LinearSystem.load(path)
    for name in ("a", "b", "c", "d", "keep", "x0", "u0"):
        np.testing.assert_array_equal(getattr(back, name), getattr(system, name))
    assert (back.state_names, back.input_names, back.output_names) == (system.state_names, system.input_names, system.output_names)
    assert back.manoeuvre == system.manoeuvre and back.manoeuvre.coordinated
    assert back.model == system.model and back.model.aero == model.aero.options
    assert back.model.aircraft_digest == gtm.content_digest()
    with np.load(path, allow_pickle=False) as f:
        assert str(f["format"]) == FILE_FORMAT and float(f["mach"]) == pytest.approx(0.75, abs=1e-12)
    glide = dataclasses.replace(system, manoeuvre=SteadyManoeuvre(200.0, 3000.0, math.inf, None))
    assert LinearSystem.load(glide.save(tmp_path / "glide.npz")).manoeuvre.climb_angle_rad is None


def test_bad_files_and_calls_are_refused(tmp_path, level):
    model, point = level
    other = tmp_path / "other.npz"
    np.savez(other, A=np.eye(2))
    with pytest.raises(ValueError, match="format = '', expected 'flexsim-linear-system-1'"):
        LinearSystem.load(other)
    with pytest.raises(FileNotFoundError, match="no such file"):
        LinearSystem.load(tmp_path / "missing.npz")
    system = linear_system(model, point)
    with pytest.raises(ValueError, match=r"must end in \.npz"):
        system.save(tmp_path / "model.txt")
    with pytest.raises(FileNotFoundError, match="does not exist"):
        system.save(tmp_path / "no" / "model.npz")
    with pytest.raises(ValueError, match="u0: the controls"):
        linear_system(model, point.x)
    with pytest.raises(ValueError, match="a state of 3 entries for a model of 60 states"):
        linear_system(model, np.zeros(3), np.zeros(4))


def test_missing_python_control_names_the_extra(level, monkeypatch):
    model, point = level
    system = linear_system(model, point)
    monkeypatch.setitem(sys.modules, "control", None)  # import control -> ImportError
    with pytest.raises(MissingDependencyError, match=r"pip install 'flexsim\[control\]'"):
        system.to_statespace()
    with pytest.raises(ImportError):
        state_space(model, point)


def test_wrong_inputs_are_refused_naming_the_argument(tmp_path, gtm, level):
    """Inputs are checked where they enter: an Aircraft or a name where a model is expected, a truncated or damaged
    file, a NaN or ragged operating point: each a clear error naming the argument, never numpy's or zipfile's."""
    model, point = level
    with pytest.raises(TypeError, match=r"model = .*must be an AircraftModel, not a flexsim.aircraft.definition.Aircraft; "
                                        r"an Aircraft is the definition; build the model with flexsim.AircraftModel"):
        linear_system(gtm, point)
    with pytest.raises(TypeError, match=r"model = 'gtm': must be an AircraftModel.*load_aircraft\('gtm'\)"):
        fs.state_space("gtm", point)
    with pytest.raises(TypeError, match="model = .*must be an AircraftModel"):
        fs.linearize(gtm, point)
    with pytest.raises(TypeError, match=r"aircraft = 'gtm': must be an Aircraft.*flexsim.load_aircraft\('gtm'\)"):
        AircraftModel("gtm")
    with pytest.raises(TypeError, match=r"aircraft = .*must be an Aircraft.*model.aircraft"):
        AircraftModel(model)
    path = linear_system(model, point).save(tmp_path / "full.npz")
    data = path.read_bytes()
    for cut in (len(data) // 2, len(data) - 30, 10):
        damaged = tmp_path / f"cut{cut}.npz"
        damaged.write_bytes(data[:cut])
        with pytest.raises(ValueError, match=r"not a readable \.npz file, truncated or damaged"):
            LinearSystem.load(damaged)
    x = point.x.copy()
    x[7] = np.nan
    with pytest.raises(ValueError, match=r"point\[7\] = nan: must be finite"):
        linear_system(model, x, point.u)
    with pytest.raises(ValueError, match="u0 = .*must be an array of numbers"):
        linear_system(model, point.x, [1.0, [2.0, 3.0], 0.0, 0.0])
