"""Statics and linearised vibration of the strain-based beam (:mod:`flexsim.structure.strain_beam`).

Sources: Su & Cesnik, Int. J. Solids Struct. 48 (2011), eqs. 13-20 (generalized forces ``Q = J_pᵀ F + J_θᵀ M``
from virtual work, static equilibrium ``K ε = Q(ε)``, Newton-Raphson with load stepping); the geometric (load)
stiffness of a preload as the derivative of its generalized force, ``K_T = K − ∂Q/∂q`` (Bathe, *Finite Element
Procedures*, 2nd ed. 2014, §6.2: the tangent stiffness of a conservative or follower load).

Units SI, frames as in :mod:`flexsim.structure.strain_beam`: forces [N] and moments [N m] in global components
(dead) or in the tip section's axes ``e1, e2, e3`` (follower); gravity is an acceleration vector [m/s²].
The generalized force conjugate to ``q`` has the units of ``K q`` (N for extension, N m for curvature × m).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eig, eigh

from flexsim._arrays import frozen_array
from flexsim.errors import FlexsimError
from flexsim.structure.strain_beam import (BeamKinematics, BeamProperties, beam_kinematics, mass_points,
                                           mass_matrix, stiffness_matrix)

__all__ = ["BeamLoads", "BeamConvergenceError", "NewtonSettings", "StaticSolution", "solve_static",
           "load_stiffness", "tangent_stiffness", "BeamModes", "vibration_modes", "LoadModel"]


class BeamConvergenceError(FlexsimError, RuntimeError):
    """The Newton solution of a beam's static equilibrium did not converge (the message says where and why)."""


class LoadModel(Protocol):
    """Anything that gives the generalized force of its loads on a beam in a configuration."""

    def generalized_force(self, beam: BeamProperties, kin: BeamKinematics) -> NDArray[np.float64]:
        """``Q`` conjugate to ``q``, shape (n,)."""


def _vector(name: str, value, unit: str) -> NDArray:
    arr = np.array(value, dtype=float)
    if arr.shape != (3,) or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} = {value!r}: must be 3 finite numbers [{unit}]")
    return frozen_array(arr)


@dataclass(frozen=True)
class BeamLoads:
    """Static loads on a clamped beam (validated, frozen). All default to zero.

    Parameters
    ----------
    tip_force_n, tip_moment_nm : array_like, shape (3,)
        Dead force [N] and moment [N m] at the tip node, global components (fixed direction).
    tip_follower_force_n, tip_follower_moment_nm : array_like, shape (3,)
        Follower force [N] and moment [N m] at the tip, components in the tip section axes (turn with it).
    gravity_m_s2 : array_like, shape (3,)
        Acceleration of gravity, global components [m/s²] (e.g. ``(0, 0, -9.80665)``), acting on the mass centres.
    distributed_force_n_m : array_like, shape (3,)
        Dead force per unit undeformed length on the reference axis, global components [N/m].
    """

    tip_force_n: ArrayLike = field(default_factory=lambda: np.zeros(3))
    tip_moment_nm: ArrayLike = field(default_factory=lambda: np.zeros(3))
    tip_follower_force_n: ArrayLike = field(default_factory=lambda: np.zeros(3))
    tip_follower_moment_nm: ArrayLike = field(default_factory=lambda: np.zeros(3))
    gravity_m_s2: ArrayLike = field(default_factory=lambda: np.zeros(3))
    distributed_force_n_m: ArrayLike = field(default_factory=lambda: np.zeros(3))

    def __post_init__(self) -> None:
        for name, unit in (("tip_force_n", "N"), ("tip_moment_nm", "N m"), ("tip_follower_force_n", "N"),
                           ("tip_follower_moment_nm", "N m"), ("gravity_m_s2", "m/s^2"),
                           ("distributed_force_n_m", "N/m")):
            object.__setattr__(self, name, _vector(name, getattr(self, name), unit))

    def generalized_force(self, beam: BeamProperties, kin: BeamKinematics) -> NDArray[np.float64]:
        """``Q = J_pᵀ F + J_θᵀ M`` summed over the loads (Su & Cesnik 2011 eq. 13; virtual work), shape (n,)."""
        r_tip = kin.tip_rotation
        force = self.tip_force_n + r_tip @ self.tip_follower_force_n
        moment = self.tip_moment_nm + r_tip @ self.tip_follower_moment_nm
        q = kin.tip_jac_position.T @ force + kin.tip_jac_rotation.T @ moment
        if np.any(self.gravity_m_s2):
            pts = mass_points(beam, kin)  # the sections' mass centres and the point masses
            q = q + np.einsum("p,pik,i->k", pts.mass, pts.jac_c, self.gravity_m_s2)
        if np.any(self.distributed_force_n_m):
            q = q + np.einsum("p,pik,i->k", kin.points_weight, kin.jac_position, self.distributed_force_n_m)
        return q


