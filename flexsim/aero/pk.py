"""The p-k method for a frequency-dependent state matrix ``A(ω)``: one implementation for every model.

Sources: Hassig, "An approximate true damping solution of the flutter equation by determinant iteration",
J. Aircraft 8(11), 885-889 (1971) — the p-k iteration; Hodges & Pierce, *Introduction to Structural Dynamics
and Aeroelasticity*, 2nd ed. (2011) §5.5 — the same iteration for the typical section; Golub & Van Loan,
*Matrix Computations*, 4th ed. (2013) §7.6.1 — shifted inverse iteration.

A root ``p`` [1/s, or units of a reference frequency] of a p-k problem is a fixed point
``p ∈ eig(A(Im p))``: the aerodynamics are evaluated at the root's own frequency (for Theodorsen's
``C(k)``, ``k = ω b / U``). From a start pair ``(p₀, v₀)`` (an eigenpair of a frequency-independent
approximation, e.g. the quasi-steady state matrix) the iteration repeats: evaluate ``A`` at ``ω = Im p``,
take the eigenpair of ``A(ω)`` that continues the tracked one, set ``p`` to its eigenvalue; until
``|ΔIm p| < rtol max(1, |Im p|)``.

Continuing the tracked pair costs one complex LU of ``A(ω) - p I`` and three solves from the previous
vector (inverse iteration with the previous root as shift; the eigenvalue is the Rayleigh quotient of the
result; compiled, :func:`_inverse_rounds`). The step falls back to a full ``eig`` of ``A(ω)`` with the original matching rule (largest
correlation of eigenvectors, ties broken by distance of the eigenvalues) when the new vector correlates
below ``0.9`` with the old one or its residual ``|A v - p v|`` stays above ``1e-13 |A|₁`` after a second
round shifted by the Rayleigh quotient. Both rules pick the
same eigenpair of the same matrix, so the fixed points equal those of a full ``eig`` per step to
round-off (measured in ``benchmarks/bench_compare.py``).

Roots are distinct: two starts that converge to the same fixed point (near-degenerate pairs, e.g. the
symmetric and antisymmetric modes of the two wing halves, whose eigenvectors mix) would hide one root. The
later start is then tracked again with full ``eig`` steps that exclude the eigenvalues nearest the roots
already found, which leads it to the other member of the pair.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from numba import njit

__all__ = ["PkRoot", "pk_track", "pk_roots"]

_MIN_CORRELATION = 0.9
_RESIDUAL = 1e-13
_SOLVES = 3
_ROUNDS = 4


@dataclass(frozen=True, eq=False)
class PkRoot:
    """One converged p-k root.

    Attributes
    ----------
    eigenvalue : complex
        ``p`` with ``p ∈ eig(A(|Im p|))`` to the iteration's tolerance.
    vector : ndarray (complex), shape (n,)
        Right eigenvector of ``A(|Im p|)``, unit 2-norm.
    iterations : int
        p-k iterations (evaluations of ``A``).
    full_eigs : int
        Iterations that used a full ``eig`` (fallbacks and exclusions).
    converged : bool
        Whether ``|ΔIm p| < rtol max(1, |Im p|)`` was reached within ``max_iter``.
    """

    eigenvalue: complex
    vector: np.ndarray
    iterations: int
    full_eigs: int
    converged: bool


def _match(vals: np.ndarray, vecs: np.ndarray, p: complex, vec: np.ndarray, excluded: np.ndarray | None) -> int:
    """Index of the eigenpair of a full ``eig`` that continues (p, vec): largest correlation, then nearest."""
    corr = np.abs(vecs.conj().T @ vec) / (np.linalg.norm(vecs, axis=0) * np.linalg.norm(vec))
    score = corr - 1e-3 * np.abs(vals - p) / max(abs(p), 1.0)
    if excluded is not None:
        score = np.where(excluded, -np.inf, score)
    return int(np.argmax(score))


@njit(cache=True, nogil=True)
def _lu_factor(m: np.ndarray) -> tuple[np.ndarray, bool]:
    """In-place LU with partial pivoting of a complex square matrix, LAPACK ``zgetf2``'s algorithm (pivot: the
    largest |Re| + |Im| of the column, the first on ties). Returns the pivot rows and False for an exactly zero pivot."""
    n = m.shape[0]
    piv = np.empty(n, np.int64)
    for k in range(n):
        p = k
        big = abs(m[k, k].real) + abs(m[k, k].imag)
        for i in range(k + 1, n):
            size = abs(m[i, k].real) + abs(m[i, k].imag)
            if size > big:
                big, p = size, i
        piv[k] = p
        if big == 0.0:
            return piv, False
        if p != k:
            for j in range(n):
                m[k, j], m[p, j] = m[p, j], m[k, j]
        inv = 1.0 / m[k, k]
        for i in range(k + 1, n):
            m[i, k] *= inv
            f = m[i, k]
            if f != 0.0:
                for j in range(k + 1, n):
                    m[i, j] -= f * m[k, j]
    return piv, True


@njit(cache=True, nogil=True)
def _lu_solve(lu: np.ndarray, piv: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve with the factors of :func:`_lu_factor` (row interchanges, unit lower, upper triangle)."""
    n = lu.shape[0]
    x = b.copy()
    for k in range(n):
        p = piv[k]
        if p != k:
            x[k], x[p] = x[p], x[k]
    for i in range(n):
        acc = x[i]
        for j in range(i):
            acc -= lu[i, j] * x[j]
        x[i] = acc
    for i in range(n - 1, -1, -1):
        acc = x[i]
        for j in range(i + 1, n):
            acc -= lu[i, j] * x[j]
        x[i] = acc / lu[i, i]
    return x


