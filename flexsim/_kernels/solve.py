"""Compiled solution of E V_dot = f (paper eq. 33): Gaussian elimination and the block elimination of
:func:`flexsim._kernels.layout.solve_structure`'s pattern into a Schur complement of the coupling core."""

from __future__ import annotations

import numpy as np

from flexsim._kernels.layout import kernel


@kernel
def _gauss(a, b):
    """Overwrite b (n, r) with x of a x = b, a (n, n) overwritten with its LU factors: Gaussian elimination with
    partial pivoting (the LU of LAPACK's gesv, unblocked). Raises ZeroDivisionError on an exactly singular matrix;
    a non-finite a or b gives a non-finite x (no check, so that an integrator sees the non-finite derivative)."""
    n = a.shape[0]
    r = b.shape[1]
    for k in range(n):
        piv = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                piv = i
        if piv != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[piv, j]
                a[piv, j] = tmp
            for j in range(r):
                tmp = b[k, j]
                b[k, j] = b[piv, j]
                b[piv, j] = tmp
        pivot = a[k, k]
        if pivot == 0.0:
            raise ZeroDivisionError("system matrix of the equations of motion is singular")
        inv = 1.0 / pivot
        for i in range(k + 1, n):
            f = a[i, k] * inv
            if f != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= f * a[k, j]
                for j in range(r):
                    b[i, j] -= f * b[k, j]
    for k in range(n - 1, -1, -1):
        for c in range(r):
            acc = b[k, c]
            for j in range(k + 1, n):
                acc -= a[k, j] * b[j, c]
            b[k, c] = acc / a[k, k]


@kernel
def solve(a, b):
    """x with a x = b by Gaussian elimination with partial pivoting (a (n, n), b (n,); :func:`_gauss`).
    Raises ZeroDivisionError on an exactly singular matrix."""
    n = b.shape[0]
    lu = a.copy()
    x = np.empty((n, 1))
    for i in range(n):
        x[i, 0] = b[i]
    _gauss(lu, x)
    return x[:, 0].copy()


@kernel
def blocks_decoupled(m, perm, ptr):
    """Whether the entries of m between different diagonal blocks of :func:`solve_structure` are all zero."""
    nb = ptr.shape[0] - 2
    for b in range(nb):
        for c in range(nb):
            if c == b:
                continue
            for i in range(ptr[b], ptr[b + 1]):
                for j in range(ptr[c], ptr[c + 1]):
                    if m[perm[i], perm[j]] != 0.0:
                        return False
    return True


@kernel
def block_solve(m, f, perm, ptr):
    """V_dot with E V_dot = f over the active entries, by block elimination (:func:`solve_structure`), (n_v,)
    (zero in the inactive entries); m (n_v, n_v) = E, f (n_v,).

    With E ordered [[D, E_dc], [E_cd, E_cc]], D block-diagonal (blocks coupled only through the core c):
    X_b = D_b^-1 [E_bc, f_b] per block (:func:`_gauss`), the Schur complement S = E_cc - sum_b E_cb X_b[:, :-1]
    and g = f_c - sum_b E_cb X_b[:, -1]; V_c = S^-1 g; V_b = X_b[:, -1] - X_b[:, :-1] V_c. The same algebra as one
    elimination of the whole matrix (the GTM: a 10 x 10 core and five 4 x 4 blocks instead of 30 x 30); pivoting
    is within each block and within S, which suffices for E = M(q) + M_a, M(q) symmetric positive definite
    (eq. 33) and the apparent mass small beside it. If an entry between two blocks is not zero (a pattern that
    :func:`solve_structure` did not foresee), one elimination of the whole active matrix (:func:`_gauss`).
    Raises ZeroDivisionError on an exactly singular block or core.
    """
    n_v = m.shape[0]
    nb = ptr.shape[0] - 2
    c0 = ptr[nb]
    n_a = ptr[nb + 1]
    nc = n_a - c0
    if nb == 0 and n_a == n_v:  # no split, every entry active: one elimination of m itself
        return solve(m, f)
    out = np.zeros(n_v)
    if not blocks_decoupled(m, perm, ptr):
        a = np.empty((n_a, n_a))
        x = np.empty((n_a, 1))
        for i in range(n_a):
            x[i, 0] = f[perm[i]]
            for j in range(n_a):
                a[i, j] = m[perm[i], perm[j]]
        _gauss(a, x)
        for i in range(n_a):
            out[perm[i]] = x[i, 0]
        return out
    s = np.empty((nc, nc))
    g = np.empty((nc, 1))
    for i in range(nc):
        g[i, 0] = f[perm[c0 + i]]
        for j in range(nc):
            s[i, j] = m[perm[c0 + i], perm[c0 + j]]
    x = np.empty((c0, nc + 1))
    k_max = 0
    for b in range(nb):
        k_max = max(k_max, ptr[b + 1] - ptr[b])
    d_buf = np.empty(k_max * k_max)  # each block's D_b and [E_bc, f_b], as views of two buffers
    xb_buf = np.empty(k_max * (nc + 1))
    for b in range(nb):
        lo = ptr[b]
        k = ptr[b + 1] - lo
        d = d_buf[:k * k].reshape((k, k))
        xb = xb_buf[:k * (nc + 1)].reshape((k, nc + 1))
        for i in range(k):
            ri = perm[lo + i]
            for j in range(k):
                d[i, j] = m[ri, perm[lo + j]]
            for j in range(nc):
                xb[i, j] = m[ri, perm[c0 + j]]
            xb[i, nc] = f[ri]
        _gauss(d, xb)
        for i in range(nc):
            ri = perm[c0 + i]
            for t in range(k):
                e = m[ri, perm[lo + t]]
                if e != 0.0:
                    for j in range(nc):
                        s[i, j] -= e * xb[t, j]
                    g[i, 0] -= e * xb[t, nc]
        for t in range(k):
            for j in range(nc + 1):
                x[lo + t, j] = xb[t, j]
    _gauss(s, g)
    for i in range(nc):
        out[perm[c0 + i]] = g[i, 0]
    for t in range(c0):
        acc = x[t, nc]
        for j in range(nc):
            acc -= x[t, j] * g[j, 0]
        out[perm[t]] = acc
    return out
