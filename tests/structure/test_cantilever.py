"""Uniform cantilever wing: closed-form frequencies and static sag (restrained, single component).

Sources: Euler-Bernoulli clamped-free beam omega_n = (beta_n L)^2 sqrt(EI/(m L^4)) and uniform shaft
omega_k = (2k-1) (pi/2L) sqrt(GJ/I_theta) (reference aero-kinematics.md 6.2-6.3; Meirovitch,
"Fundamentals of Vibrations", 2001, ch. 8); tip deflection under uniform load q L^4/(8 EI) (Timoshenko &
Gere, "Mechanics of Materials", table of beam deflections).
"""

from dataclasses import replace

import numpy as np
from scipy.linalg import eigh

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel
from flexsim.structure.shapes import bending_shapes, cantilever_beta_l

G = 9.80665


def _uncoupled_goland():
    """The bundled uniform (Goland) wing with the CG on the elastic axis, so bending and torsion decouple."""
    a = load_aircraft("goland_wing")
    c = a.components[0]
    k = c.sections.station_m.size
    c0 = replace(c, sections=replace(c.sections, cg_offset_m=np.zeros(k)))
    return replace(a, components=(c0,)), c0


def test_uniform_cantilever_frequencies_match_closed_forms():
    # Acceptance: first three bending and first two torsion frequencies within 0.5 %.
    aircraft, wing = _uncoupled_goland()
    model = AircraftModel(aircraft, variant="restrained", gravity_m_s2=0.0)
    w = in_vacuo_modes(model).frequencies_rad_s
    sec = wing.sections
    L, m, ei, gj, ith = wing.length_m, sec.mass_kg_per_m[0], sec.ei_nm2[0], sec.gj_nm2[0], sec.torsional_inertia_kg_m[0]
    bending = cantilever_beta_l(3) ** 2 * np.sqrt(ei / (m * L**4))
    torsion = np.array([1.0, 3.0]) * np.pi / (2 * L) * np.sqrt(gj / ith)
    expected = np.sort(np.concatenate([bending, torsion]))
    np.testing.assert_allclose(w, expected, rtol=5e-3)
    # The shape functions are the exact eigenfunctions here, so the agreement is in fact ~1e-9.
    np.testing.assert_allclose(w, expected, rtol=1e-8)


def test_mode_labels_identify_bending_and_torsion():
    aircraft, _ = _uncoupled_goland()
    modes = in_vacuo_modes(AircraftModel(aircraft, variant="restrained", gravity_m_s2=0.0)).modes
    assert [m.dominant_dof for m in modes[:2]] == ["right_wing bending 1", "right_wing torsion 1"]
    assert all(abs(m.dominant_fraction - 1.0) < 1e-9 for m in modes)


def test_clamped_wing_sags_q_l4_over_8ei_under_own_weight():
    # Acceptance: static tip deflection under own weight within 1 % of q L^4 / (8 EI), q = m g.
    aircraft = load_aircraft("goland_wing")  # bending under uniform load does not depend on the CG offset
    wing = aircraft.components[0]
    model = AircraftModel(aircraft, variant="restrained", aero=None)
    _, f = model.generalized_forces(model.layout.zeros(), np.zeros(4))
    st = model.structure
    nq = st.dofs.nq
    q = np.linalg.solve(st.k_bending, f[6 : 6 + nq])  # K q = U_gravity (eq. 33 at rest)
    tip = bending_shapes(wing.length_m, wing.length_m, wing.bending_modes)[0] @ q
    sec = wing.sections
    exact = sec.mass_kg_per_m[0] * G * wing.length_m**4 / (8 * sec.ei_nm2[0])
    assert tip > 0  # z_w is down: the wing sags
    np.testing.assert_allclose(tip, exact, rtol=1e-2)
    # Modal truncation error with m = 3 is 0.06 % (series of docs/reference/aero-kinematics.md §6.2); assert it is that small.
    np.testing.assert_allclose(tip, exact, rtol=1e-3)


def test_eigen_solution_independent_of_variant_plumbing():
    # Restrained modes from the model equal eigh(K, M0) on the elastic block (no rigid DOFs).
    aircraft, _ = _uncoupled_goland()
    model = AircraftModel(aircraft, variant="restrained", aero=None)
    st = model.structure
    lam = eigh(st.stiffness[6:, 6:], st.inertia.m0[6:, 6:], eigvals_only=True)
    np.testing.assert_allclose(in_vacuo_modes(model).frequencies_rad_s, np.sqrt(lam), rtol=1e-12)


def test_modal_structural_damping_gives_the_requested_ratio():
    # Every clamped mode of the restrained wing gets damping ratio zeta: eigenvalues -zeta w +- i w sqrt(1 - zeta^2).
    from flexsim.linear.linearize import linearize

    aircraft, _ = _uncoupled_goland()
    zeta = 0.02
    model = AircraftModel(aircraft, variant="restrained", aero=None, gravity_m_s2=0.0, structural_damping=zeta)
    lin = linearize(model, model.layout.zeros(), np.zeros(4))
    lam = np.linalg.eigvals(lin.a)
    lam = lam[lam.imag > 0]
    ratios = -lam.real / np.abs(lam)
    np.testing.assert_allclose(ratios, zeta, rtol=1e-6)
