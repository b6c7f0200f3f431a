"""Munk's moment of slender bodies in the flow: fuselage and nacelles (not in the paper).

The paper's aircraft carries aerodynamic loads on its lifting strips only. A fuselage or nacelle inclined to
the flow carries, in potential flow, no net force but a couple that turns it broadside to the flow (Munk,
"The aerodynamic forces on airship hulls", NACA Report 184, 1924):

    M = 1/2 rho V^2 Vol (k2 - k1) sin(2 alpha)                                  (Munk 1924)

with alpha the angle between the body's axis and the flow, Vol its volume and k1, k2 the longitudinal and
transverse apparent-mass coefficients. It is the steady part of Kirchhoff's equations for a body translating
in an ideal fluid: with the apparent-mass tensor A = rho Vol (k1 a a^T + k2 (I - a a^T)) (a: unit axis),
the fluid's moment on the body is M = (A v) x v (Newman, *Marine Hydrodynamics*, 1977, sec. 4.13), i.e.

    M = rho Vol (k2 - k1) (v . a) (v x a)                                       [N m]

for the velocity v of the body relative to the air, in the axes of the component carrying it. In body axes
with a = x_b and v = V (cos alpha, 0, sin alpha) this is M_y = 1/2 rho V^2 Vol (k2 - k1) sin(2 alpha), nose up
for alpha > 0 (statically destabilising; it moves the neutral point forward); with v = V (cos beta, sin beta, 0)
it is N = -1/2 rho V^2 Vol (k2 - k1) sin(2 beta), turning the nose away from the wind (a negative Cn_beta).

k1, k2 are those of the prolate spheroid of the body's fineness ratio l/d (Munk's practice), Lamb,
*Hydrodynamics*, 6th ed., 1932, sec. 373, with e = sqrt(1 - (d/l)^2):

    alpha0 = 2 (1 - e^2)/e^3 (1/2 ln((1 + e)/(1 - e)) - e),   beta0 = 1/e^2 - (1 - e^2)/(2 e^3) ln((1 + e)/(1 - e))
    k1 = alpha0 / (2 - alpha0),                                k2 = beta0 / (2 - beta0)

(a sphere: k1 = k2 = 1/2; l/d = 10: k1 = 0.021, k2 = 0.979).

The body's velocity is that of its reference point, v_p = A_i(q) V + omega_sec x rho_i, as for the drag items
(:mod:`flexsim.model.drag`), and its axis is the body x axis (fuselage and nacelles of a transport). The couple
enters the equations of motion through the section rotation at the point by virtual work, Q = B_i^T M_i
(eqs. 17-24): it pitches and yaws the aircraft and bends the component that carries it.

Simplifications (docs/options.md "Fuselage and nacelle moments"): potential flow (no viscous cross-flow lift,
which adds a small stabilising normal force at larger angles), no wing-body interference (the wing's upwash
ahead of it and downwash behind), the axis does not follow the carrying beam's elastic rotation, the couple is
applied at one section (a rigid-body-exact resultant, not its distribution along the body), the rotary
apparent-mass terms (pitch damping of the body) are neglected, and the bodies see the aircraft's motion in
still air (a gust's change of the body moment is neglected; the strips do see the wind).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from flexsim import _kernels as _k
from flexsim._arrays import kernel_arg
from flexsim._immutable import Immutable
from flexsim.model.drag import attached_items_maps
from flexsim.structure.model import StructuralModel

__all__ = ["SlenderBodies", "spheroid_apparent_mass", "munk_moment"]


def spheroid_apparent_mass(fineness: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """Longitudinal and transverse apparent-mass coefficients k1, k2 [-] of a prolate spheroid (Lamb 1932, sec. 373).

    Parameters
    ----------
    fineness : float or ndarray
        Length over diameter l/d, > 1 (a sphere, l/d = 1, is the limit k1 = k2 = 1/2).
    """
    lam = np.asarray(fineness, dtype=float)
    if np.any(~np.isfinite(lam)) or np.any(lam <= 1.0):
        raise ValueError(f"fineness = {fineness!r}: the length over diameter of a prolate spheroid must be > 1")
    e = np.sqrt(1.0 - 1.0 / lam**2)
    log = np.log((1.0 + e) / (1.0 - e))
    alpha0 = 2.0 * (1.0 - e**2) / e**3 * (0.5 * log - e)
    beta0 = 1.0 / e**2 - (1.0 - e**2) / (2.0 * e**3) * log
    return alpha0 / (2.0 - alpha0), beta0 / (2.0 - beta0)


def munk_moment(v_p: np.ndarray, axis: np.ndarray, coeff: np.ndarray) -> np.ndarray:
    """Munk moment M = coeff (v . a)(v x a) of each body, shape (k, 3) [N m] (module docstring; the compiled
    kernel :func:`flexsim._kernels.munk_moments`).

    Parameters
    ----------
    v_p : ndarray, shape (k, 3)
        Velocity of each body relative to the air [m/s].
    axis : ndarray, shape (k, 3)
        Unit axis of each body, same axes as ``v_p``.
    coeff : ndarray, shape (k,)
        rho Vol (k2 - k1) [kg].
    """
    return _k.munk_moments(kernel_arg(v_p), kernel_arg(axis), kernel_arg(coeff))


class _BodiesOf(NamedTuple):
    """What :class:`flexsim._kernels.SlenderBodyData` reads of a model: its slender bodies and structure."""

    bodies: "SlenderBodies"
    structure: StructuralModel


class SlenderBodies(Immutable):
    """Slender bodies of an aircraft with their kinematic maps (built once; :meth:`generalized_force` per call).

    Parameters
    ----------
    structure : StructuralModel
        Its aircraft's ``aero_settings.bodies`` items are used.

    Attributes
    ----------
    names : tuple of str
    volume_m3, k1, k2 : ndarray, shape (k,)
        Volumes [m^3] and apparent-mass coefficients [-] (Lamb's spheroid of each body's fineness ratio).
    axis : ndarray, shape (k, 3)
        Body axes (unit, the body x axis) in the axes of the carrying component.
    """

    def __init__(self, structure: StructuralModel) -> None:
        items = structure.aircraft.aero_settings.bodies
        self.names = tuple(b.name for b in items)
        self.volume_m3 = np.array([b.volume_m3 for b in items], dtype=float)
        self.k1, self.k2 = spheroid_apparent_mass(np.array([b.length_m / b.diameter_m for b in items], dtype=float))
        k = len(items)
        #: The bodies' maps (:func:`flexsim.model.drag.attached_items_maps`): g0, g1, offsets (k, 3) [m].
        self.g0, self.g1, self.offset_m = attached_items_maps(structure, items)
        self.axis = np.zeros((k, 3))
        for j, b in enumerate(items):
            self.axis[j] = structure.aircraft.component(b.component).dcm[:, 0]  # body x in component axes
        #: Vol (k2 - k1) of each body (k,) [m^3]: Munk's moment per unit density and dynamic pressure.
        self.vol_dk = self.volume_m3 * (self.k2 - self.k1)
        #: The bodies' packed data (:class:`flexsim._kernels.KernelData`), filled by their term data class as for the
        #: model (:meth:`flexsim._kernels.SlenderBodyData.fields_of`).
        self.kernel_data = _k.pack_fields(_k.fields_of(_BodiesOf(self, structure), (_k.SlenderBodyData,)))

    @property
    def n_items(self) -> int:
        """Number of bodies k."""
        return self.volume_m3.size

    def moments(self, q: np.ndarray, vel: np.ndarray, rho: float) -> np.ndarray:
        """Munk moment of every body in the axes of its component, shape (k, 3) [N m].

        Parameters
        ----------
        q : ndarray, shape (nq,)
            Bending coordinates [m].
        vel : ndarray, shape (n_v,)
            Global velocity vector V.
        rho : float
            Air density [kg/m^3].
        """
        return _k.body_moments(*self.kernel_data, kernel_arg(q), kernel_arg(vel), float(rho))

    def generalized_force(self, q: np.ndarray, vel: np.ndarray, rho: float) -> np.ndarray:
        """Q_body = sum_i B_i^T M_i, shape (n_v,) [N, N m] (module docstring); arguments as :meth:`moments`."""
        return _k.body_force(*self.kernel_data, kernel_arg(q), kernel_arg(vel), float(rho))
