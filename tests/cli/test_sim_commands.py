"""``flexsim simulate AIRCRAFT`` and ``--aircraft``: a user's aircraft flies the named manoeuvres from its own cruise
point, with a structural limit measured from its trim."""

from __future__ import annotations

import pytest

from flexsim.cli.main import main
from flexsim.sim.manoeuvres import build_manoeuvre
from tests.cli.small_aircraft import rc_glider_toml


@pytest.fixture(scope="module")
def glider(tmp_path_factory):
    path = tmp_path_factory.mktemp("rc") / "rc.toml"
    path.write_text(rc_glider_toml("min_speed_eas_m_s = 6.0\ncruise_altitude_m = 500.0\ncruise_speed_m_s = 10.0"))
    return str(path)


def test_simulate_aircraft_flies_its_doublet_at_its_cruise_point(glider, capsys):
    assert main(["simulate", glider, "--no-log", "--duration", "0.4"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("elevator-doublet: rc-glider:") and "H = 500 m (envelope.cruise_altitude_m = 500)" in out
    assert "10.00 m/s TAS (envelope.cruise_speed_m_s = 10)" in out and "reached t_end" in out
    assert main(["simulate", "aileron-roll", "--aircraft", glider, "--speed-m-s", "12", "--no-log", "--duration", "0.2"]) == 0
    assert "12.00 m/s TAS (given)" in capsys.readouterr().out


def test_structural_limit_is_measured_from_the_trim(glider):
    """The bound is the level trim's tip deflection plus simulate's default quarter of the wing length (1 m wing)."""
    setup = build_manoeuvre("elevator-doublet", aero="quasi-steady", aircraft=glider)
    tip = abs(setup.initial.summary()["tip_deflection_m"])
    assert setup.wing_tip_deflection_m == pytest.approx(tip + 0.25 * 1.0, rel=1e-12) and tip > 0.0
    assert build_manoeuvre("elevator-doublet", aero="quasi-steady").wing_tip_deflection_m is None  # the GTM: simulate's


@pytest.mark.parametrize(("argv", "message"), [
    (["simulate", "barrel-roll"], "'barrel-roll': unknown; valid manoeuvres: level-turn-entry"),
    (["simulate", "flutter-onset", "--mach", "0.1"], "mach: flutter-onset is a wind tunnel"),
    (["simulate", "climb", "--mach", "0.1", "--speed-m-s", "30"], "--mach 0.1 and --speed-m-s 30: give the speed once"),
])
def test_bad_simulate_arguments_are_refused(argv, message, capsys):
    assert main(argv) == 2
    assert message in capsys.readouterr().err


def test_script_refuses_the_aircraft_options(tmp_path, capsys):
    script = tmp_path / "s.py"
    script.write_text("raise SystemExit(0)\n")
    assert main(["simulate", str(script), "--aircraft", "gtm"]) == 2
    assert "--aircraft: apply to named manoeuvres and aircraft" in capsys.readouterr().err
