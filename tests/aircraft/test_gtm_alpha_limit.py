"""The GTM's angle-of-attack limit ``[aero] max_alpha_deg`` comes from NASA's T2 wind-tunnel database.

Source: ``flexsim/aircraft/data/sources/t2_aero_basic_beta0.csv`` (NASA GTM_DesignSim commit 9717143,
``T2_polynomial_aerodatabase.mat``, C6_bas at beta = 0). The limit is the largest tabulated alpha up to which the
normal-force coefficient CN = -CZ stays within 10 % of its least-squares line over alpha = 0-6 deg: 11 deg
(8.2 % below the line; 12.6 % below at 12 deg), the figures quoted in docs/aircraft-format.md and
flexsim/aircraft/definition.py.
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.definition import DEFAULT_MAX_ALPHA_DEG, AeroSettings
from flexsim.aircraft.t2_data import t2_linear_alpha_limit_deg
from flexsim.aircraft.toml_loader import load_aircraft, parse_aircraft
from flexsim.errors import AircraftDefinitionError


def test_limit_is_the_end_of_the_t2_linear_lift_range():
    alpha_deg, shortfall = t2_linear_alpha_limit_deg()
    assert alpha_deg == 11.0
    assert shortfall == pytest.approx(0.082, abs=5e-4)
    # one step further the lift is 12.6 % below the line: the 10 % tolerance falls between the two
    assert t2_linear_alpha_limit_deg(tolerance=0.125)[0] == 11.0
    assert t2_linear_alpha_limit_deg(tolerance=0.127)[0] == 12.0


@pytest.mark.parametrize("name", ["gtm", "gtm_uncalibrated", "gtm_paper"])
def test_bundled_gtm_files_carry_the_source_value(name):
    limit = load_aircraft(name).aero_settings.max_alpha_rad
    assert math.degrees(limit) == pytest.approx(t2_linear_alpha_limit_deg()[0], abs=1e-12)


def test_default_is_the_gtm_value():
    assert DEFAULT_MAX_ALPHA_DEG == t2_linear_alpha_limit_deg()[0]
    assert AeroSettings().max_alpha_rad == pytest.approx(np.deg2rad(DEFAULT_MAX_ALPHA_DEG), rel=1e-15)
    goland = load_aircraft("goland_wing")  # a file without the key
    assert goland.aero_settings.max_alpha_rad == AeroSettings().max_alpha_rad


def _gtm_with(line: str) -> str:
    text = load_aircraft("gtm").source
    toml = open(text, encoding="utf-8").read()
    return toml.replace("max_alpha_deg = 11.0", line, 1)


def test_file_value_is_read_in_degrees():
    ac = parse_aircraft(_gtm_with("max_alpha_deg = 14.5"), "x.toml")
    assert ac.aero_settings.max_alpha_rad == pytest.approx(math.radians(14.5), rel=1e-15)


@pytest.mark.parametrize("value, shown", [("0.0", "0.0"), ("-5", "-5.0"), ("45", "45.0"), ("nan", "nan"), ("inf", "inf")])
def test_bad_file_value_names_the_key_value_and_range(value, shown):
    with pytest.raises(AircraftDefinitionError, match=rf"aero\.max_alpha_deg = {shown}: must be in \(0, 30\] deg"):
        parse_aircraft(_gtm_with(f"max_alpha_deg = {value}"), "x.toml")
    with pytest.raises(AircraftDefinitionError, match=r"aero\.max_alpha_deg = '11': must be a number"):
        parse_aircraft(_gtm_with('max_alpha_deg = "11"'), "x.toml")
