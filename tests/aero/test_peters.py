"""Tests of the Peters–Johnson deformable-airfoil airloads (flexsim.aero.peters).

Sources: docs/reference/aero-kinematics.md §1.2–1.8 (matrices, flap expansion, Theodorsen test values),
Theodorsen NACA Rep. 496 (via flexsim.aero.theodorsen), Garrick NACA Rep. 567 (plunge thrust).
Each test states its tolerance.
"""

import re

import numpy as np
import pytest
from numpy.polynomial import chebyshev

from flexsim.aero import peters as pj
from flexsim.aero.theodorsen import theodorsen_function, theodorsen_load_matrix, theodorsen_operator

A_EA, D_HINGE = -0.3, 0.5  # reference §1.7 set-up, rho = b = U = 1


def harmonic_section_loads(k: float, n_terms: int, a: float = A_EA, d: float = D_HINGE) -> np.ndarray:
    """3x3 harmonic load matrix of the Peters model with the exact wake λ0 = (1 - C)(w0 + w1/2) (eq. 27)."""
    section = pj.flapped_section(n_terms, a, d, 1.0)
    q = np.eye(3)
    p = 1j * k
    w = section.downwash(q, p * q, 1.0)
    lambda0 = (1.0 - theodorsen_function(k)) * pj.circulatory_downwash(w)
    return section.loads(q, p * q, p * p * q, 1.0, 0.0, lambda0, 1.0).T


def test_matrices_match_reference_n5():
    """Reference §1.4 5x5 blocks (πρ normalisation); exact rationals, tol 1e-15."""
    m = pj.peters_matrices(5)
    mass = np.array(
        [
            [1, 0, -1 / 2, 0, 0],
            [0, 1 / 8, 0, -1 / 8, 0],
            [-1 / 2, 0, 1 / 3, 0, -1 / 12],
            [0, -1 / 8, 0, 3 / 16, 0],
            [0, 0, -1 / 12, 0, 2 / 15],
        ]
    )
    damping = np.array(
        [[2, 2, 0, 0, 0], [-1, 0, 1, 0, 0], [0, -1, 0, 1, 0], [0, 0, -1, 0, 1], [0, 0, 0, -1, 0]]
    )
    stiffness = np.array(
        [[0, 2, 4, 6, 8], [0, -1, 0, 0, 0], [0, 0, -2, 0, 0], [0, 0, 0, -3, 0], [0, 0, 0, 0, -4]]
    )
    speed_rate = np.array(
        [[0, 1, 0, 0, 0], [0, 0, 0.5, 0, 0], [0, -0.5, 0, 0.5, 0], [0, 0, -0.5, 0, 0.5], [0, 0, 0, -0.5, 0]]
    )
    derivative = np.array(
        [[0, 1, 0, 3, 0], [0, 0, 4, 0, 8], [0, 0, 0, 6, 0], [0, 0, 0, 0, 8], [0, 0, 0, 0, 0]]
    )
    for got, expected in [
        (m.mass, mass),
        (m.damping, damping),
        (m.stiffness, stiffness),
        (m.speed_rate, speed_rate),
        (m.derivative, derivative),
        (m.inflow, [2, -1, 0, 0, 0]),
    ]:
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-15)


def test_derivative_matrix_against_numpy_chebyshev():
    """[D] columns equal numpy's Chebyshev derivative of T_m (independent implementation); tol 1e-12."""
    n = 12
    d = pj.chebyshev_derivative_matrix(n)
    for m in range(n):
        expected = np.zeros(n)
        deriv = chebyshev.chebder(np.eye(n)[m])
        expected[: deriv.size] = deriv
        np.testing.assert_allclose(d[:, m], expected, atol=1e-12)


