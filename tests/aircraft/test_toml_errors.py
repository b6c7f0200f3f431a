"""Malformed aircraft files are rejected with one clear error naming file, field, value and range.

Each case edits a valid minimal file; the expected message fragments are part of the contract
(docs/aircraft-format.md).
"""

import re

import pytest

from flexsim.aircraft.toml_loader import load_aircraft, parse_aircraft
from flexsim.errors import AircraftDefinitionError

VALID = """
schema_version = 1
name = "test wing"

[components.right_wing]
root_m = [0.0, 0.0, 0.0]
euler_deg = [0.0, 0.0, 90.0]
length_m = 5.0
bending_modes = 2
torsion_modes = 2

[components.right_wing.sections]
station_m = [0.0, 2.5, 5.0]
mass_kg_per_m = [30.0, 25.0, 20.0]
cg_offset_m = [0.1, 0.1, 0.1]
torsional_inertia_kg_m = [5.0, 4.0, 3.0]
ei_nm2 = [1e7, 8e6, 6e6]
gj_nm2 = [1e6, 8e5, 6e5]
chord_m = [1.5, 1.4, 1.3]
ea_fraction = [0.35, 0.35, 0.35]

[[lumped_masses]]
name = "tip_store"
component = "right_wing"
position_m = [0.0, 4.5, 0.0]
mass_kg = 50.0
"""

CASES = [
    # (description, (old, new) substitution, regex the message must match)
    ("unknown key", ("length_m = 5.0", "length_m = 5.0\nspan_m = 3.0"), r"components\.right_wing\.span_m: unknown key; allowed keys: .*length_m"),
    ("missing field", ("ei_nm2 = [1e7, 8e6, 6e6]\n", ""), r"components\.right_wing\.sections\.ei_nm2: missing required field"),
    ("negative mass", ("mass_kg_per_m = [30.0, 25.0, 20.0]", "mass_kg_per_m = [30.0, -25.0, 20.0]"), r"mass_kg_per_m\[1\] = -25\.0: must be >= 0"),
    ("zero stiffness", ("gj_nm2 = [1e6, 8e5, 6e5]", "gj_nm2 = [1e6, 0.0, 6e5]"), r"gj_nm2\[1\] = 0\.0: must be > 0"),
    ("non-increasing stations", ("station_m = [0.0, 2.5, 5.0]", "station_m = [0.0, 2.5, 2.5]"), r"station_m\[2\] = 2\.5: must be > station_m\[1\] = 2\.5 \(strictly increasing\)"),
    ("stations not reaching the tip", ("station_m = [0.0, 2.5, 5.0]", "station_m = [0.0, 2.5, 4.0]"), r"station_m\[-1\] = 4\.0: must equal length_m = 5\.0"),
    ("lumped mass off its component", ("position_m = [0.0, 4.5, 0.0]", "position_m = [0.0, 7.5, 0.0]"), r"lumped_masses\.tip_store\.position_m = \[0\.0, 7\.5, 0\.0\]: projects to station 7\.5 m, off component right_wing \(0 to 5 m\)"),
    ("m out of range", ("bending_modes = 2", "bending_modes = 11"), r"bending_modes = 11: must be an integer in \[0, 10\]"),
    ("n not an integer", ("torsion_modes = 2", "torsion_modes = 1.5"), r"torsion_modes = 1\.5: must be an integer in \[0, 10\]"),
    ("wrong type", ("length_m = 5.0", 'length_m = "five"'), r"length_m = 'five': must be a number"),
    ("table length mismatch", ("chord_m = [1.5, 1.4, 1.3]", "chord_m = [1.5, 1.4]"), r"chord_m = \[1\.5, 1\.4\]: must have 3 entries, one per station"),
    ("unknown component", ("[components.right_wing]", "[components.canard]"), r"components\.canard: unknown component; allowed: fuselage, right_wing"),
    ("inertia below parallel-axis bound", ("torsional_inertia_kg_m = [5.0, 4.0, 3.0]", "torsional_inertia_kg_m = [5.0, 0.1, 3.0]"), r"torsional_inertia_kg_m\[1\] = 0\.1: must be >= mass_kg_per_m \* cg_offset_m\^2 = 0\.25"),
    ("elastic axis outside chord", ("ea_fraction = [0.35, 0.35, 0.35]", "ea_fraction = [0.35, 1.2, 0.35]"), r"ea_fraction\[1\] = 1\.2: must be in \[0, 1\]"),
    ("bad frame", ("name = \"test wing\"", "name = \"test wing\"\n[frame]\nkind = \"wind\""), r"frame\.kind = 'wind': must be \"body\" or \"design\""),
    ("schema version", ("schema_version = 1", "schema_version = 7"), r"schema_version = 7: this flexsim reads version 1"),
    ("toml syntax", ("length_m = 5.0", "length_m = = 5.0"), r"not valid TOML"),
    ("negative lumped mass", ("mass_kg = 50.0", "mass_kg = -50.0"), r"lumped_masses\.tip_store\.mass_kg = -50\.0: must be in \(0\.0, inf\]"),
    ("damping out of range", ("name = \"test wing\"", "name = \"test wing\"\nstructural_damping_ratio = 0.5"), r"structural_damping_ratio = 0\.5: must be in \[0\.0, 0\.1\]"),
    ("wrong control surface", ("[[lumped_masses]]", "[components.right_wing.control_surface]\nkind = \"rudder\"\nhinge_fraction = 0.7\nstart_m = 1.0\nend_m = 4.0\n\n[[lumped_masses]]"), r"control_surface\.kind = 'rudder': must be 'aileron' on right_wing"),
]


