"""Elasticity and structural damping: their data and generalized forces (paper eqs. 14-16), compiled.

Tuzcu & Nguyen (2014) eqs. (14)-(16): the strain energy V = 1/2 (q^T K q + xi^T K~ xi) of the bending coordinates
q [m] and torsion coordinates xi [rad] gives the generalized force -K [0, 0, q, xi]; the optional modal damping of
the clamped elastic modes (not in the paper, :meth:`flexsim.structure.model.StructuralModel.damping`) adds
-C_el [s, eta]. Velocities V = [v, omega, s, eta]; SI units.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexsim._kernels.layout import _f2, _flag, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class ElasticityData:
    """Stiffness and damping of the elastic coordinates."""

    k_bending: np.ndarray = packed(2, "K (nq, nq): bending stiffness [N/m] (eq. 15)")
    k_torsion: np.ndarray = packed(2, "K~ (nxi, nxi): torsion stiffness [N m/rad] (eq. 15)")
    c_el: np.ndarray = packed(2, "C_el (n_el, n_el): modal damping of the clamped elastic modes [N s/m, N m s/rad]")
    has_damping: int = packed(0, "1 with structural damping (C_el applied)", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): the stiffness of its structure
        and C_el of its damping ratio (``terms.structural_damping``, else the aircraft's; 0: none)."""
        st = model.structure
        zeta = model.terms.structural_damping
        if zeta is None:
            zeta = model.aircraft.structural_damping_ratio
        n_el = st.dofs.nq + st.dofs.nxi
        return dict(k_bending=st.k_bending, k_torsion=st.k_torsion,
                    c_el=st.damping(float(zeta)) if zeta else np.zeros((n_el, n_el)), has_damping=bool(zeta))


K_BENDING, K_TORSION, C_EL = (ElasticityData.index[n] for n in ("k_bending", "k_torsion", "c_el"))
HAS_DAMPING = ElasticityData.index["has_damping"]


@kernel
def elastic_force(F, I, q, xi, vel, f):
    """f += -K [0, 0, q, xi] - C_el [0, 0, s, eta] (eqs. 14-16); q (nq,) [m], xi (nxi,) [rad], vel (n_v,) V;
    f (n_v,) in place."""
    nq, nxi = q.shape[0], xi.shape[0]
    k_b = _f2(F, I, K_BENDING)
    k_t = _f2(F, I, K_TORSION)
    for i in range(nq):
        acc = 0.0
        for k in range(nq):
            acc += k_b[i, k] * q[k]
        f[6 + i] -= acc
    for i in range(nxi):
        acc = 0.0
        for k in range(nxi):
            acc += k_t[i, k] * xi[k]
        f[6 + nq + i] -= acc
    if _flag(I, HAS_DAMPING):
        c_el = _f2(F, I, C_EL)
        n_el = vel.shape[0] - 6
        for i in range(n_el):
            acc = 0.0
            for k in range(n_el):
                acc += c_el[i, k] * vel[6 + k]
            f[6 + i] -= acc
