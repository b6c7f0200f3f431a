"""The left-right mirror of the aircraft's coordinates, built from its geometry, and mode symmetry.

A mode of a left-right symmetric aircraft is *symmetric* when the motion of every point equals the
mirror image (y -> -y) of the motion of its mirror point, *antisymmetric* when it equals minus that image.
The mirror acts on the global velocity vector V = [v, omega, s, eta] (paper eq. 9) as a matrix P with
P^2 = I; symmetric modes satisfy P V = V, antisymmetric ones P V = -V.

P is not written by hand: for every coordinate k of V the velocity field it produces (points on every
component's elastic axis, translation and section rotation, body axes, from the kinematic map G(0) of
eqs. 5-6 and 18) is reflected, S = diag(1, -1, 1) for translations (a polar vector) and -S for rotations
(an axial vector), and read at the mirror point on the mirror component; P's column k is the
combination of coordinates producing that reflected field (least squares; exact for a symmetric aircraft).
For the paper's GTM this gives u, w, q and the fuselage's vertical bending even; v, p, r, the fuselage
torsion and the fin (vertical tail) bending and torsion odd; q_R <-> q_L and xi_R <-> -xi_L (the left
half's axes are the mirror of the right half's rotated by 180 deg about its span, paper Table 1
psi = -110.55 deg, so equal and opposite torsion coordinates are a symmetric nose-up twist).

The split of a mode's kinetic energy into symmetric and antisymmetric parts uses the mass matrix of the
undeformed aircraft M(0) (eq. 8), for which P^T M P = M holds exactly, so that the two parts add up to
the total.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.aircraft.definition import Aircraft
from flexsim.structure.kinematic_map import DofIndex, point_maps

__all__ = ["MirrorOperator", "mirror_operator", "SYMMETRY_THRESHOLD", "TIE_RTOL", "mode_symmetry", "ranked"]

#: A mode is "symmetric" ("antisymmetric") when at least this share of its kinetic energy is in the
#: symmetric (antisymmetric) part; otherwise "mixed". In symmetric flight the two classes separate
#: exactly (shares 1 and 0 to round-off); the turns of the paper mix them by a few per cent at most.
SYMMETRY_THRESHOLD = 0.9

#: Two mirror coordinates (e.g. right and left wing torsion 1) whose magnitudes differ by less than this
#: relative amount are a tie, broken by coordinate order (the right half, listed first in V, wins), so that
#: labels do not flip between halves on round-off. Measured round-off asymmetry of the GTM's modes in
#: level flight: <= 1e-6 for the wing pairs, <= 1e-5 for the fin, QS and p-k (2026-12-01).
TIE_RTOL = 1e-4

_S = np.diag([1.0, -1.0, 1.0])
#: Stations sampled per component, as fractions of its length (more than the bending/torsion modes).
_FRACTIONS = np.linspace(0.0, 1.0, 9)
_GEOMETRY_TOL_M = 1e-6


@dataclass(frozen=True, eq=False)
class MirrorOperator:
    """The mirror y -> -y acting on the global velocity vector V (module docstring).

    Attributes
    ----------
    matrix : ndarray, shape (n_v, n_v)
        P, with P^2 = I; entries 0 and +-1 for an aircraft whose mirror components share mode shapes.
    partner : tuple of int
        For every coordinate k, the coordinate j with |P[j, k]| = 1 (k itself for a coordinate that maps
        onto itself, e.g. u or the fin bending); -1 when column k is not a single coordinate.
    sign : tuple of float
        P[partner[k], k] (0 where partner is -1).
    """

    matrix: np.ndarray
    partner: tuple[int, ...]
    sign: tuple[float, ...]

    def symmetric_fraction(self, shape: np.ndarray, mass: np.ndarray) -> float:
        """Share of the kinetic energy of ``shape`` (over V, complex) in its symmetric part [-].

        ``mass`` is M(0) (n_v, n_v); the symmetric part is (shape + P shape) / 2.
        """
        sym = 0.5 * (shape + self.matrix @ shape)
        anti = shape - sym
        e_s = float(np.real(np.vdot(sym, mass @ sym)))
        e_a = float(np.real(np.vdot(anti, mass @ anti)))
        total = e_s + e_a
        return e_s / total if total > 0 else 1.0


def _fields(aircraft: Aircraft, dofs: DofIndex) -> tuple[np.ndarray, list[tuple[int, int]]]:
    """Velocity fields of every coordinate of V at sampled points, body axes.

    Returns F with shape (n_points * 6, n_v) (translation then rotation per point) and, per point, the
    (component index, station index) it came from.
    """
    rows, where = [], []
    for ci, comp in enumerate(aircraft.components):
        maps = point_maps(aircraft, dofs, comp, _FRACTIONS * comp.length_m)
        ct = maps.dcm.T  # component -> body
        for k in range(_FRACTIONS.size):
            rows.append(np.vstack([ct @ maps.g0[k, 0:3], ct @ maps.g0[k, 3:6]]))
            where.append((ci, k))
    return np.vstack(rows), where


def _mirror_points(aircraft: Aircraft) -> dict[tuple[int, int], tuple[int, int]] | None:
    """(component, station) -> its mirror point's (component, station); None if the geometry is not symmetric."""
    pts = {}
    for ci, comp in enumerate(aircraft.components):
        for k, f in enumerate(_FRACTIONS):
            pts[(ci, k)] = comp.root_m + f * comp.length_m * comp.dcm[0, :]
    out = {}
    for key, r in pts.items():
        image = _S @ r
        match = [k2 for k2, r2 in pts.items() if np.linalg.norm(r2 - image) <= _GEOMETRY_TOL_M * max(1.0, np.linalg.norm(r))
                 and k2[1] == key[1]]
        if not match:
            return None
        out[key] = match[0]
    return out


