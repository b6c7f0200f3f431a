"""Eigen-analysis of a trimmed steady manoeuvre: modes, their classification, and the p-k method.

Source: Tuzcu & Nguyen (2014), "Numerical Model": linearise eq. (33) about the steady manoeuvre and
solve the eigenvalue problem; the first 12 eigenvalues are rigid-body dominated, the others elastic; the
"US" results use the frequency-domain wake (Theodorsen, eq. 27), valid at flutter.

Three aerodynamic models (docs/design.md, "Aerodynamics on the aircraft"): ``quasi-steady`` (lambda0 = 0), ``unsteady`` (Peters finite-state
inflow in state space), ``theodorsen`` (p-k iteration: lambda0 = (1 - C(k_j)) (w0 + w1/2) at every strip,
k_j = omega b_j / u0_j, iterated on omega for every mode until consistent).

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
from dataclasses import dataclass
from typing import Callable

import numpy as np

from flexsim._threads import single_blas_thread
from flexsim.aero.pk import PkStateMatrix, pk_roots
from flexsim.aircraft.definition import ContentKey
from flexsim.linear._pk_kernels import w34_jacobian
from flexsim.linear.linearize import LinearModel, linearize
from flexsim.linear.symmetry import decoupled, mirror_bases
from flexsim.model.aircraft_model import AircraftModel
from flexsim.structure.mirror import TIE_RTOL

__all__ = ["Mode", "Spectrum", "spectrum", "linear_spectrum", "PkStateMatrix", "pk_state_matrix", "PK_METHODS"]

#: Ways of continuing a p-k root from one iteration to the next (see :mod:`flexsim.aero.pk`).
PK_METHODS = ("inverse-iteration", "eig")



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
    """

    eigenvalue: complex
    kind: str
    elastic_fraction: float
    dominant_dof: str
    shape: np.ndarray
    inflow_participation: float = 0.0

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


def _classify(model: AircraftModel, lin: LinearModel, vals: np.ndarray, vecs: np.ndarray, aero_model: str) -> Spectrum:
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
    modes = []
    for k in range(vals.size):
        if lag[k] or no_energy[k]:
            modes.append(Mode(complex(vals[k]), "aerodynamic", 0.0, "inflow", shapes[:, k].copy(), float(inflow_share[k])))
            continue
        frac_el = float(frac[k])
        rigid = frac_el < 0.5 and abs(vals[k]) < cut
        modes.append(Mode(complex(vals[k]), "rigid" if rigid else "elastic", frac_el, labels_full[dominant[k]],
                          shapes[:, k].copy(), float(inflow_share[k])))
    modes.sort(key=lambda m: -m.eigenvalue.real)
    return Spectrum(tuple(modes), aero_model)


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
    from flexsim.linear.modes import in_vacuo_modes

    analysis = in_vacuo_modes(AircraftModel(key.aircraft, aero=None, gravity_m_s2=0.0))
    freqs = analysis.frequencies_rad_s[analysis.n_rigid :]
    return float(freqs[0]) if freqs.size else np.inf


@single_blas_thread
def spectrum(model: AircraftModel, x0: np.ndarray, u0: np.ndarray, *, aero_model: str = "unsteady",
             pk_model: AircraftModel | None = None, pk_method: str = "inverse-iteration",
             mirror_split: bool = True) -> Spectrum:
    """Eigen-analysis of ``model`` linearised about (x0, u0).

    Parameters
    ----------
    model : AircraftModel
        Its aerodynamic model is used as is for ``quasi-steady`` and ``unsteady``.
    x0, u0 : ndarray
        Trim state and controls.
    aero_model : {"quasi-steady", "unsteady", "theodorsen"}
        Label of the analysis; ``theodorsen`` runs the p-k iteration and needs ``pk_model``.
    pk_model : AircraftModel, optional
        A finite-state (``unsteady``) model of the same aircraft, used to build the lambda0 input and
        w0 + w1/2 output matrices of the p-k method; ``model`` must then be the quasi-steady model.
    pk_method : {"inverse-iteration", "eig"}
        How each p-k step continues a root (:mod:`flexsim.aero.pk`): shifted inverse iteration with a full
        ``eig`` fallback (default), or a full ``eig`` every step (the reference; same roots, slower).
    mirror_split : bool
        p-k only: solve the symmetric and antisymmetric halves apart when the flight keeps the mirror symmetry
        (default; :mod:`flexsim.linear.symmetry`, measured on A); False always uses the full matrix (the
        reference; same roots to round-off, slower).
    """
    if pk_method not in PK_METHODS:
        raise ValueError(f"pk_method = {pk_method!r}: must be one of {', '.join(PK_METHODS)}")
    return linear_spectrum(model, linearize(model, x0, u0), aero_model=aero_model, pk_model=pk_model,
                           pk_method=pk_method, mirror_split=mirror_split)


@single_blas_thread
def linear_spectrum(model: AircraftModel, lin: LinearModel, *, aero_model: str = "unsteady",
                    pk_model: AircraftModel | None = None, pk_method: str = "inverse-iteration",
                    mirror_split: bool = True) -> Spectrum:
    """:func:`spectrum` from a linearisation already made: ``lin = linearize(model, x0, u0)`` (other arguments as
    there), e.g. one linearisation shared by the quasi-steady and p-k analyses of the same trim."""
    if pk_method not in PK_METHODS:
        raise ValueError(f"pk_method = {pk_method!r}: must be one of {', '.join(PK_METHODS)}")
    if aero_model != "theodorsen":
        vals, vecs = np.linalg.eig(lin.a)
        return _classify(model, lin, vals, vecs, aero_model)
    if pk_model is None:
        raise ValueError('aero_model = "theodorsen" needs pk_model: the finite-state model of the same aircraft')
    return _pk(model, pk_model, lin, pk_method, mirror_split)


