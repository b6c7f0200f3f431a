"""``flexsim trim --nonlinear-beams`` and ``flexsim flutter --nonlinear-beams``: the command prints what the API computes
for the model with the geometrically nonlinear beams (to the printed digits), and refuses what it cannot honour."""

from __future__ import annotations

import json

import numpy as np
import pytest

import flexsim as fs
from flexsim.cli.main import main
from flexsim.model.terms import NonlinearBeams

#: Speed of sound at 20 km [m/s] (ISA, 216.65 K): the flutter scan below, 34-40 m/s, in Mach.
A_20KM = 295.0696


def _run(argv, capsys):
    code = main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_trim_prints_the_nonlinear_trim(capsys):
    code, out, _ = _run(["trim", "phc_hale", "--nonlinear-beams", "4", "--json"], capsys)
    assert code == 0
    doc = json.loads(out)
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(nonlinear_beams=NonlinearBeams(4)))
    point = fs.trim(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0))
    assert doc["alpha_deg"] == pytest.approx(point.alpha_rad * 57.29577951308232, rel=1e-12)
    assert doc["terms"]["nonlinear_beams"] == {"elements_per_beam": 4, "stability": "clamped-wing"}
    assert doc["tip_deflection_fraction"]["right_wing"] == pytest.approx(point.tip_deflection_fraction[0], rel=1e-12)


def test_trim_prints_the_named_roots_about_the_nonlinear_trim(capsys):
    code, out, _ = _run(["trim", "phc_hale", "--nonlinear-beams", "4", "--roots", "quasi-steady", "--json"], capsys)
    assert code == 0
    doc = json.loads(out)
    names = [r["name"] for r in doc["roots"]]
    assert "phugoid" in names and "short period" in names and doc["verdict"].startswith(("stable", "unstable"))
    code, out, _ = _run(["trim", "phc_hale", "--nonlinear-beams", "4", "--roots", "--json"], capsys)  # unsteady
    assert code == 0
    unsteady = json.loads(out)
    assert "unsteady strips" in unsteady["verdict"] and "phugoid" in [r["name"] for r in unsteady["roots"]]
    code, out, _ = _run(["trim", "phc_hale", "--nonlinear-beams", "4", "--roots", "--turn-radius-m", "1000", "--json"],
                        capsys)
    assert code == 0 and json.loads(out)["verdict"].startswith("stable about the nonlinear trim (unsteady strips")


def test_flutter_prints_the_nonlinear_flutter_point(capsys):
    argv = ["flutter", "phc_hale", "--nonlinear-beams", "4", "--altitudes", "20000", "--mach-min", f"{34 / A_20KM:.6f}",
            "--mach-max", f"{40 / A_20KM:.6f}"]
    code, out, _ = _run(argv + ["--json"], capsys)
    assert code == 0
    row = json.loads(out)["rows"][0]
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(nonlinear_beams=NonlinearBeams(4)))
    point = fs.flutter(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0), "unsteady",
                       mach_range=(round(34 / A_20KM, 6), round(40 / A_20KM, 6)))
    assert row["speed_m_s"] == pytest.approx(point.speed_m_s, rel=1e-9) and row["terms"] == point.terms
    code, text, _ = _run(argv, capsys)
    assert code == 0 and f"{point.speed_m_s:10.3f}" in text and "wing clamped at the trimmed root" in text


def test_free_aircraft_flutter_prints_the_api_point(capsys):
    """``--free-aircraft``: the model's ``NonlinearBeams(stability="free-aircraft")``, the whole free aircraft about
    each trim; the row is the API's (its scan and terms), the header says which structure was linearised."""
    argv = ["flutter", "phc_hale", "--nonlinear-beams", "4", "--free-aircraft", "--altitudes", "20000",
            "--mach-min", f"{34 / A_20KM:.6f}", "--mach-max", f"{40 / A_20KM:.6f}"]
    code, out, _ = _run(argv + ["--json"], capsys)
    assert code == 0
    row = json.loads(out)["rows"][0]
    beams = NonlinearBeams(4, stability="free-aircraft")
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(nonlinear_beams=beams))
    point = fs.flutter(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0), "unsteady",
                       mach_range=(round(34 / A_20KM, 6), round(40 / A_20KM, 6)))
    assert row["scanned_m_s"] == pytest.approx(list(point.speeds_m_s), rel=1e-12) and row["terms"] == point.terms
    assert row["terms"]["nonlinear_beams"]["stability"] == "free-aircraft"
    assert row["warnings"][0].startswith("free aircraft with Peters' strips")
    code, text, _ = _run(argv, capsys)
    assert code == 0 and text.startswith("Flutter of the free aircraft about the nonlinear trim")
    code, _, err = _run(argv + ["--vg", "x.png"], capsys)
    assert code == 2 and "--vg with --free-aircraft" in err
    with pytest.raises(ValueError, match="nonlinear_beams.stability = 'free-aircraft': the V-g diagram"):
        fs.vg_diagram(model, manoeuvre=fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0), models=("FS",),
                      speeds_m_s=[30.0, 35.0])


