"""Compiled kernels of the strain-based beam's kinematics (:mod:`flexsim.structure.strain_beam`).

The one implementation of the exponential map of SE(3) and its left Jacobian (Barfoot, *State Estimation for
Robotics*, 2017, eqs. 7.80-7.86) and of the chain of element transforms and point Jacobians of a beam of
constant-strain elements (Su & Cesnik, Int. J. Solids Struct. 48, 2011, eqs. 1-5); the module docstring of
:mod:`flexsim.structure.strain_beam` gives the formulas, frames and units. Everything is written with explicit
loops over 3-vectors and 3 × 3 matrices: a beam of a few tens of elements costs microseconds, where the same
steps in NumPy cost a call overhead each.

The θ-coefficients switch to their Taylor series below θ = 1e-2 (the closed forms lose digits there).
"""

from __future__ import annotations

import numpy as np
from numba import njit

_jit = njit(cache=True, nogil=True)
_inline = njit(cache=True, nogil=True, inline="always")


@_inline
def _coefficients(theta):
    """sinθ/θ, (1-cosθ)/θ², (θ-sinθ)/θ³, (θ²+2cosθ-2)/(2θ⁴), (2θ-3sinθ+θcosθ)/(2θ⁵)."""
    s2 = theta * theta
    if theta < 1e-2:
        return (1 - s2 / 6 + s2 * s2 / 120, 0.5 - s2 / 24 + s2 * s2 / 720, 1 / 6 - s2 / 120 + s2 * s2 / 5040,
                1 / 24 - s2 / 720 + s2 * s2 / 40320, 1 / 120 - s2 / 2520 + s2 * s2 / 120960)
    t, t2 = theta, s2
    s, c = np.sin(t), np.cos(t)
    return (s / t, (1 - c) / t2, (t - s) / (t2 * t), (t2 + 2 * c - 2) / (2 * t2 * t2),
            (2 * t - 3 * s + t * c) / (2 * t2 * t2 * t))


@_inline
def _hat(v, out):
    out[0, 0], out[0, 1], out[0, 2] = 0.0, -v[2], v[1]
    out[1, 0], out[1, 1], out[1, 2] = v[2], 0.0, -v[0]
    out[2, 0], out[2, 1], out[2, 2] = -v[1], v[0], 0.0


@_inline
def _mm(a, b, out):
    for i in range(3):
        for j in range(3):
            out[i, j] = a[i, 0] * b[0, j] + a[i, 1] * b[1, j] + a[i, 2] * b[2, j]


@_inline
def _exp_one(rho, phi, rot, pos, work):
    """``R = I + sinc φ^ + a1 φ^²`` and ``p = J(φ) ρ`` (Barfoot eqs. 7.80-7.83), written into rot (3, 3), pos (3,);
    work: scratch (>= 2, 3, 3)."""
    theta = np.sqrt(phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2])
    sinc, a1, a2, _, _ = _coefficients(theta)
    ph = work[0]
    ph2 = work[1]
    _hat(phi, ph)
    _mm(ph, ph, ph2)
    for i in range(3):
        acc = 0.0
        for j in range(3):
            eye = 1.0 if i == j else 0.0
            rot[i, j] = eye + sinc * ph[i, j] + a1 * ph2[i, j]
            acc += (eye + a1 * ph[i, j] + a2 * ph2[i, j]) * rho[j]
        pos[i] = acc


@_inline
def _left_jacobian_one(rho, phi, out, work):
    """``𝒥 = [[J, Q], [0, J]]`` (Barfoot eqs. 7.85-7.86; translation first), written into out (6, 6);
    work: scratch (>= 10, 3, 3)."""
    theta = np.sqrt(phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2])
    _, a1, a2, a3, a4 = _coefficients(theta)
    ph, rh, ph2, pr, rp = work[0], work[1], work[2], work[3], work[4]
    prp, p2r, rp2, prpp, pprp = work[5], work[6], work[7], work[8], work[9]
    _hat(phi, ph)
    _hat(rho, rh)
    _mm(ph, ph, ph2)
    _mm(ph, rh, pr)
    _mm(rh, ph, rp)
    _mm(pr, ph, prp)
    _mm(ph2, rh, p2r)
    _mm(rh, ph2, rp2)
    _mm(prp, ph, prpp)
    _mm(ph, prp, pprp)
    for i in range(6):
        for j in range(6):
            out[i, j] = 0.0
    for i in range(3):
        for j in range(3):
            eye = 1.0 if i == j else 0.0
            jac = eye + a1 * ph[i, j] + a2 * ph2[i, j]
            out[i, j] = jac
            out[3 + i, 3 + j] = jac
            out[i, 3 + j] = (0.5 * rh[i, j] + a2 * (pr[i, j] + rp[i, j] + prp[i, j])
                             + a3 * (p2r[i, j] + rp2[i, j] - 3.0 * prp[i, j]) + a4 * (prpp[i, j] + pprp[i, j]))


