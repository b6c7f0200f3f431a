"""``flexsim flutter --wind-tunnel``: the components asked for, each model's failure in its own row, the options that
belong to it refused elsewhere, and messages in the command line's words."""

from __future__ import annotations

import json

import pytest

import flexsim.linear.flutter as flutter_module
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.cli.main import main
from flexsim.cli.validation import in_user_words
from tests.cli.small_aircraft import rc_glider_toml


@pytest.fixture(scope="module")
def glider(tmp_path_factory):
    path = tmp_path_factory.mktemp("rc") / "rc.toml"
    path.write_text(rc_glider_toml())
    return path


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_components_are_the_structure_in_the_tunnel(glider, capsys):
    """The CLI's wing alone is the API's ``aircraft.subset(["right_wing"])`` (the same computation: equal to round-off),
    and it differs from the whole aircraft clamped at its body origin (the wing's divergence, a torsion-bending static
    instability of the 1 m cantilever, is far above the whole aircraft's, whose fuselage and tail diverge first)."""
    argv = ["flutter", str(glider), "--wind-tunnel", "--models", "US", "--speed-range-m-s", "5", "150", "--json"]
    wing = _json(capsys, [*argv, "--components", "right_wing"])
    whole = _json(capsys, argv)
    api = flutter_module.wind_tunnel(load_aircraft(glider).subset(["right_wing"]), aero_model="theodorsen",
                                     speed_range=(5.0, 150.0))
    (row,) = wing["wind_tunnel"]
    assert wing["components"] == ["right_wing"] and whole["components"][0] == "fuselage"
    assert row["divergence_speed_m_s"] == pytest.approx(api.divergence_speed_m_s, rel=1e-9)
    assert row["flutter_speed_m_s"] == api.flutter_speed_m_s or row["flutter_speed_m_s"] == pytest.approx(
        api.flutter_speed_m_s, rel=1e-9)
    assert whole["wind_tunnel"][0]["divergence_speed_m_s"] != pytest.approx(row["divergence_speed_m_s"], rel=0.05)


def test_one_model_failing_leaves_the_others_rows(glider, capsys, monkeypatch):
    """A model whose search fails is reported in its own row (in the option's words); the others' results stand."""
    real = flutter_module.wind_tunnel

    def failing_qs(aircraft, *, aero_model, **kw):
        if aero_model == "quasi-steady":
            raise flutter_module.FlutterNotFound("quasi-steady: an elastic mode is already unstable at the lowest speed "
                                                 "5 m/s (growth rate 0.1 1/s); lower speed_range[0]")
        return real(aircraft, aero_model=aero_model, **kw)

    monkeypatch.setattr(flutter_module, "wind_tunnel", failing_qs)
    argv = ["flutter", str(glider), "--wind-tunnel", "--components", "right_wing", "--models", "QS,US",
            "--speed-range-m-s", "5", "150"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    qs_line = next(line for line in out.splitlines() if line.startswith("QS"))
    us_line = next(line for line in out.splitlines() if line.startswith("US"))
    assert "no result" in qs_line and "lower the lower speed of --speed-range-m-s" in qs_line
    assert "speed_range[0]" not in out and "divergence" in us_line
    doc = _json(capsys, [*argv, "--json"])
    rows = {r["model"]: r for r in doc["wind_tunnel"]}
    assert "error" in rows["QS"] and rows["US"]["divergence_speed_m_s"] > 5.0


@pytest.mark.parametrize(("extra", "message"), [
    (["--speed-range-m-s", "5", "60"], "--speed-range-m-s: apply to --wind-tunnel"),
    (["--components", "right_wing"], "--components: apply to --wind-tunnel"),
])
def test_tunnel_options_without_the_tunnel_are_refused(glider, capsys, extra, message):
    assert main(["flutter", str(glider), "--models", "US", *extra]) == 2
    assert message in capsys.readouterr().err


@pytest.mark.parametrize(("extra", "flag"), [(["--workers", "2"], "--workers"), (["--mach-min", "0.1"], "--mach-min")])
def test_flight_options_in_the_tunnel_are_refused(glider, capsys, extra, flag):
    assert main(["flutter", str(glider), "--wind-tunnel", *extra]) == 2
    err = capsys.readouterr().err
    assert f"--wind-tunnel: {flag} describe a flight" in err


def test_vg_points_without_vg_in_the_tunnel_are_refused(glider, capsys):
    """--vg draws a V-g diagram in the tunnel too; its points without --vg are refused as in a flight."""
    assert main(["flutter", str(glider), "--wind-tunnel", "--vg-points", "9"]) == 2
    assert "--vg-points 9: applies to --vg" in capsys.readouterr().err


@pytest.mark.parametrize(("api", "option"), [("lower mach_range[0]", "lower --mach-min"),
                                             ("raise mach_range[1].", "raise --mach-max."),
                                             ("speed_range = (1, 2)", "--speed-range-m-s = (1, 2)")])
def test_messages_name_the_options(api, option):
    assert in_user_words(api) == option
    assert in_user_words("envelope.cruise_altitude_m = 3") == "envelope.cruise_altitude_m = 3"  # a file's field: kept
