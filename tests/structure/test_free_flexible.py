"""Free-flying rigid body with strain-based beams (flexsim.structure.free_flexible) against invariants and closed forms.

* Relative kinematics from the block matrix exponential: positions, frames and velocities equal
  strain_beam.beam_kinematics (J_p q̇, J_θ q̇) to round-off (1e-12); the acceleration J̇_p q̇ equals a central second
  difference of the positions (step 1e-4: truncation ~1e-8 relative; tolerance 1e-6 relative).
* Mass matrix: its strain block is strain_beam.mass_matrix (to round-off); its rigid block at ε = 0 is the mass and
  the inertia about o of the body and the straight rods (closed forms m L, m L³/3).
* Conservation in vacuum without damping (Kane's form of the quasi-coordinate equations is exact, so energy and
  momenta drift only with the integrator's error): scipy solve_ivp DOP853, rtol = atol = 1e-10.
* Very stiff beams: the body rates follow the rigid body's torque-free Euler equations with the inertia of the
  undeformed structure; the neglected deformation is of relative size (Ω/ω₁)² (Ω body rate, ω₁ lowest elastic
  frequency), here < 2e-4, so the tolerance 2e-3 relative.
* Small-deflection limit: with a massless body the two wing halves are one free-free beam of length 2L; its bending
  frequencies are λ² √(EI/(m (2L)⁴)), λ = 4.7300, 7.8532, 10.9956 (Blevins, *Formulas for Natural Frequency and
  Mode Shape*, table 8-1) and torsion k π/(2L) √(GJ/I); constant-strain elements converge at second order
  (measured, first five modes: largest error 1.6 % at 8 elements per half, 0.40 % at 16, 0.10 % at 32), tolerance
  0.5 % at 16 elements. The linearisation equals a finite-difference Jacobian of the right-hand side.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from flexsim.structure.free_flexible import (FreeFlexibleStructure, RigidBody, beam_relative_motion,
                                             conserved_quantities, free_flight_rhs, free_free_frequencies,
                                             generalized_mass_matrix, initial_state)
from flexsim.structure.strain_beam import BeamProperties, beam_kinematics, mass_matrix

#: Root frames in body axes (x forward, y right, z down): e1 outboard, e3 up.
RIGHT = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, -1]])
LEFT = np.array([[0.0, -1, 0], [-1, 0, 0], [0, 0, -1]])
BOOM = np.array([[-1.0, 0, 0], [0, -1, 0], [0, 0, 1]])


def _hale(n_el=1, stiffness=1.0):
    """HALE-like: 16 m wing halves (EI 2e4, GJ 1e4 N m², 0.75 kg/m) continuous through the centreline, a tail boom."""
    def wing(rot):
        return BeamProperties(length_m=16.0, n_elements=n_el, gj_nm2=1e4 * stiffness, ei_flap_nm2=2e4 * stiffness,
                              ei_chord_nm2=4e5 * stiffness, mass_kg_per_m=0.75, cg_offset_m=0.05,
                              torsion_inertia_kg_m=1.0, flap_inertia_kg_m=0.1, chord_inertia_kg_m=1.0,
                              root_rotation=rot)
    boom = BeamProperties(length_m=10.0, n_elements=1, gj_nm2=1e4 * stiffness, ei_flap_nm2=4e4 * stiffness,
                          ei_chord_nm2=4e4 * stiffness, mass_kg_per_m=0.5, torsion_inertia_kg_m=1.0,
                          flap_inertia_kg_m=0.5, chord_inertia_kg_m=0.5, root_position_m=(-1, 0, 0),
                          root_rotation=BOOM)
    return FreeFlexibleStructure(RigidBody(50.0, (0.2, 0, 0.1), np.diag([5.0, 2, 6])), (wing(RIGHT), wing(LEFT), boom))


def test_relative_motion_matches_the_beam_kinematics():
    beam = BeamProperties(length_m=16.0, n_elements=4, gj_nm2=1e4, ei_flap_nm2=2e4, ei_chord_nm2=4e5,
                          mass_kg_per_m=0.75, ea_n=1e7, root_rotation=RIGHT, root_position_m=(0.3, 0.1, 0))
    rng = np.random.default_rng(0)
    q, qd = rng.normal(size=beam.n_coordinates) * 0.1, rng.normal(size=beam.n_coordinates) * 0.2
    kin = beam_kinematics(beam, q)
    e = kin.points_element
    p, pd, pdd, rot, rd, _ = beam_relative_motion(beam, q, qd, e, kin.points_s / beam.element_length_m - e)
    assert np.abs(p - kin.positions).max() < 1e-12 * 16 and np.abs(rot - kin.rotations).max() < 1e-12
    assert np.abs(pd - kin.jac_position @ qd).max() < 1e-12 * np.abs(pd).max()
    w = rd @ np.swapaxes(rot, 1, 2)
    assert np.abs(w + np.swapaxes(w, 1, 2)).max() < 1e-12
    w_vec = np.stack([w[:, 2, 1], w[:, 0, 2], w[:, 1, 0]], -1)
    assert np.abs(w_vec - kin.jac_rotation @ qd).max() < 1e-12 * np.abs(w_vec).max()
    h = 1e-4
    fd = (beam_kinematics(beam, q + h * qd).positions - 2 * p + beam_kinematics(beam, q - h * qd).positions) / h**2
    assert np.abs(fd - pdd).max() < 1e-6 * np.abs(pdd).max()


def test_mass_matrix_blocks():
    st = _hale(n_el=2)
    mass = generalized_mass_matrix(st, np.zeros(st.n_strains))
    s = st.strain_slices()[0]
    beam = st.beams[0]
    block = mass_matrix(beam, beam_kinematics(beam, np.zeros(beam.n_coordinates)))
    assert np.abs(mass[6 + s.start:6 + s.stop, 6 + s.start:6 + s.stop] - block).max() < 1e-12 * np.abs(block).max()
    m_total = 50 + 2 * 0.75 * 16 + 0.5 * 10
    assert mass[0, 0] == pytest.approx(m_total, rel=1e-12)
    # roll inertia about o: body (5 + 50·0.1²), rods along y (2·m L³/3), boom torsion inertia along x
    i_xx = 5 + 50 * 0.1**2 + 2 * 0.75 * 16**3 / 3 + 1.0 * 10 + 2 * (0.1 * 16)
    assert mass[3, 3] == pytest.approx(i_xx, rel=1e-12)


def _conservation(t_end, tol, rate_scale):
    st = _hale()
    rng = np.random.default_rng(0)
    y0 = initial_state(st, velocity_m_s=(10, 0, 1), rate_rad_s=(1.0, -0.3, 0.5),
                       strain_rates=rng.normal(size=st.n_strains) * rate_scale)
    sol = solve_ivp(lambda t, y: free_flight_rhs(st, t, y), (0, t_end), y0, method="DOP853", rtol=1e-10,
                    atol=1e-10, dense_output=True)
    assert sol.status == 0
    c0 = conserved_quantities(st, y0)
    worst = np.zeros(3)
    tip = 0.0
    for t in np.linspace(0, t_end, 41):
        y = sol.sol(t)
        c = conserved_quantities(st, y)
        worst = np.maximum(worst, [abs(c.energy_j / c0.energy_j - 1),
                                   np.linalg.norm(c.angular_momentum_cg - c0.angular_momentum_cg)
                                   / np.linalg.norm(c0.angular_momentum_cg),
                                   np.linalg.norm(c.linear_momentum - c0.linear_momentum)
                                   / np.linalg.norm(c0.linear_momentum)])
        kin = beam_kinematics(st.beams[0], y[7:7 + st.beams[0].n_coordinates])
        tip = max(tip, np.linalg.norm(kin.tip_position - (0, 16, 0)))
    assert worst.max() < tol, worst
    return tip


def test_energy_and_momenta_conserved_over_one_second():
    _conservation(1.0, 1e-9, 0.2)


@pytest.mark.slow
def test_energy_and_momenta_conserved_over_ten_seconds_in_large_motion():
    tip = _conservation(10.0, 1e-8, 0.3)
    assert tip > 0.25 * 16


@pytest.mark.slow
def test_stiff_beams_follow_euler_equations():
    st = _hale(stiffness=100.0)
    omega1 = free_free_frequencies(st)[0]
    rate = np.array([0.3, 0.05, 0.1])
    assert (np.linalg.norm(rate) / omega1) ** 2 < 2e-4
    y0 = initial_state(st, rate_rad_s=rate)
    sol = solve_ivp(lambda t, y: free_flight_rhs(st, t, y), (0, 2.0), y0, method="DOP853", rtol=1e-9, atol=1e-10)
    # rigid inertia about the mass centre of the undeformed structure (body + rods), from the mass matrix at ε = 0
    mass = generalized_mass_matrix(st, np.zeros(st.n_strains))
    m = mass[0, 0]
    c = np.array([mass[2, 4], mass[0, 5], mass[1, 3]]) / m  # M_vω = −m c^, so c from its entries
    c_hat = np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])
    inertia = mass[3:6, 3:6] + m * c_hat @ c_hat
    euler = solve_ivp(lambda t, w: np.linalg.solve(inertia, -np.cross(w, inertia @ w)), (0, 2.0), rate,
                      method="DOP853", rtol=1e-12, atol=1e-14, t_eval=sol.t)
    n = st.n_strains
    omega = sol.y[10 + n:13 + n]
    assert np.abs(omega - euler.y).max() < 2e-3 * np.linalg.norm(rate)
    assert np.abs(omega - rate[:, None]).max() > 1e-2 * np.linalg.norm(rate)  # the motion is not a trivial spin


def test_free_free_frequencies_of_a_free_beam():
    length, mu, ei, ei_c, gj, it = 16.0, 0.75, 2e4, 8e4, 1e4, 0.1

    def wing(rot):
        return BeamProperties(length_m=length, n_elements=16, gj_nm2=gj, ei_flap_nm2=ei, ei_chord_nm2=ei_c,
                              mass_kg_per_m=mu, torsion_inertia_kg_m=it, root_rotation=rot)
    st = FreeFlexibleStructure(RigidBody(0.0), (wing(RIGHT), wing(LEFT)))
    lam = np.array([4.730040745, 7.853204624, 10.99560784])
    ref = np.sort(np.r_[lam**2 * np.sqrt(ei / (mu * (2 * length) ** 4)),
                        lam**2 * np.sqrt(ei_c / (mu * (2 * length) ** 4)),
                        np.pi / (2 * length) * np.sqrt(gj / it)])
    freq = free_free_frequencies(st)
    assert np.abs(freq[:5] / ref[:5] - 1).max() < 5e-3

    # the linearisation equals a central-difference Jacobian of the right-hand side about rest
    n = st.n_strains
    y0 = initial_state(st)
    jac = np.zeros((n, n))
    h = 1e-6
    for k in range(n):
        d = np.zeros(st.n_states)
        d[7 + k] = h
        jac[:, k] = (free_flight_rhs(st, 0, y0 + d) - free_flight_rhs(st, 0, y0 - d))[13 + n:] / (2 * h)
    mass = generalized_mass_matrix(st, np.zeros(n))
    full = np.zeros((6 + n, n))
    full[6:] = -st.stiffness()
    expected = np.linalg.solve(mass, full)[6:]
    assert np.abs(jac - expected).max() < 1e-6 * np.abs(expected).max()
    fd_freq = np.sort(np.sqrt(np.abs(np.linalg.eigvals(jac).real)))
    assert np.abs(fd_freq / freq - 1).max() < 1e-6


@pytest.mark.parametrize("field, value", [("mass_kg", -1.0), ("cg_m", (0, 0)), ("inertia_kg_m2", -np.eye(3))])
def test_rigid_body_validation(field, value):
    kwargs = {"mass_kg": 1.0, field: value}
    with pytest.raises(ValueError, match=field):
        RigidBody(**kwargs)


def test_singular_structure_refused():
    with pytest.raises(ValueError, match="singular"):
        FreeFlexibleStructure(RigidBody(1.0))


def test_modal_damping_of_the_clamped_modes():
    """``damping_ratio`` ζ gives every mode of the beams with the body clamped the damping ratio ζ: with a body 1e8 times
    the beams' mass (clamped to 1e-8) the linearised free flight at rest has elastic roots −ζω ± jω√(1 − ζ²), damping
    ratio ζ = 0.02 within 1e-6 (the Jacobian's central differences: 1e-8); ζ = 0 leaves the equations undamped."""
    base = _hale(n_el=2)
    heavy = RigidBody(1e10, (0.0, 0.0, 0.0), np.diag([1e12, 1e12, 1e12]))
    st = FreeFlexibleStructure(heavy, base.beams, damping_ratio=0.02)
    n = st.n_strains
    y0 = initial_state(st)
    cols = list(range(7, st.n_states))  # strains and velocities
    jac = np.zeros((len(cols), len(cols)))
    for j, c in enumerate(cols):
        h = 1e-6
        up, down = y0.copy(), y0.copy()
        up[c] += h
        down[c] -= h
        jac[:, j] = (free_flight_rhs(st, 0.0, up)[cols] - free_flight_rhs(st, 0.0, down)[cols]) / (2 * h)
    lam = np.linalg.eigvals(jac)
    elastic = lam[np.abs(lam.imag) > 1e-3]
    assert elastic.size == 2 * n
    assert np.abs(-elastic.real / np.abs(elastic) - 0.02).max() < 1e-6
    assert np.abs(FreeFlexibleStructure(heavy, base.beams).damping()).max() == 0.0
    with pytest.raises(ValueError, match="damping_ratio = 1.5: must be a damping ratio in"):
        FreeFlexibleStructure(heavy, base.beams, damping_ratio=1.5)
