"""Statics and vibration of the strain-based beam against closed forms (flexsim.structure.beam_statics).

Sources and tolerances, per test:
* Tip couple: an inextensible cantilever under a tip moment M bends into a circular arc of curvature κ = M/EI,
  tip at (sin κL/κ, (1 − cos κL)/κ) (Timoshenko & Gere, *Theory of Elastic Stability*, 1961, §2.7). The constant-
  strain element maps strains to positions exactly, so ONE element gives the arc to round-off; asserted 1e-3 L
  (the acceptance figure) and measured ~1e-16 L for κL up to 2π.
* Elastica: a cantilever under a dead tip load P normal to it (Bisshopp & Drucker, Q. Appl. Math. 3 (1945)
  272-275): with α² = PL²/EI, k² = (1 + sin θ0)/2, sin φ1 = 1/(k√2), α = K(k) − F(φ1, k); tip x/L = √(2 sin θ0)/α,
  y/L = 1 − 2(E(k) − E(φ1, k))/α (scipy.special elliptic integrals). Their Table 1 (y/L = 0.30172, 0.60325,
  0.81061 at α² = 1, 3, 10) is printed beside. Within 0.5 % with 16 elements (measured 0.09 %; 8 elements: 0.35 %,
  error ∝ 1/N² as a piecewise-constant curvature).
* Small load: Euler-Bernoulli tip deflection PL³/3EI (Timoshenko & Gere, Mechanics of Materials); the strain-based
  element's discretisation error at 16 elements is 1/(4·16²)·(3/2) ≈ 0.1 % (measured 0.087 %), asserted 0.2 %.
* Buckling (dead compressive tip load, tangent stiffness singular): Euler's P_cr = π² EI/(4L²); 16 elements, 0.2 %.
* Beck's column (tangential follower tip load, flutter by coalescence of the first two frequencies): P_cr =
  20.05 EI/L² (Beck 1952; Bolotin, *Nonconservative Problems of the Theory of Elastic Stability*, 1963, §3); 24
  elements, 1 % (measured +0.3-0.5 %; 16 elements +1.0 %, 32 elements +0.3 %).
* PHC wing (Patil, Hodges & Cesnik, J. Aircraft 38(1) 2001, Table 1 data): natural frequencies within 2 % of the
  closed-form cantilever values (Euler-Bernoulli bending, uniform torsion: what PHC's "exact" column is), with 16
  elements; PHC's own printed values beside. About a deformed equilibrium (dead tip force), the torsion-like and
  chord-like frequencies separate as PHC's curves of frequency against tip displacement (digitised in
  luizpancini/AeroBeams.jl test/referenceData/SMW/freqsVsTipOOP.txt): within 8 % there (digitisation of a
  printed figure, and PHC's 4-node mixed elements against 16 constant-strain elements here).
"""

import numpy as np
import pytest
from scipy.linalg import eig
from scipy.optimize import brentq
from scipy.special import ellipe, ellipeinc, ellipk, ellipkinc

from flexsim.structure.beam_statics import (BeamConvergenceError, BeamLoads, NewtonSettings, solve_static,
                                            tangent_stiffness, vibration_modes)
from flexsim.structure.strain_beam import BeamProperties, beam_kinematics, mass_matrix

#: Bisshopp & Drucker (1945) Table 1: α² = PL²/EI -> vertical tip deflection y/L.
BISSHOPP_DRUCKER = {1.0: 0.30172, 3.0: 0.60325, 10.0: 0.81061}


def _unit_beam(n, **kw):
    return BeamProperties(length_m=1.0, n_elements=n, gj_nm2=1.0, ei_flap_nm2=1.0, ei_chord_nm2=100.0,
                          mass_kg_per_m=1.0, torsion_inertia_kg_m=0.01, **kw)


@pytest.mark.parametrize("kappa_l", [0.5, np.pi / 2, np.pi, 1.5 * np.pi, 2 * np.pi])
def test_tip_couple_gives_an_exact_circular_arc_with_one_element(kappa_l):
    beam = _unit_beam(1)
    sol = solve_static(beam, BeamLoads(tip_moment_nm=[0.0, -kappa_l, 0.0]))  # about -e2: bends towards +z
    x, z = np.sin(kappa_l) / kappa_l, (1 - np.cos(kappa_l)) / kappa_l
    err = np.abs(sol.tip_position_m - [x, 0.0, z]).max()
    print(f"kL = {kappa_l:.4f}: tip ({sol.tip_position_m[0]:.6f}, {sol.tip_position_m[2]:.6f}) exact ({x:.6f}, {z:.6f})")
    assert err < 1e-3 and err < 1e-12  # acceptance 1e-3 L; the map is exact