def test_flutter_writes_the_nonlinear_vg_diagram(tmp_path, capsys):
    png = tmp_path / "vg.png"
    argv = ["flutter", "phc_hale", "--nonlinear-beams", "4", "--altitudes", "20000", "--mach-min", f"{34 / A_20KM:.6f}",
            "--mach-max", f"{40 / A_20KM:.6f}", "--vg", str(png), "--vg-points", "4"]
    code, text, _ = _run(argv, capsys)
    assert code == 0 and png.stat().st_size > 0
    line = next(ln for ln in text.splitlines() if ln.startswith("V-g diagram H = 20000 m"))
    speed = float(line.split(" crosses at ")[1].split(" m/s")[0])
    table = next(ln for ln in text.splitlines() if ln.strip().startswith("20000"))
    assert abs(speed - float(table.split()[1])) < 0.05  # two routes to one point: crossing and search tolerances


def test_flutter_in_a_turn_prints_the_api_point(capsys):
    """In a turn both wings are analysed about the banked nonlinear trim; the row is the API's point."""
    rng = (round(26 / A_20KM, 6), round(30 / A_20KM, 6))
    argv = ["flutter", "phc_hale", "--nonlinear-beams", "4", "--altitudes", "20000", "--turn-radius-m", "1000",
            "--mach-min", f"{rng[0]:.6f}", "--mach-max", f"{rng[1]:.6f}"]
    code, out, _ = _run(argv + ["--json"], capsys)
    assert code == 0
    row = json.loads(out)["rows"][0]
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(nonlinear_beams=NonlinearBeams(4)))
    point = fs.flutter(model, fs.SteadyManoeuvre.turn(20000.0, 1000.0, speed_m_s=25.0), "unsteady", mach_range=rng)
    assert row["turn_radius_m"] == 1000.0 and row["scanned_m_s"] == pytest.approx(list(point.speeds_m_s), rel=1e-12)
    assert row["component"] == point.component
    assert any("both wings analysed" in w for w in row["warnings"])
    code, text, _ = _run(argv, capsys)
    assert code == 0 and "turn R = 1000 m (the less stable wing)" in text


@pytest.mark.parametrize("extra, words", [
    (["--models", "QS"], "--models QS: with --nonlinear-beams"),
    (["--vg", "x.txt"], "--vg 'x.txt': must name a .png file"),
    (["--mode", "x.rrd"], "--mode: not available with --nonlinear-beams"),
    (["--nonlinear-beams", "0"], "--nonlinear-beams = 0: must be an integer in 1-64"),
    (["--load-factor", "9"], "--load-factor = 9.0: must be a load factor in [1, 6]"),
    (["--load-factor", "1.2", "--climb-deg", "2"], "--load-factor 1.2, --climb-deg 2"),
    (["--load-factor", "1.2", "--turn-radius-m", "1000"], "--load-factor 1.2, --turn-radius-m 1000"),
    (["--coordinated"], "--coordinated: applies to turns only"),
])
def test_flutter_refuses_what_it_cannot_honour(extra, words, capsys):
    argv = ["flutter", "phc_hale", "--altitudes", "20000", *(["--nonlinear-beams"] if "--nonlinear-beams" not in extra
                                                             else []), *extra]
    code, _, err = _run(argv, capsys)
    assert code == 2 and words in err, err


