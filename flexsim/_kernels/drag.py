"""Parasite drag: its data and its generalized force (by virtual work, paper eqs. 17-24), compiled.

Sources: Raymer (2018) sec. 12.5, parasite drag of the file's drag items (:mod:`flexsim.model.drag`); the paper
(Tuzcu & Nguyen 2014) eqs. 5-6, 18 for the velocity of an attached point (:func:`point_velocity`, also used by the
slender bodies, :mod:`~flexsim._kernels.bodies`). Component axes, SI units.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexsim._kernels.layout import _f1, _f2, _f3, _f4, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class ParasiteDragData:
    """The file's parasite-drag items (Raymer 2018 sec. 12.5; :class:`flexsim.model.drag.ParasiteDrag`): k items, each
    a drag area at a point attached to a component, moving with it (maps as for the velocity of an attached point)."""

    drag_area: np.ndarray = packed(1, "S C_D0 of each item (k,) [m^2]")
    drag_g0: np.ndarray = packed(3, "velocity and rotation of the point per unit V at q = 0 (k, 6, n_v)")
    drag_g1: np.ndarray = packed(4, "the q part of its velocity map in the omega columns (k, 3, 3, nq)")
    drag_offset: np.ndarray = packed(2, "offset of the point from its attachment (k, 3) [m], component axes")
    has_drag: int = packed(0, "1 with parasite-drag items", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): the items of its
        ``parasite_drag`` (:class:`flexsim.model.drag.ParasiteDrag`), none without."""
        p, d = model.parasite_drag, model.structure.dofs
        if p is None:
            return dict(drag_g0=np.zeros((0, 6, d.n_v)), drag_g1=np.zeros((0, 3, 3, d.nq)), has_drag=False)
        return dict(drag_area=p.area_m2.reshape(p.n_items), drag_g0=p.g0, drag_g1=p.g1, drag_offset=p.offset_m,
                    has_drag=True)


DRAG_AREA = ParasiteDragData.index["drag_area"]
DRAG_G0 = ParasiteDragData.index["drag_g0"]
DRAG_G1 = ParasiteDragData.index["drag_g1"]
DRAG_OFFSET = ParasiteDragData.index["drag_offset"]
HAS_DRAG = ParasiteDragData.index["has_drag"]


@kernel
def point_velocity(g0, g1, offset, j, q, vel, g1q):
    """Velocity v_p [m/s] of attached point j, component axes, as three floats, and the q part g1[j] q (3, 3) of its
    map A_j(q) written into ``g1q``: v_p = A_j(q) V + omega_sec x rho_j with A_j(q) = g0[j, 0:3] + g1[j] q on the
    omega columns and omega_sec = g0[j, 3:6] V (paper eqs. 5-6, 18; drag items and slender bodies)."""
    n_v = vel.shape[0]
    nq = q.shape[0]
    for r in range(3):
        for c in range(3):
            acc = 0.0
            for k in range(nq):
                acc += g1[j, r, c, k] * q[k]
            g1q[r, c] = acc
    vp0 = vp1 = vp2 = om0 = om1 = om2 = 0.0
    for i in range(n_v):
        vi = vel[i]
        vp0 += g0[j, 0, i] * vi
        vp1 += g0[j, 1, i] * vi
        vp2 += g0[j, 2, i] * vi
        om0 += g0[j, 3, i] * vi
        om1 += g0[j, 4, i] * vi
        om2 += g0[j, 5, i] * vi
    vp0 = vp0 + g1q[0, 0] * vel[3] + g1q[0, 1] * vel[4] + g1q[0, 2] * vel[5]
    vp1 = vp1 + g1q[1, 0] * vel[3] + g1q[1, 1] * vel[4] + g1q[1, 2] * vel[5]
    vp2 = vp2 + g1q[2, 0] * vel[3] + g1q[2, 1] * vel[4] + g1q[2, 2] * vel[5]
    rho_j = offset[j]
    vp0 += om1 * rho_j[2] - om2 * rho_j[1]
    vp1 += om2 * rho_j[0] - om0 * rho_j[2]
    vp2 += om0 * rho_j[1] - om1 * rho_j[0]
    return vp0, vp1, vp2


@kernel
def parasite_drag(F, I, q, vel, rho):
    """Generalized force of the drag items (Raymer 2018 sec. 12.5; :mod:`flexsim.model.drag`), (n_v,).

    f_i = -1/2 rho f |v_p| v_p at the item's point (component axes, :func:`point_velocity`);
    Q = A_i(q)^T f_i + B_i^T (rho_i x f_i) (virtual work, eqs. 17-24) [N, N m].
    """
    n_v = vel.shape[0]
    out = np.zeros(n_v)
    area = _f1(F, I, DRAG_AREA)
    g0 = _f3(F, I, DRAG_G0)
    g1 = _f4(F, I, DRAG_G1)
    offset = _f2(F, I, DRAG_OFFSET)
    g1q = np.empty((3, 3))
    for j in range(area.shape[0]):
        vp0, vp1, vp2 = point_velocity(g0, g1, offset, j, q, vel, g1q)
        rho_i = offset[j]
        speed = math.sqrt(vp0 * vp0 + vp1 * vp1 + vp2 * vp2)
        c = -0.5 * rho * area[j] * speed
        f0, f1, f2 = c * vp0, c * vp1, c * vp2
        mu0 = rho_i[1] * f2 - rho_i[2] * f1
        mu1 = rho_i[2] * f0 - rho_i[0] * f2
        mu2 = rho_i[0] * f1 - rho_i[1] * f0
        for i in range(n_v):
            out[i] += g0[j, 0, i] * f0 + g0[j, 1, i] * f1 + g0[j, 2, i] * f2
            out[i] += g0[j, 3, i] * mu0 + g0[j, 4, i] * mu1 + g0[j, 5, i] * mu2
        for a in range(3):  # the q part of A_i(q) on the omega columns
            out[3 + a] += g1q[0, a] * f0 + g1q[1, a] * f1 + g1q[2, a] * f2
    return out
