"""Named manoeuvres, example scripts and the ``flexsim simulate`` command.

Sources and tolerances:
* Every registered manoeuvre builds and runs (short durations, quasi-steady aerodynamics where the physics
  allows); unknown names get an error listing the valid ones.
* Goland wing flutter speed with this model: 136.2 m/s (Peters N = 6, incompressible as the bundled file
  sets), within 2 % of the literature's 137.2 m/s (Goland 1945; Patil, Hodges & Cesnik 2001); flutter-onset runs at 1.05 times it.
* The example scripts run headless through ``flexsim simulate SCRIPT.py`` and write their log where --log
  says.
"""

from pathlib import Path

import numpy as np
import pytest

from flexsim.cli.main import main
from flexsim.io.flight_log import read_flight_log
from flexsim.sim.manoeuvres import build_manoeuvre, goland_flutter_speed, manoeuvre_names, pulse_schedule
from flexsim.sim.run_settings import OutputSettings

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
NAMES = ("level-turn-entry", "climb", "elevator-doublet", "aileron-roll", "gust-encounter", "flutter-onset")


def test_registry_lists_the_six_manoeuvres_and_rejects_unknown_names():
    assert manoeuvre_names() == NAMES
    with pytest.raises(ValueError, match="manoeuvre = 'barrel-roll': unknown; valid manoeuvres: level-turn-entry, climb, "
                                         "elevator-doublet, aileron-roll, gust-encounter, flutter-onset"):
        build_manoeuvre("barrel-roll")
    with pytest.raises(ValueError, match="aero = 'theodorsen': must be one of unsteady, quasi-steady"):
        build_manoeuvre("climb", aero="theodorsen")
    with pytest.raises(ValueError, match=r"duration_s = 0: must be a finite number > 0"):
        build_manoeuvre("climb", duration_s=0)


@pytest.mark.parametrize("name", NAMES)
def test_every_manoeuvre_builds_and_runs(name):
    setup = build_manoeuvre(name, aero="quasi-steady", duration_s=0.3)
    result = setup.simulate(output=OutputSettings(rate_hz=20.0))
    assert result.status == "completed" and result.t[-1] == pytest.approx(0.3)
    assert np.all(np.isfinite(result.x)) and setup.duration_s == 0.3


def test_goland_flutter_speed_and_the_flutter_onset_setup():
    speed_f = goland_flutter_speed("unsteady")
    assert speed_f == pytest.approx(136.17, abs=0.05)
    assert speed_f == pytest.approx(137.2, rel=0.02)
    setup = build_manoeuvre("flutter-onset")
    assert float(setup.metadata["tunnel_speed_m_s"]) == pytest.approx(1.05 * speed_f, rel=1e-3)


def test_pulse_schedule_is_exact_trapezoids():
    sched = pulse_schedule(np.array([1e4, 0.0, -0.1, 0.0]), [(2, 1.0, 1.5, 0.02), (2, 1.5, 2.0, -0.02)], ramp_s=0.05)
    assert sched(0.5)[2] == pytest.approx(-0.1)
    assert sched(1.025)[2] == pytest.approx(-0.09)
    assert sched(1.3)[2] == pytest.approx(-0.08)
    assert sched(1.55)[2] == pytest.approx(-0.12)
    assert sched(3.0)[2] == pytest.approx(-0.1)
    with pytest.raises(ValueError, match=r"pulse \(7, 1.0, 2.0\)"):
        pulse_schedule(np.zeros(4), [(7, 1.0, 2.0, 0.1)])


def test_cli_simulate_named_manoeuvre_writes_the_log(tmp_path, capsys):
    log = tmp_path / "gust.mcap"
    code = main(["simulate", "gust-encounter", "--duration", "0.2", "--aero", "quasi-steady", "--log", str(log)])
    out = capsys.readouterr().out
    assert code == 0 and "status: completed" in out and str(log) in out
    assert read_flight_log(log).metadata["manoeuvre"] == "gust-encounter"


def test_cli_simulate_runs_a_script(tmp_path, capsys):
    log = tmp_path / "climb.mcap"
    code = main(["simulate", str(EXAMPLES / "climb.py"), "--duration", "0.2", "--aero", "quasi-steady", "--log", str(log)])
    out = capsys.readouterr().out
    assert code == 0 and "altitude gained" in out
    assert read_flight_log(log).t[-1] == pytest.approx(0.2)


def test_cli_simulate_reports_bad_input(tmp_path, capsys):
    assert main(["simulate", "barrel-roll", "--no-log"]) == 2
    assert "valid manoeuvres: level-turn-entry" in capsys.readouterr().err
    assert main(["simulate", str(tmp_path / "missing.py")]) == 2
    assert "not found" in capsys.readouterr().err
    assert main(["simulate", "climb", "--duration", "0.1", "--aero", "quasi-steady", "--log", str(tmp_path / "x.log")]) == 2
    assert "must end in .mcap" in capsys.readouterr().err


def test_example_scripts_exist_and_use_the_registry():
    for name in NAMES:
        script = EXAMPLES / f"{name.replace('-', '_')}.py"
        text = script.read_text()
        assert f'build_manoeuvre("{name}"' in text and "script_arguments" in text
