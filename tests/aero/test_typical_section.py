"""Tests of the typical-section flutter model (flexsim.aero.typical_section).

Sources: Hodges & Pierce (2011) ch. 5 and docs/reference/aero-kinematics.md §3.2 (a = -1/5, e = -1/10,
μ = 20, r² = 6/25, σ = 2/5): Peters N = 6 U_F = 2.1654, ω_F = 0.6545; exact Theodorsen U_F = 2.1839,
ω_F = 0.6490; divergence √(μr²/(2(½ + a))) = 2.8284; eigenvalues at V = 1 and 2.
"""

import numpy as np
import pytest

from flexsim.aero.theodorsen import theodorsen_load_matrix, theodorsen_operator
from flexsim.aero.typical_section import (
    TypicalSection,
    divergence_speed,
    flutter_analysis,
    pk_roots,
    state_eigenvalues,
    state_matrices,
    structural_matrices,
)

SECTION = TypicalSection(a=-0.2, e=-0.1, mu=20.0, r2=0.24, sigma=0.4)


def _sorted(values):
    values = np.asarray(values)
    return values[np.lexsort((values.imag, values.real))]


def test_eigenvalues_peters_n6_v1():
    """Reference §3.2 eigenvalues at V = 1 (Peters N = 6), printed to 5 decimals: tol 2e-5."""
    expected = [
        -0.03596 + 0.40299j, -0.03596 - 0.40299j, -0.03856 + 0.95944j, -0.03856 - 0.95944j,
        -2.28513 + 5.52176j, -2.28513 - 5.52176j, -2.58737, -1.99471, -0.32776, -0.05807,
    ]  # fmt: skip
    np.testing.assert_allclose(_sorted(state_eigenvalues(SECTION, 1.0)), _sorted(expected), atol=2e-5)


def test_structural_eigenvalues_peters_n6_v2():
    """Reference §3.2 structural pairs at V = 2: -0.17513 ± 0.49788i, -0.05403 ± 0.71010i (tol 2e-5)."""
    roots = state_eigenvalues(SECTION, 2.0)
    for expected in (-0.17513 + 0.49788j, -0.05403 + 0.71010j):
        assert np.min(np.abs(roots - expected)) < 2e-5


def test_flutter_peters_n6():
    """Reference §3.2: U_F/(bω_θ) = 2.1654 (within 0.5 % of 2.165, and 2e-4 of 2.1654);
    ω_F/ω_θ = 0.6545 (tol 2e-4)."""
    result = flutter_analysis(SECTION, "peters", 6)
    assert result.flutter_speed == pytest.approx(2.165, rel=5e-3)
    assert result.flutter_speed == pytest.approx(2.1654, abs=2e-4)
    assert result.flutter_frequency == pytest.approx(0.6545, abs=2e-4)
    assert abs(state_eigenvalues(SECTION, result.flutter_speed)[0].real) < 1e-7


def test_flutter_theodorsen_pk():
    """Reference §3.2 exact Theodorsen: U_F = 2.1839 (within 0.5 % of 2.184; tol 2e-4), ω_F = 0.6490 (2e-4).
    At the crossing the flutter determinant with Theodorsen's harmonic loads at k_F = ω_F/U_F is singular
    (independent of the p-k loop): |det| < 1e-6 of the structural scale."""
    result = flutter_analysis(SECTION, "theodorsen")
    assert result.flutter_speed == pytest.approx(2.184, rel=5e-3)
    assert result.flutter_speed == pytest.approx(2.1839, abs=2e-4)
    assert result.flutter_frequency == pytest.approx(0.6490, abs=2e-4)
    mass, stiffness = structural_matrices(SECTION)
    omega, speed = result.flutter_frequency, result.flutter_speed
    aero = theodorsen_load_matrix(omega / speed, SECTION.a, 1.0, 1.0, speed)
    flutter_matrix = -(omega**2) * mass + stiffness - np.diag([-1.0, 1.0]) @ aero
    assert abs(np.linalg.det(flutter_matrix)) < 1e-6 * np.linalg.det(stiffness)


