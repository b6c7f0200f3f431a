"""The wing's downwash at the horizontal tail: its data and the tail strips' velocity change, compiled (not in the
paper).

Source: USAF DATCOM sec. 4.4.1 (Hoak et al. 1978): d epsilon/d alpha at Mach M is the incompressible gradient
times CL_alpha,w(M) / CL_alpha,w(0); the downwash follows the circulation the wing carries
(:func:`flexsim.model.coupling.tail_downwash`). Quasi-steady: the wake's travel time to the tail is neglected.
Body axes, SI units.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexsim._kernels.layout import _f1, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class DownwashData:
    """The wing's downwash at the horizontal tail (USAF DATCOM sec. 4.4.1; :func:`tail_downwash`; not in the paper)."""

    downwash_gradient: np.ndarray = packed(1, "[(d epsilon / d alpha) at M -> 0] (1,) [-] (0: none)")
    dw_wing_weight: np.ndarray = packed(1, "Cl_a0 b w of each wing strip over their sum, 0 elsewhere (n_s,) [-]")
    dw_tail_nz: np.ndarray = packed(1, "n . z_body of the tail strips, 0 elsewhere (n_s,) [-]")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): the gradient and the wing's
        and tail's strip weights of its strip coupling (``model.aero``); no downwash without aerodynamics."""
        a = model.aero
        if a is None:
            return dict(downwash_gradient=[0.0])
        return dict(downwash_gradient=[a.downwash_gradient], dw_wing_weight=a.dw_wing_weight, dw_tail_nz=a.dw_tail_nz)


DOWNWASH_GRADIENT = DownwashData.index["downwash_gradient"]
DW_WING_WEIGHT = DownwashData.index["dw_wing_weight"]
DW_TAIL_NZ = DownwashData.index["dw_tail_nz"]


@kernel
def tail_downwash(wing_weight, u0, wc, speed, beta, gradient):
    """Downwash angle epsilon [rad] of the wing at the horizontal tail (not in the paper;
    :func:`flexsim.model.coupling.tail_downwash`): epsilon = (d epsilon/d alpha)_0 L_w / L_alpha0,w =
    gradient sum_j weight_j u0_j wc_j / (beta max(V, 1)^2) (USAF DATCOM sec. 4.4.1 compressibility scaling)."""
    acc = 0.0
    for j in range(u0.shape[0]):
        acc += wing_weight[j] * (u0[j] * wc[j])
    return gradient * acc / (beta * max(speed, 1.0) ** 2)


@kernel
def has_downwash(F, I):
    """Whether the model has a downwash gradient (0: the tail sees the free stream, as in the paper)."""
    return _f1(F, I, DOWNWASH_GRADIENT)[0] != 0.0


@kernel
def downwash_velocity(F, I, u0, wc, speed, beta):
    """Change of the tail strips' normal velocity relative to the air, (n_s,) [m/s]: -epsilon V (n . z_b), epsilon
    from :func:`tail_downwash` at flight speed V = ``speed`` [m/s] and compressibility factor ``beta``."""
    n_s = u0.shape[0]
    out = np.zeros(n_s)
    eps = tail_downwash(_f1(F, I, DW_WING_WEIGHT), u0, wc, speed, beta, _f1(F, I, DOWNWASH_GRADIENT)[0])
    nz = _f1(F, I, DW_TAIL_NZ)
    for j in range(n_s):
        out[j] = -eps * speed * nz[j]
    return out
