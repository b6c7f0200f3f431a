"""Gravity: its data and its generalized force (paper eq. 32), compiled.

Tuzcu & Nguyen (2014) eq. (32): the gravity force per unit volume C_i C [0, 0, rho_i g]; its generalized force
is exactly Q_g = M(q) [g_b; 0] with g_b = C [0, 0, g] the gravity vector in body axes (:mod:`flexsim.structure.loads`
shows the identity). Body axes, SI units; Euler angles 3-2-1 [rad].
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexsim._kernels.layout import _f1, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class GravityData:
    """Gravity of the model (:class:`flexsim.model.terms.Terms`: ``gravity_m_s2``)."""

    g: np.ndarray = packed(1, "[g] (1,): gravitational acceleration g [m/s^2] of eq. 32 (0: no gravity)")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): g from its terms."""
        return dict(g=[model.terms.gravity_m_s2])


G = GravityData.index["g"]


@kernel
def gravity_force(F, I, m, eul, f):
    """f += Q_g = M(q) [g_b; 0], g_b = C [0, 0, g] = g [-sin theta, sin phi cos theta, cos phi cos theta] (eq. 32).

    m (n_v, n_v) M(q) [kg ...]; eul (3,) [phi, theta, psi] [rad]; f (n_v,) the right-hand side, added to in place.
    """
    g = _f1(F, I, G)[0]
    if g == 0.0:
        return
    sf, cf = math.sin(eul[0]), math.cos(eul[0])
    st, ct = math.sin(eul[1]), math.cos(eul[1])
    g0, g1, g2 = -st * g, sf * ct * g, cf * ct * g
    for i in range(f.shape[0]):
        f[i] += m[i, 0] * g0 + m[i, 1] * g1 + m[i, 2] * g2