def mirror_operator(aircraft: Aircraft, dofs: DofIndex | None = None) -> MirrorOperator | None:
    """The mirror operator of ``aircraft`` built from its geometry, or None if it is not left-right symmetric.

    The aircraft is symmetric when every sampled elastic-axis point has a mirror point at the same station
    of some component and the reflected velocity field of every coordinate is reproduced exactly (to
    1e-8 of its size) by a combination of coordinates.
    """
    dofs = dofs or DofIndex.from_aircraft(aircraft)
    images = _mirror_points(aircraft)
    if images is None:
        return None
    f, where = _fields(aircraft, dofs)
    index = {w: i for i, w in enumerate(where)}
    g = np.empty_like(f)
    for i, w in enumerate(where):
        j = index[images[w]]
        g[6 * i : 6 * i + 3] = _S @ f[6 * j : 6 * j + 3]
        g[6 * i + 3 : 6 * i + 6] = -_S @ f[6 * j + 3 : 6 * j + 6]
    p, *_ = np.linalg.lstsq(f, g, rcond=None)
    if np.linalg.norm(f @ p - g) > 1e-8 * max(1.0, np.linalg.norm(g)):
        return None
    p[np.abs(p) < 1e-9] = 0.0
    n = p.shape[0]
    partner, sign = [], []
    for k in range(n):
        col = p[:, k]
        nz = np.flatnonzero(col)
        if nz.size == 1 and abs(abs(col[nz[0]]) - 1.0) < 1e-9:
            col[nz[0]] = np.sign(col[nz[0]])
            partner.append(int(nz[0]))
            sign.append(float(col[nz[0]]))
        else:
            partner.append(-1)
            sign.append(0.0)
    return MirrorOperator(p, tuple(partner), tuple(sign))


def mode_symmetry(fraction: float) -> str:
    """"symmetric", "antisymmetric" or "mixed" from the symmetric energy share (:data:`SYMMETRY_THRESHOLD`)."""
    if fraction >= SYMMETRY_THRESHOLD:
        return "symmetric"
    if 1.0 - fraction >= SYMMETRY_THRESHOLD:
        return "antisymmetric"
    return "mixed"


def ranked(values: np.ndarray, mirror: MirrorOperator | None, candidates=None, rtol: float = TIE_RTOL) -> list[int]:
    """Indices of ``values`` (>= 0, over V) in decreasing order, mirror ties broken deterministically.

    A coordinate whose mirror partner has a value within ``rtol`` (relative) takes the larger of the two
    as its sort key, so the pair sorts together, lower index first. ``candidates`` restricts the indices.
    """
    values = np.asarray(values, dtype=float)
    idx = range(values.size) if candidates is None else candidates
    key = {}
    for k in idx:
        v = values[k]
        j = mirror.partner[k] if mirror is not None else -1
        if j >= 0 and j != k and abs(values[j] - v) <= rtol * max(abs(values[j]), abs(v)):
            v = max(v, values[j])
        key[k] = v
    return sorted(key, key=lambda k: (-key[k], k))
