"""Point masses on strain-based beams (strain_beam.PointMass, mass_points) against closed forms and invariants.

* A light cantilever (m L / M = 0.01) carrying a tip mass M: its first flapwise and chordwise bending frequencies are
  √(3 EI / ((M + 33 m L / 140) L³)) (Blevins, *Formulas for Natural Frequency and Mode Shape*, table 8-8, Rayleigh's
  effective mass; its error is O((m L / M)²) = 1e-4); its first torsion frequency with the tip mass's inertia J about
  the axis is √(GJ / (L (J + I_t L / 3))). Constant-strain elements converge at second order in bending (measured
  relative error 2.0e-3, 4.9e-4, 1.2e-4 at 8, 16, 32 elements) and are exact in torsion: tolerance 1e-3 at 16.
* A point mass at mid-span under gravity: the tip deflection of a cantilever loaded by P = M g at a = L/2 is
  P a² (3L − a) / (6 EI) = 5 P L³ / (48 EI) (Roark's *Formulas for Stress and Strain*, table 8.1 case 1a); load
  small (tip 5e-6 L) so the geometric nonlinearity is below 1e-9. Constant-strain elements take each element's
  curvature at its mean, so the tip deflection ∫ κ (L − x) dx is the midpoint rule on a quadratic integrand, short by
  exactly ℓ² a P / (12 EI) (its error term; the station on an element boundary): tolerance 1e-6 against that.
* A free-flying structure with offset point masses (3-D offsets, full inertia tensors) in vacuum conserves energy
  and angular momentum (Kane's form is exact; DOP853 at rtol = atol = 1e-10: tolerance 1e-9 over 1 s) — this
  exercises the masses' relative accelerations ``R̈ o``.
* Its strain block of the mass matrix equals strain_beam.mass_matrix of the beam with the masses (to round-off).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from flexsim.structure.beam_statics import BeamLoads, solve_static, vibration_modes
from flexsim.structure.free_flexible import (FreeFlexibleStructure, RigidBody, conserved_quantities, free_flight_rhs,
                                             generalized_mass_matrix, initial_state)
from flexsim.structure.strain_beam import BeamProperties, PointMass, beam_kinematics, mass_matrix

RIGHT = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, -1]])
LEFT = np.array([[0.0, -1, 0], [-1, 0, 0], [0, 0, -1]])


def _cantilever(n_el, *masses, mass_kg_per_m=0.01):
    return BeamProperties(length_m=10.0, n_elements=n_el, gj_nm2=5e3, ei_flap_nm2=2e4, ei_chord_nm2=4e5,
                          mass_kg_per_m=mass_kg_per_m, torsion_inertia_kg_m=1e-3, flap_inertia_kg_m=1e-4,
                          chord_inertia_kg_m=1e-4, point_masses=masses)


def test_tip_mass_frequencies():
    tip = PointMass(10.0, 10.0, inertia_kg_m2=np.diag([2.0, 1e-3, 1e-3]), name="tip body")
    f = vibration_modes(_cantilever(16, tip)).frequencies_rad_s[:3]
    mass = 10.0 + 33.0 / 140.0 * 0.01 * 10.0
    expected = [math.sqrt(3 * 2e4 / (mass * 10.0**3)), math.sqrt(3 * 4e5 / (mass * 10.0**3)),
                math.sqrt(5e3 / (10.0 * (2.0 + 1e-3 * 10.0 / 3.0)))]
    assert np.abs(np.sort(f) / np.sort(expected) - 1).max() < 1e-3


def test_mid_span_mass_under_gravity():
    mid = PointMass(5.0, 1e-3, name="store")
    beam = _cantilever(8, mid, mass_kg_per_m=1e-12)  # its own weight: a tip deflection 1e-8 of the store's
    sol = solve_static(beam, BeamLoads(gravity_m_s2=(0.0, 0.0, -9.81)))
    p = 1e-3 * 9.81
    ell = 10.0 / 8
    expected = 5 * p * 10.0**3 / (48 * 2e4) - ell**2 * 5.0 * p / (12 * 2e4)
    assert -sol.kinematics.tip_position[2] == pytest.approx(expected, rel=1e-6)


def test_station_beyond_the_beam_is_refused():
    with pytest.raises(ValueError, match=r"point_masses\[0\] \(engine\): station_m = 12.0"):
        _cantilever(2, PointMass(12.0, 1.0, name="engine"))
    with pytest.raises(ValueError, match="engine: mass_kg = -1"):
        PointMass(1.0, -1, name="engine")
    with pytest.raises(ValueError, match="symmetric"):
        PointMass(1.0, 1.0, inertia_kg_m2=[[1, 2, 0], [0, 1, 0], [0, 0, 1]])


def _aircraft():
    engine = PointMass(5.3, 20.0, offset_m=(0.1, 0.8, -0.5), inertia_kg_m2=[[2.0, 0.1, 0.0], [0.1, 3.0, 0.2],
                                                                          [0.0, 0.2, 1.5]], name="engine")

    def wing(rot):
        return BeamProperties(length_m=16.0, n_elements=2, gj_nm2=1e4, ei_flap_nm2=2e4, ei_chord_nm2=4e5,
                              mass_kg_per_m=0.75, cg_offset_m=0.05, torsion_inertia_kg_m=1.0, flap_inertia_kg_m=0.1,
                              chord_inertia_kg_m=1.0, root_rotation=rot, point_masses=(engine,))
    return FreeFlexibleStructure(RigidBody(50.0, (0.2, 0, 0.1), np.diag([5.0, 2, 6])), (wing(RIGHT), wing(LEFT)))


def test_free_structure_with_point_masses_conserves_energy_and_momentum():
    st = _aircraft()
    rng = np.random.default_rng(1)
    y0 = initial_state(st, velocity_m_s=(10, 0, 1), rate_rad_s=(1.0, -0.3, 0.5),
                       strain_rates=rng.normal(size=st.n_strains) * 0.2)
    sol = solve_ivp(lambda t, y: free_flight_rhs(st, t, y), (0, 1.0), y0, method="DOP853", rtol=1e-10, atol=1e-10)
    assert sol.status == 0
    c0, c1 = conserved_quantities(st, y0), conserved_quantities(st, sol.y[:, -1])
    assert abs(c1.energy_j / c0.energy_j - 1) < 1e-9
    assert (np.linalg.norm(c1.angular_momentum_cg - c0.angular_momentum_cg)
            / np.linalg.norm(c0.angular_momentum_cg)) < 1e-9
    # the strains moved the engines: a test of their relative motion, not of a rigid body
    assert np.abs(sol.y[7:7 + st.n_strains, -1]).max() > 1e-3


def test_mass_matrix_carries_the_point_masses():
    st = _aircraft()
    rng = np.random.default_rng(2)
    eps = rng.normal(size=st.n_strains) * 0.02
    mass = generalized_mass_matrix(st, eps)
    s, beam = st.strain_slices()[0], st.beams[0]
    block = mass_matrix(beam, beam_kinematics(beam, eps[s]))
    assert np.abs(mass[6 + s.start:6 + s.stop, 6 + s.start:6 + s.stop] - block).max() < 1e-12 * np.abs(block).max()
    assert mass[0, 0] == pytest.approx(50 + 2 * (0.75 * 16 + 20.0), rel=1e-12)