@pytest.mark.parametrize("desc, edit, pattern", CASES, ids=[c[0] for c in CASES])
def test_malformed_file_rejected_with_clear_message(desc, edit, pattern):
    old, new = edit
    assert old in VALID, desc
    text = VALID.replace(old, new, 1)
    with pytest.raises(AircraftDefinitionError) as info:
        parse_aircraft(text, source="bad.toml")
    message = str(info.value)
    assert message.startswith("bad.toml: "), message
    assert re.search(pattern, message), message
    assert "Traceback" not in message


def test_valid_minimal_file_parses():
    a = parse_aircraft(VALID, source="ok.toml")
    assert a.component_names == ("right_wing",)
    assert a.lumped_masses[0].name == "tip_store"


def test_missing_file_names_the_bundled_aircraft(tmp_path):
    with pytest.raises(FileNotFoundError, match="neither a bundled aircraft .*gtm.* nor an existing TOML file"):
        load_aircraft(tmp_path / "nope.toml")


def test_file_errors_carry_the_path(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text(VALID.replace("bending_modes = 2", "bending_modes = -1"))
    with pytest.raises(AircraftDefinitionError, match=re.escape(str(path)) + r": components\.right_wing\.bending_modes = -1"):
        load_aircraft(path)


@pytest.mark.parametrize("table, fragment", [
    ('[aero]\ncompressibility = "glauert"\n', "aero.compressibility = 'glauert': must be one of 'prandtl-glauert', 'none'"),
    ("[aero]\ncompressibility = 1\n", "aero.compressibility = 1: must be"),
    ("[aero]\nmach_cap = 0.9\n", "aero.mach_cap: unknown key"),
])
def test_aircraft_aero_settings_are_checked(table, fragment):
    text = VALID.replace('name = "test wing"\n', f'name = "test wing"\n{table}')
    with pytest.raises(AircraftDefinitionError, match=re.escape(fragment)):
        parse_aircraft(text, source="t.toml")
    ok = parse_aircraft(VALID.replace('name = "test wing"\n', 'name = "test wing"\n[aero]\ncompressibility = "none"\n'))
    assert ok.aero_settings.compressibility == "none"
