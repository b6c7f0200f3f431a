"""Strip airloads on the strain-based beam (flexsim.model.beam_aero) against thin-airfoil closed forms.

* A steady strip at angle of attack α carries lift 2πρbU² sin α normal to the wind and no drag (the Peters normal
  force 2πρbU² sin α cos α plus the leading-edge suction 2πρbU² sin² α; thin-airfoil theory, Bisplinghoff,
  Ashley & Halfman 1955 §5-6) and, about a reference axis a semichords aft of mid-chord, the moment
  (½ + a) b × normal force nose up (the normal force at the quarter chord; the suction acts along the chord). Round-off tolerance 1e-12.
* With a profile drag coefficient cd0 the strip adds the drag ½ρU² 2b cd0 along the wind (the in-section air
  velocity) to that lift, for strips given one by one (arrays) or all alike (scalars) (round-off, 1e-12).
* The strips follow the deformed sections: a wing rolled by a dihedral angle Γ about the wind carries the same lift,
  turned with it (1e-12).
* The linear aeroelastic system of a wing in still air (U = 0) has the in-vacuo frequencies of
  flexsim.structure.beam_statics.vibration_modes plus the (apparent-mass) shift: at U = 0 the inflow decouples
  and the structural roots equal those of (M + M_a, K); asserted against a direct generalized eigenproblem, 1e-8.
"""

import numpy as np
import pytest
from scipy.linalg import eigvals

from flexsim.model.beam_aero import TunnelFlow, WingAero, _steady_section_loads, aeroelastic_system, section_loads
from flexsim.structure.strain_beam import BeamProperties, beam_kinematics, mass_matrix, stiffness_matrix


def _wing(root=np.eye(3)):
    return BeamProperties(length_m=4.0, n_elements=4, gj_nm2=1e4, ei_flap_nm2=2e4, ei_chord_nm2=4e6,
                          mass_kg_per_m=0.75, torsion_inertia_kg_m=0.1, root_rotation=root)


def _rot_x(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rot_y(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


@pytest.mark.parametrize("alpha_deg", [2.0, 10.0])
@pytest.mark.parametrize("axis_fraction", [0.5, 0.35])
def test_steady_strip_lift_is_normal_to_the_wind_with_the_quarter_chord_moment(alpha_deg, axis_fraction):
    alpha, rho, u, chord = np.radians(alpha_deg), 0.9, 20.0, 1.2
    beam = _wing(_rot_x(alpha))
    kin = beam_kinematics(beam, np.zeros(beam.n_coordinates))
    b, a = WingAero(chord_m=chord, axis_fraction=axis_fraction).strips(beam, kin)
    force, moment = _steady_section_loads(kin, b, a, TunnelFlow(u, rho))
    lift = 2 * np.pi * rho * (chord / 2) * u**2 * np.sin(alpha)
    assert np.allclose(force, [0.0, 0.0, lift], rtol=0, atol=1e-12 * lift)
    assert np.allclose(moment, [(0.5 + a[0]) * chord / 2 * lift * np.cos(alpha), 0.0, 0.0], rtol=0, atol=1e-12 * lift)


@pytest.mark.parametrize("per_strip", [False, True])
def test_profile_drag_acts_along_the_wind(per_strip):
    alpha, rho, u, chord, cd0 = np.radians(5.0), 0.9, 20.0, 1.2, 0.02
    beam = _wing(_rot_x(alpha))
    kin = beam_kinematics(beam, np.zeros(beam.n_coordinates))
    b, a = WingAero(chord_m=chord).strips(beam, kin)
    p = b.size
    wind = np.array([0.0, -u, 0.0])
    args = (np.full(p, rho), np.tile(wind, (p, 1)), np.full(p, cd0)) if per_strip else (rho, wind, cd0)
    force, _ = section_loads(kin.rotations, b, a, args[1], args[0], cd0=args[2])
    lift = 2 * np.pi * rho * (chord / 2) * u**2 * np.sin(alpha)
    drag = 0.5 * rho * u**2 * chord * cd0
    assert np.allclose(force, [0.0, -drag, lift], rtol=0, atol=1e-12 * lift)


def test_strips_follow_a_dihedral_wing():
    alpha, gamma = np.radians(4.0), np.radians(25.0)
    flat = _wing(_rot_x(alpha))
    rolled = _wing(_rot_y(-gamma) @ _rot_x(alpha))  # dihedral about the wind axis y
    loads = []
    for beam in (flat, rolled):
        kin = beam_kinematics(beam, np.zeros(beam.n_coordinates))
        b, a = WingAero(chord_m=1.0).strips(beam, kin)
        loads.append(_steady_section_loads(kin, b, a, TunnelFlow(15.0, 1.2))[0])
    assert np.allclose(loads[1], loads[0] @ _rot_y(-gamma).T, atol=1e-10)


def test_still_air_system_has_the_structural_roots_with_apparent_mass():
    beam, aero = _wing(), WingAero(chord_m=1.0)
    q0 = np.zeros(beam.n_coordinates)
    k = stiffness_matrix(beam)
    system = aeroelastic_system(beam, aero, TunnelFlow(0.0, 1.2), q0, k)
    n = beam.n_coordinates
    roots = np.linalg.eigvals(system.state_matrix)
    structural = np.sort(np.abs(roots[np.abs(roots.imag) > 1e-6].imag))[::2]
    # apparent mass of the strips at rest: M_a from the Peters [M] (πρb² plunge, πρb⁴/8 pitch about mid-chord)
    kin = beam_kinematics(beam, q0)
    rho, b = 1.2, 0.5
    e1, e3 = kin.rotations[:, :, 0], kin.rotations[:, :, 2]
    pn = np.einsum("pi,pik->pk", e3, kin.jac_position)
    a1 = np.einsum("pi,pik->pk", e1, kin.jac_rotation)
    ma = np.pi * rho * b**2 * (np.einsum("p,pk,pl->kl", kin.points_weight, pn, pn)
                               + b**2 / 8 * np.einsum("p,pk,pl->kl", kin.points_weight, a1, a1))
    expected = np.sort(np.sqrt(eigvals(k, mass_matrix(beam, kin) + ma).real))
    assert np.allclose(structural, expected[: structural.size], rtol=1e-8)
    assert structural.size == n


@pytest.mark.parametrize("incidence", [0.0, 0.05, -0.3])
def test_steady_resultant_is_normal_to_the_wind_with_an_incidence(incidence):
    """Kutta-Joukowski for a thin section without drag: the steady force is normal to the in-section air velocity
    whatever the incidence (rigging or a flap's equivalent angle), and its magnitude is 2 pi rho b |V_in| w0 with
    w0 = w_n + u0 alpha_i (thin-airfoil lift at the effective angle). A resultant tilted by the incidence would make a
    deflected flap produce thrust."""
    rot = np.eye(3)[None]  # e1 = x (span), e2 = y (leading edge), e3 = z
    u0, wn, rho, b = 30.0, 2.0, 1.1, 0.4
    va = np.array([[0.0, -u0, wn]])  # air velocity: from the leading edge, and up through the section
    force, _ = section_loads(rot, np.array([b]), np.array([0.0]), va, rho, incidence=incidence)
    v_in = va[0]
    assert abs(force[0] @ v_in) < 1e-12 * np.linalg.norm(force[0]) * np.linalg.norm(v_in)
    w0 = wn + u0 * incidence
    assert np.linalg.norm(force[0]) == pytest.approx(2 * np.pi * rho * b * abs(w0) * np.linalg.norm(v_in), rel=1e-12)