@_jit
def se3_exp_batch(rho, phi, rot, pos):
    """:func:`_exp_one` over rows: rho, phi (m, 3) -> rot (m, 3, 3), pos (m, 3)."""
    work = np.empty((2, 3, 3))
    for k in range(rho.shape[0]):
        _exp_one(rho[k], phi[k], rot[k], pos[k], work)


@_jit
def se3_left_jacobian_batch(rho, phi, out):
    """:func:`_left_jacobian_one` over rows: rho, phi (m, 3) -> out (m, 6, 6)."""
    work = np.empty((10, 3, 3))
    for k in range(rho.shape[0]):
        _left_jacobian_one(rho[k], phi[k], out[k], work)


@_inline
def _twist_columns(rot, pos, strain, length, first, z, work, jl, vec):
    """Spatial-twist Jacobian ``Ad(T) 𝒥(ξ) ℓ B`` (6, ns) of a piece of element of length ``length`` from the frame
    (rot, pos), strains ``[e, κ]``; ``first``: index of the first free strain (0 extensible, 1 not).
    Scratch: work (12, 3, 3), jl (6, 6), vec (4, 3)."""
    rho, phi, jt, jb = vec[0], vec[1], vec[2], vec[3]
    rho[0], rho[1], rho[2] = length * (1.0 + strain[0]), 0.0, 0.0
    for i in range(3):
        phi[i] = length * strain[1 + i]
    _left_jacobian_one(rho, phi, jl, work)
    ph = work[10]
    _hat(pos, ph)
    phr = work[11]
    _mm(ph, rot, phr)
    ns = 4 - first
    for c in range(ns):
        k = c + first  # 0: extension (column e1 of the translation), 1-3: curvature about e_(k-1) (rotation)
        for i in range(3):
            if k == 0:
                jt[i], jb[i] = length * jl[i, 0], length * jl[3 + i, 0]
            else:
                jt[i], jb[i] = length * jl[i, 2 + k], length * jl[3 + i, 2 + k]
        for i in range(3):
            top = 0.0
            bottom = 0.0
            for j in range(3):
                top += rot[i, j] * jt[j] + phr[i, j] * jb[j]
                bottom += rot[i, j] * jb[j]
            z[i, c] = top
            z[3 + i, c] = bottom


