"""Section fields for the geometrically nonlinear beam: chordwise bending and extension stiffness, flapwise rotary
inertia (docs/aircraft-format.md, "Fields of the geometrically nonlinear beam").

* They load, validated, with errors naming the field, the value and the allowed range.
* The linear structure does not use them, and says so (``Aircraft.nonlinear_beam_fields``): its matrices are
  exactly those of the same file without them (existing files load unchanged and mean what they mean today).
* The bundled aircraft of the paper's fields have none.
"""

from __future__ import annotations

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import bundled_aircraft_names, load_aircraft, parse_aircraft
from flexsim.errors import AircraftDefinitionError
from flexsim.structure.model import StructuralModel

BASE = """
schema_version = 1
name = "wing"
[components.right_wing]
root_m = [0.0, 0.0, 0.0]
euler_deg = [0.0, 0.0, 90.0]
length_m = 16.0
bending_modes = 2
torsion_modes = 2
[components.right_wing.sections]
station_m = [0.0, 16.0]
mass_kg_per_m = [0.75, 0.75]
cg_offset_m = [0.1, 0.1]
torsional_inertia_kg_m = [0.1, 0.1]
ei_nm2 = [2.0e4, 2.0e4]
gj_nm2 = [1.0e4, 1.0e4]
chord_m = [1.0, 1.0]
"""
EXTRA = "ei_chord_nm2 = [4.0e6, 4.0e6]\nea_n = [1.0e8, 2.0e8]\nflap_inertia_kg_m = [5.0e-4, 5.0e-4]\n"


def test_the_fields_load_read_only_and_are_listed():
    aircraft = parse_aircraft(BASE + EXTRA, source="wing.toml")
    table = aircraft.component("right_wing").sections
    assert table.ei_chord_nm2.tolist() == [4.0e6, 4.0e6] and table.ea_n.tolist() == [1.0e8, 2.0e8]
    assert table.flap_inertia_kg_m.tolist() == [5.0e-4, 5.0e-4]
    assert not table.ea_n.flags.writeable
    assert aircraft.nonlinear_beam_fields == ("components.right_wing.sections.ei_chord_nm2",
                                              "components.right_wing.sections.ea_n",
                                              "components.right_wing.sections.flap_inertia_kg_m")
    plain = parse_aircraft(BASE, source="wing.toml").component("right_wing").sections
    assert plain.ei_chord_nm2 is None and plain.ea_n is None and plain.flap_inertia_kg_m is None


def test_the_linear_structure_is_the_same_with_and_without_them():
    with_fields = StructuralModel(parse_aircraft(BASE + EXTRA, source="a.toml"))
    without = StructuralModel(parse_aircraft(BASE, source="b.toml"))
    assert np.array_equal(with_fields.k_bending, without.k_bending)
    assert np.array_equal(with_fields.k_torsion, without.k_torsion)
    assert with_fields.mass_properties.mass_kg == without.mass_properties.mass_kg
    assert np.array_equal(with_fields.mass_properties.inertia_cg_kg_m2, without.mass_properties.inertia_cg_kg_m2)


@pytest.mark.parametrize("name", ["gtm", "gtm_uncalibrated", "goland_wing", "maewing1"])
def test_files_of_the_paper_fields_have_none(name):
    assert name in bundled_aircraft_names()
    assert load_aircraft(name).nonlinear_beam_fields == ()


@pytest.mark.parametrize("extra, message", [
    ("ei_chord_nm2 = [4.0e6, -1.0]\n", r"sections\.ei_chord_nm2\[1\] = -1\.0: must be > 0"),
    ("ea_n = [1.0e8]\n", r"sections\.ea_n = \[100000000\.0\]: must have 2 entries, one per station"),
    ("ea_n = [1.0e8, 1.0e15]\n", r"sections\.ea_n\[1\] = 1000000000000000\.0: outside the plausible range \[1, 1e\+13\] N"),
    ("ei_chord_nm2 = [4.0e6, \"stiff\"]\n", r"sections\.ei_chord_nm2\[1\] = 'stiff': must be a number"),
    ("flap_inertia_kg_m = [-1e-4, 0.0]\n", r"sections\.flap_inertia_kg_m\[0\] = -0\.0001: must be >= 0"),
    # room = 0.1 - 0.75 * 0.1^2 = 0.0925 kg m: the rest is the inertia about the normal axis
    ("flap_inertia_kg_m = [0.0, 0.095]\n", r"sections\.flap_inertia_kg_m\[1\] = 0\.095: must be <= torsional_inertia_kg_m "
                                           r"- mass_kg_per_m \* cg_offset_m\^2 = 0\.0925"),
])
def test_bad_values_are_refused_naming_the_field(extra, message):
    with pytest.raises(AircraftDefinitionError, match=r"components\.right_wing\." + message):
        parse_aircraft(BASE + extra, source="wing.toml")
