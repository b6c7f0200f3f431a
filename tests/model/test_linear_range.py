"""The range of the linear structure (flexsim.model.linear_range): its limits from closed forms, and the one check.

* Bending limit: a cantilever under a dead tip load, the elastica EI theta'' = -P cos(theta), theta(0) = 0,
  theta'(L) = 0, integrated here (shooting, rtol 1e-12). Published check: Bisshopp & Drucker (1945), Q. Appl. Math.
  3(3), 272-275, tip deflection 0.30172 L at P L^2 / EI = 1 (asserted to 5e-5 L, their table's last digit). At the
  stated limit, a linear tip deflection of DEFLECTION_LIMIT_FRACTION L, linear theory P L^3 / 3 EI exceeds the
  elastica by LINEAR_RANGE_ERROR (2 %) to within 0.05 percentage points (the limit 0.14 is 0.1406 rounded).
* Twist limit: 1 - sin(psi)/psi = 2 % at TWIST_LIMIT_RAD (to 1e-4, the constant's rounding).
* The check names the worst beam, its deflection as a fraction of its length, and the nonlinear option in one line;
  it is silent within the range, takes trajectories, and the trim carries its line (GTM level flight: within the
  range, tip 0.76 m of 18.25 m = 4 %).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from flexsim.aircraft.toml_loader import load_aircraft, parse_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.linear_range import (
    DEFLECTION_LIMIT_FRACTION,
    LINEAR_RANGE_ERROR,
    TWIST_LIMIT_RAD,
    linear_range_note,
    nonlinear_fields_note,
)
from flexsim.model.sensors import structural_sensors
from flexsim.trimming import SteadyManoeuvre, trim


def elastica_tip_deflection(load: float) -> float:
    """Tip deflection / L of a cantilever (L = 1, EI = 1) under a dead tip load P L^2 / EI = ``load``."""
    def shoot(slope0: float):
        return solve_ivp(lambda s, y: [y[1], -load * math.cos(y[0]), math.sin(y[0])], (0.0, 1.0), [0.0, slope0, 0.0],
                         rtol=1e-12, atol=1e-14)

    slope0 = brentq(lambda k: shoot(k).y[1, -1], 0.0, load + 1e-12, xtol=1e-14)  # curvature 0 at the free end
    return float(shoot(slope0).y[2, -1])


def test_elastica_matches_bisshopp_and_drucker():
    assert elastica_tip_deflection(1.0) == pytest.approx(0.30172, abs=5e-5)


def test_the_bending_limit_is_where_linear_theory_errs_by_two_percent():
    load = 3.0 * DEFLECTION_LIMIT_FRACTION  # linear tip deflection P L^3 / 3 EI = 0.14 L
    error = (load / 3.0) / elastica_tip_deflection(load) - 1.0
    assert error == pytest.approx(LINEAR_RANGE_ERROR, abs=5e-4)


def test_the_twist_limit_is_where_the_linear_rotation_errs_by_two_percent():
    assert 1.0 - math.sin(TWIST_LIMIT_RAD) / TWIST_LIMIT_RAD == pytest.approx(LINEAR_RANGE_ERROR, abs=1e-4)


_WING = """
schema_version = 1
name = "long wing"
[components.right_wing]
root_m = [0.0, 0.0, 0.0]
euler_deg = [0.0, 0.0, 90.0]
length_m = 16.0
bending_modes = 2
torsion_modes = 1
[components.right_wing.sections]
station_m = [0.0, 16.0]
mass_kg_per_m = [0.75, 0.75]
torsional_inertia_kg_m = [0.1, 0.1]
ei_nm2 = [2.0e4, 2.0e4]
gj_nm2 = [1.0e4, 1.0e4]
chord_m = [1.0, 1.0]
"""


@pytest.fixture(scope="module")
def wing_model():
    return AircraftModel(parse_aircraft(_WING, source="wing.toml"), variant="restrained")


def _state(model, tip_m: float = 0.0, twist_rad: float = 0.0) -> np.ndarray:
    """A state with the right wing's tip at ``tip_m`` (first bending shape) and twisted by ``twist_rad``."""
    sensor = structural_sensors(model)["right_wing"]
    x = np.zeros(model.layout.n_states)
    x[sensor.q_idx[0]] = tip_m / sensor.w_tip[0]
    x[sensor.xi_idx[0]] = twist_rad / sensor.psi_tip[0]
    return x


def test_silent_within_the_range_and_one_line_beyond(wing_model):
    assert linear_range_note(wing_model, _state(wing_model, tip_m=-0.13 * 16.0, twist_rad=0.3)) is None
    note = linear_range_note(wing_model, _state(wing_model, tip_m=-0.42 * 16.0))
    assert "\n" not in note
    assert note.startswith("linear structure beyond its range: right_wing tip deflection -6.72 m = 42% of its 16 m length")
    assert note.endswith("the geometrically nonlinear beam, Terms(nonlinear_beams=NonlinearBeams()), docs/nonlinear-beams.md")
    twisted = linear_range_note(wing_model, _state(wing_model, twist_rad=math.radians(25.0)))
    assert "right_wing tip twist +25 deg" in twisted


def test_a_trajectory_counts_its_largest_excursion(wing_model):
    xs = np.stack([_state(wing_model, tip_m=t) for t in (0.0, -1.0, -3.0, -1.0)])
    note = linear_range_note(wing_model, xs, " (largest of the run)")
    assert "tip deflection -3 m = 19% of its 16 m length (largest of the run)" in note


def test_the_trim_carries_the_line():
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.78), classify=False)
    assert abs(point.tip_deflection_m) / 18.25 < 0.05 and point.linear_range is None


def test_fields_of_the_nonlinear_beam_are_named():
    assert nonlinear_fields_note(load_aircraft("gtm")) is None
    extra = _WING + "ei_chord_nm2 = [4.0e6, 4.0e6]\nea_n = [1.0e8, 1.0e8]\n"
    note = nonlinear_fields_note(parse_aircraft(extra, source="wing.toml"))
    assert note.startswith("sections.ei_chord_nm2 of right_wing; sections.ea_n of right_wing: used by the geometrically "
                           "nonlinear beam only (docs/nonlinear-beams.md)")