@dataclass(frozen=True)
class NewtonSettings:
    """Settings of the static Newton-Raphson solution (validated, frozen).

    Parameters
    ----------
    tolerance : float
        Converged when ``|K q − λQ|∞ <= tolerance × max(|λQ|∞, |K q|∞, 1e-12)`` and the last step
        ``|Δq|∞ <= tolerance × max(|q|∞, 1)`` (dimensionless; default 1e-10).
    max_iterations : int
        Newton iterations per load step (default 30).
    load_steps : int
        Initial number of equal load increments (default 1); a step that fails is halved, down to
        ``1 / 2**max_halvings`` of the load.
    max_halvings : int
        Default 8.
    difference_step : float
        Central-difference step in ``q`` for the load stiffness ``∂Q/∂q`` (default 1e-6, in the units of q).
    """

    tolerance: float = 1e-10
    max_iterations: int = 30
    load_steps: int = 1
    max_halvings: int = 8
    difference_step: float = 1e-6

    def __post_init__(self) -> None:
        for name, lo, hi in (("tolerance", 1e-15, 1e-2), ("difference_step", 1e-10, 1e-2)):
            v = getattr(self, name)
            if not isinstance(v, (int, float)) or isinstance(v, bool) or not lo <= v <= hi:
                raise ValueError(f"{name} = {v!r}: must be a number in [{lo:g}, {hi:g}]")
        for name, lo, hi in (("max_iterations", 1, 1000), ("load_steps", 1, 10000), ("max_halvings", 0, 30)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not lo <= v <= hi:
                raise ValueError(f"{name} = {v!r}: must be an integer in {lo}-{hi}")


@dataclass(frozen=True, eq=False)
class StaticSolution:
    """A converged static equilibrium.

    Attributes
    ----------
    q : ndarray, shape (n,)
        Element strains.
    kinematics : BeamKinematics
        Frames and Jacobians at ``q``.
    iterations : int
        Newton iterations over all load steps.
    residual : float
        Final ``|K q − Q|∞`` (units of Q).
    """

    q: NDArray
    kinematics: BeamKinematics
    iterations: int
    residual: float

    @property
    def tip_position_m(self) -> NDArray:
        """Tip reference-axis position [m], shape (3,)."""
        return self.kinematics.tip_position


def load_stiffness(beam: BeamProperties, loads: LoadModel, q: ArrayLike, step: float = 1e-6) -> NDArray[np.float64]:
    """``∂Q/∂q`` by central differences (step in the units of q), shape (n, n): the preload's geometric stiffness
    is ``−∂Q/∂q`` (Bathe 2014 §6.2). Nonsymmetric for follower loads."""
    q = np.asarray(q, dtype=float)
    out = np.empty((q.size, q.size))
    for i in range(q.size):
        dq = np.zeros_like(q)
        dq[i] = step
        out[:, i] = (loads.generalized_force(beam, beam_kinematics(beam, q + dq))
                     - loads.generalized_force(beam, beam_kinematics(beam, q - dq))) / (2.0 * step)
    return out


def tangent_stiffness(beam: BeamProperties, loads: LoadModel | None, q: ArrayLike, step: float = 1e-6) -> NDArray:
    """Tangent stiffness ``K_T = K − ∂Q/∂q`` at ``q`` (elastic plus the preload's geometric stiffness), (n, n)."""
    k = stiffness_matrix(beam)
    return k if loads is None else k - load_stiffness(beam, loads, q, step)


def _newton(beam, loads, k, q, factor, settings):
    """Newton iterations at load factor ``factor``; returns (q, iterations, residual, converged, why)."""
    why = ""
    for it in range(1, settings.max_iterations + 1):
        kin = beam_kinematics(beam, q)
        load = factor * loads.generalized_force(beam, kin)
        r = k @ q - load
        if not np.all(np.isfinite(r)):
            return q, it, np.inf, False, "the residual is not finite"
        tangent = k - factor * load_stiffness(beam, loads, q, settings.difference_step)
        try:
            dq = np.linalg.solve(tangent, -r)
        except np.linalg.LinAlgError:
            return q, it, float(np.abs(r).max()), False, "the tangent stiffness is singular (a limit point?)"
        q = q + dq
        kin = beam_kinematics(beam, q)
        load = factor * loads.generalized_force(beam, kin)
        r = k @ q - load
        res = float(np.abs(r).max())
        scale = max(np.abs(load).max(), np.abs(k @ q).max(), 1e-12)
        if res <= settings.tolerance * scale and np.abs(dq).max() <= settings.tolerance * max(np.abs(q).max(), 1.0):
            return q, it, res, True, ""
        worst = int(np.argmax(np.abs(r)))
        why = f"residual {res:.3e} (tolerance {settings.tolerance * scale:.3e}), largest at {beam.coordinate_name(worst)}"
    return q, settings.max_iterations, res, False, why


def solve_static(beam: BeamProperties, loads: LoadModel, settings: NewtonSettings = NewtonSettings(),
                 q0: ArrayLike | None = None) -> StaticSolution:
    """Static equilibrium ``K q = Q(q)`` by Newton-Raphson with load stepping (Su & Cesnik 2011 §3).

    The tangent is ``K − ∂Q/∂q`` (:func:`load_stiffness`), so dead loads (whose Jacobians change with the
    configuration), follower loads and gravity converge quadratically.

    Parameters
    ----------
    beam : BeamProperties
    loads : LoadModel
        E.g. :class:`BeamLoads`, or the strip airloads of :mod:`flexsim.model.beam_aero`.
    settings : NewtonSettings
    q0 : array_like, shape (n,), optional
        Starting strains (default: the undeformed beam); the load is applied in steps from there.

    Returns
    -------
    StaticSolution

    Raises
    ------
    BeamConvergenceError
        Naming the load factor reached, the residual and the coordinate where it is largest.
    """
    k = stiffness_matrix(beam)
    q = np.zeros(beam.n_coordinates) if q0 is None else np.array(q0, dtype=float)
    if q.shape != (beam.n_coordinates,) or not np.all(np.isfinite(q)):
        raise ValueError(f"q0 must be {beam.n_coordinates} finite strains; got shape {q.shape}")
    done, increment, total_it, halvings = 0.0, 1.0 / settings.load_steps, 0, 0
    kin = beam_kinematics(beam, q)
    load = loads.generalized_force(beam, kin)
    res = float(np.abs(k @ q - load).max())
    if res <= settings.tolerance * max(np.abs(load).max(), np.abs(k @ q).max(), 1e-12):
        return StaticSolution(q=q, kinematics=kin, iterations=0, residual=res)  # q0 is already the equilibrium
    while done < 1.0 - 1e-12:
        target = min(1.0, done + increment)
        q_new, it, res, ok, why = _newton(beam, loads, k, q, target, settings)
        total_it += it
        if ok:
            q, done = q_new, target
            continue
        halvings += 1
        if halvings > settings.max_halvings:
            raise BeamConvergenceError(
                f"static equilibrium of the beam not found: Newton failed at load factor {target:.4g} (converged up "
                f"to {done:.4g}) after {settings.max_halvings} halvings of the load step: {why}; try more "
                f"NewtonSettings.load_steps, or the load exceeds what the beam can carry (buckling, a limit point)")
        increment *= 0.5
    kin = beam_kinematics(beam, q)
    return StaticSolution(q=q, kinematics=kin, iterations=total_it, residual=res)


@dataclass(frozen=True, eq=False)
class BeamModes:
    """Small vibrations about an equilibrium ``q0``: ``M(q0) δq̈ + K_T δq = 0``.

    Attributes
    ----------
    frequencies_rad_s : ndarray, shape (n,)
        Natural frequencies [rad/s], ascending.
    shapes : ndarray, shape (n, n)
        Mode shapes in strain coordinates (columns, mass-normalised when K_T is symmetric).
    q0 : ndarray, shape (n,)
    """

    frequencies_rad_s: NDArray
    shapes: NDArray
    q0: NDArray


def vibration_modes(beam: BeamProperties, loads: LoadModel | None = None, q0: ArrayLike | None = None,
                    step: float = 1e-6) -> BeamModes:
    """Natural frequencies about the equilibrium ``q0`` under ``loads`` (undeformed and unloaded by default).

    Mass matrix from the exact kinematics at ``q0`` (:func:`~flexsim.structure.strain_beam.mass_matrix`); stiffness
    ``K_T = K − ∂Q/∂q`` including the preload's geometric stiffness (Bathe 2014 §6.2). Follower loads make
    ``K_T`` nonsymmetric: the general eigenproblem is solved then and complex frequencies (flutter of the
    structure under a follower load) are refused with an error naming the mode.

    Returns
    -------
    BeamModes
    """
    q0 = np.zeros(beam.n_coordinates) if q0 is None else np.asarray(q0, dtype=float)
    kin = beam_kinematics(beam, q0)
    m = mass_matrix(beam, kin)
    try:
        np.linalg.cholesky(m)
    except np.linalg.LinAlgError:
        raise ValueError("the beam's mass matrix is singular: a strain moves no mass (give torsion_inertia_kg_m > 0 "
                         "for twist, or the section inertias); vibration frequencies are not defined") from None
    kt = tangent_stiffness(beam, loads, q0, step)
    if np.abs(kt - kt.T).max() <= 1e-8 * np.abs(kt).max():
        lam, vec = eigh(0.5 * (kt + kt.T), m)
    else:
        lam, vec = eig(kt, m)
        if np.abs(lam.imag).max() > 1e-6 * np.abs(lam).max():
            raise ValueError("the loaded beam has complex eigenvalues (a follower load beyond its flutter load); "
                             "vibration frequencies are not defined")
        lam, vec = lam.real, vec.real
    order = np.argsort(lam)
    lam, vec = lam[order], vec[:, order]
    if lam[0] < 0.0:
        raise ValueError(f"the equilibrium is unstable (tangent stiffness eigenvalue {lam[0]:.4g} < 0: buckled); "
                         "vibration frequencies are not defined")
    return BeamModes(frequencies_rad_s=np.sqrt(lam), shapes=vec, q0=q0.copy())
