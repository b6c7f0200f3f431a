"""Flutter and divergence of the Patil-Hodges-Cesnik wing clamped in a wind tunnel (flexsim.linear.beam_flutter).

Reference: Patil, Hodges & Cesnik, *Nonlinear aeroelasticity and flight dynamics of high-altitude long-endurance
aircraft*, J. Aircraft 38(1) 2001: the 16 m wing (chord 1 m, EA and CG at mid-chord, 0.75 kg/m, 0.1 kg m, GJ 1e4,
EI 2e4 / 4e6 N m²) at 20 km (ρ 0.0889 kg/m³), strip theory with Peters' finite-state inflow:
* linear (undeformed): flutter 32.21 m/s at 22.61 rad/s, divergence 37.29 m/s — within 2 % (acceptance);
* bent by a dead vertical tip force (no weight): flutter speed and frequency against the static tip displacement,
  PHC's figure as digitised in luizpancini/AeroBeams.jl test/referenceData/SMW/flutterSpeedVsTipDisp.txt and
  flutterFreqVsTipDisp.txt — within 10 % (acceptance; the digitised curve itself scatters by ~2 % around a smooth
  line, and PHC's and this beam's discretisations differ).
* pitched at the root with weight (g = 9.80665 m/s²), so that the airloads and gravity bend the wing and the strips
  follow it: flutter speed and frequency against root angle of attack, the reference curve of AeroBeams.jl for this
  wing (test/referenceData/SMW/flutterSpeedVsRootAoA.txt, flutterFreqVsRootAoA.txt, the branch above 0.63°) —
  within 10 % (measured at 4°: +0.4 % and −2.3 %; at 2°: −0.1 % and −1.6 %).
16 elements, 2 Gauss points (strips) per element, 6 inflow states.
"""

import numpy as np
import pytest

import flexsim as fs
from flexsim.linear.beam_flutter import StripRangeWarning, WingTunnelSettings
from flexsim.model.beam_aero import WingAero
from flexsim.structure.strain_beam import BeamProperties

RHO_20KM = 0.0889
#: PHC 2001 (digitised, AeroBeams flutterSpeedVsTipDisp.txt / flutterFreqVsTipDisp.txt): tip [m] -> U_F [m/s], ω_F.
PHC_TIP = [0.00549, 0.14888, 0.29824, 0.47138, 0.63253, 0.79967, 0.95484, 1.1339, 1.3070, 1.4562, 1.5995, 1.7309,
           1.9103, 2.0836, 2.2688, 2.4420, 2.5376, 2.6629, 2.7584]
PHC_SPEED = [32.147, 31.942, 31.667, 30.697, 29.518, 28.408, 27.159, 25.772, 24.384, 23.414, 22.512, 22.307, 22.728,
             23.011, 22.667, 22.114, 21.630, 20.867, 20.313]
PHC_FREQ_TIP = [0.015814, 0.18909, 0.38025, 0.56539, 0.74452, 0.97741, 1.2163, 1.4014, 1.6044, 1.8014, 2.0163, 2.2493,
                2.4463, 2.7390]
PHC_FREQ = [22.615, 22.410, 21.997, 21.305, 20.405, 19.367, 18.189, 17.289, 16.180, 15.211, 14.033, 13.134, 12.373,
            11.545]


def _phc_wing():
    return BeamProperties(length_m=16.0, n_elements=16, gj_nm2=1e4, ei_flap_nm2=2e4, ei_chord_nm2=4e6,
                          mass_kg_per_m=0.75, torsion_inertia_kg_m=0.1, flap_inertia_kg_m=5e-4,
                          chord_inertia_kg_m=0.1 - 5e-4, gauss_points=2)


def test_phc_linear_flutter_and_divergence_within_2_percent():
    result = fs.nonlinear_wing_tunnel(_phc_wing(), WingAero(chord_m=1.0, axis_fraction=0.5),
                                      WingTunnelSettings(RHO_20KM, (31.0, 38.0)))
    fl, dv = result.flutter, result.divergence
    print(f"flutter {fl.speed_m_s:.3f} m/s {fl.frequency_rad_s:.3f} rad/s (PHC 32.21, 22.61); "
          f"divergence {dv.speed_m_s:.3f} m/s (PHC 37.29)")
    assert fl.kind == "flutter" and dv.kind == "divergence"
    assert fl.speed_m_s == pytest.approx(32.21, rel=0.02) and fl.frequency_rad_s == pytest.approx(22.61, rel=0.02)
    assert dv.speed_m_s == pytest.approx(37.29, rel=0.02)
    assert np.abs(fl.tip_displacement_m).max() < 1e-12  # nothing loads the wing statically


