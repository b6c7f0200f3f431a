"""Tests of Theodorsen's function and exact loads (flexsim.aero.theodorsen).

Sources: Theodorsen NACA Rep. 496 (1935); Hodges & Pierce (2011) ch. 5; docs/reference/aero-kinematics.md
§3.1 (C(k) table), §1.6 (flap constants), §1.7 (load values, ρ = b = U = 1, a = -0.3, d = 0.5).
"""

import numpy as np
import pytest
from scipy.special import kv

from flexsim.aero.peters import flap_shape_coefficients
from flexsim.aero.theodorsen import (
    theodorsen_constants,
    theodorsen_function,
    theodorsen_load_matrix,
    theodorsen_operator,
    theodorsen_positive,
    theodorsen_scalar,
)

C_TABLE = {
    0.01: 0.982422 - 0.045652j,
    0.05: 0.909009 - 0.130644j,
    0.10: 0.831924 - 0.172302j,
    0.20: 0.727580 - 0.188624j,
    0.30: 0.664971 - 0.179319j,
    0.50: 0.597936 - 0.150710j,
    1.00: 0.539435 - 0.100273j,
    2.00: 0.512955 - 0.057691j,
}


def test_c_table_values():
    """Reference §3.1 table, 6 decimals: tol 1e-6 absolute (vectorised call)."""
    k = np.array(list(C_TABLE))
    np.testing.assert_allclose(theodorsen_function(k), list(C_TABLE.values()), rtol=0, atol=1e-6)


def test_c_bessel_k_form_and_limits():
    """Bessel-K form K1(ik)/(K0(ik) + K1(ik)) agrees to 1e-12 (reference §3.1); C(0) = 1; C(∞) → 1/2."""
    k = np.geomspace(1e-3, 50.0, 40)
    bessel = kv(1, 1j * k) / (kv(0, 1j * k) + kv(1, 1j * k))
    np.testing.assert_allclose(theodorsen_function(k), bessel, rtol=1e-12)
    assert theodorsen_function(0.0) == 1.0 + 0.0j
    assert isinstance(theodorsen_function(0.3), complex)
    np.testing.assert_array_equal(theodorsen_function([0.0, 0.0]), [1.0, 1.0])
    assert abs(theodorsen_function(1e4) - 0.5) < 1e-4


@pytest.mark.parametrize("bad", [-0.1, [0.2, -1.0], float("nan"), float("inf")])
def test_negative_or_nonfinite_k_rejected(bad):
    """k < 0 (or non-finite) raises ValueError naming the reduced frequency."""
    with pytest.raises(ValueError, match="reduced frequency k"):
        theodorsen_function(bad)


def test_flap_constants_reference_identities():
    """Reference §1.6–1.7 identities at d = 0.5: -T4 = 0.61418 (tol 1e-5); F0 + F1/2 = T11/(2π);
    T10 = √(1 - d²) + acos d, T11 = acos d (1 - 2d) + √(1 - d²)(2 - d) (tol 1e-14)."""
    for d in (0.5, 0.6, -0.2):
        t = theodorsen_constants(-0.3, d)
        f = flap_shape_coefficients(2, d)
        assert f[0] + 0.5 * f[1] == pytest.approx(t.T11 / (2 * np.pi), abs=1e-14)
        assert t.T10 == pytest.approx(np.sqrt(1 - d * d) + np.arccos(d), abs=1e-14)
        assert t.T6 == t.T2
    assert -theodorsen_constants(-0.3, 0.5).T4 == pytest.approx(0.61418, abs=1e-5)


@pytest.mark.parametrize(
    ("k", "column", "expected"),
    [
        (0.2, 1, [4.723446 + 0.174601j, 0.979247 - 0.593398j, -0.050050 - 0.038198j]),
        (1.0, 0, [-2.511559 + 3.389369j, 1.068484 + 0.677874j, 0.118834 - 0.038121j]),
        (1.0, 2, [2.068456 + 0.931242j, -0.772677 - 0.860949j, -0.082660 - 0.130548j]),
    ],
)
def test_load_matrix_reference_values(k, column, expected):
    """Reference §1.7 [L, M_EA, H] per unit amplitude (6 decimals): tol 1e-6 absolute."""
    got = theodorsen_load_matrix(k, -0.3, 1.0, 1.0, 1.0, 0.5)[:, column]
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-6)


def test_plunge_pitch_block_hodges_pierce_form():
    """Hodges & Pierce ch. 5: L = πρb²(ḧ + Uα̇ - baα̈) + 2πρUbC Q; M_EA = -πρb³[½ḧ + Uα̇ + b(1/8 - a/2)α̈]
    + b(½ + a)L. Evaluated independently here for k = 0.4, ρ = 1.2, b = 0.7, U = 30; tol 1e-12 rel."""
    k, rho, b, u, a = 0.4, 1.2, 0.7, 30.0, -0.35
    p = 1j * k * u / b
    c_k = theodorsen_function(k)
    expected = np.zeros((2, 2), complex)
    for j, (h, al) in enumerate([(1.0, 0.0), (0.0, 1.0)]):
        q34 = p * h + u * al + b * (0.5 - a) * p * al
        apparent = np.pi * rho * b**2 * (p * p * h + u * p * al - b * a * p * p * al)
        lift = apparent + 2 * np.pi * rho * u * b * c_k * q34
        moment = -np.pi * rho * b**3 * (0.5 * p * p * h + u * p * al + b * (1 / 8 - a / 2) * p * p * al)
        expected[:, j] = [lift, moment + b * (0.5 + a) * lift]
    got = theodorsen_load_matrix(k, a, rho, b, u)
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


def test_quasi_steady_option():
    """quasi_steady=True equals C ≡ 1 (paper: λ0 = 0); steady lift slope 2πρU²b per rad; tol 1e-12."""
    op = theodorsen_operator(-0.2, 1.1, 0.5, 20.0, 0.6)
    k = np.array([0.0, 0.3, 1.5])
    qs = theodorsen_load_matrix(k, -0.2, 1.1, 0.5, 20.0, 0.6, quasi_steady=True)
    p = (1j * k * 20.0 / 0.5)[:, None, None]
    manual = p * p * op.mass + p * op.damping + op.stiffness + op.circulation[:, None] * (
        op.downwash_displacement + p * op.downwash_rate
    )
    np.testing.assert_allclose(qs, manual, rtol=1e-12)
    assert qs[0, 0, 1].real == pytest.approx(2 * np.pi * 1.1 * 20.0**2 * 0.5, rel=1e-12)
    assert not np.allclose(qs[1], theodorsen_load_matrix(0.3, -0.2, 1.1, 0.5, 20.0, 0.6))


def test_compiled_c_equals_numpy_expression_bit_for_bit():
    """The compiled C(k) (Cephes' Bessel functions called from numba, Smith's complex division as numpy does it)
    equals numpy's evaluation of C = (J1 - i Y1) / ((J1 + Y0) + i (J0 - Y1)) exactly, 1e-8 <= k <= 1e3."""
    from scipy.special import j0, j1, y0, y1

    k = np.geomspace(1e-8, 1e3, 20001)
    bj0, bj1, by0, by1 = j0(k), j1(k), y0(k), y1(k)
    reference = (bj1 - 1j * by1) / ((bj1 + by0) + 1j * (bj0 - by1))
    assert np.array_equal(theodorsen_positive(k), reference)
    assert np.array_equal(theodorsen_positive(k[:12].reshape(3, 4)), reference[:12].reshape(3, 4))
    assert theodorsen_scalar(0.5) == theodorsen_function(0.5)
