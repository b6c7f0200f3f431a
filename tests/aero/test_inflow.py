"""Tests of the Peters finite-state inflow model (flexsim.aero.inflow).

Sources: docs/reference/aero-kinematics.md §2.1 (coefficients), §2.2 (accuracy against C(k), static gain,
Wagner step response); Peters, Karunamoorthy & Cao (1995). Tolerances are stated per test.
"""

import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from flexsim.aero.inflow import (
    induced_inflow,
    inflow_coefficients,
    inflow_state_derivative,
    inflow_transfer_function,
)
from flexsim.aero.theodorsen import theodorsen_function


@pytest.mark.parametrize(
    ("n", "expected"),
    [
        (4, [12, -30, 20, -1]),
        (6, [30, -210, 560, -630, 252, -1]),
        (8, [56, -756, 4200, -11550, 16632, -12012, 3432, -1]),
    ],
)
def test_b_coefficients_reference(n, expected):
    """Reference §2.1 integer b_n; exact (tol 1e-9 absolute on integers up to 1.7e4)."""
    np.testing.assert_allclose(inflow_coefficients(n).b, expected, rtol=0, atol=1e-9)


def test_c_d_and_a_matrix_n4():
    """Reference §2.1: c_n = 2/n, d = [1/2, 0, ...], A for N = 4 (printed to 4 decimals; tol 5e-5)."""
    coeffs = inflow_coefficients(4)
    np.testing.assert_allclose(coeffs.c, [2, 1, 2 / 3, 0.5], rtol=1e-15)
    np.testing.assert_allclose(coeffs.d, [0.5, 0, 0, 0], rtol=1e-15)
    expected = [
        [19, -45.5, 30, -1.5],
        [6.75, -15, 9.75, -0.5],
        [4.3333, -9.8333, 6.6667, -0.5],
        [3.25, -7.5, 5.125, -0.25],
    ]
    np.testing.assert_allclose(coeffs.A, expected, rtol=0, atol=5e-5)
    np.testing.assert_allclose(coeffs.A_inv @ coeffs.A, np.eye(4), atol=1e-10)


@pytest.mark.parametrize("n", range(1, 11))
def test_b_sums_to_one(n):
    """Reference §2.1: Σ b_n = 1 for every N (tol 1e-9, the entries reach ~1e8 at N = 10)."""
    assert inflow_coefficients(n).b.sum() == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize(("n", "gain"), [(4, 0.48718), (6, 0.49898), (8, 0.49995)])
def test_static_gain(n, gain):
    """Reference §2.2: λ0(0+) = ½ bᵀA⁻¹c (exact value 0.5); printed to 5 decimals, tol 6e-6."""
    coeffs = inflow_coefficients(n)
    assert 0.5 * coeffs.b @ coeffs.A_inv_c == pytest.approx(gain, abs=6e-6)


def test_transfer_function_approximates_one_minus_c():
    """Reference §2.2, N = 6: max |λ0/(w0 + w1/2) - (1 - C(k))| over k ∈ (0, 3] is 0.0157 (< 0.016),
    with errors 0.013 / 0.0064 / 0.0006 at k = 0.1 / 0.5 / 1.0 (tol 5e-4)."""
    coeffs = inflow_coefficients(6)
    k = np.linspace(1e-3, 3.0, 3000)
    error = np.abs(inflow_transfer_function(coeffs, k) - (1.0 - theodorsen_function(k)))
    assert error.max() < 0.016
    assert error.max() > 0.015  # the model is an approximation; a zero error would mean C(k) was used
    k_check = np.array([0.1, 0.5, 1.0])
    at = np.abs(inflow_transfer_function(coeffs, k_check) - (1.0 - theodorsen_function(k_check)))
    np.testing.assert_allclose(at, [0.013, 0.0064, 0.0006], atol=5e-4)


def test_transfer_function_matches_state_equation():
    """The harmonic transfer is the steady-state response of the ODE (reference §2.1); tol 1e-12."""
    coeffs = inflow_coefficients(5)
    k = 0.37
    lam_hat = np.linalg.solve(1j * k * coeffs.A + np.eye(5), coeffs.c * 1j * k)  # b = u0 = 1, Q̂ = 1
    residual = 1j * k * lam_hat - inflow_state_derivative(coeffs, lam_hat, 1j * k, 1.0, 1.0)
    np.testing.assert_allclose(residual, 0.0, atol=1e-12)
    transfer = complex(inflow_transfer_function(coeffs, k))
    assert induced_inflow(coeffs, lam_hat) == pytest.approx(transfer, rel=1e-12)


def test_wagner_step_response_n6():
    """Reference §2.2: unit step in w0 + w1/2, φ(s) = 1 - λ0(s) = 0.602, 0.672, 0.791, 0.872, 0.934 at
    s = 1, 2, 5, 10, 20 for N = 6 (printed to 3 decimals, tol 1e-3). Integrates inflow_state_derivative."""
    coeffs = inflow_coefficients(6)
    u0, b = 2.0, 0.5  # reduced time s = u0 t / b
    s_eval = np.array([1.0, 2.0, 5.0, 10.0, 20.0])
    sol = solve_ivp(
        lambda t, lam: inflow_state_derivative(coeffs, lam, 0.0, u0, b),
        (0.0, s_eval[-1] * b / u0),
        coeffs.A_inv_c.copy(),  # impulse of the forcing rate: λ(0+) = A⁻¹c
        t_eval=s_eval * b / u0,
        rtol=1e-10,
        atol=1e-12,
    )
    phi = 1.0 - induced_inflow(coeffs, sol.y.T)
    np.testing.assert_allclose(phi, [0.602, 0.672, 0.791, 0.872, 0.934], atol=1e-3)


def test_vectorised_over_strips():
    """λ̇ for a (strips, N) state equals row-by-row evaluation; tol 1e-12."""
    coeffs = inflow_coefficients(6)
    rng = np.random.default_rng(3)
    lam = rng.normal(size=(7, 6))
    forcing, u0, b = rng.normal(size=7), rng.uniform(10, 50, 7), rng.uniform(0.5, 2, 7)
    batch = inflow_state_derivative(coeffs, lam, forcing, u0, b)
    for i in range(7):
        single = coeffs.A_inv @ (coeffs.c * forcing[i] - u0[i] / b[i] * lam[i])
        np.testing.assert_allclose(batch[i], single, rtol=1e-12, atol=1e-12)


def test_coefficients_are_read_only():
    """The cached coefficient arrays cannot be modified in place."""
    with pytest.raises(ValueError):
        inflow_coefficients(6).A[0, 0] = 1.0


@pytest.mark.parametrize("bad", [0, 11, 2.5, -1, True, "6", None])
def test_bad_n_states_raises(bad):
    """n_states outside 1–10 or not an int: ValueError naming the parameter, the value and the range."""
    with pytest.raises(ValueError, match=r"n_states.*1\.\.10.*" + re.escape(repr(bad))):
        inflow_coefficients(bad)
