"""Results outside the range of the model's aerodynamics say so, where they are produced.

The strip aerodynamics are subsonic; the Prandtl-Glauert factor is capped at M 0.95 and incompressible strips have
no Mach dependence (Anderson, *Fundamentals of Aerodynamics*, 5th ed., 2011, sec. 11.4;
:mod:`flexsim.linear.validity`). Cases:

* the Goland wing in the wind tunnel at 20 km, 10-1000 m/s, incompressible strips (the bundled file): divergence
  at M 3.17 (strip-theory closed form U_D = 936 m/s at rho 0.0889 kg/m^3, Hodges & Pierce 2011, sec. 4.2; M = U_D /
  295.07 m/s) carries a note naming the Mach number and "incompressible"; with the Prandtl-Glauert factor (a new
  case of the class) the note names the cap instead; a flutter speed at M 0.73 carries none;
* the V-g diagram of the same wing at 20 km, p-k, 300-500 m/s: its crossing into instability (M > 1) is noted;
* a V-g diagram whose branches are unstable from its first speed on names them (no crossing marks them);
* an aircraft without an elastic mode: the wind tunnel says so instead of "none", the flight search's error says
  so instead of "largest elastic real part -inf";
* a flutter point whose trim is pitch-unstable (static margin < 0) says so in its warnings.
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.atmosphere import speed_of_sound
from flexsim.linear.flutter import FlutterAnalysis, FlutterNotFound, wind_tunnel
from flexsim.linear.validity import MACH_LIMIT, mach_note
from flexsim.linear.vg import vg_diagram
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.trimming import SteadyManoeuvre
from tests.linear.hale_like import write_hale

H = 20000.0


def test_mach_note_only_beyond_the_limit():
    assert mach_note("flutter", MACH_LIMIT - 1e-9, "prandtl-glauert") is None
    assert "capped at M 0.95" in mach_note("flutter", 0.9847, "prandtl-glauert")
    assert "M 1.0170" in mach_note("flutter", 1.017, "none") and "incompressible" in mach_note("flutter", 1.017, "none")


@pytest.mark.parametrize("compressibility, words", [("file", "incompressible"), ("prandtl-glauert", "capped at M 0.95")])
def test_wind_tunnel_divergence_beyond_the_subsonic_range_is_noted(compressibility, words):
    goland = load_aircraft("goland_wing")
    res = wind_tunnel(goland, aero_model="quasi-steady", speed_range=(10.0, 1000.0), speed_step=20.0, altitude_m=H,
                      compressibility=compressibility)
    assert res.divergence_speed_m_s / speed_of_sound(H) > 1.0
    (note,) = [w for w in res.warnings if w.startswith("divergence")]
    assert f"M {res.divergence_speed_m_s / speed_of_sound(H):.4f}" in note and words in note
    if res.flutter_speed_m_s is not None and res.flutter_speed_m_s / speed_of_sound(H) < MACH_LIMIT:
        assert not [w for w in res.warnings if w.startswith("flutter")]


def test_vg_crossing_beyond_the_subsonic_range_is_noted():
    goland = load_aircraft("goland_wing")
    model = AircraftModel(goland, variant="restrained", aero=AeroOptions("quasi-steady"), gravity_m_s2=0.0, altitude_m=H,
                          restrained_velocity_m_s=[300.0, 0.0, 0.0])
    d = vg_diagram(model, speeds_m_s=np.linspace(300.0, 500.0, 6), models=["US"])
    first = d.flutter("theodorsen")
    assert first is not None and first.mach > 1.0
    assert any(f"M {first.mach:.4f}" in w for w in d.warnings)
    assert d.as_dict()["warnings"] == list(d.warnings)


def test_an_aircraft_without_elastic_modes_is_named_so(tmp_path):
    rigid = load_aircraft(write_hale(tmp_path, rigid_wings=True))
    res = wind_tunnel(rigid, aero_model="quasi-steady", speed_range=(5.0, 60.0), altitude_m=H, divergence=False)
    assert res.flutter_speed_m_s is None and any("no elastic degree of freedom" in w for w in res.warnings)
    with pytest.raises(FlutterNotFound, match="no oscillatory elastic mode") as err:
        FlutterAnalysis(rigid, "quasi-steady").search(SteadyManoeuvre.level(H, mach=0.1), mach_range=(0.08, 0.17),
                                                      mach_step=0.03)
    assert "-inf" not in str(err.value)


def test_a_flutter_point_of_a_pitch_unstable_trim_says_so(tmp_path):
    """The payload 2 m aft of the wing root puts the CG behind the neutral point (static margin < 0, Etkin & Reid 1996,
    sec. 2.3): the flutter point is still found, and its warnings name the static instability of its trim."""
    aft = load_aircraft(write_hale(tmp_path, payload_x_m=2.0))
    fp = FlutterAnalysis(aft, "theodorsen").search(SteadyManoeuvre.level(H, mach=0.1), mach_range=(0.06, 0.2), mach_step=0.02)
    assert fp.trim.stability.static_margin_mac < 0.0
    (note,) = [w for w in fp.warnings if "not a stable equilibrium" in w]
    assert "statically unstable" in note and "static margin" in note


def test_vg_names_branches_unstable_over_the_whole_range(tmp_path):
    """The clamped HALE wing pair at 20 km, quasi-steady, 10-20 m/s: its first-torsion branches are unstable from
    the first speed on (the quasi-steady model's low-speed instability), so no crossing marks them; the diagram and the
    printed summary say so instead of "no flutter in the range", and the p-k ("US") branches are all stable there."""
    from flexsim.cli.flutter_commands import _vg_lines

    hale = load_aircraft(write_hale(tmp_path))
    model = AircraftModel(hale, variant="restrained", aero=AeroOptions("quasi-steady"), gravity_m_s2=0.0, altitude_m=H,
                          restrained_velocity_m_s=[10.0, 0.0, 0.0])
    d = vg_diagram(model, speeds_m_s=np.linspace(10.0, 20.0, 5), models=["QS", "US"])
    above = d.unstable_throughout("quasi-steady")
    assert any("torsion 1" in label for label in above) and d.unstable_throughout("theodorsen") == ()
    assert d.flutter("quasi-steady") is None
    text = "\n".join(_vg_lines([(d, tmp_path / "vg.png")]))
    assert "QS  unstable throughout the range" in text and above[0] in text
    assert d.plot(tmp_path / "vg.png").read_bytes()[:4] == b"\x89PNG"
