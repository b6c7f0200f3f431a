"""One name per mode: the name every output gives a mode (modes, trim roots and verdicts, flutter tables, V-g
legends, mode recordings).

A mode (a velocity shape phi over V = [v, omega, s, eta], paper eq. 9) is named by its elastic coordinate with the
largest kinetic-energy share Re(conj(phi_i) (M phi)_i) (M the mass matrix, eq. 8; rigid-body coordinates are not
candidates: an elastic mode is named by what bends or twists, never by the body rate it drags along), and, for a
left-right symmetric aircraft, by its symmetry (:mod:`flexsim.structure.mirror`: at least
:data:`~flexsim.structure.mirror.SYMMETRY_THRESHOLD` of the kinetic energy in the mirror-symmetric or -antisymmetric
part). A coordinate of a mirror pair (right and left wing, right and left horizontal tail) names the pair, so that
the two halves of a symmetric mode are never called by one side:

* ``"wings torsion 1 (antisymmetric)"``: the pair ``right_wing`` / ``left_wing``, an antisymmetric mode;
* ``"fuselage bending 1 (symmetric)"``: a coordinate that is its own mirror image;
* ``"right_wing torsion 1 (mixed)"``: neither class (a turn's strong coupling, or equal modes of two
  uncoupled halves), the side with the larger share (mirror ties to the right, :func:`~flexsim.structure.mirror.ranked`);
* ``"right_wing bending 1"``: an aircraft that is not left-right symmetric (no symmetry to name).
"""

from __future__ import annotations

import numpy as np

from flexsim.structure.mirror import mode_symmetry, ranked

__all__ = ["pair_name", "mode_name", "elastic_coordinate"]

_SIDES = ("right_", "left_")


def pair_name(label: str, partner: str) -> str:
    """The name of a mirror pair of coordinates, e.g. ("right_wing torsion 1", "left_wing torsion 1") -> "wings torsion 1".

    Components named ``right_X`` / ``left_X`` give ``Xs``; other pairs are joined, ``"a/b torsion 1"``.
    """
    comp, rest = label.split(" ", 1)
    other = partner.split(" ", 1)[0]
    stems = {c[len(s):] for c in (comp, other) for s in _SIDES if c.startswith(s)}
    if len(stems) == 1 and all(any(c.startswith(s) for s in _SIDES) for c in (comp, other)):
        return f"{stems.pop()}s {rest}"
    first, second = sorted((comp, other))
    return f"{first}/{second} {rest}"


def elastic_coordinate(structure, shape: np.ndarray, mass: np.ndarray | None = None) -> int | None:
    """Index in V of the elastic coordinate with the largest kinetic-energy share of ``shape`` (mirror ties to the right
    half), or None when no elastic coordinate takes part.

    Parameters
    ----------
    structure : StructuralModel
        Supplies the DOF index, M(0) and the mirror.
    shape : ndarray (complex), shape (n_v,)
        Velocity shape over V [m/s, rad/s per unit].
    mass : ndarray, shape (n_v, n_v), optional
        The mass matrix to weigh with [kg, kg m, kg m^2]; default M(0).
    """
    mass = structure.inertia.mass_matrix(np.zeros(structure.dofs.nq)) if mass is None else mass
    shape = np.asarray(shape, dtype=complex)
    share = np.real(np.conj(shape) * (mass @ shape))
    elastic = [k for k in range(6, share.size) if share[k] > 0.0]
    if not elastic:
        return None
    return ranked(share, structure.mirror, candidates=elastic)[0]


def mode_name(structure, shape: np.ndarray, mass: np.ndarray | None = None, m0: np.ndarray | None = None) -> str | None:
    """The name of a mode (module docstring), or None when no elastic coordinate takes part (a rigid-body mode).

    Parameters
    ----------
    structure : StructuralModel
    shape : ndarray (complex), shape (n_v,)
        Velocity shape over V.
    mass : ndarray, shape (n_v, n_v), optional
        Mass matrix that weighs the coordinates' shares [kg, kg m, kg m^2]; default M(0). The symmetry is always
        measured with M(0), for which the mirror conserves kinetic energy exactly.
    m0 : ndarray, shape (n_v, n_v), optional
        M(0), when the caller has it (naming many modes).
    """
    m0 = structure.inertia.mass_matrix(np.zeros(structure.dofs.nq)) if m0 is None else m0
    k = elastic_coordinate(structure, shape, m0 if mass is None else mass)  # M(0) unless the caller weighs otherwise
    if k is None:
        return None
    labels = structure.dofs.labels
    mirror = structure.mirror
    if mirror is None:
        return labels[k]
    symmetry = mode_symmetry(mirror.symmetric_fraction(np.asarray(shape, dtype=complex), m0))
    partner = mirror.partner[k]
    base = pair_name(labels[k], labels[partner]) if symmetry != "mixed" and partner not in (-1, k) else labels[k]
    return f"{base} ({symmetry})"
