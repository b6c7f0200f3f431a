"""`flexsim trim/flutter/sweep` with the formulation option and the paper comparison.

* gtm_paper weighs the paper's 889.4 kN (Tables 2-3: T_e / sin(theta) = 889.41-889.47 kN), and its level trim
  (formulation "paper" from its file) has T_e = W sin(theta) to 1e-6 (body-x equilibrium, docs/design.md).
* `flexsim flutter` labels every row with its settings and formulation, names the critical mode's symmetry and
  flags it when it is not the paper's (symmetric, q_f1 the largest linear coordinate).
* The sweep scorecard's text and JSON carry the same fields; the paper's values sit under "paper" only.
"""

import json
import math

import pytest

from flexsim.cli.main import main
from flexsim.cli.paper_report import sweep_report


def _json(capsys, *argv):
    assert main(list(argv)) == 0
    return json.loads(capsys.readouterr().out)


def test_trim_of_the_paper_aircraft_balances_thrust_and_weight(capsys):
    d = _json(capsys, "trim", "gtm_paper", "--altitude-m", "9144", "--mach", "0.7791", "--no-limits", "--json")
    assert d["formulation"] == "paper"
    assert d["weight_kN"] == pytest.approx(889.4, rel=1e-4)
    assert d["thrust_kN"] / (d["weight_kN"] * math.sin(math.radians(d["theta_deg"]))) == pytest.approx(1.0, abs=1e-6)
    d = _json(capsys, "trim", "gtm", "--formulation", "paper", "--altitude-m", "9144", "--mach", "0.7791", "--no-limits", "--json")
    assert d["formulation"] == "paper" and d["weight_kN"] == pytest.approx(980.8, rel=1e-3)


def test_flutter_prints_both_settings_labelled(capsys):
    argv = ["flutter", "gtm", "--models", "QS", "--altitudes", "9144", "--mach-min", "0.78", "--mach-max", "0.85", "--workers", "1"]
    doc = _json(capsys, *argv, "--json")
    rows = {r["settings"]: r for r in doc["rows"]}
    assert set(rows) == {"paper-replication", "physical"}
    assert rows["paper-replication"]["formulation"] == "paper" and rows["physical"]["formulation"] == "physical"
    for r in rows.values():
        assert r["mode_symmetry"] in ("symmetric", "antisymmetric", "mixed")
        assert r["aero_density_kg_m3"] == pytest.approx(0.4590, rel=1e-3) and r["aero_density_fixed"] is False  # ISA 9144 m
        assert isinstance(r["mode_matches_paper"], bool) and r["participation"]
    assert doc["paper"]["table_qs"][3][1] == 0.7329  # the paper's values only under "paper"
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "paper Table 2" in out and "M_F" in out and "w_F" in out and "T_e" in out and "[rad/s]" in out
    assert "paper-replication" in out and "physical" in out
    if not all(r["mode_matches_paper"] for r in rows.values()):
        assert "[not the paper's]" in out
    lines = out.splitlines()
    assert max(map(len, lines)) <= 100  # readable in a 100-column terminal
    assert lines[0].startswith("M_F vs the paper's: QS ") and lines[0].endswith(f"critical mode in {sum(r['mode_matches_paper'] for r in rows.values())}/2 rows")
    mach = {r["settings"]: r["mach"] for r in doc["rows"]}
    for label, r in rows.items():  # the compact comparison column: M_F and w_F against Table 2's 9144 m row [%]
        row = next(x for x in lines if x.startswith(label) and f"{r['mach']:7.4f}" in x)
        d = r["vs_paper_percent"]
        assert d["mach"] == pytest.approx(100 * (mach[label] / 0.7329 - 1))
        assert row.split()[-2:] == [f"{d['mach']:+.1f}", f"{d['omega_rad_s']:+.1f}"]


def test_sweep_scorecard_text_and_json():
    rows = []
    for g, thrust in ((-15.0, -200.0), (-5.0, -40.0), (0.0, 8.0), (15.0, 260.0)):
        rows.append({"model": "US", "altitude_m": 9144.0, "climb_angle_deg": g, "turn_radius_m": math.inf,
                     "mach": 0.9121 + 1e-4 * g, "omega_rad_s": 36.35 - 1e-3 * g, "thrust_kN": thrust})
    lines, doc = sweep_report(rows, "climb")
    trends = {t["quantity"]: t for t in doc["scorecard"]["trends"]}
    assert trends["dM_F/dgamma"]["sign"] == 1 and trends["dM_F/dgamma"]["match"] is True
    assert trends["domega_F/dgamma"]["sign"] == -1 and trends["domega_F/dgamma"]["match"] is True
    assert doc["scorecard"]["matches_US"] == [2, 2]
    glide = doc["scorecard"]["glide"][0]
    assert glide["gamma_deg"] == pytest.approx(-5.0 + 5.0 * 40.0 / 48.0)  # T_e = 0 between -5 and 0 deg
    assert doc["paper"]["glide_9144_US"]["gamma_deg"] == -3.12
    text = "\n".join(lines)
    assert "US: 2 of 2 trend signs as the paper's" in text and "paper glide at 9144 m" in text
