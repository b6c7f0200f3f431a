"""``flexsim trim`` and ``flexsim flutter`` say in one line when the linear structure is beyond its range
(flexsim.model.linear_range; its limits: tests/model/test_linear_range.py; simulate and the environments:
tests/sim/test_linear_range_summary.py, tests/envs/test_linear_range_reset.py).

* ``flexsim trim phc_hale`` at 20 km and 25 m/s: the tips deflect 7.49 m, 47 % of the 16 m semispan; the line is
  printed once, and the JSON carries it; ``flexsim trim gtm`` (4 %) prints none.
* ``flexsim flutter phc_hale --altitudes 20000 --models FS``: one line, at the flutter point (tips 8.4 m, 52 %).
* ``flexsim flutter phc_wing --wind-tunnel``: the fields only the nonlinear beam uses are named in one line.
"""

from __future__ import annotations

import json

from flexsim.cli.main import main

HALE_TRIM = ["trim", "phc_hale", "--altitude-m", "20000", "--mach", "0.0847"]


def test_flexsim_trim_says_it_in_one_line(capsys):
    assert main(HALE_TRIM) == 0
    lines = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("linear structure beyond its range")]
    assert len(lines) == 1
    assert "right_wing tip deflection -7.49 m = 47% of its 16 m length" in lines[0]
    assert lines[0].endswith("results need the geometrically nonlinear beam, Terms(nonlinear_beams=NonlinearBeams()), docs/nonlinear-beams.md")
    assert main([*HALE_TRIM, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["linear_range"] == lines[0]
    assert main(["trim", "gtm"]) == 0
    assert "linear structure beyond" not in capsys.readouterr().out


def test_flexsim_flutter_says_it_in_one_line(capsys):
    assert main(["flutter", "phc_hale", "--altitudes", "20000", "--models", "FS"]) == 0
    lines = [ln for ln in capsys.readouterr().out.splitlines() if "linear structure beyond its range" in ln]
    assert len(lines) == 1 and lines[0].endswith("— at the flutter point of FS h = 20000 m")
    assert "right_wing tip deflection -8.3" in lines[0]


def test_flexsim_flutter_names_the_fields_the_linear_structure_does_not_use(capsys):
    assert main(["flutter", "phc_wing", "--wind-tunnel", "--altitudes", "20000", "--models", "FS"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[-1] == ("sections.ei_chord_nm2 of right_wing; sections.flap_inertia_kg_m of right_wing: used by the "
                       "geometrically nonlinear beam only (docs/nonlinear-beams.md); the linear structure (the paper's) "
                       "bends each beam in one plane and twists it")
