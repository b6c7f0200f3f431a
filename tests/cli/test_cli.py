"""The flexsim command line: info and modes, text and JSON output, clear errors."""

import json
import subprocess
import sys

import numpy as np
import pytest

from flexsim.cli.main import main


def _run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_info_json_reports_mass_cg_inertia(capsys):
    code, out, _ = _run(capsys, "info", "gtm", "--json")
    assert code == 0
    data = json.loads(out)
    assert data["mass_kg"] == pytest.approx(100.0e3, rel=0.01)
    assert data["cg_design_m"][0] == pytest.approx(22.34, rel=0.01)
    assert len(data["inertia_cg_body_kg_m2"]) == 3


def test_info_text(capsys):
    code, out, _ = _run(capsys, "info")
    assert code == 0 and "mass" in out and "Ixx" in out


def test_modes_free_gtm_lists_six_rigid_modes(capsys):
    code, out, _ = _run(capsys, "modes", "gtm", "--json")
    data = json.loads(out)
    assert code == 0 and data["n_rigid"] == 6 and data["variant"] == "free"
    elastic = data["modes"][6]
    assert elastic["frequency_rad_s"] > 1.0 and elastic["component"] in {"wings", "fuselage"}


def test_modes_restrained_single_wing(capsys):
    code, out, _ = _run(capsys, "modes", "gtm", "--components", "right_wing", "--variant", "restrained", "--bending-modes", "3", "--torsion-modes", "2")
    assert code == 0
    assert "0 rigid-body modes" in out
    assert out.count("right_wing") >= 5


def test_toml_path_accepted(capsys, tmp_path):
    from importlib import resources

    text = (resources.files("flexsim.aircraft") / "data" / "goland_wing.toml").read_text()
    path = tmp_path / "wing.toml"
    path.write_text(text)
    code, out, _ = _run(capsys, "modes", str(path), "--variant", "restrained", "--json")
    assert code == 0 and len(json.loads(out)["modes"]) == 5


def test_bad_aircraft_gives_one_line_error(capsys, tmp_path):
    code, _, err = _run(capsys, "info", str(tmp_path / "missing.toml"))
    assert code == 2
    assert "flexsim info: error: aircraft" in err and "Traceback" not in err
    bad = tmp_path / "bad.toml"
    bad.write_text('schema_version = 1\nname = "x"\n[components.right_wing]\nroot_m = [0,0,0]\n')
    code, _, err = _run(capsys, "info", str(bad))
    assert code == 2 and "missing required field" in err


def test_console_script_entry_point():
    # The installed command (pyproject [project.scripts]) runs the same main().
    result = subprocess.run([sys.executable, "-m", "flexsim.cli.main", "modes", "goland_wing", "--variant", "restrained", "--count", "2"], capture_output=True, text=True, check=True)
    assert "right_wing bending 1" in result.stdout


def test_quick_exit_keeps_output_and_exit_code():
    """``python -m flexsim.cli.main`` ends ``info`` (and ``flutter``) with os._exit after flushing: the whole output is
    written (a JSON document that parses) and the exit code is main's (2 for a bad argument, with its message)."""
    ok = subprocess.run([sys.executable, "-m", "flexsim.cli.main", "info", "--json"], capture_output=True, text=True)
    assert ok.returncode == 0 and json.loads(ok.stdout)["aircraft"]
    bad = subprocess.run([sys.executable, "-m", "flexsim.cli.main", "flutter", "--altitudes", "-6000"], capture_output=True,
                         text=True)
    assert bad.returncode == 2 and "flexsim flutter: error: --altitudes = -6000.0" in bad.stderr and not bad.stdout


def test_aero_plot_and_gtm_lift_slopes(capsys, tmp_path):
    # The GTM sectional Cl_alpha from the vortex lattice is below 2 pi everywhere and falls
    # towards the tips (over the outboard strips, past its maximum near 85 % semispan on this notional
    # planform of taper 0.2, whose sectional cl rises outboard before the tip loss).
    plot = tmp_path / "cla.png"
    code, out, _ = _run(capsys, "aero", "gtm", "--json", "--plot", str(plot))
    assert code == 0
    assert plot.stat().st_size > 10_000 and plot.read_bytes()[:4] == b"\x89PNG"
    rows = json.loads(out)["strips"]
    for name in ("right_wing", "left_wing", "right_htail", "left_htail"):
        cla = np.array([r["lift_slope_per_rad"] for r in rows if r["component"] == name])
        assert np.all(cla < 2 * np.pi)
        assert cla[-1] < cla.max() and np.argmax(cla) >= len(cla) // 2
    code, out, _ = _run(capsys, "aero", "gtm", "--mach", "0.6", "--json")
    cla6 = np.array([r["lift_slope_per_rad"] for r in json.loads(out)["strips"]])
    cla0 = np.array([r["lift_slope_per_rad"] for r in rows])
    np.testing.assert_allclose(cla6 / cla0, 1.25, rtol=1e-12)  # Prandtl-Glauert 1/sqrt(1 - 0.36)
