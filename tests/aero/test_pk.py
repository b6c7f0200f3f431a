"""The p-k kernel (flexsim/aero/pk.py) on a problem with closed-form roots.

A(omega) = T D(omega) T^-1 with 2x2 blocks D_i = [[0, 1], [-(k_i + kappa_i omega^2), -d_i]] and a fixed,
non-orthogonal T (non-normal A with the eigenvalues of D). Each block has the eigenvalues
-d_i/2 +- i sqrt(k_i + kappa_i omega^2 - d_i^2/4), so its p-k root p = -d_i/2 + i omega_i solves
omega_i^2 = k_i + kappa_i omega_i^2 - d_i^2/4: omega_i = sqrt((k_i - d_i^2/4) / (1 - kappa_i)).
Blocks 2 and 3 are near-degenerate (frequencies 0.3 % apart). Tolerance: 1e-9 relative with rtol 1e-12.
A double root: the block diagonal of A(omega) with itself (two equal, uncoupled systems, as the two halves of a
clamped wing pair) has every root twice; both starts of a double eigenvalue (independent eigenvectors) keep it.
"""

import numpy as np
import pytest

from flexsim.aero.pk import pk_roots, pk_track

K = np.array([4.0, 9.0, 9.06])
D = np.array([0.2, 0.3, 0.25])
KAPPA = np.array([0.1, -0.2, -0.19])
EXACT = -D / 2 + 1j * np.sqrt((K - D**2 / 4) / (1 - KAPPA))
T = np.random.default_rng(3).normal(size=(6, 6)) + 3.0 * np.eye(6)
T_INV = np.linalg.inv(T)


def a_of(omega: float) -> np.ndarray:
    d = np.zeros((6, 6))
    for i in range(3):
        d[2 * i, 2 * i + 1] = 1.0
        d[2 * i + 1, 2 * i] = -(K[i] + KAPPA[i] * omega**2)
        d[2 * i + 1, 2 * i + 1] = -D[i]
    return T @ d @ T_INV


def _starts():
    vals, vecs = np.linalg.eig(a_of(0.0))
    up = np.flatnonzero(vals.imag > 0)
    return vals[up], vecs[:, up]


@pytest.mark.parametrize("inverse_iteration", [True, False])
def test_roots_match_closed_form(inverse_iteration):
    starts, vecs = _starts()
    roots = pk_roots(a_of, starts, vecs, rtol=1e-12, inverse_iteration=inverse_iteration)
    found = np.sort_complex(np.array([r.eigenvalue for r in roots]))
    np.testing.assert_allclose(found, np.sort_complex(EXACT), rtol=1e-9)
    assert all(r.converged for r in roots)
    for r in roots:  # the vector is an eigenvector of A at the root's own frequency
        a = a_of(r.eigenvalue.imag)
        assert np.linalg.norm(a @ r.vector - r.eigenvalue * r.vector) < 1e-9 * np.abs(a).max()


def test_inverse_iteration_needs_no_full_eig_near_a_root():
    starts, vecs = _starts()
    first = pk_roots(a_of, starts, vecs, rtol=1e-12)
    again = pk_track(a_of, first[0].eigenvalue, first[0].vector, rtol=1e-12)
    assert again.full_eigs == 0
    assert again.eigenvalue == pytest.approx(first[0].eigenvalue, rel=1e-12)


def test_a_start_met_twice_yields_the_other_roots():
    """Starts that converge to a root already found are tracked again, excluding it: roots stay distinct."""
    starts, vecs = _starts()
    k = int(np.argmin(np.abs(starts - 9j)))
    roots = pk_roots(a_of, np.array([starts[k]] * 3), np.stack([vecs[:, k]] * 3, axis=1), rtol=1e-12)
    found = np.array([r.eigenvalue for r in roots])
    assert np.min(np.abs(found[:, None] - found[None, :]) + np.eye(3)) > 1e-3
    np.testing.assert_allclose(np.sort_complex(found), np.sort_complex(EXACT), rtol=1e-9)


def test_compiled_lu_solves_and_detects_a_singular_shift():
    """The inverse step's compiled LU (partial pivoting, LAPACK zgetf2's algorithm) solves a random complex system
    to 1e-12 relative against numpy.linalg.solve, and reports an exactly singular matrix instead of dividing by 0."""
    from flexsim.aero.pk import _lu_factor, _lu_solve

    rng = np.random.default_rng(7)
    a = rng.normal(size=(30, 30)) + 1j * rng.normal(size=(30, 30))
    b = rng.normal(size=30) + 1j * rng.normal(size=30)
    lu = a.copy()
    piv, ok = _lu_factor(lu)
    assert ok
    np.testing.assert_allclose(_lu_solve(lu, piv, b), np.linalg.solve(a, b), rtol=1e-12)
    singular = a.copy()
    singular[:, 3] = 0.0
    assert not _lu_factor(singular)[1]


def test_a_double_root_is_kept_twice():
    def twice(omega: float) -> np.ndarray:
        a = a_of(omega)
        out = np.zeros((12, 12))
        out[:6, :6] = out[6:, 6:] = a
        return out

    vals, vecs = np.linalg.eig(twice(0.0))
    up = np.flatnonzero(vals.imag > 0)
    roots = pk_roots(twice, vals[up], vecs[:, up], rtol=1e-12)
    assert all(r.converged for r in roots)
    found = np.sort_complex(np.array([r.eigenvalue for r in roots]))
    np.testing.assert_allclose(found, np.sort_complex(np.repeat(EXACT, 2)), rtol=1e-9)
