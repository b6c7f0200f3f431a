"""The Pazy wing in the wind tunnel: vibration, and flutter onset against root pitch (flexsim.linear.beam_flutter).

The wing: the bundled ``pazy_wing`` (the AePW3 Large Deflection Working Group's equivalent beam, with skin, no tip
mass; sources in flexsim/aircraft/data/pazy_wing.md) as a 32- (vibration) or 16-element (flutter) strain-based beam
(:func:`flexsim.structure.beam_sections.beam_from_sections`). References, all from the public repository
UM-A2SRL/AePW3-LDWG (the files named below):

* vacuum frequencies: UM/NAST's beam and the ground vibration test (Avin et al., AIAA J. 2022),
  03_2023_JA_Riso_Cesnik/01_Modal_Undeformed/00_Comparisons/GFEM_vs_Beam.xlsx — within 3 % of UM/NAST's beam
  (the same equivalent beam; the stiffness couplings K14, K23, ... are left out here and the node masses are smeared
  over equal elements);
* strip theory lacks the tip loss: the lift slope of each strip follows the spanwise lift-slope distribution that
  UM/NAST uses (04_2023_JFS_Riso_Cesnik/01_Static_Aeroelastic/00_Aero_Coefficients/aero_coeff.txt: 5.61 /rad at the
  root falling to 0 at the tip; 11 of its points below, averaged over each element); its quarter-chord moment slope
  (−0.047 … +0.083, an aerodynamic centre 0.8-2 % of the chord off the quarter chord) is left out;
* static tip deflection at 5° root pitch without weight, UM/NAST with the same lift-slope distribution
  (04_2023_JFS_Riso_Cesnik/01_Static_Aeroelastic/02_Sweeps/static_aeroelastic_aoa5_UM_NAST_sweep.txt, nonlinear
  kinematics and follower airloads): 9.875 % and 18.575 % of the span at 30 and 40 m/s — within 4 % (the two
  beams differ by the couplings and mass smearing above, ~1-2 % in the frequencies; the file's frame for the
  vertical displacement is not stated, and between the pitched and the tunnel's frame it differs by 1 − cos 5° = 0.4 %);
* flutter of the undeformed wing with that distribution: UM/NAST 72.40 m/s at 34.72 Hz (05_Flutter_Undeformed/
  00_Comparisons/GFEM_vs_Beam.xlsx, "3-D aerodynamics" column) — within 3 %;
* flutter onset against root pitch, sea level (1.225 kg/m³), without weight as in the references: measured
  (Drachinsky & Raveh, AIAA J. 2022, tabulated in 03_2023_JA_Riso_Cesnik/06_Flutter_Deformed/00_Comparisons/
  Beam_vs_Tests.xlsx) 49/43/38 m/s at 3/5/7° sweeping the speed up — within 15 % (acceptance); UM/NAST
  (…/01_Beam/flutter_deformed_skin1_tipmass0_onset_vs_aoa.txt) and SHARPy (ngoiz/pazy-aepw3-results,
  06_DeformedWingFlutter/sharpy_skin_on, Zenodo 10.5281/zenodo.4299868) printed beside.
"""

from dataclasses import replace

import numpy as np
import pytest

import flexsim as fs
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.beam_flutter import WingTunnelSettings
from flexsim.model.beam_aero import StripAirloads, TunnelFlow, WingAero
from flexsim.structure.beam_sections import beam_from_sections, element_means
from flexsim.structure.beam_statics import solve_static, vibration_modes
from flexsim.structure.strain_beam import beam_kinematics

RHO_SEA_LEVEL = 1.225
#: aero_coeff.txt (LDWG, above): spanwise position [m] -> sectional lift slope [1/rad] (11 of its 46 rows).
CLA_Y = [0.0, 0.153, 0.2295, 0.306, 0.3825, 0.42075, 0.459, 0.49725, 0.530719, 0.540281, 0.549844]
CLA = [5.6057, 5.5415, 5.4472, 5.2772, 4.9608, 4.6957, 4.2901, 3.6149, 2.4582, 2.0600, 0.0]
#: root pitch [deg] -> measured onset sweeping up / down [m/s] (Beam_vs_Tests.xlsx).
MEASURED_UP = {3.0: 49.0, 5.0: 43.0, 7.0: 38.0}
MEASURED_DOWN = {3.0: 55.0, 5.0: 48.0}
#: root pitch [deg] -> UM/NAST (tip loss) and SHARPy (UVLM) onsets [m/s].
UM_NAST = {0.0: 72.40, 1.0: 61.73, 3.0: 48.24, 5.0: 41.44, 7.0: 37.19}
SHARPY = {1.0: 60.25, 3.0: 49.34, 5.0: 42.87, 7.0: 38.51}


