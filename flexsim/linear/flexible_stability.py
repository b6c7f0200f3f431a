"""Stability of the whole free-flying very flexible aircraft about its nonlinear trim (quasi-steady strips).

The state of the free-flying aircraft (:mod:`flexsim.structure.free_flexible`, the paper's eq. 2 in Kane's form) is
``y = [X (3), quaternion (4), ε (n), v (3), ω (3), ε̇ (n)]``; its rate is :func:`free_flight_rhs` with the
generalized airloads and thrust of :meth:`flexsim.model.flexible_aircraft.FlexibleAircraft.airloads` (quasi-steady
strips: no apparent mass, no wake) added to ``Q``. The Jacobian ``A = ∂ẏ/∂y`` about a trim point
(:func:`flexsim.trimming.flexible_trim.trim_flexible`) is taken by central differences (step ``10⁻⁶ max(1, |y_j|)``,
truncation O(h²) and round-off O(ε/h): about 1e-8 relative in the eigenvalues that matter here) on every state but
the position (the density is held at the trim's), so the eigenvalues include the rigid-body modes (phugoid, short
period, Dutch roll, roll, spiral) coupled with the deformed wings, and four neutral roots: the heading and, from the
quaternion's norm, one more. The preload's geometric stiffness enters through the dependence of the equations on ε.
About the bottom of a pull-up (``ω ≠ 0``) the attitude turns, so the linearisation is the frozen one of the linear
model's pull-up (:mod:`flexsim.trimming.manoeuvre`). SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from flexsim.structure.free_flexible import FreeFlexibleStructure, free_flight_rhs
from flexsim.trimming.flexible_trim import FlexibleTrimPoint

__all__ = ["FreeAircraftSpectrum", "free_aircraft_spectrum", "NEUTRAL_1_S"]

#: Roots closer to zero than this [1/s] count as neutral (a period over 20 min; module docstring).
NEUTRAL_1_S = 5e-3


@dataclass(frozen=True, eq=False)
class FreeAircraftSpectrum:
    """Eigenvalues of the free aircraft about a nonlinear trim.

    Attributes
    ----------
    eigenvalues : ndarray of complex, shape (m,)
        [1/s], all states but the position.
    eigenvectors : ndarray of complex, shape (m, m)
        Columns, in the reduced state ``[quaternion, ε, v, ω, ε̇]``.
    n_strains : int
    """

    eigenvalues: NDArray
    eigenvectors: NDArray
    n_strains: int

    @property
    def phugoid(self) -> tuple:
        """The phugoid's roots: the non-neutral roots below 1 rad/s whose eigenvectors are led by the forward speed
        ``v_x`` (more than half of the unit eigenvector; the long-period exchange of speed and height). One
        complex root (its upper half) while it oscillates; two real roots once it has split (a very flexible
        aircraft at high speed); empty when none is found. Roots within :data:`NEUTRAL_1_S` of zero are left out:
        the heading's and the quaternion norm's neutral roots, which the frozen linearisation of a pull-up (a
        turning attitude) shifts by up to 3e-3 1/s on the bundled HALE."""
        n = self.n_strains
        lam, vec = self.eigenvalues, self.eigenvectors
        out = []
        for k in np.flatnonzero((np.abs(lam) < 1.0) & (np.abs(lam) > NEUTRAL_1_S) & (lam.imag >= 0.0)):
            if abs(vec[4 + n, k]) / np.linalg.norm(vec[:, k]) > 0.5:
                out.append(complex(lam[k]) if lam[k].imag > 1e-9 else complex(lam[k].real, 0.0))
        return tuple(sorted(out, key=lambda z: (z.real, z.imag)))


def free_aircraft_spectrum(model, point: FlexibleTrimPoint) -> FreeAircraftSpectrum:
    """Eigenvalues and eigenvectors of the free aircraft linearised about ``point`` (module docstring).

    Parameters
    ----------
    model : AircraftModel
        The model the trim was computed for (its gravity).
    point : FlexibleTrimPoint

    Returns
    -------
    FreeAircraftSpectrum
    """
    flex = point.aircraft
    g = float(model.terms.gravity_m_s2)
    structure = FreeFlexibleStructure(flex.structure.body, flex.structure.beams, np.array([0.0, 0.0, g]))
    n = structure.n_strains
    theta = point.theta_rad
    y0 = np.concatenate([[0.0, 0.0, -point.manoeuvre.altitude_m],
                         [np.cos(theta / 2), 0.0, np.sin(theta / 2), 0.0], point.strains,
                         point.velocity_m_s, point.rate_rad_s, np.zeros(n)])
    u, rho = point.controls, point.density_kg_m3

    def rate(y):
        eps, vel = y[7:7 + n], y[7 + n:]
        q = flex.airloads(eps, vel[:3], vel[3:6], u, rho, epsdot=vel[6:])
        return free_flight_rhs(structure, 0.0, y, q)[3:]

    keep = np.arange(3, y0.size)
    a = np.zeros((keep.size, keep.size))
    for j, col in enumerate(keep):
        h = 1e-6 * max(1.0, abs(y0[col]))
        up, down = y0.copy(), y0.copy()
        up[col] += h
        down[col] -= h
        a[:, j] = (rate(up) - rate(down)) / (2.0 * h)
    lam, vec = np.linalg.eig(a)
    return FreeAircraftSpectrum(eigenvalues=lam, eigenvectors=vec, n_strains=n)
