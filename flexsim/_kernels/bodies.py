"""Slender bodies: their data and the generalized force of their Munk moments (virtual work, eqs. 17-24), compiled.

Sources: Munk (1924), NACA Report 184, the moment of a slender body in a flow inclined to its axis (Newman,
*Marine Hydrodynamics*, 1977, sec. 4.13); :class:`flexsim.model.bodies.SlenderBodies` builds the data; the body
velocity from :func:`flexsim._kernels.drag.point_velocity` (paper eqs. 5-6, 18). Component axes, SI units.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexsim._kernels.drag import point_velocity
from flexsim._kernels.layout import _f1, _f2, _f3, _f4, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class SlenderBodyData:
    """The file's slender bodies' Munk moments (Munk 1924, NACA Report 184; :class:`flexsim.model.bodies.SlenderBodies`)."""

    body_vol_dk: np.ndarray = packed(1, "rho-free coefficient Vol (k2 - k1) of each body (k_b,) [m^3]")
    body_g0: np.ndarray = packed(3, "velocity and rotation per unit V at q = 0 (k_b, 6, n_v)")
    body_g1: np.ndarray = packed(4, "the q part of the velocity map (k_b, 3, 3, nq)")
    body_offset: np.ndarray = packed(2, "offset from the attachment (k_b, 3) [m]")
    body_axis: np.ndarray = packed(2, "unit axis of each body (k_b, 3), component axes")
    has_bodies: int = packed(0, "1 with slender bodies", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): the bodies of its ``bodies``
        (:class:`flexsim.model.bodies.SlenderBodies`), none without."""
        b, d = model.bodies, model.structure.dofs
        if b is None:
            return dict(body_g0=np.zeros((0, 6, d.n_v)), body_g1=np.zeros((0, 3, 3, d.nq)), has_bodies=False)
        return dict(body_vol_dk=b.vol_dk.reshape(b.n_items), body_g0=b.g0, body_g1=b.g1, body_offset=b.offset_m,
                    body_axis=b.axis, has_bodies=True)


BODY_VOL_DK = SlenderBodyData.index["body_vol_dk"]
BODY_G0 = SlenderBodyData.index["body_g0"]
BODY_G1 = SlenderBodyData.index["body_g1"]
BODY_OFFSET = SlenderBodyData.index["body_offset"]
BODY_AXIS = SlenderBodyData.index["body_axis"]
HAS_BODIES = SlenderBodyData.index["has_bodies"]


@kernel
def munk_moments(v_p, axis, coeff):
    """Munk moment M = coeff (v . a)(v x a) of each body (k, 3) [N m] (Munk, NACA Report 184, 1924; Newman,
    *Marine Hydrodynamics*, 1977, sec. 4.13): v_p (k, 3) velocity relative to the air [m/s], axis (k, 3) unit
    axes, coeff (k,) = rho Vol (k2 - k1) [kg]; all in one set of axes."""
    out = np.empty((v_p.shape[0], 3))
    for j in range(v_p.shape[0]):
        vp = v_p[j]
        ax = axis[j]
        c = coeff[j] * (vp[0] * ax[0] + vp[1] * ax[1] + vp[2] * ax[2])
        out[j, 0] = c * (vp[1] * ax[2] - vp[2] * ax[1])
        out[j, 1] = c * (vp[2] * ax[0] - vp[0] * ax[2])
        out[j, 2] = c * (vp[0] * ax[1] - vp[1] * ax[0])
    return out


@kernel
def body_moments(F, I, q, vel, rho):
    """Munk moment of every slender body (k, 3) [N m], component axes (:mod:`flexsim.model.bodies`;
    :func:`munk_moments` of the body velocities of :func:`point_velocity`)."""
    vol_dk = _f1(F, I, BODY_VOL_DK)
    g0 = _f3(F, I, BODY_G0)
    g1 = _f4(F, I, BODY_G1)
    offset = _f2(F, I, BODY_OFFSET)
    v_p = np.empty((vol_dk.shape[0], 3))
    g1q = np.empty((3, 3))
    for j in range(vol_dk.shape[0]):
        v_p[j, 0], v_p[j, 1], v_p[j, 2] = point_velocity(g0, g1, offset, j, q, vel, g1q)
    return munk_moments(v_p, _f2(F, I, BODY_AXIS), rho * vol_dk)


@kernel
def body_force(F, I, q, vel, rho):
    """Q_body = sum_i B_i^T M_i (n_v,) [N, N m] of the Munk moments (virtual work, eqs. 17-24)."""
    n_v = vel.shape[0]
    out = np.zeros(n_v)
    mom = body_moments(F, I, q, vel, rho)
    g0 = _f3(F, I, BODY_G0)
    for j in range(mom.shape[0]):
        for i in range(n_v):
            out[i] += g0[j, 3, i] * mom[j, 0] + g0[j, 4, i] * mom[j, 1] + g0[j, 5, i] * mom[j, 2]
    return out

