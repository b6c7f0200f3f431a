"""The top-level API: ``import flexsim as fs`` (lazy), ``fs.flutter`` on the user's model, the flutter search range."""

from __future__ import annotations

import dataclasses
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import flexsim as fs
from flexsim.errors import AircraftDefinitionError
from flexsim.aircraft.toml_loader import parse_aircraft
from flexsim.atmosphere import isa_density, speed_of_sound
from tests.installed import child_env

ROOT = Path(__file__).resolve().parents[1]
SAILPLANE = ROOT / "examples" / "aircraft" / "sailplane15.toml"


def test_import_flexsim_loads_no_numerical_library():
    """``import flexsim`` is cheap: numpy, scipy and numba are imported only when an API name is first used."""
    code = ("import sys, flexsim; heavy = [m for m in ('numpy', 'scipy', 'numba') if m in sys.modules]; print(heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120,
                         env=child_env(base={"PATH": ""}, safe_path=True))
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


def test_every_api_name_resolves_and_is_the_documented_object():
    from flexsim.linear.flutter import flutter
    from flexsim.sim.disturbances import DrydenTurbulence, OneMinusCosineGust
    from flexsim.trimming.solver import trim

    for name in fs.__all__:
        assert getattr(fs, name) is not None, name
    assert fs.trim is trim and fs.flutter is flutter
    assert fs.OneMinusCosineGust is OneMinusCosineGust and fs.DrydenTurbulence is DrydenTurbulence
    assert set(dir(fs)) >= set(fs.__all__)
    with pytest.raises(AttributeError, match="no attribute 'nonexistent'"):
        fs.nonexistent  # noqa: B018


def test_fs_trim_stays_the_function_after_the_subpackage_is_imported():
    """``fs.trim`` is the function, whatever subpackage was imported before (the solver's, imported by the rest)."""
    import flexsim.trimming.solver  # noqa: F401 - binds the subpackage on its parent, which must not win
    from flexsim.trimming import TrimPoint

    assert callable(fs.trim) and fs.trim.__name__ == "trim"
    assert TrimPoint.__module__ == "flexsim.trimming.solver"


@pytest.fixture(scope="module")
def gtm():
    return fs.load_aircraft("gtm")


def test_flutter_analysis_of_a_model_uses_that_model_and_its_options(gtm):
    """Built from a model: the model itself where it is of the kind needed, siblings sharing its aircraft object
    (no file re-loaded) and its options otherwise."""
    qs = fs.AircraftModel(gtm, aero=fs.AeroOptions("quasi-steady", formulation="paper"), structural_damping=0.0)
    an = fs.FlutterAnalysis.from_model(qs, "theodorsen")
    assert an.qs is qs and an.qs_linear is qs
    assert an.fs.aircraft is gtm and an.fs.aero.options.model == "unsteady"
    assert an.fs.formulation == "paper" and an.fs.terms.structural_damping == 0.0
    fs_model = fs.AircraftModel(gtm, aero=fs.AeroOptions("unsteady", n_inflow=4))
    an = fs.FlutterAnalysis.from_model(fs_model, "unsteady")
    assert an.fs is fs_model and an.qs.aero.options.model == "quasi-steady" and an.qs.aircraft is gtm


def test_flutter_of_a_model_equals_the_analysis_of_its_aircraft(gtm):
    """The same search from the model and from the aircraft: the same flutter point, bit for bit."""
    man = fs.SteadyManoeuvre.level(9144.0, mach=0.8)
    model = fs.AircraftModel(gtm, aero="quasi-steady")
    a = fs.flutter(model, man, "quasi-steady", mach_range=(0.78, 0.85))
    from flexsim.linear.flutter import scan_step

    b = fs.FlutterAnalysis(gtm, "quasi-steady").search(man, mach_range=(0.78, 0.85), mach_step=scan_step((0.78, 0.85)))
    assert a.mach == b.mach and a.frequency_rad_s == b.frequency_rad_s
    assert a.mach_range == (0.78, 0.85)


def test_flutter_refuses_models_it_cannot_search(gtm):
    with pytest.raises(ValueError, match="wind_tunnel"):
        fs.flutter(fs.AircraftModel(gtm, variant="restrained", aero="quasi-steady"), fs.SteadyManoeuvre.level(0.0, mach=0.6))
    with pytest.raises(ValueError, match="without aerodynamics"):
        fs.flutter(fs.AircraftModel(gtm, aero=None), fs.SteadyManoeuvre.level(0.0, mach=0.6))
    with pytest.raises(ValueError, match="structural_damping: set on the model"):
        fs.FlutterAnalysis(fs.AircraftModel(gtm, aero="quasi-steady"), structural_damping=0.0)
    with pytest.raises(TypeError, match="AircraftModel"):
        fs.FlutterAnalysis.from_model(gtm)


def test_search_range_of_the_paper_aircraft_is_its_envelope(gtm):
    model = fs.AircraftModel(gtm, aero="quasi-steady")
    r = fs.search_range(model, fs.SteadyManoeuvre.level(9144.0, mach=0.6))
    assert (r.mach_min, r.mach_max) == (0.5, 0.95)
    assert "envelope.min_mach" in r.lower_source and "envelope.max_mach" in r.upper_source
    r = fs.search_range(model, fs.SteadyManoeuvre.level(9144.0, mach=0.6), mach_min=0.6)
    assert r.mach_min == 0.6 and r.lower_source == "given"


