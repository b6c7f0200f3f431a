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
already found, which leads it to the other member of the pair. Two exceptions keep the root as found: starts
that are themselves equal with independent eigenvectors (MAC < 0.99: a double root, the two uncoupled halves of a
clamped wing pair), and a retrack that
does not converge (its last iterate is no root of the problem; before this rule such an iterate appeared as a
spurious, strongly unstable root at isolated speeds of the clamped HALE wing pair).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numba import njit

from flexsim.aero.theodorsen import theodorsen_function, theodorsen_positive, theodorsen_scalar

__all__ = ["PkRoot", "PkStateMatrix", "pk_track", "pk_roots"]

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


@njit(cache=True, nogil=True)
def _assemble(a_qs: np.ndarray, b_lambda: np.ndarray, c_w: np.ndarray, c: np.ndarray) -> np.ndarray:
    """``a_qs + (b_lambda diag(1 - c)) @ c_w`` (complex ``c_w``, C-contiguous; ``c`` = C(k_j)): the arithmetic numpy does for the same
    expression with a real ``c_w`` (the real factors promoted to complex, one ``zgemm``)."""
    m, n_s = b_lambda.shape
    scaled = np.empty((m, n_s), np.complex128)
    for j in range(n_s):
        w = 1.0 - c[j]
        for i in range(m):
            scaled[i, j] = complex(b_lambda[i, j] * w.real, b_lambda[i, j] * w.imag)
    return a_qs + scaled @ c_w


@dataclass(frozen=True, eq=False)
class PkStateMatrix:
    """The p-k state matrix of Theodorsen's model (paper eq. 27), ``A(omega) = A_qs + B_lambda diag(1 - C(k_j)) C_w``.

    ``k_j = omega b_j / u0_j`` at every unsteady strip j; C is Theodorsen's function
    (:func:`flexsim.aero.theodorsen.theodorsen_function`). Calling it with ``omega`` [rad/s] returns
    ``A(omega)``, ndarray (complex), shape (m, m). Built by :func:`flexsim.linear.stability.pk_state_matrix`;
    :func:`pk_track` follows its roots in compiled code (:func:`_track_kernel`).

    Attributes
    ----------
    a_qs : ndarray, shape (m, m)
        Quasi-steady state matrix [1/s and the layout's mixed units].
    b_lambda : ndarray, shape (m, n_s)
        d x_dot / d lambda0_j per unsteady strip [per m/s].
    c_w : ndarray, shape (n_s, m)
        d (w0 + w1/2)_j / dx [m/s per state unit].
    semichord_over_speed_s : ndarray, shape (n_s,)
        b_j / u0_j [s], so that k_j = omega b_j / u0_j.
    """

    a_qs: np.ndarray
    b_lambda: np.ndarray
    c_w: np.ndarray
    semichord_over_speed_s: np.ndarray

    def __post_init__(self) -> None:
        # the operands of the compiled assembly, made once: contiguous float64, and C_w promoted to complex
        object.__setattr__(self, "_operands", (np.ascontiguousarray(self.a_qs, dtype=float),
                                               np.ascontiguousarray(self.b_lambda, dtype=float),
                                               np.ascontiguousarray(self.c_w, dtype=complex),
                                               np.ascontiguousarray(self.semichord_over_speed_s, dtype=float)))

    def __call__(self, omega: float) -> np.ndarray:
        a_qs, b_lambda, c_w, s = self._operands
        k = abs(omega) * s
        # k > 0 finite (the usual case): C(k) without theodorsen_function's checks, the same values
        c = theodorsen_positive(k) if math.isfinite(omega) and k.size and k.min() > 0.0 else theodorsen_function(k)
        return _assemble(a_qs, b_lambda, c_w, np.asarray(c, dtype=complex).reshape(-1))

    def projected(self, basis: np.ndarray) -> "PkStateMatrix":
        """``Q^T A(omega) Q`` for an orthonormal real ``basis`` Q (m, r) of an invariant subspace of every A(omega)."""
        return PkStateMatrix(basis.T @ self.a_qs @ basis, basis.T @ self.b_lambda, self.c_w @ basis,
                             self.semichord_over_speed_s)


