"""Aircraft files that parse but describe no aircraft are refused with the field, the value and the allowed range:
a schema version that is not the integer 1, a component root far from the fuselage, a lumped mass far from the beam
that carries it, a section centre of mass off its chord (docs/aircraft-format.md, "Plausible ranges")."""

from __future__ import annotations

import re

import pytest

from flexsim.aircraft.toml_loader import parse_aircraft
from flexsim.errors import AircraftDefinitionError
from tests.cli.small_aircraft import rc_glider_toml

GLIDER = rc_glider_toml("")


def _refused(text: str, message: str) -> None:
    with pytest.raises(AircraftDefinitionError, match=re.escape(message)):
        parse_aircraft(text)


@pytest.mark.parametrize("version", ["true", '"1"', "1.0"])
def test_schema_version_is_the_integer_one(version):
    _refused(GLIDER.replace("schema_version = 1", f"schema_version = {version}", 1), "schema_version = ")


def test_wing_root_beside_the_fuselage():
    """The glider's fuselage is 1 m long: a root may lie 0.2 x 1 + 1 = 1.2 m from its axis (the roots are 0.02 m off);
    30 m (and, a new case of the class, 1.5 m) is refused."""
    for y in ("30.0", "1.5"):
        _refused(GLIDER.replace("root_m = [0.3, 0.02, 0.0]", f"root_m = [0.3, {y}, 0.0]", 1),
                 f"components.right_wing.root_m = ")
    parse_aircraft(GLIDER.replace("root_m = [0.3, 0.02, 0.0]", "root_m = [0.3, 1.1, 0.0]", 1))  # within 1.2 m


@pytest.mark.parametrize(("component", "position", "distance"), [
    ("fuselage", "[0.5, 0.0, -11.0]", "11"),   # a heavy mass 11 m below the 1 m fuselage
    ("right_wing", "[0.0, 0.5, -2.0]", "2"),   # a new case: 2 m below the 1 m wing (reach 1.2 m)
])
def test_lumped_mass_far_from_its_beam(component, position, distance):
    text = GLIDER + (f'[[lumped_masses]]\nname = "ballast"\ncomponent = "{component}"\nposition_m = {position}\n'
                     'mass_kg = 0.3\n')
    _refused(text, "lumped_masses.ballast.position_m = ")
    with pytest.raises(AircraftDefinitionError, match=f"lies {distance}"):
        parse_aircraft(text)


@pytest.mark.parametrize(("offset", "edge"), [("0.15", "behind the trailing edge"), ("-0.07", "ahead of the leading edge")])
def test_section_centre_of_mass_off_the_chord(offset, edge):
    """The wing's chord is 0.2 m with its elastic axis at 30 %: cg_offset_m in [-0.06, 0.14] m keeps the centre of mass
    on the chord; 0.15 m lies behind the trailing edge, -0.07 m (a new case) ahead of the leading edge."""
    text = GLIDER.replace("chord_m = [0.2, 0.2]", f"chord_m = [0.2, 0.2]\ncg_offset_m = [{offset}, 0.0]", 1)
    _refused(text, f"cg_offset_m[0] = {float(offset)!r}: must put the section's centre of mass on its chord, between "
                   "the leading and the trailing edge: in [-0.06, 0.14] m")