@_jit
def beam_chain(strains, ell, root_rot, root_pos, sigma, first, node_rot, node_pos, prot, ppos, jac_pos, jac_rot,
               tip_pos, tip_rot):
    """Frames and Jacobians of a beam (outputs written in place; shapes as in ``BeamKinematics``).

    strains (N, 4); ell element length [m]; root_rot (3, 3), root_pos (3,); sigma (G,) Gauss fractions of an element;
    first: 0 (extensible) or 1. Outputs: node_rot (N+1, 3, 3), node_pos (N+1, 3), prot (P, 3, 3), ppos (P, 3),
    jac_pos, jac_rot (P, 3, n), tip_pos, tip_rot (3, n), P = N G, n = N (4 - first).
    """
    n_el = strains.shape[0]
    ns = 4 - first
    n_g = sigma.shape[0]
    node_rot[0] = root_rot
    node_pos[0] = root_pos
    rho = np.zeros(3)
    phi = np.empty(3)
    r_e = np.empty((3, 3))
    p_e = np.empty(3)
    z = np.empty((6, ns))
    work = np.empty((12, 3, 3))
    jl = np.empty((6, 6))
    vec = np.empty((4, 3))
    twist = np.zeros((6, n_el * ns))  # the spatial twists of the whole elements before the current point
    for j in range(n_el):
        rho[0] = ell * (1.0 + strains[j, 0])
        for i in range(3):
            phi[i] = ell * strains[j, 1 + i]
        _exp_one(rho, phi, r_e, p_e, work)
        _mm(node_rot[j], r_e, node_rot[j + 1])
        for i in range(3):
            node_pos[j + 1, i] = node_pos[j, i] + (node_rot[j, i, 0] * p_e[0] + node_rot[j, i, 1] * p_e[1]
                                                   + node_rot[j, i, 2] * p_e[2])
    for j in range(n_el):
        for g in range(n_g):
            f = sigma[g]
            k = j * n_g + g
            rho[0] = f * ell * (1.0 + strains[j, 0])
            for i in range(3):
                phi[i] = f * ell * strains[j, 1 + i]
            _exp_one(rho, phi, r_e, p_e, work)
            _mm(node_rot[j], r_e, prot[k])
            for i in range(3):
                ppos[k, i] = node_pos[j, i] + (node_rot[j, i, 0] * p_e[0] + node_rot[j, i, 1] * p_e[1]
                                               + node_rot[j, i, 2] * p_e[2])
            _twist_columns(node_rot[j], node_pos[j], strains[j], f * ell, first, z, work, jl, vec)
            for c in range(j * ns):
                for i in range(3):
                    jac_rot[k, i, c] = twist[3 + i, c]
            for c in range(ns):
                for i in range(3):
                    jac_rot[k, i, j * ns + c] = z[3 + i, c]
            for c in range(j * ns + ns, n_el * ns):
                for i in range(3):
                    jac_rot[k, i, c] = 0.0
            x, y, w = ppos[k, 0], ppos[k, 1], ppos[k, 2]
            for c in range(n_el * ns):
                if c < j * ns:
                    t0, t1, t2 = twist[0, c], twist[1, c], twist[2, c]
                elif c < j * ns + ns:
                    t0, t1, t2 = z[0, c - j * ns], z[1, c - j * ns], z[2, c - j * ns]
                else:
                    t0, t1, t2 = 0.0, 0.0, 0.0
                r0, r1, r2 = jac_rot[k, 0, c], jac_rot[k, 1, c], jac_rot[k, 2, c]
                jac_pos[k, 0, c] = t0 - (y * r2 - w * r1)
                jac_pos[k, 1, c] = t1 - (w * r0 - x * r2)
                jac_pos[k, 2, c] = t2 - (x * r1 - y * r0)
        _twist_columns(node_rot[j], node_pos[j], strains[j], ell, first, z, work, jl, vec)
        for c in range(ns):
            for i in range(6):
                twist[i, j * ns + c] = z[i, c]
    x, y, w = node_pos[n_el, 0], node_pos[n_el, 1], node_pos[n_el, 2]
    for c in range(n_el * ns):
        r0, r1, r2 = twist[3, c], twist[4, c], twist[5, c]
        tip_rot[0, c], tip_rot[1, c], tip_rot[2, c] = r0, r1, r2
        tip_pos[0, c] = twist[0, c] - (y * r2 - w * r1)
        tip_pos[1, c] = twist[1, c] - (w * r0 - x * r2)
        tip_pos[2, c] = twist[2, c] - (x * r1 - y * r0)


