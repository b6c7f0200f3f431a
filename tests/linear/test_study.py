"""Flutter studies: chained parallel runs, CSV/JSON/PNG outputs, glide interpolation."""

import json
import math

import pytest

from flexsim.linear.study import StudyCase, glide_from_climb, plot_study, plot_trim, run_study, write_results


def test_small_turn_study_runs_in_parallel_and_writes_outputs(tmp_path):
    # Two radii at sea level, finite-state model: both flutter near the level-flight point (M ~ 0.66 on
    # the calibrated notional GTM) and the chained search seeds the second with the first.
    cases = [StudyCase("gtm", "FS", 0.0, turn_radius_m=r, mach_min=0.6, mach_max=0.75) for r in (10000.0, 12000.0)]
    cases.append(StudyCase("gtm", "FS", 0.0, climb_angle_deg=0.0, mach_min=0.6, mach_max=0.75))
    rows = run_study(cases, workers=2, progress=False)
    assert [r["turn_radius_m"] for r in rows] == [10000.0, 12000.0, math.inf]
    assert all("mach" in r for r in rows), rows
    # every row names the mode's symmetry (the calibrated GTM's wing mode is antisymmetric)
    assert all(r["mode_symmetry"] == "antisymmetric" and r["participation"] for r in rows)
    assert abs(rows[1]["mach"] - rows[2]["mach"]) < abs(rows[0]["mach"] - rows[2]["mach"]) + 1e-3  # tends to level
    csv_path, json_path = write_results(rows, tmp_path, "turn")
    assert len(json.loads(json_path.read_text())) == 3 and csv_path.read_text().count("\n") == 4
    png = plot_study(rows, "turn", tmp_path / "turn.png")
    assert png.read_bytes()[:4] == b"\x89PNG"
    trim_png = plot_trim(rows, "turn", tmp_path / "trim.png", altitude_m=0.0)
    assert trim_png.read_bytes()[:4] == b"\x89PNG"
    with pytest.raises(ValueError, match="altitude_m = 9144.0: no flutter point"):
        plot_trim(rows, "turn", tmp_path / "none.png", altitude_m=9144.0)


def test_glide_interpolated_where_thrust_vanishes():
    rows = [
        {"model": "US", "altitude_m": 9144.0, "climb_angle_deg": -5.0, "thrust_kN": -20.0, "mach": 0.76, "omega_rad_s": 35.0},
        {"model": "US", "altitude_m": 9144.0, "climb_angle_deg": 0.0, "thrust_kN": 30.0, "mach": 0.78, "omega_rad_s": 34.0},
    ]
    glide = glide_from_climb(rows)
    assert glide["gamma_deg"] == pytest.approx(-3.0)
    assert glide["mach"] == pytest.approx(0.768)


def test_bad_model_rejected():
    with pytest.raises(ValueError, match="model = 'XX'"):
        StudyCase("gtm", "XX", 0.0)
