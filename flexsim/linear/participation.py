"""What takes part in a mode: the paper's normalisation (q_f1 = 1 m), its leading coordinates and its symmetry.

Source: Tuzcu & Nguyen (2014), Figs. 11 and 16 and their text: the flutter mode's displacements
(shape / eigenvalue) normalised so that the fuselage's first bending coordinate q_f1 = 1 m, with the
largest linear displacements [m] and the largest angles listed separately, each with its phase relative
to q_f1. Symmetry: :mod:`flexsim.structure.mirror` (mirror of the two halves' coordinates, kinetic-energy
split with M(0), eq. 8).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexsim.structure.mirror import mode_symmetry, ranked

__all__ = ["Participation", "ModeDescription", "describe_mode", "Q_F1_PARTICIPATION", "N_LEADING"]

#: Smallest |q_f1| relative to the largest elastic amplitude for which the mode is normalised by q_f1.
Q_F1_PARTICIPATION = 1e-3
#: Leading linear coordinates and leading angles listed per mode (the paper's figures show about 6 of each).
N_LEADING = 6


@dataclass(frozen=True)
class Participation:
    """One coordinate of a normalised mode.

    Attributes
    ----------
    label : str
        DOF label, e.g. ``"fuselage bending 1"`` (q_f1), ``"w"`` (rigid plunge, body z), ``"q"`` (pitch).
    kind : {"linear", "angle"}
        Rigid translations u, v, w and bending coordinates are linear [m]; rigid rotations p, q, r and
        torsion coordinates are angles [deg].
    magnitude : float
        |amplitude| in ``unit`` per unit of the normalising coordinate.
    unit : {"m", "deg"}
    phase_deg : float
        Phase relative to the normalising coordinate, in (-180, 180] [deg].
    """

    label: str
    kind: str
    magnitude: float
    unit: str
    phase_deg: float

    def as_dict(self) -> dict:
        """Plain dict for JSON rows."""
        return {"label": self.label, "kind": self.kind, "magnitude": self.magnitude, "unit": self.unit, "phase_deg": self.phase_deg}


@dataclass(frozen=True, eq=False)
class ModeDescription:
    """A mode's displacements normalised as in the paper, its symmetry and leading coordinates.

    Attributes
    ----------
    shape : ndarray (complex), shape (n_v,)
        Displacements (eigenvector / eigenvalue) divided by the normalising coordinate's.
    normalised_by : int
        Index in V of the normalising coordinate (q_f1 when it takes part, else the largest elastic one).
    symmetry : {"symmetric", "antisymmetric", "mixed", "n/a"}
        "n/a" for an aircraft that is not left-right symmetric.
    symmetric_fraction : float
        Share of the mode's kinetic energy in its mirror-symmetric part [-] (nan when "n/a").
    leading : tuple of Participation
        Up to :data:`N_LEADING` linear coordinates, then up to :data:`N_LEADING` angles, each by
        decreasing magnitude (mirror ties: right half first).
    """

    shape: np.ndarray
    normalised_by: int
    symmetry: str
    symmetric_fraction: float
    leading: tuple[Participation, ...]


def _phase_deg(z: complex) -> float:
    """Phase in (-180, 180] [deg]; within 1e-6 deg of +-180 it is 180 (no flip between -180 and 180 on round-off)."""
    ph = math.degrees(math.atan2(z.imag, z.real))
    return 180.0 if abs(abs(ph) - 180.0) < 1e-6 else ph


def describe_mode(structure, velocity_shape: np.ndarray, eigenvalue: complex) -> ModeDescription:
    """Normalise a mode as in the paper's Figs. 11/16 and describe it.

    Parameters
    ----------
    structure : StructuralModel
        Supplies the DOF index, M(0) and the mirror operator.
    velocity_shape : ndarray (complex), shape (n_v,)
        Velocity part of the eigenvector over V = [v, omega, s, eta] (eq. 9).
    eigenvalue : complex
        [1/s].
    """
    dofs = structure.dofs
    mirror = structure.mirror
    disp = np.asarray(velocity_shape, dtype=complex) / eigenvalue
    mag = np.abs(disp)
    elastic = list(range(6, dofs.n_v))
    largest = ranked(mag, mirror, candidates=elastic)[0] if elastic else 0
    ref = largest
    if "fuselage" in dofs.component_names:
        fus = dofs.v_bending("fuselage")
        if fus.stop > fus.start and mag[fus.start] >= Q_F1_PARTICIPATION * mag[largest]:
            ref = fus.start
    shape = disp / disp[ref]
    labels = dofs.labels
    linear = [0, 1, 2] + list(range(6, 6 + dofs.nq))
    angles = [3, 4, 5] + list(range(6 + dofs.nq, dofs.n_v))
    nmag = np.abs(shape)
    leading = []
    for kind, cands, unit, scale in (("linear", linear, "m", 1.0), ("angle", angles, "deg", math.degrees(1.0))):
        for k in ranked(nmag, mirror, candidates=cands)[:N_LEADING]:
            leading.append(Participation(labels[k], kind, float(nmag[k] * scale), unit, _phase_deg(complex(shape[k]))))
    if mirror is None:
        return ModeDescription(shape, ref, "n/a", math.nan, tuple(leading))
    frac = mirror.symmetric_fraction(np.asarray(velocity_shape, dtype=complex), structure.inertia.mass_matrix(np.zeros(dofs.nq)))
    return ModeDescription(shape, ref, mode_symmetry(frac), frac, tuple(leading))