@pytest.mark.parametrize(("n", "speed"), [(1, 1.871), (4, 2.204), (8, 2.1802)])
def test_flutter_peters_other_orders(n, speed):
    """Reference §3.2 table: Peters N = 1, 4, 8 flutter speeds (printed to 3–4 decimals; tol 1e-3)."""
    assert flutter_analysis(SECTION, "peters", n).flutter_speed == pytest.approx(speed, abs=1e-3)


def test_divergence_speed():
    """Divergence √(μr²/(2(½ + a))) = 2.8284 (reference §3.2); tol 1e-10 of the closed form."""
    closed_form = np.sqrt(SECTION.mu * SECTION.r2 / (2 * (0.5 + SECTION.a)))
    assert divergence_speed(SECTION) == pytest.approx(closed_form, rel=1e-10)
    assert closed_form == pytest.approx(2.8284, abs=1e-4)
    roots = state_eigenvalues(SECTION, closed_form)
    assert np.min(np.abs(roots)) < 1e-8  # a zero eigenvalue at divergence in the state-space model too
    assert divergence_speed(TypicalSection(a=-0.6)) == float("inf")


def test_quasi_steady_state_space_matches_theodorsen_with_c_equal_one():
    """Cross-check of the strip kernel against Theodorsen's operator: each quasi-steady eigenvalue p makes
    M_s p² + K_s - P Λ_qs(p) singular, Λ_qs with C = 1 (Hodges & Pierce ch. 5); tol 1e-9 relative."""
    speed = 1.3
    mass, stiffness = structural_matrices(SECTION)
    op = theodorsen_operator(SECTION.a, 1.0, 1.0, speed)
    signs = np.diag([-1.0, 1.0])
    for p in state_eigenvalues(SECTION, speed, "quasi_steady"):
        aero = p * p * op.mass + p * op.damping + op.stiffness + np.outer(
            op.circulation, op.downwash_displacement + p * op.downwash_rate
        )
        matrix = mass * p * p + stiffness - signs @ aero
        assert abs(np.linalg.det(matrix)) < 1e-9 * np.abs(np.linalg.det(stiffness)) * max(1.0, abs(p)) ** 4


def test_implicit_mass_matrix_is_used():
    """The apparent mass sits in E (not lagged): E differs from I in the acceleration and inflow rows."""
    e_mat, _ = state_matrices(SECTION, 1.0, "peters", 6)
    mass, _ = structural_matrices(SECTION)
    assert not np.allclose(e_mat[2:4, 2:4], mass)
    assert np.any(e_mat[4:, 2:4] != 0.0)


def test_pk_roots_approach_still_air_frequencies():
    """As U → 0 the p-k roots tend to the still-air frequencies with apparent mass, eig(K_s, M_s - P M_nc)
    (Hodges & Pierce ch. 5; the circulatory terms vanish with U); U = 0.01, tol 1e-3 relative."""
    speed = 0.01
    roots = pk_roots(SECTION, speed)
    mass, stiffness = structural_matrices(SECTION)
    added = np.diag([-1.0, 1.0]) @ theodorsen_operator(SECTION.a, 1.0, 1.0, speed).mass
    still_air = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(mass - added, stiffness)).real))
    np.testing.assert_allclose(np.sort(roots.imag), still_air, rtol=1e-3)
    assert np.all(roots.real < 0.0)


@pytest.mark.parametrize(("kwargs", "match"), [({"model": "vlm"}, "model"), ({"n_states": 11}, "n_states")])
def test_bad_options_raise(kwargs, match):
    """Unknown model or n_states outside 1–10 raise ValueError with a clear message."""
    with pytest.raises(ValueError, match=match):
        flutter_analysis(SECTION, **kwargs)
