"""Thrust: its data and its generalized force (paper eqs. 17-24), compiled.

Tuzcu & Nguyen (2014) eqs. (17)-(24): a point force of magnitude T_e along each engine's thrust line enters the
equations of motion by virtual work as Q_T = T_e (t0 + t1 q), linear in the bending coordinates through the
mounts' displacement and rotation (built by :class:`flexsim.structure.model.StructuralModel`). Body axes, SI units.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexsim._kernels.layout import _f1, _f2, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class ThrustData:
    """The engines' generalized force per newton of thrust (:class:`flexsim.model.terms.Terms`:
    ``thrust_follows_deflection`` False packs t1 = 0)."""

    thrust_t0: np.ndarray = packed(1, "t0 (n_v,): generalized force per newton of T_e at q = 0 [-, m]")
    thrust_t1: np.ndarray = packed(2, "t1 (n_v, nq): its change with the bending coordinates [1/m, -]")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): its structure's thrust map,
        t1 = 0 unless ``terms.thrust_follows_deflection``."""
        thrust = model.structure.thrust
        return dict(thrust_t0=thrust.t0,
                    thrust_t1=thrust.t1 if model.terms.thrust_follows_deflection else np.zeros_like(thrust.t1))


THRUST_T0, THRUST_T1 = ThrustData.index["thrust_t0"], ThrustData.index["thrust_t1"]


@kernel
def thrust_force(F, I, q, u, f):
    """f += Q_T = T_e (t0 + t1 q) (eqs. 17-24); q (nq,) [m], u (4,) with u[0] = T_e [N]; f (n_v,) in place."""
    if u[0] == 0.0:
        return
    t0 = _f1(F, I, THRUST_T0)
    t1 = _f2(F, I, THRUST_T1)
    nq = q.shape[0]
    for i in range(f.shape[0]):
        acc = t0[i]
        for k in range(nq):
            acc += t1[i, k] * q[k]
        f[i] += u[0] * acc
