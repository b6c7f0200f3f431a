"""`flexsim trim --coordinated --json` reports sideslip, load factor and bank."""

import json
import math

import pytest

from flexsim.cli.main import main


def test_trim_coordinated_json(capsys):
    code = main(["trim", "gtm", "--altitude-m", "9144", "--mach", "0.78", "--turn-radius-m", "5000", "--coordinated", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert abs(out["sideslip_deg"]) < 0.05
    g_over = out["speed_m_s"] ** 2 / (9.80665 * 5000.0)
    assert math.tan(math.radians(out["bank_wind_deg"])) == pytest.approx(g_over, rel=0.01)
    assert out["load_factor_total"] == pytest.approx(1.0 / math.cos(math.radians(out["bank_wind_deg"])), rel=0.005)
    assert math.tan(math.radians(out["phi_deg"])) == pytest.approx(g_over, rel=0.01)


def test_coordinated_without_a_turn_is_a_clear_error(capsys):
    assert main(["trim", "gtm", "--coordinated"]) == 2
    assert "--coordinated: applies to turns only" in capsys.readouterr().err