def pk_state_matrix(qs_model: AircraftModel, fs_model: AircraftModel, lin: LinearModel) -> PkStateMatrix:
    """The p-k state matrix A(omega) of the "US" model (paper eq. 27) over the kept states of ``lin``.

    A(omega) = A_qs + B_lambda diag(1 - C(k_j)) C_w with k_j = omega b_j / u0_j at every unsteady strip:
    B_lambda = d x_dot / d lambda0_j (finite-state model, central differences) and C_w = d (w0 + w1/2)_j / dx.

    Parameters
    ----------
    qs_model, fs_model : AircraftModel
        Quasi-steady and finite-state models of the same aircraft.
    lin : LinearModel
        Linearisation of ``qs_model`` (its A is A_qs; its x0, u0 the trim).

    Returns
    -------
    PkStateMatrix
        Callable: ``a_of(omega [rad/s]) -> ndarray (complex), shape (m, m)``.
    """
    x0, u0 = lin.x0, lin.u0
    coupling = fs_model.aero
    strips = coupling.strips
    idx = np.flatnonzero(strips.unsteady)
    n_in = coupling.options.n_inflow
    lay_fs, lay_qs = fs_model.layout, qs_model.layout
    # finite-state state at the trim: same configuration/velocities, zero inflow
    x_fs = lay_fs.zeros()
    x_fs[: lay_fs.inflow.start] = x0[: lay_qs.n_states]
    # input matrix: d x_dot / d lambda0_j (perturb the strip's inflow states by 2 eps: lambda0 = 1/2 b^T lam)
    eps = 1e-4
    steps = np.zeros((idx.size, lay_fs.n_states))
    for c in range(idx.size):
        steps[c, lay_fs.inflow.start + c * n_in : lay_fs.inflow.start + (c + 1) * n_in] = 2 * eps
    # all 2 n_strips right-hand sides in one compiled call (each row equal to fs_model.rhs bit for bit)
    rhs = fs_model.rhs_batch(0.0, np.concatenate([x_fs + steps, x_fs - steps]), np.tile(u0, (2 * idx.size, 1)))
    b_lam = ((rhs[: idx.size] - rhs[idx.size :])[:, : lay_qs.n_states] / (2 * eps)).T
    # output matrix: w0 + w1/2 at the strips per unit state, central differences over the configuration and velocity
    # states (w0 + w1/2 does not depend on position and attitude), in one compiled call
    c_w = w34_jacobian(*fs_model.kernel_data, *coupling.kernel_data, x_fs, np.asarray(u0, dtype=float),
                       lay_fs.inflow.start, lay_fs.inflow.stop, strips.n_strips, idx.astype(np.int64), lay_fs.q.start,
                       lay_qs.n_states)
    keep = lin.keep
    b_k, c_k = b_lam[keep], c_w[:, keep]
    _, _, q, xi, vel = fs_model.unpack(x_fs)
    kin = coupling.kinematics(q, xi, vel, x_fs[lay_fs.inflow], u0)
    b_over_u = strips.semichord_m[idx] / np.maximum(kin.u0[idx], 1e-6)
    return PkStateMatrix(lin.a, b_k, c_k, b_over_u)


def _pk(qs_model: AircraftModel, fs_model: AircraftModel, lin: LinearModel, method: str, mirror_split: bool = True) -> Spectrum:
    """p-k iteration with Theodorsen's C(k) at every strip (paper eq. 27, the "US" model).

    In flight that keeps the mirror symmetry (:mod:`flexsim.linear.symmetry`: the coupling blocks of A_qs and of
    A(omega) at k = 0.1 and 1 on the mean strip vanish to round-off) the symmetric and antisymmetric halves are
    solved apart, each from the eigenpairs of its own quasi-steady block (same roots as the full matrix to
    round-off, a quarter of the work per LU and an eighth per full eig); otherwise (turns) the full matrix.
    """
    a_of = pk_state_matrix(qs_model, fs_model, lin)
    parts: list[tuple[np.ndarray | None, PkStateMatrix]] = [(None, a_of)]
    bases = mirror_bases(qs_model, lin.keep) if mirror_split else None
    if bases is not None:
        omega_1 = 1.0 / float(np.mean(a_of.semichord_over_speed_s))  # k = 1 on the mean strip
        if all(decoupled(a, bases) for a in (a_of.a_qs, a_of(0.1 * omega_1), a_of(omega_1))):
            parts = [(basis, a_of.projected(basis)) for basis in bases]
    inverse = method == "inverse-iteration"
    all_vals, all_vecs = [], []
    for basis, part in parts:
        vals0, vecs0 = np.linalg.eig(part.a_qs)
        out_vals, out_vecs = vals0.astype(complex).copy(), vecs0.astype(complex).copy()
        track = np.flatnonzero((vals0.imag > 0.5) & (vals0.real >= -20.0))
        roots = pk_roots(part, vals0[track], vecs0[:, track], inverse_iteration=inverse)
        for k, root in zip(track, roots):
            out_vals[k], out_vecs[:, k] = root.eigenvalue, root.vector
            conj = np.argmin(np.abs(vals0 - np.conj(vals0[k])))
            if conj != k:
                out_vals[conj], out_vecs[:, conj] = np.conj(root.eigenvalue), np.conj(root.vector)
        all_vals.append(out_vals)
        all_vecs.append(out_vecs if basis is None else basis @ out_vecs)
    vals = np.concatenate(all_vals)
    vecs = all_vecs[0] if len(all_vecs) == 1 else np.concatenate(all_vecs, axis=1)
    return _classify(qs_model, lin, vals, vecs, "theodorsen")