@pytest.mark.parametrize("kappa_l", [np.pi / 3, 2 * np.pi])
def test_tip_couple_arc_with_any_root_orientation_and_a_follower_couple(kappa_l):
    c, s = np.cos(0.7), np.sin(0.7)
    root = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]) @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    beam = _unit_beam(1, root_rotation=root, root_position_m=[1.0, 2.0, 3.0])
    sol = solve_static(beam, BeamLoads(tip_follower_moment_nm=[0.0, -kappa_l, 0.0]))
    local = np.array([np.sin(kappa_l), 0.0, 1 - np.cos(kappa_l)]) / kappa_l
    assert np.abs(sol.tip_position_m - ([1.0, 2.0, 3.0] + root @ local)).max() < 1e-10  # round-off of sin 2π


def _elastica(alpha2):
    """Tip (x/L, y/L) of the elastica under a dead tip load (Bisshopp & Drucker 1945)."""
    alpha = np.sqrt(alpha2)

    def mismatch(theta0):
        m = (1 + np.sin(theta0)) / 2
        return ellipk(m) - ellipkinc(np.arcsin(1 / np.sqrt(2 * m)), m) - alpha

    theta0 = brentq(mismatch, 1e-9, np.pi / 2 - 1e-12, xtol=1e-14)
    m = (1 + np.sin(theta0)) / 2
    phi1 = np.arcsin(1 / np.sqrt(2 * m))
    return np.sqrt(2 * np.sin(theta0)) / alpha, 1 - 2 * (ellipe(m) - ellipeinc(phi1, m)) / alpha


@pytest.mark.parametrize("alpha2", [1.0, 3.0, 10.0])
def test_dead_tip_load_follows_the_elastica(alpha2):
    x, y = _elastica(alpha2)
    assert y == pytest.approx(BISSHOPP_DRUCKER[alpha2], abs=1e-5)  # the closed form reproduces their table
    sol = solve_static(_unit_beam(16), BeamLoads(tip_force_n=[0.0, 0.0, alpha2]), NewtonSettings(load_steps=2))
    tip = sol.tip_position_m
    print(f"PL²/EI = {alpha2}: tip y/L {tip[2]:.5f}, x/L {tip[0]:.5f}; elastica {y:.5f}, {x:.5f}; "
          f"Bisshopp & Drucker {BISSHOPP_DRUCKER[alpha2]}")
    assert abs(tip[2] / y - 1) < 0.005 and abs(tip[0] / x - 1) < 0.005


def test_small_load_limit_is_euler_bernoulli():
    p = 1e-4
    sol = solve_static(_unit_beam(16), BeamLoads(tip_force_n=[0.0, 0.0, p]))
    assert sol.tip_position_m[2] == pytest.approx(p / 3.0, rel=2e-3)


def test_gravity_sag_of_a_uniform_cantilever_is_ql4_over_8ei():
    # Timoshenko & Gere: uniform load q = m g: tip deflection q L^4 / (8 EI), small-load limit; 16 elements: 0.2 %.
    sol = solve_static(_unit_beam(16), BeamLoads(gravity_m_s2=[0.0, 0.0, -1e-4]))
    assert sol.tip_position_m[2] == pytest.approx(-1e-4 / 8.0, rel=2e-3)


def test_euler_buckling_load_from_the_tangent_stiffness():
    beam = _unit_beam(16)
    zero = np.zeros(beam.n_coordinates)

    def lowest(p):
        kt = tangent_stiffness(beam, BeamLoads(tip_force_n=[-p, 0.0, 0.0]), zero)
        return np.linalg.eigvalsh(0.5 * (kt + kt.T))[0]

    assert brentq(lowest, 1.0, 5.0, xtol=1e-8) == pytest.approx(np.pi**2 / 4, rel=2e-3)


