"""linearize() takes a trim point as its operating point and names its states and inputs
(named results, python-control's OperatingPoint / StateSpace names).

The linear model about a TrimPoint equals the one about its (x, u) exactly (same Jacobian); its state names are the
vocabulary names of the kept states (X, Y, Z and psi dropped); bad calls raise ValueError naming u0.
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.io.vocabulary import CONTROL_NAMES
from flexsim.linear.linearize import linearize
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.naming import state_names
from flexsim.trimming import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def trimmed():
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    return model, trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))


def test_a_trim_point_is_an_operating_point_and_the_result_is_named(trimmed):
    model, point = trimmed
    lin = linearize(model, point)
    ref = linearize(model, point.x, point.u)
    np.testing.assert_array_equal(lin.a, ref.a)
    np.testing.assert_array_equal(lin.b, ref.b)
    names = state_names(model)
    assert len(lin.state_names) == lin.a.shape[0] == model.layout.n_states - 4
    assert lin.state_names == tuple(names[i] for i in lin.keep)
    assert not {"x_north_m", "y_east_m", "z_down_m", "psi_rad"} & set(lin.state_names)
    assert lin.state_names[:2] == ("phi_rad", "theta_rad") and lin.input_names == CONTROL_NAMES == ("thrust_N", "aileron_rad", "elevator_rad", "rudder_rad")


def test_missing_or_doubled_controls_are_rejected(trimmed):
    model, point = trimmed
    with pytest.raises(ValueError, match="u0: the controls .* are required"):
        linearize(model, point.x)
    with pytest.raises(ValueError, match="u0: a TrimPoint supplies its own controls"):
        linearize(model, point, point.u)