def test_search_range_converts_equivalent_airspeeds_at_the_altitude():
    """V_TAS = V_EAS sqrt(rho_0 / rho(h)) (ISA), M = V_TAS / a(h): the sailplane's 21 and 77 m/s EAS at 1000 m."""
    sailplane = fs.load_aircraft(str(SAILPLANE))
    r = fs.search_range(fs.AircraftModel(sailplane, aero="quasi-steady"), fs.SteadyManoeuvre.glide(1000.0, mach=0.1))
    factor = math.sqrt(1.225 / float(isa_density(1000.0))) / speed_of_sound(1000.0)
    assert r.mach_min == pytest.approx(21.0 * factor, rel=1e-12)
    assert r.mach_max == pytest.approx(77.0 * factor, rel=1e-12)


def test_stall_estimate_without_an_envelope_trims_at_the_alpha_limit(gtm):
    """Without [envelope], the lower end is the estimated stall: the level trim there flies at max_alpha_deg (within
    0.1 deg: the secant stops at 1e-3 in Mach, where d alpha / dM is about 70 deg per unit Mach for the GTM)."""
    model = fs.AircraftModel(dataclasses.replace(gtm, envelope=None), aero="quasi-steady")
    r = fs.search_range(model, fs.SteadyManoeuvre.level(0.0, mach=0.6))
    assert "stall estimate" in r.lower_source and r.mach_max == 0.95
    point = fs.trim(model, fs.SteadyManoeuvre.level(0.0, mach=r.mach_min), check_limits=False)
    assert math.degrees(point.alpha) == pytest.approx(math.degrees(gtm.aero_settings.max_alpha_rad), abs=0.1)


def test_no_flutter_in_the_envelope_says_where_it_searched():
    """The sailplane in a glide at 1000 m: no finite-state flutter within its envelope; the error names the range."""
    sailplane = fs.load_aircraft(str(SAILPLANE))
    model = fs.AircraftModel(sailplane, aero="unsteady")
    with pytest.raises(fs.FlutterNotFound) as info:
        fs.flutter(model, fs.SteadyManoeuvre.glide(1000.0, mach=0.1), "unsteady")
    lo, hi = info.value.mach_range
    assert f"{lo:.3f} <= M <= {hi:.3f}" in str(info.value)
    assert hi == pytest.approx(77.0 * math.sqrt(1.225 / float(isa_density(1000.0))) / speed_of_sound(1000.0))
    # searched beyond the envelope, the same model does flutter: the statement above is about the range, not a
    # model that cannot flutter
    beyond = fs.flutter(model, fs.SteadyManoeuvre.glide(1000.0, mach=0.1), "unsteady", mach_range=(hi, 0.35))
    assert hi < beyond.mach < 0.35


_MINIMAL = """
schema_version = 1
name = "x"
[components.right_wing]
root_m = [0.0, 0.0, 0.0]
euler_deg = [0.0, 0.0, 90.0]
length_m = 5.0
[components.right_wing.sections]
station_m = [0.0, 5.0]
mass_kg_per_m = [10.0, 10.0]
torsional_inertia_kg_m = [1.0, 1.0]
ei_nm2 = [1e6, 1e6]
gj_nm2 = [1e5, 1e5]
chord_m = [1.0, 1.0]
"""


@pytest.mark.parametrize(("table", "message"), [
    ("max_mach = 1.5", "envelope.max_mach = 1.5: must be in (0.0, 0.99]"),
    ("min_mach = 0.5\nmax_mach = 0.4", "envelope.min_mach = 0.5: must be below envelope.max_mach = 0.4"),
    ("max_speed_kmh = 200", "envelope.max_speed_kmh: unknown key"),
    ("min_speed_eas_m_s = \"fast\"", "envelope.min_speed_eas_m_s = 'fast': must be a number"),
])
def test_bad_envelope_is_refused_naming_the_field(table, message):
    with pytest.raises(AircraftDefinitionError, match=re.escape(message)):
        parse_aircraft(_MINIMAL + "\n[envelope]\n" + table + "\n", "x.toml")


def test_envelope_is_read_and_optional():
    assert parse_aircraft(_MINIMAL, "x.toml").envelope is None
    env = parse_aircraft(_MINIMAL + "\n[envelope]\nmax_speed_eas_m_s = 60\n", "x.toml").envelope
    assert env.max_speed_eas_m_s == 60.0 and env.min_mach is None
    assert np.isfinite(env.max_speed_eas_m_s)


def test_scan_step_is_the_papers_on_its_range_and_finer_on_a_narrow_one():
    from flexsim.linear.flutter import scan_step

    assert scan_step((0.5, 0.95)) == 0.05
    assert scan_step((0.066, 0.24)) == pytest.approx(0.174 / 8, rel=1e-12)


def test_stall_estimate_of_a_slow_aircraft_is_refitted_near_its_stall():
    """The 6 kg mAEWing1 trims at nearly the same alpha at M 0.3 and 0.6 (the secant's first two points), so the first
    extrapolation falls below M 0.01; it is clamped and refitted there, and ends where the level trim flies at
    max_alpha_deg (within 1 deg: d alpha / dM is about 700 deg per unit Mach near M 0.03, the secant stops at 1e-3)."""
    wing = fs.load_aircraft("maewing1")
    model = fs.AircraftModel(wing, aero="quasi-steady")
    r = fs.search_range(model, fs.SteadyManoeuvre.level(0.0, mach=0.05))
    assert "stall estimate" in r.lower_source and 0.01 < r.mach_min < 0.05
    point = fs.trim(model, fs.SteadyManoeuvre.level(0.0, mach=r.mach_min), check_limits=False)
    assert math.degrees(point.alpha) == pytest.approx(math.degrees(wing.aero_settings.max_alpha_rad), abs=1.0)
