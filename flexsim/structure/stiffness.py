"""Bending and torsional stiffness matrices of each beam (Tuzcu & Nguyen 2014, eqs. 14-16).

    K_i = int_0^L EI_i U_i''^T U_i'' dx,    K~_i = int_0^L GJ_i Psi_i'^T Psi_i' dx

evaluated with the beam quadrature of :mod:`flexsim.structure.sections` and the analytic derivatives of
the shape functions of eq. (1).
"""

from __future__ import annotations

import numpy as np

from flexsim.aircraft.definition import Aircraft
from flexsim.structure.kinematic_map import DofIndex
from flexsim.structure.sections import beam_quadrature
from flexsim.structure.shapes import bending_shapes, torsion_shapes

__all__ = ["stiffness_matrices"]


def stiffness_matrices(aircraft: Aircraft, dofs: DofIndex) -> tuple[np.ndarray, np.ndarray]:
    """Block-diagonal stiffness matrices of the whole aircraft (eq. 16).

    Returns
    -------
    k_bending : ndarray, shape (nq, nq)
        Acting on the bending coordinates q [N/m].
    k_torsion : ndarray, shape (nxi, nxi)
        Acting on the torsion coordinates xi [N m/rad].
    """
    kb = np.zeros((dofs.nq, dofs.nq))
    kt = np.zeros((dofs.nxi, dofs.nxi))
    for comp in aircraft.components:
        quad = beam_quadrature(comp)
        sb, st = dofs.bending[comp.name], dofs.torsion[comp.name]
        if comp.bending_modes:
            u2 = bending_shapes(quad.x, comp.length_m, comp.bending_modes, derivative=2)
            ei = comp.sections.at("ei_nm2", quad.x) * quad.w
            kb[sb, sb] = u2.T @ (ei[:, None] * u2)
        if comp.torsion_modes:
            p1 = torsion_shapes(quad.x, comp.length_m, comp.torsion_modes, derivative=1)
            gj = comp.sections.at("gj_nm2", quad.x) * quad.w
            kt[st, st] = p1.T @ (gj[:, None] * p1)
    kb = 0.5 * (kb + kb.T)
    kt = 0.5 * (kt + kt.T)
    return kb, kt
