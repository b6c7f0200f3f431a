"""One name per mode, symmetric and antisymmetric named as such, in every output.

* :func:`flexsim.structure.mode_names.pair_name`: right_/left_ components name the pair ("wings").
* The HALE aircraft of tests/linear/hale_like.py (Patil, Hodges & Cesnik 2001 wing, left-right symmetric): its first
  in-vacuo elastic modes are the wings' first bending, symmetric then antisymmetric (a free-free beam pair: the
  symmetric mode is the lower, Meirovitch, *Fundamentals of Vibrations*, 2001, sec. 8.10), named so and never by one
  side; the quasi-steady trim's verdict names the two first-torsion roots "(symmetric)" and "(antisymmetric)"; with
  ``--roots`` the verdict comes from the roots printed (their model named) and names every unstable root as the
  table does, rigid-body roots by their flight-dynamics name (e.g. "spiral [v]").
* A fast real rigid-body root is an aperiodic divergence: "statically unstable", never "dynamically" (Etkin & Reid,
  *Dynamics of Flight*, 1996, ch. 6: a real root is a non-oscillatory mode).
* The flutter table, the V-g summary and the mode recording give the flutter point of the same flight one name
  (the sailplane of examples/aircraft in a glide, quasi-steady: its critical mode is the wings' antisymmetric
  torsion, not the body rate "p" that carries the largest share of its whole eigenvector).
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.cli.main import main
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.structure.mode_names import pair_name
from flexsim.trimming import SteadyManoeuvre, trim
from flexsim.trimming.equilibrium import _rigid_root
from tests.linear.hale_like import write_hale

SAILPLANE = str(Path(__file__).resolve().parents[2] / "examples" / "aircraft" / "sailplane15.toml")


def test_pair_names():
    assert pair_name("right_wing torsion 1", "left_wing torsion 1") == "wings torsion 1"
    assert pair_name("left_htail bending 2", "right_htail bending 2") == "htails bending 2"
    assert pair_name("wing_a bending 1", "wing_b bending 1") == "wing_a/wing_b bending 1"


@pytest.fixture(scope="module")
def hale_path(tmp_path_factory):
    return write_hale(tmp_path_factory.mktemp("hale"))


def test_in_vacuo_modes_name_the_pair_and_its_symmetry(hale_path):
    modes = in_vacuo_modes(AircraftModel(load_aircraft(hale_path), aero=None, gravity_m_s2=0.0))
    elastic = [m.dominant_dof for m in modes.modes[modes.n_rigid:]]
    assert elastic[:2] == ["wings bending 1 (symmetric)", "wings bending 1 (antisymmetric)"]
    assert not any(n.startswith(("right_", "left_")) for n in elastic if not n.endswith("(mixed)"))


def test_trim_verdict_names_both_torsion_roots_by_their_symmetry(hale_path):
    model = AircraftModel(load_aircraft(hale_path), aero=AeroOptions("quasi-steady"))
    point = trim(model, SteadyManoeuvre.level(20000.0, mach=0.0847), check_limits=False)
    names = [r.name for r in point.stability.unstable if r.kind == "elastic"]
    assert "wings torsion 1 (symmetric)" in names and "wings torsion 1 (antisymmetric)" in names
    assert point.stability.aero_model == "quasi-steady"


def test_trim_roots_verdict_comes_from_the_printed_roots(hale_path, capsys):
    argv = ["trim", str(hale_path), "--altitude-m", "20000", "--mach", "0.0847", "--roots"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "(unsteady roots)" in out and "(quasi-steady roots)" not in out
    assert main([*argv, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["stability"]["aero_model"] == "unsteady"
    printed = {(round(m["real"], 6), round(abs(m["imag"]), 6)): m["name"] for m in doc["roots"]["modes"]}
    for r in doc["stability"]["unstable"]:
        same = r["name"] if r["kind"] != "rigid" else f"{r['name']} [{r['coordinate']}]"  # as describe() prints it
        assert printed[(round(r["real"], 6), round(abs(r["imag"]), 6))] == same
        if r["imag"] == 0.0:
            assert r["verdict"] != "dynamically unstable"


@pytest.mark.parametrize("coordinate", ["u", "v", "r", "p"])
def test_a_fast_real_rigid_root_is_a_static_divergence(coordinate):
    name, verdict = _rigid_root(complex(math.log(2.0) / 1.0, 0.0), coordinate)  # doubles in 1 s
    assert verdict == "statically unstable"
    assert _rigid_root(complex(0.1, 2.0), "u")[1] == "dynamically unstable"


def test_flutter_table_and_vg_name_the_flutter_point_alike(tmp_path, capsys):
    png = tmp_path / "vg.png"
    argv = ["flutter", SAILPLANE, "--altitudes", "1000", "--glide", "--models", "QS", "--workers", "1",
            "--vg", str(png), "--vg-points", "12", "--json"]
    assert main(argv) == 0
    doc = json.loads(capsys.readouterr().out)
    (row,) = doc["rows"]
    (vg,) = doc["vg"]
    first = next(c for c in vg["crossings"] if c["kind"] == "elastic" and c["direction"] == "unstable")
    assert row["mode"] == first["label"]
    assert abs(row["mach"] * vg["speed_of_sound_m_s"] - first["speed_m_s"]) < 0.05  # the same point (Brent 1e-4 in M)
    assert row["mode"].endswith(("(symmetric)", "(antisymmetric)")) and row["mode"] not in ("p", "q", "r")
