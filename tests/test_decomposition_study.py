"""The decomposition study (``studies/manoeuvre_decomposition.py``, docs/replication.md): every switch builds its
linear models from today's model with one field of ``Terms`` changed (or changes the linearisation point), and the
command the docs quote runs."""

import importlib
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _study():
    sys.path.insert(0, str(ROOT / "studies"))
    return importlib.import_module("manoeuvre_decomposition")


def test_every_switch_is_a_term_of_the_current_model():
    """Each switch of the decomposition study builds its linear models with one field of ``Terms`` changed (or
    changes the linearisation point), on today's code: no model is patched after construction."""
    import math

    import numpy as np

    md = _study()
    from flexsim.trimming import SteadyManoeuvre, trim

    source = (ROOT / "studies" / "manoeuvre_decomposition.py").read_text(encoding="utf-8")
    assert "object.__setattr__" not in source and "NUMPY_RHS" not in source
    ac = md.configure("gtm", None, 1.0, None, None)
    dec = md.Decomposition(md.Setup(ac, 9144.0, "none", 3048.0, mach_pg=0.9))
    a = 297.0
    level = trim(dec.trim_model, SteadyManoeuvre.level(9144.0, speed_m_s=0.85 * a), check_limits=False)
    turn = trim(dec.trim_model, SteadyManoeuvre.turn(9144.0, 5000.0, speed_m_s=0.85 * a), check_limits=False)
    lay = dec.trim_model.layout
    expected = {"none": {}, "rotation": {}, "static_deformation": {}, "gravity": {"gravity_m_s2": 0.0},
                "damping": {"structural_damping": 0.0}, "prandtl_glauert": {"compressibility_mach": 0.9},
                "force_resolution": {"force_resolution": "normal"}, "fin_normal": {"force_resolution": "fin-normal"},
                "fin_drag+0.3": {"fin_drag_per_lift": 0.3}, "thrust": {"thrust_follows_deflection": False},
                "density": {"aero_density_kg_m3": "rho"},
                "aero_alpha": {"aero_velocity_offset_m_s": tuple(level.x[lay.velocity][0:3] - turn.x[lay.velocity][0:3])},
                "mass_matrix": {"inertia_q_offset_m": tuple(level.x[lay.q] - turn.x[lay.q])}}
    assert set(md.SWITCHES) | {"fin_normal", "fin_drag+0.3"} == set(expected)
    for switch, fields in expected.items():
        dec.s.switch = switch
        terms = dec.terms(turn, level)
        changed = {k: v for k, v in terms.record().items() if v != md.Terms(aero=terms.aero).record()[k]}
        assert set(changed) == set(fields), switch
        for k, v in fields.items():
            got = getattr(terms, k)
            if v == "rho":
                assert 0.9 < got < 0.91  # rho(3048 m) = 0.9046 kg/m^3 (ISA)
            elif isinstance(v, (str, bool)):
                assert got == v, switch
            else:
                np.testing.assert_array_equal(np.asarray(got, float), np.asarray(v, float))
    dec.s.switch = "rotation"
    _, _, x, _ = dec._linear_models(turn, level)
    assert np.all(x[lay.velocity.start + 3: lay.velocity.start + 6] == 0.0) and not math.isnan(x.sum())


def test_the_quoted_command_parses():
    """The C1 scorecard command docs/replication.md quotes parses with the study script's own options."""
    args = ["--scaling", '{"fuselage_ei":1.587,"wing_gj":0.816,"wing_ei":0.635,"fuselage_gj":0.907,'
            '"htail_stiffness":0.907,"vtail_stiffness":0.907}', "--mass-factor", "0.907", "--incidence", "1.81", "2.7",
            "--formulation", "paper", "--fixed-density", "3048", "--damping", "0.01", "--altitude", "9144",
            "--switches", "none", "--mode-class", "symmetric", "--json", "9144.json"]
    assert " ".join(args[2:]).replace("9144", "h") in (ROOT / "docs" / "replication.md").read_text(encoding="utf-8")
    run = subprocess.run([sys.executable, str(ROOT / "studies" / "manoeuvre_decomposition.py"), *args, "--help"],
                         capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert run.returncode == 0, run.stderr
