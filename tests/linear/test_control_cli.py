"""`flexsim linearize`: the file it writes is the Python linear model of the same trim; bad input is refused with
the option, the value and the allowed range named (exit code 2, no traceback), before any computation."""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.cli.main import main
from flexsim.linear.control import INPUT_NAMES, LinearSystem, linear_system
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre, trim


def test_written_file_is_the_linear_model_of_the_trim(tmp_path, capsys):
    out = tmp_path / "climb.npz"
    assert main(["linearize", "gtm", "--altitude-m", "6096", "--mach", "0.7", "--climb-deg", "3", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "states  : 56" in text and f"written to {out}" in text
    system = LinearSystem.load(out)
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    point = trim(model, SteadyManoeuvre(system.manoeuvre.speed_m_s, 6096.0, math.inf, math.radians(3.0)))
    ref = linear_system(model, point)
    np.testing.assert_allclose(system.a, ref.a, rtol=0, atol=1e-9 * np.abs(ref.a).max())
    np.testing.assert_allclose(system.b, ref.b, rtol=0, atol=1e-9 * np.abs(ref.b).max())
    np.testing.assert_array_equal(system.c, ref.c)
    assert system.input_names == INPUT_NAMES and system.output_names == ref.output_names
    assert system.manoeuvre.climb_angle_rad == pytest.approx(math.radians(3.0), abs=1e-15)
    assert system.model.aero.model == "quasi-steady" and system.model.formulation == "physical"


def test_json_summary_of_a_turn_with_state_outputs(tmp_path, capsys):
    import json

    out = tmp_path / "turn.npz"
    assert main(["linearize", "gtm", "--altitude-m", "9144", "--mach", "0.75", "--turn-radius-m", "8000",
                 "--state-outputs", "--out", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["states"] == 56 and doc["outputs"] == 30 + 56 and doc["bytes"] == out.stat().st_size
    assert LinearSystem.load(out).manoeuvre.turn_radius_m == 8000.0


@pytest.mark.parametrize("argv, message", [
    (["--altitude-m", "9144", "--mach", "1.5"], "--mach = 1.5: must be in (0, 1)"),
    (["--altitude-m", "99000", "--mach", "0.7"], "--altitude-m = 99000.0"),
    (["--altitude-m", "9144", "--mach", "0.7", "--turn-radius-m", "50"], "--turn-radius-m = 50.0: must be |R| >= 100 m"),
    (["--altitude-m", "9144", "--mach", "0.7", "--climb-deg", "45"], "--climb-deg = 45.0: must be within +-30 deg"),
    (["--altitude-m", "9144", "--mach", "0.7", "--coordinated"], "--coordinated: applies to turns only"),
    (["--altitude-m", "9144", "--mach", "0.7", "--aero", "unsteady", "--n-inflow", "0"], "--n-inflow = 0: must be an integer in [1, 10]"),
], ids=["mach", "altitude", "radius", "climb", "coordinated", "n-inflow"])
def test_bad_options_are_named(tmp_path, capsys, argv, message):
    out = tmp_path / "x.npz"
    assert main(["linearize", "gtm", *argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flexsim linearize: error: ") and message in err and "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize("name, message", [("x.txt", "must end in .npz"), ("no/x.npz", "does not exist"),
                                           (".", "is a directory")])
def test_bad_output_paths_are_named(tmp_path, capsys, name, message):
    assert main(["linearize", "gtm", "--altitude-m", "9144", "--mach", "0.7", "--out", str(tmp_path / name)]) == 2
    err = capsys.readouterr().err
    assert "--out = " in err and message in err


def test_turn_and_climb_together_are_refused(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["linearize", "gtm", "--altitude-m", "9144", "--mach", "0.7", "--turn-radius-m", "8000", "--climb-deg", "2",
              "--out", str(tmp_path / "x.npz")])
    assert exc.value.code == 2
    assert "argument --climb-deg: not allowed with argument --turn-radius-m" in capsys.readouterr().err