def test_becks_column_flutters_at_20_05():
    beam = _unit_beam(24)
    zero = np.zeros(beam.n_coordinates)
    m = mass_matrix(beam, beam_kinematics(beam, zero))

    def complex_pair(p):
        kt = tangent_stiffness(beam, BeamLoads(tip_follower_force_n=[-p, 0.0, 0.0]), zero)
        assert np.abs(kt - kt.T).max() > 1e-3  # a follower load's stiffness is not symmetric
        lam = eig(kt, m, right=False)
        return 1.0 if np.abs(lam[np.abs(lam) < 1e3].imag).max() > 1e-9 else -1.0

    assert complex_pair(19.5) < 0 < complex_pair(20.6)
    assert brentq(complex_pair, 19.5, 20.6, xtol=1e-3) == pytest.approx(20.05, rel=0.01)


def test_convergence_error_names_the_load_factor_and_the_coordinate():
    beam = _unit_beam(4)
    with pytest.raises(BeamConvergenceError, match=r"load factor .* element \d+ .*(curvature|twist)"):
        solve_static(beam, BeamLoads(tip_force_n=[0.0, 0.0, 10.0]), NewtonSettings(max_iterations=1, max_halvings=1))


def test_a_beam_without_torsional_inertia_has_no_vibration_frequencies():
    beam = BeamProperties(length_m=1.0, n_elements=2, gj_nm2=1.0, ei_flap_nm2=1.0, ei_chord_nm2=1.0,
                          mass_kg_per_m=1.0)
    with pytest.raises(ValueError, match="mass matrix is singular.*torsion_inertia_kg_m"):
        vibration_modes(beam)


def _phc_wing(n=16):
    """PHC 2001 Table 1; the rotary inertia split as AeroBeams' SMWVacuumEigen.jl (5e-4 about the chordwise axis)."""
    return BeamProperties(length_m=16.0, n_elements=n, gj_nm2=1e4, ei_flap_nm2=2e4, ei_chord_nm2=4e6,
                          mass_kg_per_m=0.75, torsion_inertia_kg_m=0.1, flap_inertia_kg_m=5e-4,
                          chord_inertia_kg_m=0.1 - 5e-4)


def test_phc_wing_natural_frequencies_within_2_percent_of_closed_forms():
    w = vibration_modes(_phc_wing()).frequencies_rad_s[:5]
    beta = np.array([1.87510407, 4.69409113, 7.85475744])
    scale = np.sqrt(2e4 / 0.75) / 16.0**2
    closed = {"flap 1": beta[0] ** 2 * scale, "flap 2": beta[1] ** 2 * scale,
              "torsion 1": np.pi / 32 * np.sqrt(1e4 / 0.1), "chord 1": beta[0] ** 2 * np.sqrt(4e6 / 0.75) / 256,
              "flap 3": beta[2] ** 2 * scale}
    phc = {"flap 1": 2.247, "flap 2": 14.606, "torsion 1": 31.146, "chord 1": 31.739, "flap 3": 44.012}
    for (name, exact), computed in zip(sorted(closed.items(), key=lambda kv: kv[1]), w):
        print(f"{name}: {computed:.4f} rad/s, closed form {exact:.4f} ({computed / exact - 1:+.2%}), PHC {phc[name]}")
        assert computed == pytest.approx(exact, rel=0.02)


def test_phc_wing_frequencies_about_a_deformed_equilibrium_follow_phcs_curves():
    beam = _phc_wing()
    loads = BeamLoads(tip_force_n=[0.0, 0.0, 20.0])
    sol = solve_static(beam, loads)
    modes = vibration_modes(beam, loads, sol.q)
    tip = sol.tip_position_m[2]
    # digitised PHC curves (AeroBeams freqsVsTipOOP.txt): torsion-like falls, chord-like rises with tip displacement
    torsion_like = np.interp(tip, [1.2726, 1.3976, 1.5704], [19.772, 18.840, 17.703])
    chord_like = np.interp(tip, [1.2422, 1.3708, 1.5056], [42.005, 42.726, 43.306])
    w = modes.frequencies_rad_s
    print(f"tip {tip:.3f} m: torsion-like {w[2]:.3f} (PHC {torsion_like:.3f}), chord-like {w[4]:.3f} "
          f"(PHC {chord_like:.3f}); flap 1 {w[0]:.3f}, flap 2 {w[1]:.3f}, flap 3 {w[3]:.3f}")
    assert 1.3 < tip < 1.4
    assert w[2] == pytest.approx(torsion_like, rel=0.08) and w[4] == pytest.approx(chord_like, rel=0.08)
    assert np.allclose(modes.q0, sol.q)
