"""``flexsim flutter`` on any aircraft and manoeuvre: the search range, the manoeuvre options, the V-g diagram.

The notional 15 m sailplane (``examples/aircraft/sailplane15.toml``) in a glide at 1000 m: the search runs over its
``[envelope]`` (21-77 m/s EAS) and says so; rows without flutter name that range; the paper's columns are absent;
``--vg`` writes the diagram and ``--json`` carries its tracks, whose crossing agrees with the flutter search.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from flexsim.atmosphere import isa_density, speed_of_sound
from flexsim.cli.main import main

SAILPLANE = str(Path(__file__).resolve().parents[2] / "examples" / "aircraft" / "sailplane15.toml")
ARGS = ["flutter", SAILPLANE, "--altitudes", "1000", "--glide", "--models", "QS,US", "--workers", "1"]
#: The sailplane's envelope at 1000 m in Mach (EAS 21 and 77 m/s, ISA).
LO, HI = (v * math.sqrt(1.225 / float(isa_density(1000.0))) / speed_of_sound(1000.0) for v in (21.0, 77.0))


@pytest.fixture(scope="module")
def sailplane_run(tmp_path_factory):
    png = tmp_path_factory.mktemp("vg") / "sailplane_vg.png"
    import io
    from contextlib import redirect_stdout

    buf = io.StringIO()
    with redirect_stdout(buf):
        assert main([*ARGS, "--vg", str(png), "--vg-points", "12", "--json"]) == 0
    return json.loads(buf.getvalue()), png


def test_sailplane_search_runs_over_its_envelope_and_says_so(sailplane_run):
    doc, _ = sailplane_run
    rows = {r["model"]: r for r in doc["rows"]}
    for r in rows.values():
        assert r["mach_min"] == pytest.approx(LO, rel=1e-12) and r["mach_max"] == pytest.approx(HI, rel=1e-12)
        assert "envelope.min_speed_eas_m_s = 21" in r["search_range"] and r["climb_angle_deg"] is None
    # p-k: no flutter within the envelope (its first crossing is at 81.8 m/s TAS, just above the top at 80.8 m/s,
    # tests/test_api.py); the row says so and names the range searched
    assert f"{LO:.3f} <= M <= {HI:.3f}" in rows["US"]["error"]
    assert LO <= rows["QS"]["mach"] <= HI  # the quasi-steady model flutters inside it
    assert "paper" not in doc


def test_sailplane_vg_diagram_is_written_and_agrees_with_the_search(sailplane_run):
    """The QS crossing of the V-g diagram (refined on its branch) equals the QS flutter search's Mach within 1e-3
    (Brent to 1e-4 against regula falsi to 0.01 m/s = 3e-5 in Mach, on the same model)."""
    doc, png = sailplane_run
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    (vg,) = doc["vg"]
    assert {t["kind"] for t in vg["tracks"]} >= {"elastic", "short period", "Dutch roll"}
    qs = [r for r in doc["rows"] if r["model"] == "QS"][0]
    first = [c for c in vg["crossings"] if c["aero_model"] == "quasi-steady" and c["direction"] == "unstable"]
    assert first and first[0]["mach"] == pytest.approx(qs["mach"], abs=1e-3)


def test_text_output_names_the_range_and_has_no_paper_columns(capsys):
    assert main([*ARGS, "--models", "US"]) == 0
    out = capsys.readouterr().out
    assert f"M {LO:.3f}-{HI:.3f}" in out and "lower end: envelope.min_speed_eas_m_s = 21" in out
    assert "paper" not in out.lower().replace("the aircraft file's", "")
    assert "glide" in out


@pytest.mark.parametrize(("extra", "message"), [
    (["--glide", "--climb-deg", "3"], "--glide, --climb-deg"),
    (["--coordinated"], "--coordinated: applies to turns only"),
    (["--vg", "out.svg"], "--vg 'out.svg': must name a .png file"),
    (["--mach-min", "0.9", "--mach-max", "0.5"], "--mach-min, --mach-max = 0.9, 0.5"),
])
def test_bad_options_are_refused(capsys, extra, message):
    argv = ["flutter", SAILPLANE, "--altitudes", "1000", "--workers", "1", *extra]
    assert main(argv) == 2
    assert message in capsys.readouterr().err


def test_sweep_searches_each_case_over_the_aircraft_envelope(tmp_path, capsys):
    """``flexsim sweep`` on the mAEWing1 (no [envelope]: the stall estimate of each turn, a 6 kg UAV near M 0.03) finds
    its body-freedom flutter near M 0.099 (docs: flexsim/aircraft/data/maewing1.md) instead of searching the GTM's
    M 0.5-0.95, records the range in every row, and prints nothing of the paper for an aircraft that is not the paper's."""
    assert main(["sweep", "--turn", "maewing1", "--altitudes", "0", "--models", "US", "--radii-m", "200", "400",
                 "--workers", "1", "--out", str(tmp_path / "study")]) == 0
    text = capsys.readouterr().out
    assert "paper" not in text.lower()
    rows = json.loads((tmp_path / "study" / "flutter_turn.json").read_text())
    rows = rows["rows"] if isinstance(rows, dict) else rows
    assert len(rows) == 2
    for r in rows:
        assert "stall estimate" in r["search_range"] and r["search_range"].startswith("M 0.0")
        assert 0.09 < r["mach"] < 0.11
