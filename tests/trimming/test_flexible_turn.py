"""Steady turn of the geometrically nonlinear aircraft (flexsim.trimming.flexible_turn): the small-deflection limit
against the linear trim of the same turn, the turn's kinematics and force balance, the bundled HALE."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import flexsim as fs
from flexsim.kinematics import dcm_321
from flexsim.structure.free_flexible import quaternion_matrix
from flexsim.trimming.flexible_trim import trim_flexible
from flexsim.trimming.flexible_turn import euler_quaternion

G = 9.80665


def _stiff(aircraft, factor):
    """The aircraft with every flexible component's EI, GJ and chordwise EI multiplied by ``factor``."""
    def one(c):
        if not c.is_flexible:
            return c
        s = c.sections
        return dataclasses.replace(c, sections=dataclasses.replace(
            s, ei_nm2=s.ei_nm2 * factor, gj_nm2=s.gj_nm2 * factor, ei_chord_nm2=s.ei_chord_nm2 * factor))
    return dataclasses.replace(aircraft, components=tuple(one(c) for c in aircraft.components))


@pytest.fixture(scope="module")
def stiff():
    return fs.AircraftModel(_stiff(fs.load_aircraft("phc_hale"), 1e4))


def test_euler_quaternion_is_the_transposed_dcm():
    c = quaternion_matrix(euler_quaternion(0.3, 0.2, -0.4))
    np.testing.assert_allclose(c, dcm_321(0.3, 0.2, -0.4).T, atol=1e-14)


@pytest.mark.parametrize("coordinated", [False, True])
def test_stiff_turn_trims_like_the_linear_model(stiff, coordinated):
    """Small-deflection limit (EI, GJ x 1e4) in a 1000 m turn at 25 m/s: the pitch within 0.1 %, angle of attack
    within 1 %, aileron and elevator within 2 % and thrust within 0.5 % of the weight of the linear trim (the
    tolerances of the level stiff-limit test, alpha widened: the linear model takes it at o, the nonlinear at the CG
    of the undeformed aircraft). The bank within 5 %: the fin's side force (rudder, yaw-rate sidewash) carries part
    of the horizontal force and the two models' fin strips differ (measured 3.3 %); the rudder is not compared for
    the same reason (both under 2 deg)."""
    man = fs.SteadyManoeuvre.turn(20000.0, 1000.0, speed_m_s=25.0, coordinated=coordinated)
    nonlinear, linear = trim_flexible(stiff, man), fs.trim(stiff, man)
    weight = stiff.structure.mass_properties.mass_kg * G
    assert nonlinear.residual < 1e-8
    assert nonlinear.theta_rad == pytest.approx(linear.theta, rel=1e-3)
    assert nonlinear.alpha_rad == pytest.approx(linear.alpha, rel=1e-2)
    assert nonlinear.phi_rad == pytest.approx(linear.phi, rel=5e-2)
    assert nonlinear.controls[1] == pytest.approx(linear.u[1], rel=2e-2)
    assert nonlinear.controls[2] == pytest.approx(linear.u[2], rel=2e-2)
    assert abs(nonlinear.controls[0] - linear.u[0]) < 5e-3 * weight
    assert max(abs(nonlinear.controls[3]), abs(linear.u[3])) < math.radians(2.0)
    if coordinated:
        assert abs(nonlinear.sideslip_rad - linear.beta) < 1e-4  # at o; zero at the CG by the extra row


def test_turn_kinematics_and_bank(stiff):
    """The solved state is the turn: |v_o| = V, the body rate is Omega = V/R about the vertical (C(q) omega =
    (0, 0, V/R)), the paper's sideslip asin(sin phi sin theta) at o; the bank near the point-mass
    tan(phi) = V^2/(g R) (within 5 %, the fin's side force, see above). A left turn (R < 0) mirrors it."""
    right = trim_flexible(stiff, fs.SteadyManoeuvre.turn(20000.0, 1000.0, speed_m_s=25.0))
    left = trim_flexible(stiff, fs.SteadyManoeuvre.turn(20000.0, -1000.0, speed_m_s=25.0))
    assert np.linalg.norm(right.velocity_m_s) == pytest.approx(25.0, rel=1e-12)
    c = quaternion_matrix(euler_quaternion(right.phi_rad, right.theta_rad, 0.0))
    np.testing.assert_allclose(c @ right.rate_rad_s, [0.0, 0.0, 25.0 / 1000.0], atol=1e-12)
    assert right.sideslip_rad == pytest.approx(math.asin(math.sin(right.phi_rad) * math.sin(right.theta_rad)),
                                               rel=1e-9)
    assert math.tan(right.phi_rad) == pytest.approx(25.0**2 / (G * 1000.0), rel=5e-2)
    assert left.phi_rad == pytest.approx(-right.phi_rad, rel=1e-6)
    assert left.controls[1] == pytest.approx(-right.controls[1], rel=1e-6)
    assert left.controls[2] == pytest.approx(right.controls[2], rel=1e-6)


