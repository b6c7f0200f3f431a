"""Shape functions of paper eq. (1) against the closed forms of reference aero-kinematics.md 6.2-6.3."""

import numpy as np
import pytest

from flexsim.structure.shapes import MAX_MODES, bending_shapes, cantilever_beta_l, torsion_shapes

L = 3.7
X = np.linspace(0.0, L, 4001)


def test_beta_l_matches_reference_table():
    # Reference 6.2 (30-digit values), tolerance 1e-10 absolute.
    ref = [1.87510406871, 4.69409113297, 7.85475743824, 10.9955407349, 14.1371683910, 17.2787595321]
    np.testing.assert_allclose(cantilever_beta_l(6), ref, atol=1e-10)


def test_bending_normalisation_and_boundary_values_all_modes():
    # int phi^2 = L, phi(L) = 2(-1)^(n+1), phi(0) = phi'(0) = 0 (docs/reference/aero-kinematics.md §6.2); Simpson-exact to 1e-6.
    u = bending_shapes(X, L, MAX_MODES)
    from scipy.integrate import simpson

    np.testing.assert_allclose(simpson(u**2, x=X, axis=0) / L, 1.0, rtol=1e-6)
    np.testing.assert_allclose(u[-1], 2.0 * (-1.0) ** np.arange(MAX_MODES), atol=1e-9)
    np.testing.assert_allclose(u[0], 0.0, atol=1e-12)
    np.testing.assert_allclose(bending_shapes(0.0, L, MAX_MODES, 1)[0], 0.0, atol=1e-10)
    # free end: zero moment and shear, phi''(L) = phi'''(L) = 0 -> check phi''(L) relative to its scale
    u2 = bending_shapes(L, L, MAX_MODES, 2)[0]
    scale = (cantilever_beta_l(MAX_MODES) / L) ** 2
    np.testing.assert_allclose(u2 / scale, 0.0, atol=1e-8)


def test_bending_integral_matches_reference():
    # int phi_n dx / L = 2 sigma_n / (beta_n L): reference table 6.2 column, 1e-7.
    from scipy.integrate import simpson

    u = bending_shapes(X, L, 6)
    ref = [0.78299176, 0.43393590, 0.25442530, 0.18189802, 0.14147084, 0.11574906]
    np.testing.assert_allclose(simpson(u, x=X, axis=0) / L, ref, atol=2e-8)


@pytest.mark.parametrize("derivative", [1, 2])
def test_bending_derivatives_match_finite_differences(derivative):
    # Analytic derivatives vs 4th-order central differences, 1e-6 of the derivative's scale.
    h = 1e-4
    x = np.linspace(0.1, L - 0.1, 37)
    f = lambda xx: bending_shapes(xx, L, 6, derivative - 1)
    fd = (-f(x + 2 * h) + 8 * f(x + h) - 8 * f(x - h) + f(x - 2 * h)) / (12 * h)
    exact = bending_shapes(x, L, 6, derivative)
    np.testing.assert_allclose(fd, exact, atol=1e-6 * np.abs(exact).max())


def test_torsion_shapes_closed_form():
    # psi_n(L) = (-1)^(n+1), int psi^2 = L/2, int psi = 2L/((2n-1) pi) (docs/reference/aero-kinematics.md §6.3).
    from scipy.integrate import simpson

    p = torsion_shapes(X, L, 5)
    n = np.arange(1, 6)
    np.testing.assert_allclose(p[-1], (-1.0) ** (n + 1), atol=1e-12)
    np.testing.assert_allclose(simpson(p**2, x=X, axis=0), L / 2, rtol=1e-8)
    np.testing.assert_allclose(simpson(p, x=X, axis=0), 2 * L / ((2 * n - 1) * np.pi), rtol=1e-8)
    # interior points: np.gradient is second-order there (one-sided at the ends)
    np.testing.assert_allclose(torsion_shapes(X, L, 5, 1)[1:-1], np.gradient(p, X, axis=0)[1:-1], atol=2e-5)


def test_bad_derivative_order_raises():
    with pytest.raises(ValueError, match="derivative"):
        bending_shapes(X, L, 2, derivative=3)