#: Padé coefficients b_0..b_m of exp and the 1-norm bounds θ_m below which degree m is accurate to double precision
#: without scaling (Higham, SIAM J. Matrix Anal. Appl. 26(4), 2005, table 2.3 and eq. 2.9; as in scipy.linalg.expm).
_PADE_DEGREE = np.array([3, 5, 7, 9])
_PADE_THETA = np.array([1.495585217958292e-2, 2.539398330063230e-1, 9.504178996162932e-1, 2.097847961257068])
_PADE_B = np.array([[120.0, 60.0, 12.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
                    [30240.0, 15120.0, 3360.0, 420.0, 30.0, 1.0, 0.0, 0.0, 0.0, 0.0],
                    [17297280.0, 8648640.0, 1995840.0, 277200.0, 25200.0, 1512.0, 56.0, 1.0, 0.0, 0.0],
                    [17643225600.0, 8821612800.0, 2075673600.0, 302702400.0, 30270240.0, 2162160.0, 110880.0,
                     3960.0, 90.0, 1.0]])
_PADE13 = (64764752532480000.0, 32382376266240000.0, 7771770303897600.0, 1187353796428800.0, 129060195264000.0,
           10559470521600.0, 670442572800.0, 33522128640.0, 1323241920.0, 40840800.0, 960960.0, 16380.0, 182.0, 1.0)
_THETA13 = 5.371920351148152


@_inline
def _tmul(x, y, out):
    """Product of block upper-triangular Toeplitz matrices ``[[X0, X1, X2], [0, X0, X1], [0, 0, X0]]`` stored as
    their first block rows x, y (3, k, k): ``(X0 Y0, X0 Y1 + X1 Y0, X0 Y2 + X1 Y1 + X2 Y0)`` into out."""
    k = x.shape[1]
    for i in range(k):
        for j in range(k):
            s0 = 0.0
            s1 = 0.0
            s2 = 0.0
            for m in range(k):
                s0 += x[0, i, m] * y[0, m, j]
                s1 += x[0, i, m] * y[1, m, j] + x[1, i, m] * y[0, m, j]
                s2 += x[0, i, m] * y[2, m, j] + x[1, i, m] * y[1, m, j] + x[2, i, m] * y[0, m, j]
            out[0, i, j], out[1, i, j], out[2, i, j] = s0, s1, s2


@_inline
def _lu_solve(a, b, piv):
    """Solve ``a x = b`` in place (b becomes x; a (k, k) is overwritten by its LU factors with partial pivoting,
    piv (k,) int scratch): Gaussian elimination, the right-hand side (k, k) eliminated along."""
    k = a.shape[0]
    for c in range(k):
        p = c
        for r in range(c + 1, k):
            if abs(a[r, c]) > abs(a[p, c]):
                p = r
        piv[c] = p
        if p != c:
            for j in range(k):
                a[c, j], a[p, j] = a[p, j], a[c, j]
                b[c, j], b[p, j] = b[p, j], b[c, j]
        for r in range(c + 1, k):
            f = a[r, c] / a[c, c]
            for j in range(c, k):
                a[r, j] -= f * a[c, j]
            for j in range(k):
                b[r, j] -= f * b[c, j]
    for c in range(k - 1, -1, -1):
        for j in range(k):
            acc = b[c, j]
            for m in range(c + 1, k):
                acc -= a[c, m] * b[m, j]
            b[c, j] = acc / a[c, c]


@_inline
def _tsolve(d, n, out, work, piv):
    """``X`` with ``D X = N`` for block upper-triangular Toeplitz D, N, X (first block rows, (3, k, k)): block
    back-substitution ``X0 = D0⁻¹ N0``, ``X1 = D0⁻¹ (N1 − D1 X0)``, ``X2 = D0⁻¹ (N2 − D1 X1 − D2 X0)``.
    work (k, k) scratch; d is left unchanged."""
    k = d.shape[1]
    for blk in range(3):
        for i in range(k):
            for j in range(k):
                acc = n[blk, i, j]
                for m in range(k):
                    if blk >= 1:
                        acc -= d[1, i, m] * out[blk - 1, m, j]
                    if blk == 2:
                        acc -= d[2, i, m] * out[0, m, j]
                out[blk, i, j] = acc
        work[:, :] = d[0]
        _lu_solve(work, out[blk], piv)


@_jit
def _expm_toeplitz(x, out, work, piv):
    """``exp`` of the block upper-triangular Toeplitz matrix with first block row x (3, k, k), as its first block
    row, into out: scaling and squaring with a Padé approximant of degree 3, 5, 7, 9 or 13 chosen from the 1-norm
    (Higham, SIAM J. Matrix Anal. Appl. 26(4), 2005, Algorithm 2.3: the method of scipy.linalg.expm), the powers
    and the solve done block by block (the structure is kept by products, sums and inverses).
    work (8, 3, k, k) and piv (k,) int: scratch."""
    k = x.shape[1]
    norm = 0.0
    for j in range(k):
        col0 = 0.0
        col12 = 0.0
        for i in range(k):
            col0 += abs(x[0, i, j])
            col12 += abs(x[0, i, j]) + abs(x[1, i, j]) + abs(x[2, i, j])
        norm = max(norm, col0, col12)
    xs, x2, u, v, p1, p2, t1, t2 = work[0], work[1], work[2], work[3], work[4], work[5], work[6], work[7]
    s = 0
    if norm > _PADE_THETA[_PADE_DEGREE.size - 1]:
        if norm > _THETA13:
            s = int(np.ceil(np.log2(norm / _THETA13)))
    scale = 0.5 ** s
    xs[:, :, :] = x
    if s > 0:
        xs *= scale
    _tmul(xs, xs, x2)
    degree = 13
    for d in range(_PADE_DEGREE.size):
        if norm <= _PADE_THETA[d]:
            degree = d
            break
    if degree < 13:  # U = X Σ b_(2i+1) X^(2i), V = Σ b_(2i) X^(2i)
        b = _PADE_B[degree]
        p1[:, :, :] = 0.0
        t1[:, :, :] = 0.0  # the odd sum
        v[:, :, :] = 0.0
        for i in range(k):
            p1[0, i, i] = 1.0
            t1[0, i, i] = b[1]
            v[0, i, i] = b[0]
        for i in range(1, (_PADE_DEGREE[degree] - 1) // 2 + 1):
            _tmul(p1, x2, p2)
            p1[:, :, :] = p2
            t1 += b[2 * i + 1] * p1
            v += b[2 * i] * p1
        _tmul(xs, t1, u)
    else:
        b = _PADE13
        _tmul(x2, x2, p1)  # X^4
        _tmul(p1, x2, p2)  # X^6
        t1[:, :, :] = b[13] * p2 + b[11] * p1 + b[9] * x2
        _tmul(p2, t1, t2)
        t2 += b[7] * p2 + b[5] * p1 + b[3] * x2
        for i in range(k):
            t2[0, i, i] += b[1]
        _tmul(xs, t2, u)
        t1[:, :, :] = b[12] * p2 + b[10] * p1 + b[8] * x2
        _tmul(p2, t1, v)
        v += b[6] * p2 + b[4] * p1 + b[2] * x2
        for i in range(k):
            v[0, i, i] += b[0]
    for blk in range(3):  # D = V − U into p1, N = V + U into p2
        for i in range(k):
            for j in range(k):
                p1[blk, i, j] = v[blk, i, j] - u[blk, i, j]
                p2[blk, i, j] = v[blk, i, j] + u[blk, i, j]
    _tsolve(p1, p2, out, t1[0], piv)
    for _ in range(s):
        _tmul(out, out, t2)
        out[:, :, :] = t2


@_jit
def expm_toeplitz_batch(x, out):
    """:func:`_expm_toeplitz` over the leading axis: x, out (m, 3, k, k)."""
    k = x.shape[2]
    work = np.empty((8, 3, k, k))
    piv = np.empty(k, dtype=np.int64)
    for i in range(x.shape[0]):
        _expm_toeplitz(x[i], out[i], work, piv)


@_jit
def chain_toeplitz(root, elements, points_element, points, out):
    """Frames and their first two time derivatives along a chain of element transforms, as first block rows
    ``[T, Ṫ, T̈/2]`` (3, 4, 4) of block Toeplitz matrices, whose product is the product rule
    (``T̈_(j+1) = T̈_j G + 2 Ṫ_j Ġ + T_j G̈``): nodes ``X_(j+1) = X_j X(G_j)`` from ``root``, then each point
    ``X_node(e) X(H_p)``. root (3, 4, 4); elements (N, 3, 4, 4); points_element (P,) int; points, out (P, 3, 4, 4).
    """
    n = elements.shape[0]
    nodes = np.empty((n + 1, 3, 4, 4))
    nodes[0] = root
    for j in range(n):
        _tmul(nodes[j], elements[j], nodes[j + 1])
    for k in range(points.shape[0]):
        _tmul(nodes[points_element[k]], points[k], out[k])