@njit(cache=True, nogil=True)
def _norm(x: np.ndarray) -> float:
    acc = 0.0
    for i in range(x.shape[0]):
        acc += x[i].real * x[i].real + x[i].imag * x[i].imag
    return np.sqrt(acc)


@njit(cache=True, nogil=True)
def _inverse_rounds(a: np.ndarray, p: complex, vec: np.ndarray, tol: float, rounds: int, solves: int):
    """The rounds of :func:`_inverse_step` (compiled): ``(status, shift, v)``, status 1 when the residual fell to
    ``tol``, 0 when it did not within ``rounds``, -1 when a solve failed."""
    n = a.shape[0]
    v = vec / _norm(vec)
    shift = p
    for _ in range(rounds):
        m = a.copy()
        for i in range(n):
            m[i, i] -= shift
        piv, ok = _lu_factor(m)
        if not ok:  # the shift is an eigenvalue to working precision: perturb it by round-off
            m = a.copy()
            nudged = shift + 1e-13 * max(abs(shift), 1.0)
            for i in range(n):
                m[i, i] -= nudged
            piv, ok = _lu_factor(m)
            if not ok:
                return -1, shift, v
        for _ in range(solves):
            w = _lu_solve(m, piv, v)
            norm = _norm(w)
            if not np.isfinite(norm) or norm == 0.0:
                return -1, shift, v
            v = w / norm
        av = a @ v
        shift = np.vdot(v, av)
        if _norm(av - shift * v) <= tol:
            return 1, shift, v
    return 0, shift, v


def _inverse_step(a: np.ndarray, p: complex, vec: np.ndarray) -> tuple[complex, np.ndarray] | None:
    """Shifted inverse iteration on ``a`` from (p, vec); None when it did not settle on one eigenpair.

    Up to ``_ROUNDS`` rounds: one LU of ``a - shift I`` and ``_SOLVES`` solves with the shift ``p``, then (while the
    residual is still above ``_RESIDUAL |A|_1``) as many with the Rayleigh quotient as shift (Rayleigh-quotient
    iteration: a start far from the new eigenvalue, e.g. the first step from the frequency-independent start pair,
    converges in the third or fourth round instead of falling back to a full ``eig``). The rounds are compiled
    (:func:`_inverse_rounds`; a p-k evaluation takes about a hundred of these steps on matrices of 20-60 states,
    where numpy's per-call overhead, not the arithmetic, was the cost).
    """
    a = np.ascontiguousarray(a, dtype=complex)
    tol = _RESIDUAL * np.abs(a).sum(axis=0).max()
    status, shift, v = _inverse_rounds(a, complex(p), np.ascontiguousarray(vec, dtype=complex), tol, _ROUNDS, _SOLVES)
    if status != 1:
        return None
    if abs(np.vdot(v, vec)) < _MIN_CORRELATION * np.linalg.norm(vec):
        return None
    return complex(shift), v


