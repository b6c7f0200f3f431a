"""``linear_system`` refuses an operating point it cannot linearise honestly: a non-finite state or controls, and a
trim that is not an equilibrium of the model it is given (a trim of another aircraft, variant or formulation)."""

from __future__ import annotations

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.control import linear_system
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.trimming import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def gtm_trim():
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    return model, trim(model, SteadyManoeuvre.level(9144.0, mach=0.78))


def test_nan_state_is_refused(gtm_trim):
    model, point = gtm_trim
    x = np.array(point.x)
    x[7] = np.nan
    with pytest.raises(ValueError, match=r"point\[7\] = nan: must be finite"):
        linear_system(model, x, point.u)
    with pytest.raises(ValueError, match=r"u0\[0\] = inf: must be finite"):  # a new case of the class: the controls
        linear_system(model, point.x, np.array([np.inf, 0.0, 0.0, 0.0]))


@pytest.mark.parametrize("other", [
    lambda: AircraftModel(load_aircraft("gtm_uncalibrated"), aero="quasi-steady"),  # another aircraft, same layout
    lambda: AircraftModel(load_aircraft("gtm"), aero=AeroOptions("quasi-steady", formulation="paper")),  # new case
])
def test_trim_of_another_model_is_refused(gtm_trim, other):
    _, point = gtm_trim
    with pytest.raises(ValueError, match=r"point: the trim is not an equilibrium of this model"):
        linear_system(other(), point)


def test_trim_of_the_quasi_steady_twin_is_an_equilibrium_of_the_unsteady_model(gtm_trim):
    """Zero inflow is the finite-state wake's steady state: the trim is accepted (its residual below 1e-6)."""
    _, point = gtm_trim
    system = linear_system(AircraftModel(load_aircraft("gtm"), aero=AeroOptions("unsteady", 2)), point)
    assert np.all(np.isfinite(system.a))
