"""``flexsim trim``, ``flexsim flutter`` and ``flexsim sweep``: each command on a reduced case.

* trim: level flight at M 0.75, 9144 m flies at the ISA true airspeed M a(h) (``flexsim.atmosphere``, an
  independent conversion) with gamma = phi = 0 and load factor 1 up to the thrust's share (2 %); a level turn
  of R = 9000 m banks at tan(phi) = V^2/(g R) (point-mass coordinated-turn balance, 4 %); a 3 deg climb has gamma = 3 deg.
* flutter: one altitude, quasi-steady, physical force resolution: the JSON row equals a direct
  ``FlutterAnalysis.search`` (1e-9: the CLI reports what the library computes) and the document carries the
  paper's Table 2 row (the text table itself: tests/cli/test_paper_report.py).
* sweep: one altitude, two climb angles (0 and 3 deg): writes CSV, JSON and PNG; the 0 deg point equals the
  level-flight flutter point of ``flexsim flutter`` (zero climb is level flight; 2e-4 as in
  tests/linear/test_flutter.py).
"""

import csv
import json
import math

import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.atmosphere import speed_of_sound
from flexsim.cli.main import main
from flexsim.linear.flutter import FlutterAnalysis
from flexsim.linear.paper_data import TABLE_QS
from flexsim.model.aircraft_model import STANDARD_GRAVITY
from flexsim.trimming import SteadyManoeuvre

H = 9144.0


def _json(capsys, *argv):
    assert main(list(argv)) == 0
    return json.loads(capsys.readouterr().out)


def test_trim_level_turn_and_climb(capsys):
    level = _json(capsys, "trim", "gtm", "--altitude-m", str(H), "--mach", "0.75", "--json")
    assert level["speed_m_s"] == pytest.approx(0.75 * speed_of_sound(H), rel=1e-12)
    assert level["gamma_deg"] == pytest.approx(0.0, abs=1e-9) and level["phi_deg"] == pytest.approx(0.0, abs=1e-9)
    assert level["load_factor"] == pytest.approx(1.0, rel=0.02)
    turn = _json(capsys, "trim", "gtm", "--altitude-m", str(H), "--mach", "0.75", "--turn-radius-m", "9000", "--json")
    v = turn["speed_m_s"]
    # the aerodynamic + thrust resultant balances weight and centripetal force, |F|/W = sqrt(1 + (V^2/gR)^2) (to the
    # CG's offset from o, 0.3 %); the paper's turn slips (its side force tilts F, so tan(phi) != V^2/gR: 0.658 against
    # 0.586 measured with the fuselage moments; the coordinated turn's closed forms are in tests/trimming)
    assert turn["load_factor_total"] == pytest.approx(math.hypot(1.0, v * v / (STANDARD_GRAVITY * 9000.0)), rel=3e-3)
    assert abs(turn["sideslip_deg"]) > 1.0
    climb = _json(capsys, "trim", "gtm", "--altitude-m", str(H), "--mach", "0.75", "--climb-deg", "3", "--json")
    assert climb["gamma_deg"] == pytest.approx(3.0, abs=1e-9) and climb["thrust_kN"] > level["thrust_kN"]
    assert main(["trim", "gtm", "--altitude-m", str(H), "--mach", "0.75"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("Trim of GTM-notional-A") and "load_factor" in text and "elevator_deg" in text


@pytest.fixture(scope="module")
def level_qs():
    return FlutterAnalysis(load_aircraft("gtm"), "quasi-steady").search(SteadyManoeuvre.level(H, mach=0.5), mach_range=(0.5, 0.95))


def test_flutter_one_altitude_quasi_steady(capsys, level_qs):
    doc = _json(capsys, "flutter", "gtm", "--altitudes", str(H), "--models", "QS", "--formulation", "physical",
                "--workers", "1", "--json")
    rows = doc["rows"]
    assert len(rows) == 1
    row = rows[0]
    assert (row["model"], row["altitude_m"]) == ("QS", H) and "error" not in row
    assert row["mach"] == pytest.approx(level_qs.mach, rel=1e-9)
    assert row["omega_rad_s"] == pytest.approx(level_qs.frequency_rad_s, rel=1e-9)
    assert row["mode"] == level_qs.mode.name
    assert [list(p) for p in TABLE_QS if p[0] == H] == [list(p) for p in doc["paper"]["table_qs"] if p[0] == H]


def test_sweep_one_altitude_two_climb_angles(capsys, tmp_path, level_qs):
    out = tmp_path / "study"
    assert main(["sweep", "--climb", "gtm", "--altitudes", str(H), "--models", "QS", "--angles-deg", "0", "3",
                 "--workers", "1", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "2/2 flutter points" in printed
    rows = json.loads((out / "flutter_climb.json").read_text())
    assert [r["climb_angle_deg"] for r in rows] == [0.0, 3.0] and all("mach" in r for r in rows)
    assert rows[0]["mach"] == pytest.approx(level_qs.mach, abs=2e-4)
    assert rows[1]["gamma_deg"] == pytest.approx(3.0, abs=1e-9)
    with open(out / "flutter_climb.csv", newline="") as fh:
        table = list(csv.DictReader(fh))
    assert [float(r["mach"]) for r in table] == pytest.approx([r["mach"] for r in rows], rel=1e-12)
    for png in ("flutter_climb.png", f"flutter_climb_trim_{H:.0f}m.png"):
        assert (out / png).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_wind_tunnel_gives_the_goland_wings_flutter_and_divergence(capsys):
    """``flexsim flutter goland_wing --wind-tunnel``: the clamped Goland wing flutters at Goland's 137.2 m/s
    (Goland 1945, J. Appl. Mech. 12; 2 % as docs/validation.md's goland-flutter-theodorsen-1.225) and diverges at
    the strip-theory closed form (Hodges & Pierce 2011, ch. 4; 1e-4); the JSON row is what
    ``flexsim.linear.flutter.wind_tunnel`` computes (1e-12). Without the option the flight search's error names it,
    and a flight option with it is refused, both exit 2."""
    from flexsim.linear.flutter import wind_tunnel
    from flexsim.sim.validation import goland_divergence_closed_form

    doc = _json(capsys, "flutter", "goland_wing", "--wind-tunnel", "--models", "US", "--json")
    (row,) = doc["wind_tunnel"]
    assert row["model"] == "US" and row["altitude_m"] == 0.0 and row["first_instability"] == "flutter"
    assert row["flutter_speed_m_s"] == pytest.approx(137.2, rel=0.02)
    assert row["divergence_speed_m_s"] == pytest.approx(goland_divergence_closed_form(row["density_kg_m3"]), rel=1e-4)
    direct = wind_tunnel(load_aircraft("goland_wing"), aero_model="theodorsen")
    assert row["flutter_speed_m_s"] == pytest.approx(direct.flutter_speed_m_s, rel=1e-12)
    assert row["flutter_frequency_rad_s"] == pytest.approx(direct.flutter_frequency_rad_s, rel=1e-12)
    assert main(["flutter", "goland_wing", "--models", "QS", "--workers", "1"]) == 2
    assert "--wind-tunnel" in capsys.readouterr().err
    assert main(["flutter", "goland_wing", "--wind-tunnel", "--glide"]) == 2
    assert "--wind-tunnel: --glide describe a flight" in capsys.readouterr().err
    assert main(["flutter", "goland_wing", "--wind-tunnel", "--speed-range-m-s", "300", "10"]) == 2
    assert "--speed-range-m-s 300 10: must satisfy 0 < LO < HI [m/s]" in capsys.readouterr().err
