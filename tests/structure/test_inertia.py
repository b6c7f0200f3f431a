"""Mass matrix M(q) (eqs. 7-10) and kinetic-energy derivatives (eq. 33) on the GTM.

Invariants: M symmetric positive definite for admissible q; dT/dq and dM/dt V agree with central
finite differences of T = 1/2 V^T M(q) V (step 1e-2 m, tolerance 1e-6 relative: M is quadratic in q,
so central differences are exact up to round-off, which a large step keeps small).
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.structure.model import StructuralModel


@pytest.fixture(scope="module")
def gtm():
    return StructuralModel(load_aircraft("gtm"))


def _random_state(st, seed):
    rng = np.random.default_rng(seed)
    q = 0.3 * rng.standard_normal(st.dofs.nq)  # tens of cm of modal amplitude: admissible deformations
    v = rng.standard_normal(st.dofs.n_v) * np.r_[[200, 5, 10], [0.2] * 3, [0.5] * (st.dofs.n_v - 6)]
    return q, v


@pytest.mark.parametrize("seed", range(5))
def test_mass_matrix_symmetric_positive_definite(gtm, seed):
    q, _ = _random_state(gtm, seed)
    m = gtm.inertia.mass_matrix(q)
    np.testing.assert_allclose(m, m.T, atol=1e-9 * np.abs(m).max())
    assert np.linalg.eigvalsh(m).min() > 0


@pytest.mark.parametrize("seed", range(3))
def test_dT_dq_matches_finite_differences(gtm, seed):
    q, v = _random_state(gtm, seed)
    T = lambda qq: 0.5 * v @ gtm.inertia.mass_matrix(qq) @ v
    h = 1e-2
    fd = np.array([(T(q + h * e) - T(q - h * e)) / (2 * h) for e in np.eye(q.size)])
    exact = gtm.inertia.dT_dq(v, q)
    np.testing.assert_allclose(exact, fd, rtol=1e-6, atol=1e-6 * np.abs(exact).max())


def test_mdot_v_matches_time_derivative(gtm):
    q, v = _random_state(gtm, 7)
    s = v[6 : 6 + gtm.dofs.nq]
    h = 1e-2
    fd = (gtm.inertia.mass_matrix(q + h * s) - gtm.inertia.mass_matrix(q - h * s)) @ v / (2 * h)
    exact = gtm.inertia.mdot_v(v, q, s)
    np.testing.assert_allclose(exact, fd, atol=1e-6 * np.abs(exact).max())


def test_mass_matrix_rigid_block_is_mass_cg_and_inertia(gtm):
    # M0[v, v] = m I; M0[v, omega] = -skew(m r_cg) (eqs. 8-10 for the rigid body).
    m0 = gtm.inertia.m0
    mp = gtm.mass_properties
    np.testing.assert_allclose(m0[0:3, 0:3], mp.mass_kg * np.eye(3), rtol=1e-12, atol=1e-12 * mp.mass_kg)
    s = mp.mass_kg * mp.cg_m
    skew_s = np.array([[0, -s[2], s[1]], [s[2], 0, -s[0]], [-s[1], s[0], 0]])
    np.testing.assert_allclose(m0[0:3, 3:6], -skew_s, atol=1e-9 * np.abs(m0).max())
