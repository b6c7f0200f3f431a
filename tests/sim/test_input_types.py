"""Numbers that are not numbers: a bool or a string where a duration, rate or period is asked is refused with the
parameter's name (``True`` is not 1 s), at the shared helper :func:`flexsim.errors.positive_number` and the checks of
:func:`flexsim.sim.simulate.simulate` and the named manoeuvres."""

from __future__ import annotations

import numpy as np
import pytest

from flexsim.sim.run_settings import OutputSettings

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.errors import positive_number
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.manoeuvres import build_manoeuvre
from flexsim.sim.simulate import simulate


@pytest.mark.parametrize("value", [True, False, "3", b"3", np.bool_(True)])
def test_positive_number_refuses_non_numbers(value):
    with pytest.raises(ValueError, match=r"t = .*: must be a finite number > 0 \[s\], got"):
        positive_number("t", value, "s")


def test_simulate_refuses_a_bool_duration_and_rate():
    model = AircraftModel(load_aircraft("goland_wing"), variant="restrained", gravity_m_s2=0.0)
    x0 = model.layout.zeros()
    with pytest.raises(ValueError, match=r"t_end_s = True: must be a finite number > 0 \[s\]"):
        simulate(model, x0, True, controls=np.zeros(4))
    with pytest.raises(ValueError, match=r"rate_hz = True: must be"):  # new case
        simulate(model, x0, 0.1, controls=np.zeros(4), output=OutputSettings(rate_hz=True))


def test_manoeuvre_refuses_a_bool_duration():
    with pytest.raises(ValueError, match=r"duration_s = True: must be a finite number > 0 \[s\]"):
        build_manoeuvre("climb", duration_s=True)


def test_bools_are_not_altitudes_nor_speeds():
    """New cases of the class where a flight condition enters: the ISA and a steady manoeuvre."""
    from flexsim.atmosphere import isa
    from flexsim.trimming import SteadyManoeuvre

    with pytest.raises(ValueError, match=r"altitude = True: must be a number \[m\], got bool"):
        isa(True)
    with pytest.raises(ValueError, match=r"speed_m_s = True: must be a number, got bool"):
        SteadyManoeuvre(True, 1000.0)
    with pytest.raises(ValueError, match=r"altitude_m = True: must be a number, got bool"):
        SteadyManoeuvre(100.0, True)
    with pytest.raises(ValueError, match=r"altitude_m = True"):
        AircraftModel(load_aircraft("goland_wing"), variant="restrained", altitude_m=True)
