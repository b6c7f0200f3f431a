"""Messages in the command line's words: a refused value is named by the option the user typed, not by the Python
parameter or the aircraft-file field it becomes."""

from __future__ import annotations

import pytest

from flexsim.cli.main import main


@pytest.mark.parametrize(("argv", "message"), [
    (["modes", "goland_wing", "--bending-modes", "-1"], "--bending-modes = -1: must be an integer in [0, 10]"),
    (["modes", "goland_wing", "--torsion-modes", "11"], "--torsion-modes = 11: must be an integer in [0, 10]"),
    (["flutter", "goland_wing", "--models", "US,us"], "--models 'US,us': names a model twice"),
    (["sweep", "--turn", "--models", "QS,FS,QS"], "--models 'QS,FS,QS': names a model twice"),
    (["simulate", "climb", "--duration", "nan", "--no-log"], "--duration = nan: must be a finite number > 0 [s]"),
])
def test_refusals_name_the_option(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and "components." not in err and "duration_s" not in err


def test_unknown_component_is_named_plainly(capsys):
    assert main(["info", "gtm", "--components", "wing"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flexsim info: error: component 'wing' not in aircraft") and '"' not in err
