"""Inertia: its data and its terms of the equations of motion, M(q) and -M_dot V + g(V, p) + [0, 0, dT/dq, 0]
(paper eqs. 8-10, 33), compiled.

Tuzcu & Nguyen (2014) "Flutter of Maneuvering Aircraft"; :class:`flexsim.structure.inertia.InertiaPolynomial`
builds the polynomial coefficients M0, H, M2. Body axes, SI units; V = [v, omega, s, eta].
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexsim._kernels.layout import _f1, _f2, _f3, _f4, _flag, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class InertiaData:
    """The inertia polynomial M(q) = M0 + [H q in the omega columns and rows] + [M2 : q q in the omega block]."""

    m0: np.ndarray = packed(2, "M0 (n_v, n_v): the mass matrix at q = 0 [kg, kg m, kg m^2] (eq. 9)")
    h: np.ndarray = packed(3, "H (n_v, 3, nq): the omega columns' part linear in q [kg] (eq. 10)")
    m2: np.ndarray = packed(4, "M2 (3, 3, nq, nq): the omega block's part quadratic in q [kg] (eq. 10)")
    inertia_dq: np.ndarray = packed(1, "dq (nq,) [m]: the inertia at q + dq (Terms.inertia_q_offset_m)")
    has_inertia_offset: int = packed(0, "1 when dq is applied", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): the polynomial of its structure
        (:class:`flexsim.structure.inertia.InertiaPolynomial`), dq from its terms."""
        inertia, dq = model.structure.inertia, model.terms.inertia_q_offset_m
        return dict(m0=inertia.m0, h=inertia.h, m2=inertia.m2,
                    inertia_dq=np.zeros(model.structure.dofs.nq) if dq is None else np.asarray(dq),
                    has_inertia_offset=dq is not None)


M0, H, M2, INERTIA_DQ = (InertiaData.index[n] for n in ("m0", "h", "m2", "inertia_dq"))
HAS_INERTIA_OFFSET = InertiaData.index["has_inertia_offset"]


@kernel
def inertia_term(F, I, q, vel):
    """M(q) (n_v, n_v) and the inertial generalized force -M_dot V + g(V, p) + [0, 0, dT/dq, 0] (n_v,) (eq. 33).

    p = M V, g_v = -omega x p_v, g_omega = -v x p_v - omega x p_omega (quasi-coordinates, eq. 33); :func:`inertia`
    gives M(q), dT/dq and M_dot V, at q + dq with an inertia offset (:class:`InertiaData`).
    """
    nq = q.shape[0]
    q_inertia = q
    if _flag(I, HAS_INERTIA_OFFSET):
        q_inertia = q + _f1(F, I, INERTIA_DQ)
    m, dtdq, mdot_v = inertia(_f2(F, I, M0), _f3(F, I, H), _f4(F, I, M2), vel, q_inertia, vel[6:6 + nq])
    n_v = vel.shape[0]
    p = np.empty(n_v)  # M V
    f = np.empty(n_v)
    for i in range(n_v):
        acc = 0.0
        for k in range(n_v):
            acc += m[i, k] * vel[k]
        p[i] = acc
        f[i] = -mdot_v[i]
    v = vel[0:3]
    w = vel[3:6]
    f[0] -= w[1] * p[2] - w[2] * p[1]
    f[1] -= w[2] * p[0] - w[0] * p[2]
    f[2] -= w[0] * p[1] - w[1] * p[0]
    f[3] -= v[1] * p[2] - v[2] * p[1] + w[1] * p[5] - w[2] * p[4]
    f[4] -= v[2] * p[0] - v[0] * p[2] + w[2] * p[3] - w[0] * p[5]
    f[5] -= v[0] * p[1] - v[1] * p[0] + w[0] * p[4] - w[1] * p[3]
    for i in range(nq):
        f[6 + i] += dtdq[i]
    return m, f


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