def test_hale_turn_large_deflection():
    """The bundled HALE at 20 km, 25 m/s in a 1000 m right turn: converged; the outer (left) wing flies faster and
    bends more than the inner (right) one; the tips near half the semispan. Printed beside the linear trim."""
    hale = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    man = fs.SteadyManoeuvre.turn(20000.0, 1000.0, speed_m_s=25.0)
    point = trim_flexible(hale, man)
    linear = fs.trim(hale, man, check_limits=False)
    print(f"nonlinear: alpha {math.degrees(point.alpha_rad):.3f} deg, bank {math.degrees(point.phi_rad):.3f} deg, "
          f"controls {point.controls}, tips z {point.tip_displacement_m[:, 2]} m; linear: alpha "
          f"{math.degrees(linear.alpha):.3f} deg, bank {math.degrees(linear.phi):.3f} deg, controls {linear.u}, "
          f"tip {linear.tip_deflection_m:.3f} m")
    assert point.residual < 1e-8
    fractions = point.tip_deflection_fraction
    inner, outer = (fractions[point.aircraft.beam_index(w)] for w in ("right_wing", "left_wing"))
    assert outer > inner > 0.33
    assert point.max_strip_alpha_deg < 12.0


def test_turn_flutter_preload_mirrors_and_warns():
    """Mirror symmetry of the wing's linear system about the turn (gravity with the bank): the right wing in a
    right turn has the damping and frequency of the left wing in the left turn (to 1e-6). The flutter scan of a
    turn analyses both wings and warns that the bank changes with speed at fixed radius."""
    from flexsim.linear.flexible_flutter import flexible_flutter, wing_stability
    hale = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    right = trim_flexible(hale, fs.SteadyManoeuvre.turn(20000.0, 1000.0, speed_m_s=25.0))
    left = trim_flexible(hale, fs.SteadyManoeuvre.turn(20000.0, -1000.0, speed_m_s=25.0))
    g_rr, f_rr, _ = wing_stability(hale, right, "right_wing")
    g_ll, f_ll, _ = wing_stability(hale, left, "left_wing")
    g_rl, _, _ = wing_stability(hale, right, "left_wing")
    assert g_rr == pytest.approx(g_ll, abs=1e-6)
    assert f_rr == pytest.approx(f_ll, rel=1e-6)
    assert g_rl != pytest.approx(g_rr, abs=1e-6)  # the inner and outer wings differ
    point = flexible_flutter(hale, fs.SteadyManoeuvre.turn(20000.0, 1000.0, speed_m_s=25.0), (25.0, 27.5),
                             speed_step_m_s=2.5)
    assert any("bank changes with the scanned speed" in w for w in point.warnings)


def _turn_rows() -> dict[float, list[str]]:
    from pathlib import Path
    text = (Path(__file__).parents[2] / "docs" / "flutter.md").read_text().split("<!-- hale-turn-table -->", 1)[1]
    rows = {}
    for line in text.splitlines()[3:]:
        if not line.startswith("|"):
            break
        cells = [c.strip().replace("\u2212", "-") for c in line.strip("|").split("|")]
        rows[float(cells[0])] = cells
    return rows


@pytest.mark.slow
@pytest.mark.parametrize("radius", [2000.0, 1000.0, 500.0])
def test_docs_turn_table_is_current(radius):
    """The docs' HALE turn table against the current code, at its printed precision."""
    from flexsim.linear.flexible_flutter import flexible_flutter
    cells = _turn_rows()[radius]
    hale = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    man = fs.SteadyManoeuvre.turn(20000.0, radius, speed_m_s=25.0)
    lt, nt = fs.trim(hale, man, check_limits=False), trim_flexible(hale, man)
    assert float(cells[1]) == pytest.approx(math.degrees(lt.phi), abs=0.006)
    assert float(cells[2]) == pytest.approx(math.degrees(lt.u[1]), abs=0.006)
    assert float(cells[3].rstrip(" %")) == pytest.approx(-100 * lt.tip_deflection_m / 16.0, abs=0.06)
    assert float(cells[4]) == pytest.approx(fs.flutter(hale, man, "theodorsen").speed_m_s, abs=0.006)
    assert float(cells[5]) == pytest.approx(math.degrees(nt.phi_rad), abs=0.006)
    assert float(cells[6]) == pytest.approx(math.degrees(nt.controls[1]), abs=0.006)
    inner, outer = (float(x.strip().rstrip(" %")) for x in cells[7].split("/"))
    fractions = [nt.tip_deflection_fraction[nt.aircraft.beam_index(w)] for w in ("right_wing", "left_wing")]
    assert inner == pytest.approx(100 * fractions[0], abs=0.06)
    assert outer == pytest.approx(100 * fractions[1], abs=0.06)
    flutter = flexible_flutter(hale, man, (20.0, 45.0), speed_step_m_s=2.5)
    assert cells[8] == ("none" if math.isnan(flutter.speed_m_s) else f"{flutter.speed_m_s:.2f}")
    assert float(cells[9]) == pytest.approx(flutter.speeds_m_s.max(), abs=1e-9)
