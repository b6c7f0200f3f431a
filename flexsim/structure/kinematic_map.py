"""The kinematic map from the global velocity vector to the motion of any structural point.

Source: Tuzcu & Nguyen (2014) eqs. (5)-(6) for velocities and eq. (18) for virtual displacements (which
have the same form). For a point on component i at station x_i, write the velocity of its reference point
on the elastic axis and the angular velocity of its cross-section, both in component axes, as linear maps
of the global velocity vector V = [v, omega, s, eta] (eq. 9)::

    v_ref = A(q) V,   omega_sec = B V,   G(q) = [A(q); B] = G0 + sum_k q_k G1_k

A is affine in the bending coordinates q (through the (r + u)^T omega terms of eqs. 5-6) and only its
omega columns depend on q; B is constant. From eq. (6), with parent fuselage f and component i::

    v_ref = C_i [v + omega x (r_fi + u_fi) + v_fi + alpha_fi x r_fi]
            + (C_i omega) x (x e1 + u_i) + (C_i (Omega_fi + alpha_fi)) x (x e1) + v_i
    omega_sec = C_i omega + C_i (Omega_fi + alpha_fi) + alpha_i

with u_i = e3 U_i(x) q_i, v_i = e3 U_i(x) s_i, alpha_i = e1 Psi_i(x) eta_i, Omega_fi = -e2 U_f'(x_fi) s_f.
The fuselage itself is eq. (5): the same expression with C_f = I, r_f = 0 and no parent. Every
generalized force (aerodynamics, gravity, thrust) is G^T [f; mu] (eqs. 17-24), so this map is written
once and serves the mass matrix, the loads and the output kinematics.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.aircraft.definition import Aircraft, Component
from flexsim.kinematics import skew
from flexsim.structure.shapes import bending_shapes, torsion_shapes

__all__ = ["DofIndex", "PointMaps", "point_maps"]

_E1, _E2, _E3 = np.eye(3)
_RIGID_LABELS = ("u", "v", "w", "p", "q", "r")


@dataclass(frozen=True)
class DofIndex:
    """Positions of each component's elastic coordinates in q, xi and the global velocity vector V.

    V = [v (3), omega (3), s (nq), eta (nxi)] (paper eq. 9), with the components in
    :data:`~flexsim.aircraft.definition.COMPONENT_NAMES` order inside s and inside eta.

    Attributes
    ----------
    component_names : tuple of str
    bending : dict
        Component name -> slice of its bending coordinates in q (length m_i).
    torsion : dict
        Component name -> slice of its torsion coordinates in xi (length n_i).
    nq, nxi : int
        Numbers of bending and torsion coordinates of the whole aircraft.
    """

    component_names: tuple[str, ...]
    bending: dict[str, slice]
    torsion: dict[str, slice]
    nq: int
    nxi: int

    @classmethod
    def from_aircraft(cls, aircraft: Aircraft) -> "DofIndex":
        """Index the elastic coordinates of ``aircraft`` (rigid components get empty slices)."""
        bending, torsion = {}, {}
        iq = ix = 0
        for c in aircraft.components:
            bending[c.name] = slice(iq, iq + c.bending_modes)
            torsion[c.name] = slice(ix, ix + c.torsion_modes)
            iq += c.bending_modes
            ix += c.torsion_modes
        return cls(aircraft.component_names, bending, torsion, iq, ix)

    @property
    def n_v(self) -> int:
        """Length of the global velocity vector V (6 + nq + nxi)."""
        return 6 + self.nq + self.nxi

    def v_bending(self, name: str) -> slice:
        """Slice of component ``name``'s bending rates s_i in V."""
        s = self.bending[name]
        return slice(6 + s.start, 6 + s.stop)

    def v_torsion(self, name: str) -> slice:
        """Slice of component ``name``'s torsion rates eta_i in V."""
        s = self.torsion[name]
        return slice(6 + self.nq + s.start, 6 + self.nq + s.stop)

    @property
    def labels(self) -> tuple[str, ...]:
        """Human-readable name of every entry of V, e.g. ``"right_wing bending 1"``."""
        out = list(_RIGID_LABELS)
        for kind, table in (("bending", self.bending), ("torsion", self.torsion)):
            for name in self.component_names:
                s = table[name]
                out += [f"{name} {kind} {k + 1}" for k in range(s.stop - s.start)]
        return tuple(out)


