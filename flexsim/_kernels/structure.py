"""The structure's inertia kernel: M(q), dT/dq and dM/dt V (paper eqs. 8-10, 33).

Tuzcu & Nguyen (2014) "Flutter of Maneuvering Aircraft"; :class:`flexsim.structure.inertia.InertiaPolynomial`
builds the polynomial coefficients M0, H, M2. Body axes, SI units.
"""

from __future__ import annotations

import numpy as np

from flexsim._kernels.layout import kernel

@kernel
def inertia(m0, h, m2, v, q, s):
    """M(q), dT/dq and dM/dt V in one pass (paper eqs. 8-10, 33; :class:`InertiaPolynomial`).

    M(q) = M0 + [H q in the omega columns] + [(H q)^T in the omega rows] + [M2 : q q in the omega block];
    with m2q = M2 . q (3, 3, nq) and the symmetry M2[a, d, k, l] = M2[d, a, l, k]:
    dT/dq_k = V^T H[:, :, k] omega + omega^T m2q[:, :, k] omega;
    (dM/dt V) = (H s) omega, plus (H s)^T V + (m2q . s) omega + (m2q . s)^T omega in the omega rows.

    Parameters: m0 (n_v, n_v), h (n_v, 3, nq), m2 (3, 3, nq, nq), v = V (n_v,), q (nq,) [m], s = dq/dt
    (nq,) [m/s]. Returns m (n_v, n_v), dtdq (nq,) [N], mdot_v (n_v,).
    """
    n_v = m0.shape[0]
    nq = q.shape[0]
    m = m0.copy()
    hq = np.zeros((n_v, 3))
    hs = np.zeros((n_v, 3))
    vh = np.zeros((3, nq))  # V^T H[:, a, k]
    for i in range(n_v):
        vi = v[i]
        for a in range(3):
            acc_q = 0.0
            acc_s = 0.0
            for k in range(nq):
                hik = h[i, a, k]
                acc_q += hik * q[k]
                acc_s += hik * s[k]
                vh[a, k] += vi * hik
            hq[i, a] = acc_q
            hs[i, a] = acc_s
    for i in range(n_v):
        for a in range(3):
            m[i, 3 + a] += hq[i, a]
            m[3 + a, i] += hq[i, a]
    m2q = np.zeros((3, 3, nq))
    m2qs = np.zeros((3, 3))  # (M2 . q) . s
    for a in range(3):
        for b in range(3):
            qq = 0.0
            qs = 0.0
            for k in range(nq):
                acc = 0.0
                for l in range(nq):
                    acc += m2[a, b, k, l] * q[l]
                m2q[a, b, k] = acc
                qq += acc * q[k]
                qs += acc * s[k]
            m[3 + a, 3 + b] += qq
            m2qs[a, b] = qs
    w = v[3:6]
    dtdq = np.zeros(nq)
    for k in range(nq):
        acc = 0.0
        for a in range(3):
            wm = 0.0
            for b in range(3):
                wm += w[b] * m2q[b, a, k]
            acc += w[a] * (vh[a, k] + wm)
        dtdq[k] = acc
    mdot = np.empty(n_v)
    for i in range(n_v):
        mdot[i] = hs[i, 0] * w[0] + hs[i, 1] * w[1] + hs[i, 2] * w[2]
    for a in range(3):
        acc = 0.0
        for i in range(n_v):
            acc += hs[i, a] * v[i]
        for b in range(3):
            acc += (m2qs[a, b] + m2qs[b, a]) * w[b]
        mdot[3 + a] += acc
    return m, dtdq, mdot

