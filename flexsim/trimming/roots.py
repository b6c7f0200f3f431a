"""Roots of a linearised steady manoeuvre told apart as rigid-body, elastic and aerodynamic-lag.

Source: Tuzcu & Nguyen (2014), "Numerical Model": linearise eq. (33) about the steady manoeuvre and solve the
eigenvalue problem; the first 12 eigenvalues are rigid-body dominated, the others elastic. This module holds the
classification of the roots (used by :mod:`flexsim.linear.stability` for every eigen-analysis and by the trim to
classify its own equilibrium, :mod:`flexsim.trimming.equilibrium`).

Each mode is classified by the split of its kinetic energy (velocity part phi of the eigenvector, M the
structural mass matrix at the trim) into the energy of the rigid-body motion of the whole aircraft and
the rest (Koenig's theorem): with the linear momentum P = (M phi)_v and the angular momentum about the
centre of mass H = (M phi)_omega - r_cg x P, the rigid-body part is |P|^2/m + H^H J_cg^-1 H and the
elastic fraction is 1 - rigid / (phi^H M phi). This does not depend on where the body origin o is (for the
GTM, the fuselage tail, so that cantilever fuselage modes carry large rigid-body coordinates). A mode is
rigid-body dominated when more than half of its energy is rigid-body motion AND its frequency |eigenvalue|
is below half the first in-vacuo elastic frequency: the paper's "first 12 eigenvalues" are the
flight-dynamics modes, while a fuselage-bending mode strongly coupled to pitch and heave through the tail's
aerodynamics (the paper's flutter mode, q_f1 dominant) stays an elastic mode. Restrained models have only
elastic modes. Aerodynamic-lag roots (the finite-state wake) are labelled "aerodynamic": a model with n_struct
structural states has n_struct structural roots, those least tied to the inflow states by their participation
factors (Perez-Arriaga, Verghese & Schweppe 1982: p_ik = |w_ki v_ik| normalised, left and right
eigenvectors; independent of the states' units; conjugate pairs kept together); the others, and roots with
no structural energy at all, are aerodynamic. The dominant DOF is the one with the largest share
Re(conj(phi_i) (M phi)_i); a tie between mirror coordinates (right and left halves within 1e-4,
:data:`flexsim.structure.mirror.TIE_RTOL`) names the right half, so labels do not flip between halves on round-off.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property, partial

import numpy as np
from scipy.linalg import eigh

from flexsim.aircraft.definition import ContentKey
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.jacobian import jacobian
from flexsim.structure.mirror import TIE_RTOL
from flexsim.structure.mode_names import mode_name

__all__ = ["Mode", "Spectrum", "ReducedJacobian", "reduced_jacobian", "rigid_mode_name"]


@dataclass(frozen=True, eq=False)
class ReducedJacobian:
    """A = d rhs / dx over the kept states of a steady manoeuvre (all but X, Y, Z and psi for a free aircraft,
    the rule of :func:`flexsim.linear.linearize.linearize`, which returns the same A with B and the names).

    Attributes
    ----------
    a : ndarray, shape (m, m)
    keep : ndarray of int, shape (m,)
        Indices of the kept states in the model's state vector.
    x0 : ndarray, shape (n_states,)
    """

    a: np.ndarray
    keep: np.ndarray
    x0: np.ndarray


def reduced_jacobian(model: AircraftModel, x0: np.ndarray, u0: np.ndarray) -> ReducedJacobian:
    """The state matrix of ``model`` about (x0, u0) without the ignorable states, by the central differences of
    :func:`flexsim.model.jacobian.jacobian` (the one used by :func:`flexsim.linear.linearize.linearize`)."""
    a, _ = jacobian(model, np.asarray(x0, float), np.asarray(u0, float))
    lay = model.layout
    drop = set(range(lay.position.start, lay.position.stop)) | {lay.euler.start + 2} if lay.rigid else set()
    keep = np.array([i for i in range(lay.n_states) if i not in drop], dtype=int)
    return ReducedJacobian(a[np.ix_(keep, keep)], keep, np.asarray(x0, float).copy())


@dataclass(frozen=True, eq=False)
class Mode:
    """One eigenvalue of the linearised manoeuvre.

    Attributes
    ----------
    eigenvalue : complex
        [1/s]; frequency = |Im|, damping ratio = -Re/|eigenvalue|.
    kind : {"rigid", "elastic", "aerodynamic"}
        ``aerodynamic``: an aerodynamic-lag root, more than half of its participation in the inflow states
        (module docstring); otherwise rigid-body or elastic by its kinetic energy.
    elastic_fraction : float
        Share of the kinetic energy in elastic DOFs [-].
    dominant_dof : str
        DOF label with the largest kinetic-energy share (e.g. "right_wing torsion 1").
    shape : ndarray (complex), shape (n_v,)
        Velocity part of the eigenvector over V = [v, omega, s, eta] (eq. 9); the configuration part is
        shape / eigenvalue.
    inflow_participation : float
        Sum of the participation factors of the inflow states in this mode, in [0, 1] [-].
    name : str
        The mode's name in every output: for an elastic mode :func:`flexsim.structure.mode_names.mode_name` (e.g.
        "wings torsion 1 (antisymmetric)"); for a rigid-body one its flight-dynamics name and dominant DOF
        (:func:`rigid_mode_name`, e.g. "spiral [v]"); "inflow" for an aerodynamic-lag root. Computed from ``namer``
        when first read (a flutter scan classifies every root of every speed and reads the names of a few).
    namer : str or callable () -> str
        The name, or how to compute it.
    """

    eigenvalue: complex
    kind: str
    elastic_fraction: float
    dominant_dof: str
    shape: np.ndarray
    inflow_participation: float = 0.0
    namer: str | Callable[[], str] = field(default="", repr=False)

    @cached_property
    def name(self) -> str:
        """The mode's name (``namer``'s value; see the class docstring)."""
        return self.namer() if callable(self.namer) else self.namer

    @property
    def frequency_rad_s(self) -> float:
        """Damped natural frequency |Im(eigenvalue)| [rad/s]."""
        return abs(self.eigenvalue.imag)

    @property
    def damping_ratio(self) -> float:
        """-Re / |eigenvalue| [-]."""
        return -self.eigenvalue.real / max(abs(self.eigenvalue), 1e-300)


@dataclass(frozen=True, eq=False)
class Spectrum:
    """All modes of a linearised manoeuvre, sorted by decreasing real part."""

    modes: tuple[Mode, ...]
    aero_model: str

    def of_kind(self, kind: str) -> tuple[Mode, ...]:
        """The modes of one kind ("rigid", "elastic", "aerodynamic")."""
        return tuple(m for m in self.modes if m.kind == kind)

    def max_real(self, kind: str = "elastic", min_frequency_rad_s: float = 0.5) -> float:
        """Largest real part among oscillatory modes of ``kind`` (the flutter function) [1/s]."""
        vals = [m.eigenvalue.real for m in self.modes if m.kind == kind and m.frequency_rad_s >= min_frequency_rad_s]
        return max(vals) if vals else -np.inf

    def critical(self, kind: str = "elastic", min_frequency_rad_s: float = 0.5) -> Mode:
        """The oscillatory mode of ``kind`` with the largest real part."""
        cands = [m for m in self.modes if m.kind == kind and m.frequency_rad_s >= min_frequency_rad_s]
        return max(cands, key=lambda m: m.eigenvalue.real)


def _classify(model: AircraftModel, lin, vals: np.ndarray, vecs: np.ndarray, aero_model: str) -> Spectrum:
    """Classify the roots ``vals`` (eigenvectors ``vecs`` over the kept states ``lin.keep``, linearised about
    ``lin.x0``: a :class:`~flexsim.linear.linearize.LinearModel` or :class:`ReducedJacobian`) as the module docstring says."""
    lay = model.layout
    pos = {int(k): i for i, k in enumerate(lin.keep)}
    vel_rows = np.array([pos[i] for i in range(lay.velocity.start, lay.velocity.stop)])
    _, _, q, _, _ = model.unpack(lin.x0)
    mass = model.structure.inertia.mass_matrix(q)
    active = model.active_dofs
    m_act = mass[np.ix_(active, active)]
    labels_full = model.structure.dofs.labels
    mirror = model.structure.mirror
    free = lay.rigid
    cut = 0.5 * _first_elastic_frequency(model) if free else 0.0
    mp = model.structure.mass_properties
    j_inv = np.linalg.inv(mp.inertia_cg_kg_m2)
    inflow_rows = np.array([pos[i] for i in range(lay.inflow.start, lay.inflow.stop)], dtype=int)
    inflow_share = _inflow_participation(vecs, inflow_rows)
    # as many structural roots as structural states: those least tied to the inflow states
    n_struct = vals.size - inflow_rows.size
    lag = np.zeros(vals.size, bool)
    lag[np.argsort(inflow_share, kind="stable")[n_struct:]] = True
    for k in np.flatnonzero(~lag):  # a conjugate pair is one root pair: never split it at the cut
        if vals[k].imag != 0.0:
            lag[int(np.argmin(np.abs(vals - np.conj(vals[k]))))] = False
    # every mode at once: kinetic-energy shares, elastic fraction (Koenig) and dominant DOF
    n_v = model.structure.dofs.n_v
    phi = vecs[vel_rows]  # (n_act, K)
    m_phi = m_act @ phi
    share = np.real(np.conj(phi) * m_phi)
    total = share.sum(axis=0)
    scale = np.real(np.sum(np.conj(vecs) * vecs, axis=0))
    no_energy = (total <= 1e-9 * scale * np.abs(m_act).max()) | (total <= 0)
    if free:
        p_lin = m_phi[0:3]
        h_cg = m_phi[3:6] - np.cross(mp.cg_m, p_lin, axis=0)
        rigid_energy = (np.real(np.sum(np.conj(p_lin) * p_lin, axis=0)) / mp.mass_kg
                        + np.real(np.sum(np.conj(h_cg) * (j_inv @ h_cg), axis=0)))
        with np.errstate(divide="ignore", invalid="ignore"):
            frac = np.clip(1.0 - rigid_energy / total, 0.0, 1.0)
    else:
        frac = np.ones(vals.size)
    shapes = np.zeros((n_v, vals.size), dtype=complex)
    shapes[active] = phi
    dominant = _dominant_dofs(share, active, n_v, mirror)
    m0 = model.structure.inertia.mass_matrix(np.zeros(model.structure.dofs.nq))
    modes = []
    for k in range(vals.size):
        if lag[k] or no_energy[k]:
            modes.append(Mode(complex(vals[k]), "aerodynamic", 0.0, "inflow", shapes[:, k].copy(), float(inflow_share[k]), "inflow"))
            continue
        frac_el = float(frac[k])
        rigid = frac_el < 0.5 and abs(vals[k]) < cut
        dof = labels_full[dominant[k]]
        shape = shapes[:, k].copy()
        if rigid:
            name = f"{rigid_mode_name(vals[k], dof)} [{dof}]"
        else:  # M(0): the name every output gives; computed when first read
            name = partial(_elastic_name, model.structure, shape, m0, dof)
        modes.append(Mode(complex(vals[k]), "rigid" if rigid else "elastic", frac_el, dof, shape,
                          float(inflow_share[k]), name))
    modes.sort(key=lambda m: -m.eigenvalue.real)
    return Spectrum(tuple(modes), aero_model)


def _elastic_name(structure, shape: np.ndarray, m0: np.ndarray, dominant_dof: str) -> str:
    """The name of an elastic mode (:func:`flexsim.structure.mode_names.mode_name` with M(0)), else its dominant DOF."""
    return mode_name(structure, shape, m0, m0) or dominant_dof


def rigid_mode_name(eigenvalue: complex, coordinate: str) -> str:
    """The flight-dynamics name of a rigid-body root from its dominant DOF (Etkin & Reid, *Dynamics of Flight*, 3rd
    ed., 1996, ch. 6-7): u the phugoid; w or q the short period (complex) or a pitch divergence / subsidence (real);
    v, p or r the Dutch roll (complex), the spiral (real; a stable real root in p is the roll subsidence)."""
    lam = complex(eigenvalue)
    real = lam.imag == 0.0
    if coordinate == "u":
        return "phugoid"
    if coordinate in ("w", "q"):
        return ("pitch divergence" if lam.real > 0.0 else "pitch subsidence") if real else "short period"
    if not real:
        return "Dutch roll"
    return "roll subsidence" if coordinate == "p" and lam.real < 0.0 else "spiral"


def _dominant_dofs(share: np.ndarray, active: np.ndarray, n_v: int, mirror) -> np.ndarray:
    """Index over V of the largest kinetic-energy share of every mode (columns of ``share``, rows ``active``).

    :func:`flexsim.structure.mirror.ranked` for all modes at once: a coordinate whose mirror partner's share is
    within :data:`~flexsim.structure.mirror.TIE_RTOL` takes the larger of the two, and equal keys go to the
    lower index (``argmax`` returns the first maximum).
    """
    full = np.full((n_v, share.shape[1]), -np.inf)
    full[active] = share
    key = full.copy()
    if mirror is not None:
        partner = np.asarray(mirror.partner)
        k = np.flatnonzero((partner >= 0) & (partner != np.arange(n_v)))
        v, w = full[k], full[partner[k]]
        with np.errstate(invalid="ignore"):
            tie = np.abs(w - v) <= TIE_RTOL * np.maximum(np.abs(w), np.abs(v))
        key[k] = np.where(tie, np.maximum(v, w), v)
    inactive = np.ones(n_v, bool)
    inactive[active] = False
    key[inactive] = -np.inf  # only the active coordinates are candidates
    return np.argmax(key, axis=0)


def _inflow_participation(vecs: np.ndarray, inflow_rows: np.ndarray) -> np.ndarray:
    """Share of the inflow states in every mode: sum over them of the participation factors.

    Participation factor of state i in mode k: p_ik = |w_ki v_ik| / sum_j |w_kj v_jk|, with v_k the right and
    w_k the left eigenvector (W = V^-1). It does not depend on the units or scaling of the states
    (Perez-Arriaga, Verghese & Schweppe, IEEE Trans. PAS 101(9), 1982; Kundur, *Power System Stability and
    Control*, 1994, sec. 12.2.3). Zero for every mode when there are no inflow states.
    """
    if inflow_rows.size == 0:
        return np.zeros(vecs.shape[1])
    try:
        left = np.linalg.inv(vecs)
    except np.linalg.LinAlgError:
        left = np.linalg.pinv(vecs)
    part = np.abs(left.T * vecs)  # part[i, k] = |w_ki v_ik|
    total = part.sum(axis=0)
    return part[inflow_rows].sum(axis=0) / np.where(total > 0, total, 1.0)


def _first_elastic_frequency(model: AircraftModel) -> float:
    """Lowest in-vacuo elastic frequency of the model's aircraft [rad/s] (cached by the aircraft's content)."""
    return _first_elastic_of(model.aircraft.content_key())


@functools.lru_cache(maxsize=16)
def _first_elastic_of(key: ContentKey) -> float:
    """The in-vacuo problem K phi = omega^2 M(0) phi of the free aircraft without aerodynamics and gravity (eqs. 8,
    15), solved as :func:`flexsim.linear.modes.in_vacuo_modes` solves it (same matrices, same rigid-body threshold
    1e-10 of the largest eigenvalue), for its lowest elastic frequency only (tests/trimming/test_roots.py compares the
    two)."""
    model = AircraftModel(key.aircraft, aero=None, gravity_m_s2=0.0)
    st, active = model.structure, model.active_dofs
    lam, _ = eigh(st.stiffness[np.ix_(active, active)], st.inertia.m0[np.ix_(active, active)])  # as in_vacuo_modes: bit for bit
    n_rigid = int(np.sum(np.abs(lam) <= 1e-10 * max(np.abs(lam).max(), 1e-300)))
    freqs = np.sqrt(np.maximum(lam[n_rigid:], 0.0))
    return float(freqs[0]) if freqs.size else np.inf