@dataclass(frozen=True, eq=False)
class PointMaps:
    """Kinematic maps of k points, G(q) = G0 + G1 . q (see module docstring).

    Attributes
    ----------
    g0 : ndarray, shape (k, 6, n_v)
        Rows 0-2: A at q = 0 (reference-point velocity, component axes); rows 3-5: B (section angular
        velocity, component axes). Units: 1 for v and s columns, m for omega columns, etc.
    g1 : ndarray, shape (k, 3, 3, nq)
        d A[:, omega columns] / d q: entry [j, r, a, l] is the derivative of row r, omega column a,
        with respect to bending coordinate q_l [1].
    r0 : ndarray, shape (k, 3)
        Undeformed positions of the points relative to o, body axes [m].
    dcm : ndarray, shape (3, 3)
        C_i: body components -> component components.
    """

    g0: np.ndarray
    g1: np.ndarray
    r0: np.ndarray
    dcm: np.ndarray

    def at(self, q: np.ndarray) -> np.ndarray:
        """G(q), shape (k, 6, n_v), for bending coordinates q (nq,) [m]."""
        g = self.g0.copy()
        g[:, 0:3, 3:6] += self.g1 @ q
        return g

    def positions(self, q: np.ndarray, xi: np.ndarray) -> np.ndarray:
        """Positions of the points relative to o in body axes [m], shape (k, 3).

        Linear in the elastic coordinates, with the virtual displacements of eq. (18) as the
        derivatives: r = r0 + C_i^T A[:, s, eta] [q; xi] (the form the model's kinematics assume).
        """
        n_el = q.size + xi.size
        disp = self.g0[:, 0:3, 6 : 6 + n_el] @ np.concatenate([q, xi])
        return self.r0 + disp @ self.dcm


def point_maps(aircraft: Aircraft, dofs: DofIndex, component: Component, x: np.ndarray) -> PointMaps:
    """Kinematic maps G0, G1 of points at stations ``x`` on ``component`` (paper eqs. 5-6, 18).

    Parameters
    ----------
    aircraft : Aircraft
        Supplies the parent (fuselage) of ``component``.
    dofs : DofIndex
    component : Component
    x : array_like, shape (k,)
        Stations along the component's elastic axis [m].

    Returns
    -------
    PointMaps
        In component axes x_i y_i z_i.
    """
    x = np.atleast_1d(np.asarray(x, dtype=float))
    k = x.size
    n_v = dofs.n_v
    g0 = np.zeros((k, 6, n_v))
    g1 = np.zeros((k, 3, 3, dofs.nq))
    xe1 = np.zeros((k, 3))
    xe1[:, 0] = x
    sx = skew(xe1)  # (k, 3, 3)

    parent = None
    if component.name != "fuselage" and "fuselage" in aircraft.component_names:
        parent = aircraft.component("fuselage")
    c = component.dcm
    r = component.root_m  # r_fi; zero for the fuselage, which is clamped at o

    # Rigid-body columns: v -> C_i; omega -> -C_i skew(r_fi) - skew(x e1) C_i   (eq. 6, q = 0 part)
    g0[:, 0:3, 0:3] = c
    g0[:, 0:3, 3:6] = -c @ skew(r) - sx @ c
    g0[:, 3:6, 3:6] = c

    # Own elastic columns: v_i = e3 U_i s_i; alpha_i = e1 Psi_i eta_i; u_i = e3 U_i q_i in the omega term.
    m_i, n_i = component.bending_modes, component.torsion_modes
    if m_i:
        u = bending_shapes(x, component.length_m, m_i)  # (k, m)
        g0[:, 2, dofs.v_bending(component.name)] = u
        # d/dq_l of [-skew(u_i) C_i] with u_i = e3 U_il
        g1[:, :, :, dofs.bending[component.name]] = np.einsum("ab,bc,kl->kacl", -skew(_E3), c, u)
    if n_i:
        psi = torsion_shapes(x, component.length_m, n_i)
        g0[:, 3, dofs.v_torsion(component.name)] = psi

    # Parent (fuselage) elastic motion carried into the component (eq. 6).
    if parent is not None:
        xf = np.array([r[0]])
        m_f, n_f = parent.bending_modes, parent.torsion_modes
        if m_f:
            uf = bending_shapes(xf, parent.length_m, m_f)[0]
            duf = bending_shapes(xf, parent.length_m, m_f, derivative=1)[0]
            cols = dofs.v_bending("fuselage")
            # C_i v_fi + (C_i Omega_fi) x (x e1), Omega_fi = -e2 U_f'(x_fi) s_f
            g0[:, 0:3, cols] = np.einsum("a,l->al", c @ _E3, uf) + np.einsum("kab,b,l->kal", sx, c @ _E2, duf)
            g0[:, 3:6, cols] = np.einsum("a,l->al", -(c @ _E2), duf)
            # omega x u_fi with u_fi = e3 U_f(x_fi) q_f:  -C_i skew(e3) U_fl
            g1[:, :, :, dofs.bending["fuselage"]] = np.einsum("ab,l->abl", -c @ skew(_E3), uf)
        if n_f:
            psif = torsion_shapes(xf, parent.length_m, n_f)[0]
            cols = dofs.v_torsion("fuselage")
            # C_i (alpha_fi x r_fi) + (C_i alpha_fi) x (x e1), alpha_fi = e1 Psi_f(x_fi) eta_f
            lever = -(c @ skew(r) @ _E1)[None, :] - sx @ (c @ _E1)  # (k, 3)
            g0[:, 0:3, cols] = np.einsum("ka,l->kal", lever, psif)
            g0[:, 3:6, cols] = np.einsum("a,l->al", c @ _E1, psif)
    r0 = r[None, :] + xe1 @ c  # r_fi + C_i^T x e1
    return PointMaps(g0, g1, r0, c)