def pk_track(
    a_of: Callable[[float], np.ndarray],
    p0: complex,
    v0: np.ndarray,
    *,
    rtol: float = 1e-7,
    max_iter: int = 30,
    inverse_iteration: bool = True,
    exclude: tuple[complex, ...] = (),
) -> PkRoot:
    """Follow one root of the p-k problem ``p ∈ eig(A(|Im p|))`` from a start pair (module docstring).

    Parameters
    ----------
    a_of : callable
        ``a_of(omega) -> ndarray (n, n)``, the state matrix at frequency ``omega >= 0`` (same units as p).
    p0 : complex
        Start eigenvalue (``Im p0 > 0``).
    v0 : ndarray, shape (n,)
        Start right eigenvector.
    rtol : float
        Convergence tolerance on ``Im p`` relative to ``max(1, |Im p|)``.
    max_iter : int
        Iteration limit (the last iterate is returned with ``converged = False``).
    inverse_iteration : bool
        Use shifted inverse iteration with ``eig`` fallback (default); False takes a full ``eig`` every step.
    exclude : tuple of complex
        Roots already found: every step then uses a full ``eig`` and never picks the eigenvalue of
        ``A(ω)`` nearest to one of them, nor one in the other half-plane than ``p0``.

    Returns
    -------
    PkRoot
    """
    p, vec = complex(p0), np.asarray(v0, dtype=complex)
    full = 0
    excl = np.asarray(exclude, dtype=complex)
    for it in range(1, max_iter + 1):
        a = a_of(abs(p.imag))
        step = None
        if inverse_iteration and excl.size == 0:
            step = _inverse_step(a, p, vec)
        if step is None:
            full += 1
            vals, vecs = np.linalg.eig(a)
            banned = None
            if excl.size:  # never a root already found, nor one of the other half-plane
                banned = vals.imag * np.sign(p0.imag) <= 0.0
                banned[np.argmin(np.abs(vals[:, None] - excl[None, :]), axis=0)] = True
            m = _match(vals, vecs, p, vec, banned)
            step = complex(vals[m]), vecs[:, m]
        p_new, vec = step
        done = abs(p_new.imag - p.imag) < rtol * max(1.0, abs(p.imag))
        p = p_new
        if done:
            return PkRoot(p, vec / np.linalg.norm(vec), it, full, True)
    return PkRoot(p, vec / np.linalg.norm(vec), max_iter, full, False)


def pk_roots(
    a_of: Callable[[float], np.ndarray],
    starts: np.ndarray,
    start_vectors: np.ndarray,
    *,
    rtol: float = 1e-7,
    max_iter: int = 30,
    inverse_iteration: bool = True,
    separation: float = 1e-6,
) -> list[PkRoot]:
    """Distinct p-k roots followed from several start pairs (module docstring).

    Parameters
    ----------
    a_of : callable
        As in :func:`pk_track`.
    starts : ndarray (complex), shape (k,)
        Start eigenvalues, ``Im > 0``.
    start_vectors : ndarray (complex), shape (n, k)
        Start right eigenvectors (columns).
    rtol, max_iter, inverse_iteration
        As in :func:`pk_track`.
    separation : float
        Two roots closer than ``separation max(1, |p|)`` are the same root; the later start is tracked
        again excluding the roots found (up to three times), so that the roots returned are distinct.

    Returns
    -------
    list of PkRoot, one per start, in the order of ``starts``.
    """
    roots: list[PkRoot] = []
    for k in range(len(starts)):
        root = pk_track(a_of, starts[k], start_vectors[:, k], rtol=rtol, max_iter=max_iter,
                        inverse_iteration=inverse_iteration)
        for _ in range(3):
            clash = [r.eigenvalue for r in roots if abs(r.eigenvalue - root.eigenvalue) < separation * max(1.0, abs(root.eigenvalue))]
            if not clash:
                break
            found = tuple(r.eigenvalue for r in roots)
            retry = pk_track(a_of, starts[k], start_vectors[:, k], rtol=rtol, max_iter=max_iter, exclude=found)
            root = PkRoot(retry.eigenvalue, retry.vector, root.iterations + retry.iterations,
                          root.full_eigs + retry.full_eigs, retry.converged)
        roots.append(root)
    return roots
