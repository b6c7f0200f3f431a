"""The free aircraft with nonlinear beams linearised about its nonlinear trim with Peters' unsteady strips.

:func:`flexsim.linear.flexible_stability.free_aircraft_spectrum` linearises the free-flight equations with
quasi-steady strips (:meth:`~flexsim.model.flexible_aircraft.FlexibleAircraft.free_flight_jacobian`). Here the strips
carry Peters' finite-state airloads (reference §1.3-1.4 and §2.1; Peters, Karunamoorthy & Cao 1995), the same model as
the clamped wing's :func:`flexsim.model.beam_aero.aeroelastic_system`, on every strip of the free aircraft (flexible
beams at their quadrature points, rigid components at their strip stations):

* ``{L} = πρ{b²[M]{ẇ} + b u0([B]{w} − {S}λ0)}`` — the quasi-steady part ``πρ b u0 [B]{w}`` (with its leading-edge
  suction) is already in the quasi-steady Jacobian; added here are the apparent mass ``πρ b² [M]{ẇ}`` and the
  inflow ``−πρ b u0 {S} λ0``, with the suction's change ``∂S/∂λ0 = −2πρ b (2 w0 − u0 α_i)``;
* per strip, ``[A]λ̇ + (u0/b)λ = {c}(ẇ0 + ẇ1/2)``, ``λ0 = ½ bᵀλ``;
* a strip point moves with ``L V`` (``L = [I, −p^, J_p]``, body axes) and its section turns with ``A V``
  (``A = [0, I, J_θ]``) over the generalized velocities ``V = [v, ω, ε̇]``; so ``δw0 = −(e3ᵀL + a b e1ᵀA) δV``,
  ``δw1 = b e1ᵀA δV`` and ``δẇ0 = (…) δV̇ + (e3 × V_a)ᵀ [0, 0, J_θ] δV`` (the elastic turn of ``e3`` against the air
  velocity ``V_a``; a rigid turn of the body is in ``v̇`` of the body-axis equations). About a rotating trim (a
  pull-up, a turn: body rates ``ω0``) each strip's ``V_a = −(v + ω0 × p)``, its steady ``w1 = b e1·ω0``, and ``ẇ``
  gains ``−(e3 × ω0)ᵀ J_p ε̇`` (the rotation carrying the elastic velocity) and ``ẇ1`` gains ``b (e1 × ω0)ᵀ J_θ ε̇``.

With ``M`` the generalized mass at the trim and ``M_a`` the apparent mass, the velocity rows become
``(M + M_a) δV̇ = M J_V δy − C_a δV + G_λ λ`` (``J_V`` the quasi-steady Jacobian's velocity rows: the trim is an
equilibrium in body axes, ``R = 0``). States: ``[quaternion (4), ε (n), V (6 + n), λ (P × N)]``. SI units, body axes
x forward, z down.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from flexsim.aero.inflow import inflow_coefficients
from flexsim.kinematics import skew
from flexsim.model.beam_aero import inflow_columns, peters_strip_terms, set_inflow_rows
from flexsim.structure.free_flexible import generalized_mass_matrix
from flexsim.trimming.flexible_trim import FlexibleTrimPoint

__all__ = ["UnsteadyFreeAircraft", "free_aircraft_unsteady"]


@dataclass(frozen=True, eq=False)
class UnsteadyFreeAircraft:
    """The linear free aircraft with Peters strips about a nonlinear trim.

    Attributes
    ----------
    state_matrix : ndarray, shape (4 + n + 6 + n + P N, same)
    n_strains : int
    n_strips : int
        P: strips with inflow states.
    inflow_states : int
        N per strip.
    point : FlexibleTrimPoint
    """

    state_matrix: NDArray
    n_strains: int
    n_strips: int
    inflow_states: int
    point: FlexibleTrimPoint

    @property
    def eigenvalues(self) -> NDArray:
        """Eigenvalues of the state matrix [1/s]."""
        return np.linalg.eigvals(self.state_matrix)

    def elastic_stability(self, max_frequency_rad_s: float = 200.0) -> tuple[float, float, NDArray]:
        """The least stable elastic oscillatory root: the largest damping ratio ``Re λ / |λ|`` over the complex roots
        whose eigenvector's kinetic energy ``½ δVᴴ M δV`` lies mostly (over half) in the strain rates, up to
        ``max_frequency_rad_s`` (the beams' unconverged band above; roots neutral to 1e-6 skipped, as in the
        clamped wing's :func:`~flexsim.linear.flexible_flutter.wing_stability`). An energy share, not a share of the
        state vector, so that the inflow states' units (m/s) and the strains' (1/m) do not decide.

        Returns
        -------
        growth : float
            [-] (> 0: unstable); −1 when there is no elastic oscillatory root.
        frequency_rad_s : float
        roots : ndarray of complex
            All eigenvalues [1/s].
        """
        lam, vec = np.linalg.eig(self.state_matrix)
        n = self.n_strains
        start = 4 + n
        vel = vec[start:start + 6 + n]
        mass = generalized_mass_matrix(self.point.aircraft.structure, self.point.strains)
        total = np.einsum("ik,ij,jk->k", vel.conj(), mass, vel).real
        elastic = np.einsum("ik,ij,jk->k", vel[6:].conj(), mass[6:, 6:], vel[6:]).real
        share = elastic / np.maximum(total, 1e-300)
        ratio = lam.real / np.maximum(np.abs(lam), 1e-300)
        keep = ((np.abs(lam.imag) > 1e-6 * np.abs(lam)) & (np.abs(ratio) > 1e-6) & (share > 0.5)
                & (np.abs(lam.imag) <= max_frequency_rad_s))
        if not np.any(keep):
            return -1.0, 0.0, lam
        k = int(np.argmax(np.where(keep, ratio, -np.inf)))
        return float(ratio[k]), float(abs(lam[k].imag)), lam

    def spectrum(self):
        """The roots with a structural part, named as the quasi-steady ones
        (:class:`~flexsim.linear.flexible_stability.FreeAircraftSpectrum` over the eigenvectors' rows
        ``[quaternion, ε, v, ω, ε̇]``, each rescaled to unit length there). The wake's own roots are left out: the
        real roots whose structural rows are under half of the eigenvector's length (inflow states in m/s; on the HALE
        the wake's decays, −3 to −35 1/s, have structural shares of 3e-5 to 0.2, the structure's aperiodic roots
        above 0.9) and the complex ones under a tenth."""
        from flexsim.linear.flexible_stability import FreeAircraftSpectrum

        lam, vec = np.linalg.eig(self.state_matrix)
        m = 4 + 2 * self.n_strains + 6
        part = np.linalg.norm(vec[:m], axis=0)
        share = part / np.linalg.norm(vec, axis=0)
        keep = share > np.where(np.abs(lam.imag) > 1e-9, 0.1, 0.5)
        return FreeAircraftSpectrum(lam[keep], vec[:m, keep] / part[keep], self.n_strains, self.point, "unsteady")


def _strips(flex, structure, eps: NDArray, v: NDArray, omega: NDArray, u: NDArray, rho: float) -> dict:
    """Every strip's frame, position, point and rotation Jacobians over V, semichord, axis, effective density,
    incidence and weight (flexible beams at their quadrature points, then the rigid strips)."""
    nv = structure.n_velocities
    beta = flex.compressibility_beta
    parts = {k: [] for k in ("rot", "pos", "jl", "ja", "b", "a", "rho", "rho_a", "inc", "w")}
    for s, kin, (b, a, scale, incidence, flap, _cd0) in zip(structure.strain_slices(), flex.kinematics(eps),
                                                             flex.strip_constants):
        k = kin.positions.shape[0]
        jl, ja = np.zeros((k, 3, nv)), np.zeros((k, 3, nv))
        jl[:, :, :3] = np.eye(3)
        jl[:, :, 3:6] = -skew(kin.positions)
        jl[:, :, 6 + s.start:6 + s.stop] = kin.jac_position
        ja[:, :, 3:6] = np.eye(3)
        ja[:, :, 6 + s.start:6 + s.stop] = kin.jac_rotation
        for key, value in (("rot", kin.rotations), ("pos", kin.positions), ("jl", jl), ("ja", ja), ("b", b), ("a", a),
                           ("rho", rho * np.broadcast_to(scale, b.shape) / beta),
                           ("rho_a", rho * np.broadcast_to(scale, b.shape)), ("inc", incidence + flap @ u),
                           ("w", kin.points_weight)):
            parts[key].append(np.asarray(value, float))
    r = flex.rigid_strips
    if r.b.size:
        k = r.b.size
        jl, ja = np.zeros((k, 3, nv)), np.zeros((k, 3, nv))
        jl[:, :, :3] = np.eye(3)
        jl[:, :, 3:6] = -skew(r.position)
        ja[:, :, 3:6] = np.eye(3)
        for key, value in (("rot", r.rotations), ("pos", r.position), ("jl", jl), ("ja", ja), ("b", r.b), ("a", r.a),
                           ("rho", rho * r.scale / beta), ("rho_a", rho * r.scale), ("inc", r.incidence + r.flap @ u),
                           ("w", r.width)):
            parts[key].append(np.asarray(value, float))
    out = {key: np.concatenate(value) for key, value in parts.items()}
    lifting = out["rho"] > 0.0  # a beam without lift (a fuselage) has no strips
    out = {key: value[lifting] for key, value in out.items()}
    out["va"] = -(v[None, :] + np.cross(omega, out["pos"]))
    return out


def free_aircraft_unsteady(model, point: FlexibleTrimPoint, inflow_states: int = 6) -> UnsteadyFreeAircraft:
    """The linear free aircraft with Peters' strips about ``point`` (module docstring).

    Parameters
    ----------
    model : AircraftModel
        The model the trim was computed for (its gravity).
    point : FlexibleTrimPoint
        Any nonlinear trim (level flight, climb, glide, pull-up, turn).
    inflow_states : int
        Peters inflow states per strip, 1-10.

    Returns
    -------
    UnsteadyFreeAircraft
    """
    if not isinstance(point, FlexibleTrimPoint):
        raise ValueError(f"point = {point!r}: must be a FlexibleTrimPoint (fs.trim of a model with nonlinear beams)")
    flex = point.aircraft
    structure = flex.free_structure(model.terms.gravity_m_s2)
    y0 = point.state()
    n, nv = structure.n_strains, structure.n_velocities
    jq = flex.free_flight_jacobian(structure, y0, point.controls, point.density_kg_m3)[3:]  # over y[3:]
    npos = 4 + n
    mass = generalized_mass_matrix(structure, point.strains)
    omega = np.asarray(point.rate_rad_s, float)
    s = _strips(flex, structure, point.strains, point.velocity_m_s, omega, np.asarray(point.controls, float),
                point.density_kg_m3)
    coef = inflow_coefficients(inflow_states)
    nl = coef.n_states
    e1, e2, e3 = s["rot"][:, :, 0], s["rot"][:, :, 1], s["rot"][:, :, 2]
    b, a, rho, w, va = s["b"], s["a"], s["rho"], s["w"], s["va"]
    u0 = -np.einsum("pi,pi->p", e2, va)
    w0s = np.einsum("pi,pi->p", e3, va) + u0 * s["inc"] - a * b * np.einsum("pi,i->p", e1, omega)
    pn = np.einsum("pi,pik->pk", e3, s["jl"])
    pc = np.einsum("pi,pik->pk", e2, s["jl"])
    a1 = np.einsum("pi,pik->pk", e1, s["ja"])
    # ẇ's terms in δV (body-axis components): the elastic turn of e3 against V_a, the transport of the elastic
    # velocity by the trim's rotation (−ω0 × J_p ε̇ in V̇_a), and the elastic turn of e1 against ω0 in ẇ1 = b ė1·Ω
    elastic_rotation, elastic_position = s["ja"].copy(), s["jl"].copy()
    elastic_rotation[:, :, :6] = 0.0
    elastic_position[:, :, :6] = 0.0
    rn1 = b[:, None] * np.einsum("pi,pik->pk", np.cross(e1, omega[None, :]), elastic_rotation)
    rn = (np.einsum("pi,pik->pk", np.cross(e3, va), elastic_rotation)
          - np.einsum("pi,pik->pk", np.cross(e3, omega[None, :]), elastic_position) - a[:, None] * rn1)
    w0v = -pn - (a * b)[:, None] * a1
    w1v = b[:, None] * a1
    suc_lam = -2.0 * np.pi * rho * b * (2.0 * w0s - u0 * s["inc"])        # ∂S/∂λ0
    ma, ca, g0 = peters_strip_terms(w, pn, pc, a1, w0v, w1v, rn, rn1, b, a, rho, u0, suc_lam, s["rho_a"])
    p = b.size
    size = npos + nv + p * nl
    out = np.zeros((size, size))
    out[:npos, :npos + nv] = jq[:npos]  # kinematics: unchanged
    h = np.linalg.inv(mass + ma)
    vel = slice(npos, npos + nv)
    out[vel, :npos + nv] = h @ (mass @ jq[npos:])
    out[vel, vel] -= h @ ca
    out[vel, npos + nv:] = h @ inflow_columns(g0, coef)
    f_rows = (w0v + 0.5 * w1v) @ out[vel]  # ẇ0 + ẇ1/2 of each strip per state, through δV̇
    f_rows[:, vel] += rn + 0.5 * rn1
    set_inflow_rows(out, npos + nv, coef, f_rows, u0, b)
    return UnsteadyFreeAircraft(out, n, p, nl, point)