def test_flap_coefficients_reference_values_and_quadrature():
    """Reference §1.6 table (6 decimals, tol 1e-6) and a quadrature projection of the flap shape (tol 1e-6)."""
    np.testing.assert_allclose(
        pj.flap_shape_coefficients(8, 0.5),
        [0.108998, 0.195501, 0.137832, 0.068916, 0.013783, -0.013783, -0.015752, -0.004923],
        atol=1e-6,
    )
    np.testing.assert_allclose(
        pj.flap_shape_coefficients(8, 0.6),
        [0.077548, 0.142378, 0.108650, 0.065190, 0.025207, -0.001565, -0.012144, -0.010147],
        atol=1e-6,
    )
    # h_n = (2 - δ_n0)/π ∫ h(cos φ) cos nφ dφ for the unit flap shape h(ξ) = max(ξ - d, 0) (b = 1)
    d, n = 0.3, 10
    phi = np.linspace(0.0, np.pi, 200_001)
    shape = np.maximum(np.cos(phi) - d, 0.0)
    weights = np.full(phi.size, phi[1])
    weights[[0, -1]] *= 0.5
    projected = [(2.0 - (m == 0)) / np.pi * np.sum(weights * shape * np.cos(m * phi)) for m in range(n)]
    np.testing.assert_allclose(pj.flap_shape_coefficients(n, d), projected, atol=1e-6)


def test_transformation_matrix_paper_eq26():
    """Paper eq. 26: h0 = h - abα + bβF0, h1 = bα + bβF1, h_n = bβF_n; exact, tol 1e-15."""
    a, d, b = -0.4, 0.6, 1.7
    t = pj.transformation_matrix(6, a, d, b)
    f = pj.flap_shape_coefficients(6, d)
    np.testing.assert_allclose(t[:, 0], [1, 0, 0, 0, 0, 0], atol=1e-15)
    np.testing.assert_allclose(t[:, 1], [-a * b, b, 0, 0, 0, 0], atol=1e-15)
    np.testing.assert_allclose(t[:, 2], b * f, atol=1e-15)


@pytest.mark.parametrize(
    ("k", "column", "expected"),
    [
        (0.2, 1, [4.723446 + 0.174601j, 0.979247 - 0.593398j, -0.050050 - 0.038198j]),
        (1.0, 0, [-2.511559 + 3.389369j, 1.068484 + 0.677874j, 0.118834 - 0.038121j]),
    ],
)
def test_plunge_pitch_harmonic_loads_reference_values(k, column, expected):
    """Reference §1.7 Theodorsen values (ρ=b=U=1, a=-0.3, d=0.5), rigid h/α with N_h = 2; rel tol 1e-6."""
    got = harmonic_section_loads(k, 2)[:, column]
    np.testing.assert_allclose(got, expected, rtol=1e-6, atol=1e-6 * np.abs(expected).max())


@pytest.mark.parametrize("k", [0.05, 0.2, 0.5, 1.0, 2.0])
def test_plunge_pitch_equal_theodorsen_exactly(k):
    """Lift, M_EA and hinge moment for h and α equal Theodorsen's (NACA 496) to 1e-12 rel. (reference §1.7)."""
    got = harmonic_section_loads(k, 2)[:, :2]
    expected = theodorsen_load_matrix(k, A_EA, 1.0, 1.0, 1.0, D_HINGE)[:, :2]
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12 * np.abs(expected).max())


def test_flap_loads_converge_to_theodorsen():
    """Flap-column error decreases ~O(1/N): reference §1.7 gives 1.7e-1, 1.7e-2, 4.3e-3 at N = 20, 100, 400."""
    errors = []
    for n in (20, 100, 400):
        err = 0.0
        for k in (0.05, 0.2, 0.5, 1.0, 2.0):
            got = harmonic_section_loads(k, n)[:, 2]
            exact = theodorsen_load_matrix(k, A_EA, 1.0, 1.0, 1.0, D_HINGE)[:, 2]
            err = max(err, np.max(np.abs(got - exact) / np.abs(exact)))
        errors.append(err)
    assert errors[0] > errors[1] > errors[2]
    np.testing.assert_allclose(errors, [0.169, 0.0172, 0.00427], rtol=0.05)
    expected_beta = np.array([2.068456 + 0.931242j, -0.772677 - 0.860949j, -0.082660 - 0.130548j])
    np.testing.assert_allclose(harmonic_section_loads(1.0, 400)[:, 2], expected_beta, rtol=0.01)


