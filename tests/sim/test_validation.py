"""`flexsim validate`: every built-in case is a test, user case files, and the CLI.

The references, sources and tolerances are in :mod:`flexsim.sim.validation` and docs/validation.md; each case
asserts |error| <= its tolerance against a published value or a closed form.
"""

import json
import math

import pytest

from flexsim.cli.main import main
from flexsim.sim.validation import builtin_cases, case_names, goland_divergence_closed_form, load_case, run_case


@pytest.mark.parametrize("name", case_names())
def test_builtin_case_passes(name):
    result = run_case(builtin_cases()[name])
    assert not result.error, result.error
    assert result.checks
    for c in result.checks:
        assert c.passed, f"{name}: {c.quantity} = {c.value} vs {c.reference} (error {c.error:.3g}, tol {c.tolerance})"


def test_divergence_closed_form_value():
    # Hodges & Pierce ch. 4 with the Goland data: 252.28 m/s at sea level, scaling as 1/sqrt(rho)
    assert goland_divergence_closed_form(1.225) == pytest.approx(252.278, abs=1e-3)
    assert goland_divergence_closed_form(1.02) == pytest.approx(goland_divergence_closed_form(1.225) * math.sqrt(1.225 / 1.02))


def _write(tmp_path, text):
    path = tmp_path / "case.toml"
    path.write_text(text)
    return path


def test_user_wind_tunnel_case_from_a_file(tmp_path):
    path = _write(tmp_path, '''
name = "goland divergence, my file"
kind = "wind-tunnel"
aircraft = "goland_wing"
aero_model = "quasi-steady"
density_kg_m3 = 1.225
speed_range_m_s = [200.0, 300.0]
speed_step_m_s = 25.0
[reference.divergence_speed_m_s]
value = 252.28
tolerance = 1e-4
source = "Hodges & Pierce ch. 4"
''')
    case = load_case(path)
    assert case.name == "goland divergence, my file"
    result = run_case(case)
    assert result.passed and result.checks[0].value == pytest.approx(252.278, rel=1e-5)


def test_user_case_that_misses_fails_and_the_cli_exits_1(tmp_path, capsys):
    path = _write(tmp_path, '''
kind = "wind-tunnel"
aircraft = "goland_wing"
aero_model = "quasi-steady"
speed_range_m_s = [200.0, 300.0]
speed_step_m_s = 25.0
[reference.divergence_speed_m_s]
value = 300.0
tolerance = 0.01
''')
    assert main(["validate", str(path), "--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    check = out["cases"][0]["checks"][0]
    assert not out["passed"] and check["pass"] is False and check["error"] == pytest.approx(252.278 / 300.0 - 1, rel=1e-4)


@pytest.mark.parametrize("text, fragment", [
    ('kind = "flight"\naircraft = "gtm"\n', "kind = 'flight'"),
    ('kind = "trim"\nmach = 0.7\naltitude_m = 0.0\n[reference.load_factor]\nvalue = 1.0\ntolerance = 0.1\n', "aircraft: missing"),
    ('aircraft = "gtm"\nspeed_range_m_s = [1.0, 2.0]\n', "reference: missing"),
    ('aircraft = "gtm"\nspeed_range_m_s = [1.0, 2.0]\n[reference.lift]\nvalue = 1.0\ntolerance = 0.1\n', "reference.lift"),
    ('aircraft = "gtm"\nspeed_range_m_s = [1.0, 2.0]\n[reference.flutter_speed_m_s]\nvalue = 1.0\ntolerance = 2\n', "tolerance = 2"),
    ('aircraft = "gtm"\nspeed = 3\n', "speed: unknown key"),
])
def test_bad_case_files_name_the_field(tmp_path, text, fragment):
    with pytest.raises(ValueError, match=fragment.replace("[", r"\[").replace("(", r"\(")):
        load_case(_write(tmp_path, text))


def test_cli_unknown_case_is_a_clear_error(capsys):
    assert main(["validate", "no-such-case"]) == 2
    assert "neither a built-in case" in capsys.readouterr().err