@pytest.mark.parametrize(("tip_force_n", "speeds"), [(16.0, (25.0, 29.0)), (32.0, (20.0, 24.0))])
def test_phc_flutter_against_tip_displacement_within_10_percent(tip_force_n, speeds):
    settings = WingTunnelSettings(RHO_20KM, speeds, tip_force_n=[0.0, 0.0, tip_force_n])
    fl = fs.nonlinear_wing_tunnel(_phc_wing(), WingAero(chord_m=1.0), settings).flutter
    tip = fl.tip_displacement_m[2]
    speed, freq = np.interp(tip, PHC_TIP, PHC_SPEED), np.interp(tip, PHC_FREQ_TIP, PHC_FREQ)
    print(f"tip force {tip_force_n} N: tip {tip:.3f} m, flutter {fl.speed_m_s:.2f} m/s (PHC {speed:.2f}), "
          f"{fl.frequency_rad_s:.2f} rad/s (PHC {freq:.2f})")
    assert fl.speed_m_s == pytest.approx(speed, rel=0.10) and fl.frequency_rad_s == pytest.approx(freq, rel=0.10)
    assert fl.speed_m_s < 32.21  # the bent wing flutters earlier than the straight one (PHC's finding)


#: AeroBeams.jl reference for the PHC wing with weight: root AoA [deg] -> U_F [m/s], and AoA -> ω_F [rad/s].
AOA_SPEED = ([3.2613, 3.6248, 3.9489, 4.2043, 4.4794], [21.798, 21.179, 20.697, 20.354, 19.941])
AOA_FREQ = ([3.2122, 3.6739, 4.0668, 4.4794], [17.259, 16.778, 16.640, 16.297])


def test_phc_flutter_at_a_root_pitch_with_weight():
    settings = WingTunnelSettings(RHO_20KM, (19.0, 23.0), root_pitch_deg=4.0, gravity_m_s2=9.80665)
    fl = fs.nonlinear_wing_tunnel(_phc_wing(), WingAero(chord_m=1.0), settings).flutter
    speed, freq = np.interp(4.0, *AOA_SPEED), np.interp(4.0, *AOA_FREQ)
    print(f"root pitch 4 deg: tip {fl.tip_displacement_m[2]:.3f} m, flutter {fl.speed_m_s:.2f} m/s (reference "
          f"{speed:.2f}), {fl.frequency_rad_s:.2f} rad/s (reference {freq:.2f})")
    assert fl.speed_m_s == pytest.approx(speed, rel=0.10) and fl.frequency_rad_s == pytest.approx(freq, rel=0.10)
    assert fl.tip_displacement_m[2] > 1.0  # the airloads lift the tip by metres at flutter


def test_strips_beyond_the_linear_lift_range_are_reported():
    # pitched 12 deg: every strip is at 12 deg or more (the airloads twist the wing nose up; bending keeps e2)
    settings = WingTunnelSettings(RHO_20KM, (5.0, 10.0), speed_step_m_s=5.0, root_pitch_deg=12.0)
    with pytest.warns(StripRangeWarning, match=r"at 5 m/s the static wing has strips at 12\.\d deg angle of attack"):
        result = fs.nonlinear_wing_tunnel(_phc_wing(), WingAero(chord_m=1.0), settings)
    assert np.all(result.max_strip_alpha_deg >= 12.0) and result.max_strip_alpha_deg[1] > result.max_strip_alpha_deg[0]
    quiet = WingTunnelSettings(RHO_20KM, (5.0, 10.0), speed_step_m_s=5.0, root_pitch_deg=2.0)
    assert fs.nonlinear_wing_tunnel(_phc_wing(), WingAero(chord_m=1.0), quiet).max_strip_alpha_deg.max() < 10.0


@pytest.mark.parametrize(("field", "value", "match"), [
    ("density_kg_m3", -1.0, "density_kg_m3 = -1.0: must be a finite number > 0"),
    ("speed_range_m_s", (30.0, 20.0), r"speed_range_m_s = \(30.0, 20.0\): must be 0 < lowest < highest"),
    ("root_pitch_deg", 45.0, r"root_pitch_deg = 45.0: must be a number in \[-30, 30\]"),
    ("speed_step_m_s", 0.0, "speed_step_m_s = 0.0: must be > 0"),
])
def test_bad_settings_name_the_field_and_the_range(field, value, match):
    args = dict(density_kg_m3=0.0889, speed_range_m_s=(10.0, 20.0))
    args[field] = value
    with pytest.raises(ValueError, match=match):
        WingTunnelSettings(**args)