def test_static_flap_loads_reference():
    """Reference §1.7 static flap checks at N_h = 400, d = 0.5, ρ = U = b = 1: lift 3.8308, mid-chord moment
    0.61418, hinge moment -0.11842 (tol 1e-4)."""
    section = pj.flapped_section(400, 0.0, 0.5, 1.0)
    zero = np.zeros(3)
    lift, moment_mid, hinge = section.loads([0.0, 0.0, 1.0], zero, zero, 1.0, 0.0, 0.0, 1.0)
    assert lift == pytest.approx(3.8308, abs=1e-4)
    assert moment_mid == pytest.approx(0.61418, abs=1e-4)
    assert hinge == pytest.approx(-0.11842, abs=1e-4)


def test_quasi_steady_lift_of_flat_plate():
    """Reference §8.2: steady pitch with λ0 = 0 gives L = 2πρU²bθ and M_EA = (½ + a) b L; tol 1e-12 rel."""
    rho, u, b, a, theta = 1.1, 40.0, 0.6, -0.25, 0.03
    section = pj.flapped_section(2, a, 0.5, b)
    zero = np.zeros(3)
    lift, moment, _ = section.loads([0.0, theta, 0.0], zero, zero, u, 0.0, 0.0, rho)
    assert lift == pytest.approx(2 * np.pi * rho * u**2 * b * theta, rel=1e-12)
    assert moment == pytest.approx((0.5 + a) * b * lift, rel=1e-12)


def test_matrix_form_equals_downwash_form():
    """Reference §1.3 closed form (downwash) equals §1.4 matrix form incl. u̇0 terms; random data, tol 1e-12."""
    rng = np.random.default_rng(1)
    n = 9
    mats = pj.peters_matrices(n)
    h, hd, hdd = rng.normal(size=(3, 4, n))
    u0, u0_dot, lam, rho, b = rng.uniform(0.5, 2.0, size=(5, 4))
    w = pj.downwash(mats, h, hd, u0, b)
    d_t = mats.derivative.T
    w_dot = hdd + (u0 / b)[:, None] * (hd @ d_t) + (u0_dot / b)[:, None] * (h @ d_t)
    got = pj.generalized_loads(mats, h, hd, hdd, u0, u0_dot, lam, rho, b)
    expected = pj.generalized_loads_from_downwash(mats, w, w_dot, u0, lam, rho, b)
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12)


def test_rigid_section_loads_equal_theodorsen_operator_in_time_domain():
    """Rigid section (reference §1.5): the general T-projected loads equal Theodorsen's non-circulatory
    terms plus the circulatory lift of Q - λ0, with Q = w0 + w1/2 Theodorsen's 3/4-chord downwash
    (NACA Rep. 496; paper eq. 27 with λ0 = (1 - C)Q), for random states at constant u0; tol 1e-12.
    Also checks the inflow forcing ẇ0 + ẇ1/2 = Q̇ (reference §2.1)."""
    rng = np.random.default_rng(2)
    n = 5
    theta, h_dot, theta_dot, h_ddot, theta_ddot, lam = rng.normal(size=(6, n))
    u0, rho, b = rng.uniform(0.5, 3.0, size=(3, n))
    a = rng.uniform(-0.5, 0.5, size=n)
    for i in range(n):
        op = theodorsen_operator(a[i], rho[i], b[i], u0[i])
        q2, qd2, qdd2 = np.array([0.0, theta[i]]), np.array([h_dot[i], theta_dot[i]]), np.array([h_ddot[i], theta_ddot[i]])
        q34 = op.downwash_displacement @ q2 + op.downwash_rate @ qd2
        expected = op.mass @ qdd2 + op.damping @ qd2 + op.stiffness @ q2 + op.circulation * (q34 - lam[i])
        section = pj.flapped_section(2, a[i], 0.5, b[i])
        q, qd, qdd = [0.0, theta[i], 0.0], [h_dot[i], theta_dot[i], 0.0], [h_ddot[i], theta_ddot[i], 0.0]
        got = section.loads(q, qd, qdd, u0[i], 0.0, lam[i], rho[i])[:2]
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12)
        w = section.downwash(q, qd, u0[i])
        assert q34 == pytest.approx(pj.circulatory_downwash(w), rel=1e-12)
        w_dot = section.downwash(qd, qdd, u0[i])  # constant u0: w is linear in (q, q_dot)
        forcing = op.downwash_rate @ qdd2 + op.downwash_displacement @ qd2
        expected_forcing = h_ddot[i] + u0[i] * theta_dot[i] + b[i] * (0.5 - a[i]) * theta_ddot[i]
        assert forcing == pytest.approx(expected_forcing, rel=1e-12, abs=1e-12)
        assert pj.circulatory_downwash(w_dot) == pytest.approx(expected_forcing, rel=1e-12, abs=1e-12)


