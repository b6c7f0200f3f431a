"""Eigen-analysis of a trimmed steady manoeuvre: modes, their classification, and the p-k method.

Source: Tuzcu & Nguyen (2014), "Numerical Model": linearise eq. (33) about the steady manoeuvre and
solve the eigenvalue problem; the first 12 eigenvalues are rigid-body dominated, the others elastic; the
"US" results use the frequency-domain wake (Theodorsen, eq. 27), valid at flutter.

Three aerodynamic models (docs/design.md, "Aerodynamics on the aircraft"): ``quasi-steady`` (lambda0 = 0), ``unsteady`` (Peters finite-state
inflow in state space), ``theodorsen`` (p-k iteration: lambda0 = (1 - C(k_j)) (w0 + w1/2) at every strip,
k_j = omega b_j / u0_j, iterated on omega for every mode until consistent).

Each root is classified (rigid-body, elastic or aerodynamic-lag, by its kinetic energy and its participation
factors, with its dominant DOF) by :mod:`flexsim.trimming.roots`, which the trim also uses to classify its own
equilibrium (:mod:`flexsim.trimming.equilibrium`).
"""

from __future__ import annotations

import numpy as np

from flexsim._threads import single_blas_thread
from flexsim.aero.pk import PkStateMatrix, pk_roots
from flexsim.linear._pk_kernels import w34_jacobian
from flexsim.linear.linearize import LinearModel, linearize
from flexsim.linear.symmetry import decoupled, mirror_bases
from flexsim.model.aircraft_model import AircraftModel, check_model
from flexsim.trimming.roots import Mode, Spectrum, _classify, _dominant_dofs  # noqa: F401 (_dominant_dofs: the name tests and benchmarks use)

__all__ = ["Mode", "Spectrum", "spectrum", "linear_spectrum", "PkStateMatrix", "pk_state_matrix", "PK_METHODS", "conjugate_slots"]

#: Ways of continuing a p-k root from one iteration to the next (see :mod:`flexsim.aero.pk`).
PK_METHODS = ("inverse-iteration", "eig")


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
    check_model(model)
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


def conjugate_slots(vals: np.ndarray, track: np.ndarray) -> np.ndarray:
    """Index of the complex-conjugate partner of every root ``vals[track]`` (Im > 0), each partner used once.

    The eigenvalues of a real matrix come in conjugate pairs; the p-k root followed from ``vals[k]`` replaces both
    ``vals[k]`` and its partner. Nearly equal pairs (the two halves of a clamped wing pair, equal to round-off) make
    the nearest conjugate ambiguous: two tracked roots taking the same partner would leave the other partner's
    quasi-steady value, with its own real part, in the p-k spectrum. So the partners are a one-to-one assignment of
    the untracked roots minimising the total distance |vals[j] - conj(vals[k])|
    (:func:`scipy.optimize.linear_sum_assignment`).

    Parameters
    ----------
    vals : ndarray (complex), shape (n,)
        Eigenvalues of a real matrix [1/s].
    track : ndarray of int, shape (k,)
        Indices of the tracked roots, Im > 0.

    Returns
    -------
    ndarray of int, shape (k,)
    """
    from scipy.optimize import linear_sum_assignment

    track = np.asarray(track, dtype=int)
    rest = np.setdiff1d(np.arange(vals.size), track)
    if track.size == 0:
        return track.copy()
    if rest.size < track.size:
        raise ValueError(f"track: {track.size} roots with Im > 0 but only {rest.size} other roots to be their conjugates")
    cost = np.abs(vals[rest][None, :] - np.conj(vals[track])[:, None])
    rows, cols = linear_sum_assignment(cost)
    out = np.empty(track.size, dtype=int)
    out[rows] = rest[cols]
    return out


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
        for k, conj, root in zip(track, conjugate_slots(vals0, track), roots):
            out_vals[k], out_vecs[:, k] = root.eigenvalue, root.vector
            out_vals[conj], out_vecs[:, conj] = np.conj(root.eigenvalue), np.conj(root.vector)
        all_vals.append(out_vals)
        all_vecs.append(out_vecs if basis is None else basis @ out_vecs)
    vals = np.concatenate(all_vals)
    vecs = all_vecs[0] if len(all_vecs) == 1 else np.concatenate(all_vecs, axis=1)
    return _classify(qs_model, lin, vals, vecs, "theodorsen")
