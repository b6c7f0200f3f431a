"""Flight conditions from the aircraft, not the GTM: ``trim``/``linearize`` at the file's cruise point (or a derived one,
stated), ``--speed-m-s`` beside ``--mach``, ``flutter`` over the file's altitudes, the fin's default lift slope."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import AircraftDefinitionError, parse_aircraft
from flexsim.atmosphere import isa_density, speed_of_sound
from flexsim.cli.main import main
from flexsim.linear.envelope import CRUISE_SPEED_MARGIN, DERIVED_CRUISE_ALTITUDE_M, DIVE_TO_CRUISE, cruise_point, flutter_altitudes
from flexsim.linear.study import PAPER_ALTITUDES_M
from tests.cli.small_aircraft import rc_glider_toml


def _write(tmp_path, envelope: str, name: str = "rc.toml"):
    path = tmp_path / name
    path.write_text(rc_glider_toml(envelope))
    return str(path)


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_trim_without_a_condition_flies_the_derived_cruise_point_and_says_so(tmp_path, capsys):
    """No cruise point in the file: 1000 m, at the envelope's upper end 30 m/s EAS / 1.25 (the dive speed over the
    cruise speed, CS-25.335) = 24 m/s EAS, i.e. TAS = 24 sqrt(1.225 / rho(1000 m)) (the EAS conversion of
    flexsim.linear.envelope, the same formula: to round-off); without an upper end, 1.3 x the lower end 6 m/s EAS."""
    path = _write(tmp_path, "min_speed_eas_m_s = 6.0\nmax_speed_eas_m_s = 30.0")
    out = _json(capsys, ["trim", path, "--json"])
    eas_to_tas = math.sqrt(1.225 / float(isa_density(DERIVED_CRUISE_ALTITUDE_M)))
    assert out["altitude_m"] == DERIVED_CRUISE_ALTITUDE_M
    assert out["speed_m_s"] == pytest.approx(30.0 / DIVE_TO_CRUISE * eas_to_tas, rel=1e-12)
    assert "derived: the envelope's upper end" in out["flight_condition"]
    assert main(["trim", path]) == 0
    assert "flight condition : H = 1000 m (1000 m, clear of the ground: the aircraft file gives no" in capsys.readouterr().out
    low = _json(capsys, ["trim", _write(tmp_path, "min_speed_eas_m_s = 6.0", "low.toml"), "--json"])
    assert low["speed_m_s"] == pytest.approx(CRUISE_SPEED_MARGIN * 6.0 * eas_to_tas, rel=1e-12)
    assert "derived: 1.3 x the envelope's lower end" in low["flight_condition"]


def test_trim_at_the_file_cruise_point_and_speed_option(tmp_path, capsys):
    path = _write(tmp_path, "min_speed_eas_m_s = 6.0\ncruise_altitude_m = 1000.0\ncruise_speed_m_s = 12.0")
    out = _json(capsys, ["trim", path, "--json"])
    assert out["altitude_m"] == 1000.0 and out["speed_m_s"] == pytest.approx(12.0, rel=1e-12)
    assert "envelope.cruise_speed_m_s = 12" in out["flight_condition"]
    by_speed = _json(capsys, ["trim", path, "--speed-m-s", "14", "--json"])
    by_mach = _json(capsys, ["trim", path, "--mach", repr(14.0 / speed_of_sound(1000.0)), "--json"])
    assert by_speed["speed_m_s"] == pytest.approx(14.0, rel=1e-12)
    assert by_speed["alpha_deg"] == pytest.approx(by_mach["alpha_deg"], rel=1e-9)
    with pytest.raises(SystemExit):  # argparse: not allowed with argument --mach
        main(["trim", path, "--mach", "0.03", "--speed-m-s", "10"])
    assert "--speed-m-s" in capsys.readouterr().err
    assert main(["trim", path, "--speed-m-s", "-3"]) == 2
    assert "--speed-m-s = -3.0: must be a true airspeed > 0" in capsys.readouterr().err


def test_linearize_at_the_cruise_point(tmp_path, capsys):
    path = _write(tmp_path, "cruise_altitude_m = 500.0\ncruise_mach = 0.03")
    out = _json(capsys, ["linearize", path, "--out", str(tmp_path / "lin.npz"), "--json"])
    assert "H = 500 m (envelope.cruise_altitude_m = 500), M 0.0300" in out["flight_condition"]
    assert "H = 500 m" in out["manoeuvre"]


def test_gtm_keeps_its_cruise_point_and_the_paper_altitudes():
    """The bundled GTM's cruise point (9144 m, M 0.78) and ceiling give the former defaults exactly."""
    point = cruise_point("gtm")
    assert (point.altitude_m, point.mach) == (9144.0, 0.78) and not point.derived
    altitudes, source = flutter_altitudes("gtm")
    assert altitudes == list(PAPER_ALTITUDES_M) and "envelope.max_altitude_m = 9144" in source


def test_flutter_altitudes_from_the_file(tmp_path, capsys):
    path = _write(tmp_path, "min_speed_eas_m_s = 6.0\nmax_speed_eas_m_s = 30.0")
    doc = _json(capsys, ["flutter", path, "--models", "US", "--workers", "1", "--json"])
    assert [r["altitude_m"] for r in doc["rows"]] == [0.0] and doc["altitudes_source"].startswith("sea level:")
    high = _write(tmp_path, "min_speed_eas_m_s = 6.0\nmax_speed_eas_m_s = 30.0\nmax_altitude_m = 3000.0", "high.toml")
    assert flutter_altitudes(high)[0] == [0.0, 1000.0, 2000.0, 3000.0]


def test_fin_takes_its_documented_default_lift_slope(tmp_path, capsys):
    """The glider's fin gives no lift_slope: 2 pi (docs/aircraft-format.md), the wings the vortex lattice's (< 2 pi)."""
    rows = _json(capsys, ["aero", _write(tmp_path, ""), "--json"])["strips"]
    fin = [r["lift_slope_per_rad"] for r in rows if r["component"] == "vtail"]
    wing = [r["lift_slope_per_rad"] for r in rows if r["component"] == "right_wing"]
    assert fin and np.allclose(fin, 2 * math.pi, rtol=1e-12) and max(wing) < 2 * math.pi


@pytest.mark.parametrize(("envelope", "message"), [
    ("cruise_mach = 0.05\ncruise_speed_m_s = 12.0", "envelope.cruise_speed_m_s = 12.0: give the cruise speed once"),
    ("cruise_altitude_m = 5000.0\nmax_altitude_m = 3000.0", "envelope.cruise_altitude_m = 5000.0: must not exceed"),
    ("cruise_altitude_m = 30000.0", "envelope.cruise_altitude_m = 30000.0: must be in [0.0, 20000.0]"),
    ("cruise_mach = true", "envelope.cruise_mach = True: must be a number"),
])
def test_bad_cruise_point_is_refused_with_the_field(envelope, message):
    with pytest.raises(AircraftDefinitionError, match=message.replace("[", r"\[").replace("]", r"\]")):
        parse_aircraft(rc_glider_toml(envelope))


def test_sweep_altitudes_from_the_file(tmp_path, capsys):
    path = _write(tmp_path, "min_speed_eas_m_s = 6.0\nmax_speed_eas_m_s = 30.0\ncruise_altitude_m = 600.0")
    assert main(["sweep", "--turn", path, "--models", "US", "--radii-m", "300", "--workers", "1",
                 "--out", str(tmp_path / "s"), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert sorted(r["altitude_m"] for r in rows) == [0.0, 200.0, 400.0, 600.0]