def test_pull_up_sweep_prints_linear_and_nonlinear_side_by_side(tmp_path, capsys):
    """``flexsim sweep --pull-up``: each row is the API's flutter point of its model (linear US, and the wing about the
    nonlinear trim), written to CSV and JSON; a load factor that cannot be trimmed is a row with its reason."""
    out = tmp_path / "pull"
    argv = ["sweep", "--pull-up", "phc_hale", "--nonlinear-beams", "4", "--altitudes", "20000", "--models", "US",
            "--load-factors", "1.2", "1.5", "--mach-min", f"{30 / A_20KM:.6f}", "--mach-max", f"{40 / A_20KM:.6f}",
            "--json", "--out", str(out)]
    code, text, _ = _run(argv, capsys)
    assert code == 0 and (out / "flutter_pull_up.csv").exists()
    rows = {(r["model"], r["load_factor"]): r for r in json.loads(text)["rows"]}
    hale = fs.load_aircraft("phc_hale")
    man = fs.SteadyManoeuvre.pull_up(20000.0, 1.2, mach=0.5)
    rng = (round(30 / A_20KM, 6), round(40 / A_20KM, 6))
    linear = fs.flutter(fs.AircraftModel(hale), man, "theodorsen", mach_range=rng)
    assert rows["US", 1.2]["speed_m_s"] == pytest.approx(linear.speed_m_s, rel=1e-12)
    nonlinear = fs.flutter(fs.AircraftModel(hale, terms=fs.Terms(nonlinear_beams=NonlinearBeams(4))), man, "unsteady",
                           mach_range=rng)
    assert rows["FS nonlinear", 1.2]["speed_m_s"] == pytest.approx(nonlinear.speed_m_s, rel=1e-12)
    assert rows["FS nonlinear", 1.5]["error"].startswith("no trimmable speed in the range")


def test_simulate_flies_the_nonlinear_manoeuvre_and_logs_it(tmp_path, capsys):
    """``flexsim simulate gust-encounter --aircraft phc_hale --nonlinear-beams 4``: the API's run
    (``build_flexible_manoeuvre(...).fly()``), printed to its digits, and its log with the deformed wings."""
    from flexsim.io.flight_log import read_flight_log
    from flexsim.sim.flexible_manoeuvres import build_flexible_manoeuvre

    log = tmp_path / "gust.mcap"
    code, out, _ = _run(["simulate", "gust-encounter", "--aircraft", "phc_hale", "--nonlinear-beams", "4",
                         "--duration", "2", "--log", str(log)], capsys)
    assert code == 0
    run = build_flexible_manoeuvre("gust-encounter", "phc_hale", beams=NonlinearBeams(4), duration_s=2.0).fly()
    peak = run.tip_deflection_fraction.max(axis=0)
    assert f"to {100 * peak[0]:+.1f} % in the run" in out and peak[0] > 0.25
    flight = read_flight_log(log)
    assert flight.complete and abs(flight.t[-1] - 2.0) < 1e-9
    assert np.allclose(flight.controls, run.controls)
    assert set(flight.structure) == {"right_wing", "left_wing"}


@pytest.mark.parametrize("argv, words", [
    (["simulate", "gust-encounter", "--nonlinear-beams"], "--nonlinear-beams: give --aircraft"),
    (["simulate", "level-turn-entry", "--aircraft", "phc_hale", "--nonlinear-beams"],
     "level-turn-entry: not flown with --nonlinear-beams"),
    (["simulate", "gust-encounter", "--aircraft", "phc_hale", "--nonlinear-beams", "--aero", "unsteady"],
     "--aero unsteady: with --nonlinear-beams the strips are quasi-steady"),
    (["simulate", "gust-encounter", "--aircraft", "phc_hale", "--nonlinear-beams", "--method", "Radau"],
     "--method Radau: with --nonlinear-beams"),
    (["simulate", "gust-encounter", "--aircraft", "phc_hale", "--nonlinear-beams", "--rtol", "1e-4"],
     "--rtol 0.0001: applies to --method BDF"),
    (["simulate", "gust-encounter", "--aircraft", "phc_hale", "--nonlinear-beams", "--formulation", "paper"],
     "--formulation paper: applies to the linear structure"),
    (["simulate", "x.py", "--nonlinear-beams"], "--nonlinear-beams: applies to named manoeuvres"),
])
def test_simulate_refuses_what_the_nonlinear_aircraft_cannot_fly(argv, words, capsys):
    code, _, err = _run(argv, capsys)
    assert code == 2 and words in err, err
