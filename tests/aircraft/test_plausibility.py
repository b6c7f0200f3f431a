"""Validation that knows physics: plausible ranges with the field, the value and the range
in the message; derived quantities checked after assembly; size limits; singular trims named."""

import tomllib
from importlib import resources

import numpy as np
import pytest

from flexsim.aircraft.definition import PLAUSIBLE
from flexsim.aircraft.toml_loader import MAX_FILE_BYTES, load_aircraft, parse_aircraft
from flexsim.errors import AircraftDefinitionError
from flexsim.structure.model import StructuralModel
from tests.corpus import dumps


def _doc(name):
    return tomllib.loads((resources.files("flexsim.aircraft") / "data" / f"{name}.toml").read_text())


def _load(doc):
    return StructuralModel(parse_aircraft(dumps(doc), source="t.toml"))


@pytest.mark.parametrize("key, value, needle", [
    ("ei_nm2", [9.77e12, 9.77e12], "ei_nm2[0] = 9770000000000.0: outside the plausible range [1, 1e+12] N m^2"),
    ("mass_kg_per_m", [1e300, 1e300], "mass_kg_per_m[0] = 1e+300: outside the plausible range"),
    ("chord_m", [1e6, 1e6], "chord_m[0] = 1000000.0: outside the plausible range [0, 50] m"),
])
def test_section_values_outside_plausible_ranges(key, value, needle):
    doc = _doc("goland_wing")
    doc["components"]["right_wing"]["sections"][key] = value
    with pytest.raises(AircraftDefinitionError, match=needle.replace("[", r"\[").replace("+", r"\+").replace("^", r"\^")):
        _load(doc)


@pytest.mark.parametrize("length", [float("nan"), float("inf"), 6096.0, 1e-9])
def test_length_nan_inf_and_unit_mistakes(length):
    doc = _doc("goland_wing")
    doc["components"]["right_wing"]["length_m"] = length
    with pytest.raises(AircraftDefinitionError, match=r"components.right_wing.length_m = "):
        _load(doc)


def test_massless_beam_is_refused():
    doc = _doc("goland_wing")
    s = doc["components"]["right_wing"]["sections"]
    s["mass_kg_per_m"], s["cg_offset_m"] = [0.0, 0.0], [0.0, 0.0]
    with pytest.raises(AircraftDefinitionError, match="needs mass"):
        _load(doc)


def test_lumped_mass_far_from_its_component():
    doc = _doc("gtm")
    doc["lumped_masses"][0]["position_m"][1] = 200.0  # inside the position range, 200 m beside the fuselage
    with pytest.raises(AircraftDefinitionError, match=r"from the elastic axis of fuselage: a lumped mass rides on its component"):
        _load(doc)


def test_derived_elastic_frequency_checked_after_assembly():
    """Every station value plausible, but EI x 1e-6 on the GTM gives a 0.016 rad/s wing."""
    doc = _doc("gtm")
    for c in doc["components"].values():
        c["sections"]["ei_nm2"] = [v * 1e-6 for v in c["sections"]["ei_nm2"]]
        c["sections"]["gj_nm2"] = [max(1.0, v * 1e-6) for v in c["sections"]["gj_nm2"]]
    lo = PLAUSIBLE["elastic_frequency_rad_s"][0]
    with pytest.raises(AircraftDefinitionError, match=rf"clamped elastic frequency 1 of \d+ = .* outside the plausible range \[{lo:g}"):
        _load(doc)


def test_bundled_aircraft_pass_and_have_positive_definite_inertia():
    for name in ("gtm", "goland_wing", "gtm_uncalibrated"):
        mp = StructuralModel(load_aircraft(name)).mass_properties
        assert np.linalg.eigvalsh(mp.inertia_cg_kg_m2).min() > 0


def test_size_limits_fail_fast(tmp_path):
    big = tmp_path / "big.toml"
    big.write_bytes(b"#" * (MAX_FILE_BYTES + 1))
    with pytest.raises(AircraftDefinitionError, match=rf"file size = {MAX_FILE_BYTES + 1} bytes: at most {MAX_FILE_BYTES}"):
        load_aircraft(big)
    doc = _doc("goland_wing")
    s = doc["components"]["right_wing"]["sections"]
    n = 10_001
    for k in list(s):
        s[k] = [s[k][0]] * n
    s["station_m"] = list(np.linspace(0.0, 6.096, n))
    with pytest.raises(AircraftDefinitionError, match="10001 entries: at most 10000 stations"):
        parse_aircraft(dumps(doc))


def test_nesting_bom_and_empty_files(tmp_path):
    with pytest.raises(AircraftDefinitionError, match="nested too deeply"):
        parse_aircraft("x = " + "[" * 100_000 + "]" * 100_000)
    with pytest.raises(AircraftDefinitionError, match="empty"):
        parse_aircraft("   \n")
    src = (resources.files("flexsim.aircraft") / "data" / "goland_wing.toml").read_bytes()
    (tmp_path / "bom.toml").write_bytes(b"\xef\xbb\xbf" + src)
    assert load_aircraft(tmp_path / "bom.toml").name == "Goland wing"


def test_singular_trim_is_named(tmp_path):
    """1 strip per surface: the aileron sits outboard of every strip, trim used to print -1.34e6 deg."""
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.trimming import SteadyManoeuvre, TrimError, trim

    doc = _doc("gtm")
    for c in doc["components"].values():
        if "aero" in c:
            c["aero"]["strips"] = 1
    model = AircraftModel(parse_aircraft(dumps(doc)), aero="quasi-steady")
    with pytest.raises(TrimError, match="trim singular .* do not depend on aileron delta_a"):
        trim(model, SteadyManoeuvre.level(9144.0, mach=0.78), check_limits=False)


def test_restrained_aircraft_without_elastic_coordinates_is_a_clear_error():
    """m = n = 0 on a restrained wing is legal but has nothing to analyse (numpy used to fail inside)."""
    from flexsim.errors import FlexsimError
    from flexsim.linear.modes import in_vacuo_modes
    from flexsim.model.aircraft_model import AircraftModel

    model = AircraftModel(load_aircraft("goland_wing").with_modes(0, 0), variant="restrained", gravity_m_s2=0.0)
    with pytest.raises(FlexsimError, match="no degree of freedom to analyse"):
        in_vacuo_modes(model)