@njit(cache=True, nogil=True)
def _track_kernel(a_qs: np.ndarray, b_lambda: np.ndarray, c_w: np.ndarray, s: np.ndarray, p: complex, vec: np.ndarray,
                  it: int, max_iter: int, rtol: float):
    """The p-k iterations of :func:`pk_track` on a :class:`PkStateMatrix`, compiled, from iteration ``it`` on:
    ``A(|Im p|)`` (:func:`~flexsim.aero.theodorsen.theodorsen_scalar`, :func:`_assemble`), one :func:`_inverse_step` (:func:`_inverse_rounds` and
    the correlation test), the convergence test. Returns ``(status, it, p, vec)``: 1 converged at iteration ``it``,
    0 not within ``max_iter``; 2 the inverse step of iteration ``it`` failed (the caller takes the full ``eig``
    step), 3 ``k`` not finite and positive there (the caller takes the step with the checked ``C(k)``); with 2
    and 3, ``p, vec`` are those before that iteration."""
    m = a_qs.shape[0]
    while it <= max_iter:
        omega = abs(p.imag)
        k = omega * s
        if not (math.isfinite(omega) and k.shape[0] > 0 and k.min() > 0.0):
            return 3, it, p, vec
        c = np.empty(k.shape[0], np.complex128)
        for j in range(k.shape[0]):
            c[j] = theodorsen_scalar(k[j])
        a = _assemble(a_qs, b_lambda, c_w, c)
        big = 0.0
        for j in range(m):  # |A|_1, summed over rows in order as numpy's sum(axis=0)
            col = abs(a[0, j])
            for i in range(1, m):
                col += abs(a[i, j])
            big = max(big, col)
        status, shift, v = _inverse_rounds(a, p, vec, _RESIDUAL * big, _ROUNDS, _SOLVES)
        if status != 1:
            return 2, it, p, vec
        corr = 0j
        for i in range(m):
            corr += np.conj(v[i]) * vec[i]
        if abs(corr) < _MIN_CORRELATION * _norm(vec):
            return 2, it, p, vec
        done = abs(shift.imag - p.imag) < rtol * max(1.0, abs(p.imag))
        p, vec = shift, v
        if done:
            return 1, it, p, vec
        it += 1
    return 0, max_iter, p, vec


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
    inverse = inverse_iteration and excl.size == 0
    compiled = inverse and isinstance(a_of, PkStateMatrix)
    if compiled:
        vec = np.ascontiguousarray(vec)
    it = 1
    while it <= max_iter:
        eig_step = False
        if compiled:  # the same steps as below, compiled, until one needs the full eig or the checked C(k)
            status, it, p, vec = _track_kernel(*a_of._operands, p, vec, it, max_iter, rtol)
            if status == 1:
                return PkRoot(p, vec / np.linalg.norm(vec), it, full, True)
            if status == 0:
                return PkRoot(p, vec / np.linalg.norm(vec), max_iter, full, False)
            eig_step = status == 2
        a = a_of(abs(p.imag))
        step = None
        if inverse and not eig_step:
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
        it += 1
        if compiled:
            vec = np.ascontiguousarray(vec, dtype=complex)
    return PkRoot(p, vec / np.linalg.norm(vec), max_iter, full, False)


def _double_start(starts: np.ndarray, vectors: np.ndarray, j: int, k: int, separation: float) -> bool:
    """Whether starts j and k are one double eigenvalue with two independent eigenvectors (MAC < 0.99)."""
    if abs(starts[j] - starts[k]) >= separation * max(1.0, abs(starts[k])):
        return False
    a, b = vectors[:, j], vectors[:, k]
    mac = abs(np.vdot(a, b)) ** 2 / max(float(np.real(np.vdot(a, a) * np.vdot(b, b))), 1e-300)
    return mac < 0.99


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
            near = separation * max(1.0, abs(root.eigenvalue))
            clash = [j for j, r in enumerate(roots) if abs(r.eigenvalue - root.eigenvalue) < near]
            # a clash with a root followed from an equal start with another eigenvector is a double root (two equal,
            # uncoupled halves of a clamped structure): both are kept, as the start matrix has both
            if not clash or all(_double_start(starts, start_vectors, j, k, separation) for j in clash):
                break
            found = tuple(r.eigenvalue for r in roots)
            retry = pk_track(a_of, starts[k], start_vectors[:, k], rtol=rtol, max_iter=max_iter, exclude=found)
            if not retry.converged:  # no other fixed point reached: keep the root found rather than a stray iterate
                break
            root = PkRoot(retry.eigenvalue, retry.vector, root.iterations + retry.iterations,
                          root.full_eigs + retry.full_eigs, retry.converged)
        roots.append(root)
    return roots
