"""``simulate`` says in one line when a run takes the linear structure beyond its range
(flexsim.model.linear_range; limits: tests/model/test_linear_range.py): the summary of a 0.2 s run about the PHC
HALE's level trim at 20 km and 25 m/s (tips 7.49 m, 47 % of the semispan) has the line, for the largest excursion.
"""

from __future__ import annotations

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.run_settings import EventSettings, OutputSettings
from flexsim.sim.simulate import simulate
from flexsim.trimming import SteadyManoeuvre, trim


def test_simulate_summary_says_it():
    model = AircraftModel(load_aircraft("phc_hale"), aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.level(20000.0, speed_m_s=25.0), classify=False)
    result = simulate(model, point, 0.2, events=EventSettings(wing_tip_deflection_m=15.0),
                      output=OutputSettings(rate_hz=50.0))
    assert result.linear_range is not None and "(largest of the run)" in result.linear_range
    assert result.summary().splitlines().count(result.linear_range) == 1
