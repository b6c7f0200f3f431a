"""`flexsim trim` beyond the linear aerodynamics' angle-of-attack range: a clear error, or the solution with
--no-limits (the two trims that ``studies/reliability_census.py trim`` found silently beyond it; the limit is the GTM
file's ``[aero] max_alpha_deg`` = 11 deg, tests/aircraft/test_gtm_alpha_limit.py)."""

import json

import pytest

from flexsim.cli.main import main

CASES = {
    "high": (["trim", "gtm", "--altitude-m", "20000"], "21.9"),
    "slow glide": (["trim", "gtm", "--glide", "--mach", "0.3", "--altitude-m", "3000"], "18.8"),
}


@pytest.mark.parametrize("name", list(CASES))
def test_trim_beyond_the_range_is_a_one_line_error(name, capsys):
    argv, alpha = CASES[name]
    assert main(argv) == 2
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert captured.out == "" and "Traceback" not in err and len(err.splitlines()) == 1
    assert err.startswith("flexsim trim: error: trim infeasible for ")
    assert f"angle of attack alpha = {alpha}" in err
    assert "deg at the CG beyond the range of the linear (no-stall) aerodynamics, +-11 deg = [aero] max_alpha_deg" in err


@pytest.mark.parametrize("name", list(CASES))
def test_no_limits_prints_the_trim_as_asked(name, capsys):
    argv, alpha = CASES[name]
    assert main([*argv, "--no-limits", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert f"{out['alpha_deg']:.4g}".startswith(alpha)
    assert out["residual"] < 1e-8


def test_cruise_trim_is_within_the_range(capsys):
    assert main(["trim", "gtm", "--json"]) == 0
    assert 0.0 < json.loads(capsys.readouterr().out)["alpha_deg"] < 11.0