def test_flapped_section_vectorised_over_strips():
    """Per-strip geometry (a, d, b of shape (S,)) and a time axis give the single-section results; tol 1e-12."""
    rng = np.random.default_rng(4)
    a, d, b = rng.uniform(-0.4, 0.2, 4), rng.uniform(0.3, 0.8, 4), rng.uniform(0.5, 2.0, 4)
    strips = pj.flapped_section(8, a, d, b)
    q, qd, qdd = rng.normal(size=(3, 5, 4, 3)) * 0.1  # (time, strip, dof)
    u0, u0_dot, lam, rho = rng.uniform(10.0, 50.0, 4), rng.normal(size=4), rng.normal(size=4), 1.1
    loads = strips.loads(q, qd, qdd, u0, u0_dot, lam, rho)
    drag = strips.drag(q, qd, qdd, u0, u0_dot, lam, rho)
    assert loads.shape == (5, 4, 3) and drag.shape == (5, 4)
    for s in range(4):
        single = pj.flapped_section(8, a[s], d[s], b[s])
        args = (q[:, s], qd[:, s], qdd[:, s], u0[s], u0_dot[s], lam[s], rho)
        np.testing.assert_allclose(loads[:, s], single.loads(*args), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(drag[:, s], single.drag(*args), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("n_terms", [2, 5, 40])
def test_drag_vanishes_in_steady_flow(n_terms):
    """d'Alembert: steady thin-airfoil drag is zero for any pitch/flap camber (λ0 = 0); tol 1e-12 of lift."""
    section = pj.flapped_section(n_terms, -0.3, 0.5, 0.8)
    q, zero = np.array([0.1, 0.05, 0.1]), np.zeros(3)
    drag = section.drag(q, zero, zero, 30.0, 0.0, 0.0, 1.2)
    lift = section.loads(q, zero, zero, 30.0, 0.0, 0.0, 1.2)[0]
    assert abs(drag) < 1e-12 * abs(lift)


def test_drag_plunge_thrust_matches_garrick():
    """Garrick (NACA Rep. 567, 1936): mean thrust of a plunging plate = πρbω²h̄²|C(k)|²; tol 1e-10 rel."""
    k, rho, b, u, amplitude = 0.4, 1.2, 0.5, 10.0, 0.05
    omega = k * u / b
    section = pj.flapped_section(2, 0.0, 0.5, b)
    t = np.linspace(0.0, 2.0 * np.pi / omega, 256, endpoint=False)
    phase = np.exp(1j * omega * t)[:, None]
    amp = np.array([amplitude, 0.0, 0.0])
    q, qd, qdd = (np.real(c * amp * phase) for c in (1.0, 1j * omega, -(omega**2)))
    w_hat = pj.circulatory_downwash(section.downwash(amp, 1j * omega * amp, u))
    lam = np.real((1.0 - theodorsen_function(k)) * w_hat * phase[:, 0])
    mean_drag = section.drag(q, qd, qdd, u, 0.0, lam, rho).mean()
    expected = -np.pi * rho * b * omega**2 * amplitude**2 * abs(theodorsen_function(k)) ** 2
    assert mean_drag == pytest.approx(expected, rel=1e-10)


@pytest.mark.parametrize("bad", [0, -3, 2.5, True, "4"])
def test_bad_expansion_size_raises(bad):
    """Expansion size must be a positive int; ValueError names the parameter and value."""
    with pytest.raises(ValueError, match=r"n_terms.*" + re.escape(repr(bad))):
        pj.peters_matrices(bad)


def test_bad_hinge_raises():
    """Hinge outside (-1, 1) is rejected with a clear ValueError."""
    with pytest.raises(ValueError, match="hinge"):
        pj.flap_shape_coefficients(4, 1.0)
