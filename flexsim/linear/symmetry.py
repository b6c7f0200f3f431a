"""Symmetric and antisymmetric halves of a linearised state matrix, for flight that keeps the mirror symmetry.

Source: the mirror y -> -y of the aircraft's coordinates (:mod:`flexsim.structure.mirror`, a matrix P on
V = [v, omega, s, eta], paper eq. 9, with P^2 = I). The state x = [R, Theta, q, xi, V] (:mod:`flexsim.model.layout`)
mirrors the same way: R = [X, Y, Z] like the polar vector v, Theta = [phi, theta, psi] like the axial vector
omega (roll and yaw change sign, pitch does not), q and xi like their rates s and eta. So the state mirror is
T = diag(P_a, P_a) with P_a the rows and columns of P of the model's active coordinates, and the kept states of
a steady-manoeuvre linearisation (all but X, Y, Z, psi, each its own mirror) are closed under it.

In flight that is its own mirror image (level flight and climbs of a left-right symmetric aircraft, no
sideslip, no bank) the right-hand side commutes with the mirror, f(T x, u_T) = T f(x, u), so the state matrix
does too: T A T = A. With an orthonormal basis Q = [Q_s, Q_a] of the +1 and -1 eigenspaces of T,
Q^T A Q = diag(Q_s^T A Q_s, Q_a^T A Q_a) (Golub & Van Loan, *Matrix Computations*, 4th ed., 2013, §7.1.1:
the eigenvalues of a block-diagonal matrix are those of its blocks). The two halves are the symmetric
(longitudinal + symmetric elastic) and antisymmetric (lateral-directional + antisymmetric elastic) problems;
each eigenvector of a half, Q_s w or Q_a w, is one of A.

Whether the flight keeps the symmetry is not assumed but measured on A itself: the halves are used only when
both coupling blocks Q_s^T A Q_a and Q_a^T A Q_s vanish to the round-off of the central-difference Jacobian
(:data:`COUPLING_RTOL` of the largest entry of A). The turns of the paper bank the aircraft and couple the halves
(their coupling is orders of magnitude above the tolerance): they keep the full matrix. Dropping coupling blocks
of size e changes the eigenvalues only at second order, ~ e^2 / (gap between the halves' eigenvalues), because
an eigenvector of one half has no component in the other (measured on the GTM's level flight and climbs:
eigenvalues of the halves equal to those of the full matrix to 4e-12 relative, the round-off of two different
eig calls).
"""

from __future__ import annotations

import math

import numpy as np

from flexsim.model.aircraft_model import AircraftModel

__all__ = ["COUPLING_RTOL", "mirror_bases", "decoupled"]

#: Largest coupling entry |Q_s^T A Q_a|, |Q_a^T A Q_s| relative to max |A| for which the two halves are
#: solved apart. Measured for the GTM (56 kept states, quasi-steady and Theodorsen A(omega)): 1.3e-10 in
#: level flight and in climbs (central-difference round-off of a right-hand side that is mirror-symmetric
#: up to its summation order); 1e-3 to 5e-3 in the paper's turns (R = 12 to 5 km, gtm and gtm_paper).
COUPLING_RTOL = 1e-8


def mirror_bases(model: AircraftModel, keep: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Orthonormal bases (Q_s, Q_a) of the symmetric and antisymmetric kept states, or None.

    Parameters
    ----------
    model : AircraftModel
        Free-flying model (with rigid-body states).
    keep : ndarray of int, shape (m,)
        Kept states of the linearisation (:attr:`flexsim.linear.linearize.LinearModel.keep`).

    Returns
    -------
    (ndarray (m, m_s), ndarray (m, m_a)) or None
        Columns (e_i + s e_j) / sqrt(2), (e_i - s e_j) / sqrt(2) for a mirror pair i <-> s j and e_i for a state
        that is its own mirror, over the kept states, m_s + m_a = m. None when the aircraft is not left-right
        symmetric, its mirror is not a signed permutation of the active coordinates, the model is restrained,
        or the kept states are not closed under the mirror.
    """
    lay = model.layout
    mirror = model.structure.mirror
    if mirror is None or not lay.rigid:
        return None
    active = np.asarray(model.active_dofs)
    where = {int(k): i for i, k in enumerate(active)}
    n_act = active.size
    # partner and sign of every state (configuration block, then velocity block: the same mirror)
    partner = np.empty(2 * n_act, dtype=int)
    sign = np.empty(2 * n_act)
    for i, k in enumerate(active):
        j = mirror.partner[int(k)]
        if j < 0 or j not in where:
            return None
        for block in (0, n_act):
            partner[block + i] = block + where[j]
            sign[block + i] = mirror.sign[int(k)]
    if lay.n_states != 2 * n_act:  # inflow states: the p-k problem is over the quasi-steady states only
        return None
    pos = {int(k): i for i, k in enumerate(keep)}
    m = len(keep)
    sym, anti = [], []
    for i, k in enumerate(keep):
        j, s = int(partner[k]), float(sign[k])
        if j not in pos:
            return None
        col_s, col_a = np.zeros(m), np.zeros(m)
        if j == k:
            (sym if s > 0 else anti).append(_unit(m, i))
        elif j > k:
            col_s[i] = col_a[i] = 1.0 / math.sqrt(2.0)
            col_s[pos[j]] = s / math.sqrt(2.0)
            col_a[pos[j]] = -s / math.sqrt(2.0)
            sym.append(col_s)
            anti.append(col_a)
    if not sym or not anti or len(sym) + len(anti) != m:
        return None
    return np.stack(sym, axis=1), np.stack(anti, axis=1)


def _unit(m: int, i: int) -> np.ndarray:
    e = np.zeros(m)
    e[i] = 1.0
    return e


def decoupled(a: np.ndarray, bases: tuple[np.ndarray, np.ndarray], rtol: float = COUPLING_RTOL) -> bool:
    """Whether both coupling blocks of ``a`` (real or complex, (m, m)) between the halves vanish to ``rtol`` max |a|."""
    q_s, q_a = bases
    scale = np.abs(a).max()
    return bool(max(np.abs(q_s.T @ a @ q_a).max(), np.abs(q_a.T @ a @ q_s).max()) <= rtol * scale)
