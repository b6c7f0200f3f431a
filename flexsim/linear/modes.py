"""In-vacuo natural modes of the aircraft about its undeformed, motionless configuration.

Linearising eq. (33) about q = xi = 0, V = 0 without aerodynamics and gravity leaves
M(0) V_dot = -K [q; xi] with V = d/dt [R, Theta, q, xi] at zero attitude, so the modes solve the
symmetric-definite problem K phi = omega^2 M(0) phi (eqs. 8, 15). A free aircraft has six zero
frequencies (rigid-body modes); a restrained one has none. Each mode is labelled with the degree of
freedom carrying the largest share of its kinetic energy, phi_i (M phi)_i (rigid-body coordinates of an
elastic mode carry none, since M phi has no momentum), as a fraction of the sum of the positive shares.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from flexsim.model.aircraft_model import AircraftModel, check_model
from flexsim.structure.mode_names import mode_name

__all__ = ["Mode", "ModalAnalysis", "in_vacuo_modes"]


@dataclass(frozen=True)
class Mode:
    """One in-vacuo mode.

    Attributes
    ----------
    frequency_rad_s : float
        Natural frequency omega [rad/s] (0 for a rigid-body mode).
    shape : ndarray, shape (n_v,)
        Mass-normalised mode shape over V = [v, omega, s, eta] (zeros on fixed DOFs).
    dominant_dof : str
        The mode's name (:func:`flexsim.structure.mode_names.mode_name`, e.g. "wings torsion 1 (symmetric)"), the
        name every output gives it; a rigid-body mode's DOF with the largest kinetic-energy fraction.
    dominant_fraction : float
        That fraction [-].
    """

    frequency_rad_s: float
    shape: np.ndarray
    dominant_dof: str
    dominant_fraction: float

    @property
    def frequency_hz(self) -> float:
        """Natural frequency [Hz]."""
        return self.frequency_rad_s / (2 * np.pi)

    @property
    def component(self) -> str:
        """Dominant component ("rigid body" for u, v, w, p, q, r)."""
        parts = self.dominant_dof.split(" ")
        return parts[0] if len(parts) > 1 else "rigid body"


@dataclass(frozen=True)
class ModalAnalysis:
    """All modes of a model, sorted by frequency.

    Attributes
    ----------
    modes : tuple of Mode
    n_rigid : int
        Number of rigid-body (zero-frequency) modes: 6 for a free aircraft, 0 restrained.
    """

    modes: tuple[Mode, ...]
    n_rigid: int

    @property
    def frequencies_rad_s(self) -> np.ndarray:
        """Natural frequencies [rad/s], shape (n_modes,)."""
        return np.array([m.frequency_rad_s for m in self.modes])


def in_vacuo_modes(model: AircraftModel) -> ModalAnalysis:
    """Natural modes of ``model`` in vacuum without gravity (eqs. 8, 15 at q = 0).

    Parameters
    ----------
    model : AircraftModel
        Any variant; quasi-rigid models have only rigid-body modes.

    Returns
    -------
    ModalAnalysis
    """
    check_model(model)
    st = model.structure
    active = model.active_dofs
    if active.size == 0:
        from flexsim.errors import FlexsimError

        raise FlexsimError(f"aircraft {model.aircraft.name!r}, variant {model.variant.kind.value!r}: no degree of freedom to "
                           f"analyse (the body is restrained and every component has bending_modes = torsion_modes = 0)")
    m = st.inertia.m0[np.ix_(active, active)]
    k = st.stiffness[np.ix_(active, active)]
    lam, vec = eigh(k, m)
    # Rigid-body modes: eigenvalues at round-off level relative to the stiffest mode.
    n_rigid = int(np.sum(np.abs(lam) <= 1e-10 * max(np.abs(lam).max(), 1e-300)))
    labels = [st.dofs.labels[i] for i in active]
    mirror = st.mirror  # mirror pairs and their signs from the geometry (flexsim.structure.mirror)
    twins = {} if mirror is None else {st.dofs.labels[i]: (st.dofs.labels[mirror.partner[i]], mirror.sign[i])
                                       for i in active if mirror.partner[i] not in (-1, int(i))}
    m0 = st.inertia.mass_matrix(np.zeros(st.dofs.nq))
    modes = []
    for i in range(lam.size):
        phi = vec[:, i]
        full = np.zeros(st.dofs.n_v)
        full[active] = phi
        label, share = _dominant(labels, phi, phi * (m @ phi), twins)
        name = mode_name(st, full, m0, m0) if i >= n_rigid else None  # the name every output gives the mode
        modes.append(Mode(float(np.sqrt(max(lam[i], 0.0))), full, name or label, share))
    return ModalAnalysis(tuple(modes), n_rigid)


def _dominant(labels: list[str], phi: np.ndarray, energy: np.ndarray, twins: dict) -> tuple[str, float]:
    """Label of the DOF with the largest kinetic-energy share, merging mirror-image pairs.

    When the two coordinates of a mirror pair (``twins``: label -> (mirror label, sign of the mirror map),
    :mod:`flexsim.structure.mirror`; wings, horizontal stabilizers) carry comparable energy, the mode is
    labelled "wings bending 1 (symmetric)" or "(antisymmetric)": symmetric when the twin's coordinate is
    the mirror sign times the dominant one (equal signs of q_R, q_L; opposite signs of xi_R, xi_L, both
    noses up, as the left half's axes are the right's mirrored and turned about the span).
    """
    total = energy[energy > 0].sum()
    shares = dict(zip(labels, energy / total))
    coords = dict(zip(labels, phi))
    best = max(shares, key=shares.get)
    name = best
    share = shares[best]
    if best in twins:
        twin, sign = twins[best]
        if twin in shares and shares[twin] > 0.5 * share:
            symmetric = coords[best] * sign * coords[twin] > 0
            side, rest = best.split("_", 1)
            part = rest.split(" ", 1)
            plural = {"wing": "wings", "htail": "htails"}.get(part[0], part[0] + "s")
            name = f"{plural} {part[1]} ({'symmetric' if symmetric else 'antisymmetric'})"
            share += shares[twin]
    return name, float(share)
