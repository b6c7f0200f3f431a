"""docs/aircraft-format.md: its TOML example loads, and it shows every key the loader accepts.

The example is the first ```toml block of the page; it is written to ``tmp_path`` and loaded with
``load_aircraft`` (so it must be a complete aircraft). Every key of the loader's key tables
(``flexsim.aircraft.toml_loader._*_KEYS``) must appear in the example, so a key added to the format without
documentation fails here (the ``[components.*.aero]`` table was missing).
"""

import re
import tomllib
from pathlib import Path

from flexsim.aircraft import toml_loader
from flexsim.aircraft.toml_loader import load_aircraft

DOC = Path(__file__).resolve().parents[2] / "docs" / "aircraft-format.md"


def _example() -> str:
    match = re.search(r"^```toml\n(.*?)^```", DOC.read_text(encoding="utf-8"), re.DOTALL | re.MULTILINE)
    assert match, "docs/aircraft-format.md has no ```toml example"
    return match.group(1)


def test_the_example_loads(tmp_path):
    path = tmp_path / "my_aircraft.toml"
    path.write_text(_example(), encoding="utf-8")
    aircraft = load_aircraft(path)
    assert aircraft.name == "my aircraft"
    assert [c.name for c in aircraft.components] == ["fuselage", "right_wing"]
    assert aircraft.components[1].aero.strips == 10 and [e.name for e in aircraft.engines] == ["right_engine"]


def test_the_example_shows_every_key_of_the_format():
    data = tomllib.loads(_example())
    components = data["components"].values()
    shown = {
        "top level": set(data),
        "components.*": set().union(*(c.keys() for c in components)),
        "components.*.aero": set().union(*(c.get("aero", {}).keys() for c in components)),
        "components.*.sections": set().union(*(c["sections"].keys() for c in components)),
        "components.*.control_surface": set().union(*(c.get("control_surface", {}).keys() for c in components)),
        "lumped_masses": set().union(*(m.keys() for m in data.get("lumped_masses", []))),
        "engines": set().union(*(m.keys() for m in data.get("engines", []))),
    }
    accepted = {
        "top level": toml_loader._TOP_KEYS, "components.*": toml_loader._COMPONENT_KEYS,
        "components.*.aero": toml_loader._AERO_KEYS, "components.*.sections": toml_loader._SECTION_KEYS,
        "components.*.control_surface": toml_loader._SURFACE_KEYS, "lumped_masses": toml_loader._MASS_KEYS,
        "engines": toml_loader._ENGINE_KEYS,
    }
    missing = {table: sorted(set(keys) - shown[table]) for table, keys in accepted.items() if set(keys) - shown[table]}
    assert not missing, f"keys the loader accepts but docs/aircraft-format.md's example does not show: {missing}"