def _sections():
    return next(c for c in load_aircraft("pazy_wing").components if c.name == "right_wing").sections


def _wing(n_elements=16):
    beam = beam_from_sections(_sections(), n_elements)
    y = np.array(CLA_Y)
    y[-1] = beam.length_m  # the file's tip, 0.549843728 m, to the beam's length (equal to 1e-9 m)
    return beam, WingAero(chord_m=0.1, axis_fraction=0.44, lift_slope_per_rad=element_means(y, CLA, n_elements))


def test_vacuum_frequencies_within_3_percent_of_the_um_nast_beam():
    beam = beam_from_sections(_sections(), 32)
    hz = vibration_modes(beam).frequencies_rad_s[:4] / (2 * np.pi)
    um_nast = np.array([4.1906, 28.493, 41.879, 83.065])  # OOP1, OOP2, T1, OOP3
    gvt = np.array([4.26, 28.5, 42.0, 81.5])
    for name, f, u, g in zip(("OOP1", "OOP2", "T1", "OOP3"), hz, um_nast, gvt):
        print(f"{name}: flexsim {f:.3f} Hz, UM/NAST {u} Hz ({f / u - 1:+.1%}), GVT {g} Hz ({f / g - 1:+.1%})")
    assert np.all(np.abs(hz / um_nast - 1) < 0.03)
    assert abs(beam.mass_kg_per_m.sum() * beam.length_m / 32 - 0.35660) < 1e-4  # sum of the LDWG node masses


def test_static_tip_deflection_at_5_degrees_within_4_percent_of_um_nast():
    beam, aero = _wing()
    pitch = np.radians(5.0)
    about_e1 = np.array([[1.0, 0.0, 0.0], [0.0, np.cos(pitch), -np.sin(pitch)], [0.0, np.sin(pitch), np.cos(pitch)]])
    pitched = replace(beam, root_rotation=about_e1)
    undeformed_tip = beam_kinematics(pitched, np.zeros(pitched.n_coordinates)).tip_position
    for speed, um_nast in ((30.0, 9.875), (40.0, 18.575)):
        sol = solve_static(pitched, StripAirloads(aero, TunnelFlow(speed, RHO_SEA_LEVEL)))
        tip = 100.0 * (sol.tip_position_m[2] - undeformed_tip[2]) / beam.length_m
        print(f"{speed:g} m/s: tip {tip:.3f} % of the span, UM/NAST {um_nast} % ({tip / um_nast - 1:+.1%})")
        assert abs(tip / um_nast - 1) < 0.04


def test_undeformed_flutter_with_the_spanwise_lift_slope_within_3_percent_of_um_nast():
    beam, aero = _wing()
    result = fs.nonlinear_wing_tunnel(beam, aero, WingTunnelSettings(RHO_SEA_LEVEL, (66.0, 78.0), speed_step_m_s=3.0))
    f = result.flutter
    hz = f.frequency_rad_s / (2 * np.pi)
    print(f"0 deg: flexsim {f.speed_m_s:.2f} m/s at {hz:.2f} Hz; UM/NAST 72.40 m/s at 34.72 Hz")
    assert abs(f.speed_m_s / 72.40 - 1) < 0.03
    assert abs(hz / 34.72 - 1) < 0.03


@pytest.mark.slow
@pytest.mark.parametrize("pitch_deg", [3.0, 5.0, 7.0])
def test_flutter_onset_against_root_pitch_within_15_percent_of_the_measured(pitch_deg):
    beam, aero = _wing()
    settings = WingTunnelSettings(RHO_SEA_LEVEL, (30.0, 60.0), speed_step_m_s=2.0, root_pitch_deg=pitch_deg)
    f = fs.nonlinear_wing_tunnel(beam, aero, settings).flutter
    measured = MEASURED_UP[pitch_deg]
    print(f"{pitch_deg:g} deg: flexsim {f.speed_m_s:.2f} m/s at {f.frequency_rad_s / (2 * np.pi):.2f} Hz, tip "
          f"{f.tip_displacement_m[2] / beam.length_m:.1%} of the span; measured {measured} m/s up "
          f"({f.speed_m_s / measured - 1:+.1%}), {MEASURED_DOWN.get(pitch_deg, '-')} down; UM/NAST "
          f"{UM_NAST[pitch_deg]}, SHARPy {SHARPY[pitch_deg]} m/s")
    assert abs(f.speed_m_s / measured - 1) < 0.15
    assert 0.0 < f.tip_displacement_m[2] < 0.3 * beam.length_m  # bent up, within the references' 18-22 %
