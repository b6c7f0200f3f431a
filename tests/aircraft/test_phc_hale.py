"""The bundled PHC HALE aircraft (flexsim/aircraft/data/phc_hale.md): it loads, finds its modes and trims at 20 km.

* Mass: 2 x 16 m x 0.75 kg/m (wing) + 10 m x 0.08 (boom) + 7.5 m x 0.08 (stabilizers) + 50 kg (payload) = 75.4 kg.
* Modes: restrained at the body origin (the rigid boom clamps the wing roots), each half is a uniform cantilever:
  (1.87510 / L)^2 sqrt(EI / m) = 2.24282 rad/s and (pi / 2L) sqrt(GJ / I) = 31.0456 rad/s, twice (1e-6 relative).
  Free, the wings' bending and torsion modes come in symmetric/antisymmetric pairs above six rigid-body modes.
* Trim in level flight at 20 km and 25 m/s (PHC's and AeroBeams.jl's condition): lift equals weight (the trim
  residual, 1e-8 scaled), and the linear structure's tip deflection is far beyond its range (47 % of the semispan), which
  the trim says in one line naming the nonlinear option.
"""

from __future__ import annotations

import math

import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel
from flexsim.structure.model import StructuralModel
from flexsim.trimming import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def hale():
    return load_aircraft("phc_hale")


def test_loads_with_a_wing_continuous_through_the_centreline(hale):
    assert hale.component_names == ("fuselage", "right_wing", "left_wing", "right_htail", "left_htail", "vtail")
    assert hale.component("right_wing").root_m[1] == 0.0 == hale.component("left_wing").root_m[1]
    assert StructuralModel(hale).mass_properties.mass_kg == pytest.approx(75.4, rel=1e-12)


def test_modes(hale):
    clamped = in_vacuo_modes(AircraftModel(hale, variant="restrained")).frequencies_rad_s
    flap1 = (1.87510407 / 16.0) ** 2 * math.sqrt(2.0e4 / 0.75)
    torsion1 = math.pi / 32.0 * math.sqrt(1.0e4 / 0.1)
    assert clamped[:2] == pytest.approx([flap1, flap1], rel=1e-6)
    assert [w for w in clamped if 25.0 < w < 35.0] == pytest.approx([torsion1, torsion1], rel=1e-6)
    free = in_vacuo_modes(AircraftModel(hale))
    assert free.n_rigid == 6
    labels = [m.dominant_dof for m in free.modes[6:10]]
    assert labels == ["wings bending 1 (symmetric)", "wings bending 1 (antisymmetric)",
                      "wings bending 2 (symmetric)", "wings bending 2 (antisymmetric)"]


def test_trims_at_20_km_and_says_it_is_beyond_the_linear_range(hale):
    model = AircraftModel(hale, aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.level(20000.0, speed_m_s=25.0), classify=False)
    assert point.residual < 1e-8
    assert point.load_factor_total == pytest.approx(1.0, rel=1e-6)
    assert point.tip_deflection_m / 16.0 < -0.3  # the linear structure's answer (positive down): far beyond its range
    assert point.linear_range.startswith("linear structure beyond its range: right_wing tip deflection")
    assert point.linear_range.endswith("results need the geometrically nonlinear beam, Terms(nonlinear_beams=NonlinearBeams()), docs/nonlinear-beams.md")
