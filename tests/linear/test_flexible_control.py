"""The linear model about the nonlinear trim (flexsim.linear.flexible_control, through fs.linear_system).

* Its poles are the free aircraft's spectrum about the same trim (one Jacobian: equal to the last bit).
* Its response equals the nonlinear aircraft's for small inputs: a 0.002 rad elevator step and a 0.1 m/s uniform
  up-gust held 2 s from the HALE's nonlinear trim (4 elements per wing), the linear model discretised exactly (zero-
  order hold, matrix exponential), the nonlinear one flown by ``fs.simulate_flexible`` (ROS2, 5 ms): the right wing's
  tip deflection within 1 % (elevator; measured 0.28 %) and 3 % (gust; measured 1.7 %: the gust's step at t = 0 and
  the ROS2 step) of its largest change.
* It is saved and loaded with its model record (the nonlinear beams included); a linear trim is refused by name.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

import flexsim as fs
from flexsim.linear.control import LinearSystem
from flexsim.linear.flexible_stability import free_aircraft_spectrum
from flexsim.model.terms import NonlinearBeams


@pytest.fixture(scope="module")
def hale():
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(nonlinear_beams=NonlinearBeams(4)))
    point = fs.trim(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0))
    return model, point, fs.linear_system(model, point)


def test_poles_are_the_free_aircraft_spectrum(hale):
    model, point, system = hale
    spectrum = free_aircraft_spectrum(model, point).eigenvalues
    np.testing.assert_allclose(np.sort_complex(system.poles()), np.sort_complex(spectrum), rtol=0, atol=1e-9)
    assert system.input_names[-1] == "gust_up_m_s" and system.output_names[0] == "tip_deflection_right_wing_m"


@pytest.mark.parametrize("column, amplitude, tolerance", [(2, 0.002, 0.01), (4, 0.1, 0.03)])
def test_small_input_response_is_the_nonlinear_one(hale, column, amplitude, tolerance):
    model, point, system = hale
    dt, steps, m = 0.02, 100, system.a.shape[0]
    aug = np.zeros((m + 1, m + 1))
    aug[:m, :m], aug[:m, m] = system.a * dt, system.b[:, column] * dt
    step = scipy.linalg.expm(aug)
    x, linear = np.zeros(m), []
    for _ in range(steps):
        x = step[:m, :m] @ x + step[:m, m] * amplitude
        linear.append(system.c[0] @ x)
    controls, wind = np.array(point.controls, float), None
    if column < 4:
        controls[column] += amplitude
    else:
        def up_gust(t, positions):
            return np.tile([0.0, 0.0, -amplitude], (len(positions), 1))
        wind = up_gust
    run = fs.simulate_flexible(model, point, steps * dt, controls=controls, wind=wind, sample_dt_s=dt, step_s=0.005)
    flex = point.aircraft
    tip = run.tip_positions_m[1:, 0, 2] - flex.tip_positions(point.strains)[0, 2]
    linear = np.array(linear)
    assert np.abs(tip).max() > 0.005
    assert np.abs(linear - tip).max() < tolerance * np.abs(tip).max()


def test_saved_with_its_model_and_linear_trims_refused(hale, tmp_path):
    model, point, system = hale
    back = LinearSystem.load(system.save(tmp_path / "hale.npz"))
    assert back.model == system.model and np.array_equal(back.a, system.a)
    linear_trim = fs.trim(model.replace(nonlinear_beams=None), point.manoeuvre, check_limits=False)
    with pytest.raises(ValueError, match="FlexibleTrimPoint"):
        fs.linear_system(model, linear_trim)
