"""Kinematics of the strain-based beam (flexsim.structure.strain_beam) against exact references.

* SE(3) exponential and its left Jacobian against scipy's matrix exponential and its Fréchet derivative
  (scipy.linalg.expm, expm_frechet): the closed forms of Barfoot (2017) eqs. 7.80-7.86, to 1e-12.
* Point Jacobians J_p = ∂p/∂q and J_θ (virtual rotation) against central differences of the positions and
  rotations (step 1e-6: truncation ~1e-12, round-off ~1e-10; tolerance 1e-8).
* Mass matrix: symmetric positive definite; the kinetic energy of a straight beam whose first element bends at a
  constant rate equals its closed form (integrals of the arc's velocity, below).
"""

import numpy as np
import pytest
from scipy.linalg import expm, expm_frechet

from flexsim.structure.strain_beam import (BeamProperties, beam_kinematics, mass_matrix, se3_exp, se3_left_jacobian,
                                           stiffness_matrix)


def _hat4(rho, phi):
    x = np.zeros((4, 4))
    x[:3, :3] = [[0, -phi[2], phi[1]], [phi[2], 0, -phi[0]], [-phi[1], phi[0], 0]]
    x[:3, 3] = rho
    return x


@pytest.mark.parametrize("scale", [0.0, 1e-5, 0.3, 2.0, 6.2])
def test_se3_exp_and_left_jacobian_match_the_matrix_exponential(scale):
    rng = np.random.default_rng(1)
    rho, phi = rng.normal(size=3), rng.normal(size=3) * scale
    rot, pos = se3_exp(rho, phi)
    e = expm(_hat4(rho, phi))
    assert np.abs(rot - e[:3, :3]).max() < 1e-12 and np.abs(pos - e[:3, 3]).max() < 1e-12
    jac = se3_left_jacobian(rho, phi)
    for i in range(6):
        d = np.eye(6)[i]
        twist = expm_frechet(_hat4(rho, phi), _hat4(d[:3], d[3:]), compute_expm=False) @ np.linalg.inv(e)
        col = np.r_[twist[:3, 3], twist[2, 1], twist[0, 2], twist[1, 0]]
        assert np.abs(col - jac[:, i]).max() < 1e-12


def _beam(extensible=True, n=5):
    root = expm(_hat4(np.zeros(3), [0.3, -0.2, 0.5]))[:3, :3]  # an arbitrary clamp orientation
    return BeamProperties(length_m=2.0, n_elements=n, gj_nm2=1.0, ei_flap_nm2=2.0, ei_chord_nm2=3.0,
                          mass_kg_per_m=1.5, ea_n=10.0 if extensible else None, cg_offset_m=0.1,
                          torsion_inertia_kg_m=0.02, flap_inertia_kg_m=0.001, chord_inertia_kg_m=0.019,
                          root_position_m=[0.1, -0.2, 0.3], root_rotation=root)


@pytest.mark.parametrize("extensible", [True, False])
def test_jacobians_match_finite_differences_of_the_configuration(extensible):
    beam = _beam(extensible)
    q = np.random.default_rng(0).normal(size=beam.n_coordinates) * 0.5
    kin = beam_kinematics(beam, q)
    h = 1e-6
    for i in range(beam.n_coordinates):
        dq = np.eye(beam.n_coordinates)[i] * h
        kp, km = beam_kinematics(beam, q + dq), beam_kinematics(beam, q - dq)
        assert np.abs((kp.positions - km.positions) / (2 * h) - kin.jac_position[:, :, i]).max() < 1e-8
        assert np.abs((kp.tip_position - km.tip_position) / (2 * h) - kin.tip_jac_position[:, i]).max() < 1e-8
        w = ((kp.rotations - km.rotations) / (2 * h)) @ kin.rotations.transpose(0, 2, 1)
        spin = np.stack([w[:, 2, 1], w[:, 0, 2], w[:, 1, 0]], axis=1)
        assert np.abs(spin - kin.jac_rotation[:, :, i]).max() < 1e-8
    assert np.allclose(kin.node_positions[0], beam.root_position_m) and np.allclose(kin.node_rotations[0],
                                                                                    beam.root_rotation)
    rot = kin.rotations
    assert np.abs(rot.transpose(0, 2, 1) @ rot - np.eye(3)).max() < 1e-12  # frames stay orthonormal


def test_mass_matrix_is_symmetric_positive_definite_and_gives_a_rods_rotational_energy():
    beam = _beam()
    m = mass_matrix(beam, beam_kinematics(beam, np.random.default_rng(2).normal(size=beam.n_coordinates)))
    assert np.allclose(m, m.T, atol=0) and np.linalg.eigvalsh(m)[0] > 0
    # Straight uniform beam, no offsets, a chord-curvature rate κ̇ = ω/ℓ in the first element only: there the arc
    # p(s) = (s, κ s²/2) moves at ω s²/(2ℓ) and turns at ω s/ℓ; beyond it the beam turns rigidly at ω about the
    # first node, which moves at ω ℓ/2. T = ½ m [∫0^ℓ (ω s²/2ℓ)² ds + ∫ℓ^L ω² (s - ℓ/2)² ds]
    # + ½ I_chord [∫0^ℓ (ω s/ℓ)² ds + (L - ℓ) ω²], exactly (3-point Gauss integrates the quartic exactly).
    plain = BeamProperties(length_m=2.0, n_elements=4, gj_nm2=1, ei_flap_nm2=1, ei_chord_nm2=1, mass_kg_per_m=1.5,
                           chord_inertia_kg_m=0.01)
    m0 = mass_matrix(plain, beam_kinematics(plain, np.zeros(plain.n_coordinates)))
    ell, length, omega = plain.element_length_m, 2.0, 1.0
    v = np.zeros(plain.n_coordinates)
    v[2] = omega / ell
    expected = 0.5 * (1.5 * (omega**2 * ell**3 / 20 + omega**2 * ((length - ell / 2) ** 3 - (ell / 2) ** 3) / 3)
                      + 0.01 * (omega**2 * ell / 3 + (length - ell) * omega**2))
    assert 0.5 * v @ m0 @ v == pytest.approx(expected, rel=1e-12)
    assert np.allclose(stiffness_matrix(plain), np.diag([1.0, 1.0, 1.0] * 4) * 0.5)


@pytest.mark.parametrize(("field", "value", "match"), [
    ("length_m", -1.0, "length_m = -1.0: must be a finite number > 0"),
    ("n_elements", 0, "n_elements = 0: must be an integer in 1-1000"),
    ("ei_flap_nm2", float("nan"), "ei_flap_nm2 = nan: must be a finite number > 0"),
    ("mass_kg_per_m", [1.0, 2.0], r"mass_kg_per_m has shape \(2,\): must be a number or one value per element"),
    ("root_rotation", np.diag([1.0, 1.0, -1.0]), "root_rotation must be orthonormal and right-handed"),
    ("gauss_points", 9, "gauss_points = 9: must be an integer in 1-6"),
])
def test_bad_beam_input_names_the_field_and_the_allowed_range(field, value, match):
    args = dict(length_m=1.0, n_elements=3, gj_nm2=1, ei_flap_nm2=1, ei_chord_nm2=1, mass_kg_per_m=1)
    args[field] = value
    with pytest.raises(ValueError, match=match):
        BeamProperties(**args)
    with pytest.raises(ValueError, match=r"q has shape \(2,\): must be \(9,\)"):
        beam_kinematics(BeamProperties(length_m=1.0, n_elements=3, gj_nm2=1, ei_flap_nm2=1, ei_chord_nm2=1,
                                       mass_kg_per_m=1), np.zeros(2))
