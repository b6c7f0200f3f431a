"""Engine gyroscopic moment: its data and its generalized force, compiled (not in the paper).

The spinning rotors of the engines carry an angular momentum h_e relative to the airframe. Euler's law in body
axes, which rotate with omega, dH/dt|_body + omega x H = M with H = I omega + h_e: with h_e constant in body axes
(the engine speed held, the mounts' elastic rotation neglected) the rotors add omega x h_e to the left-hand side
(Etkin & Reid, *Dynamics of Flight: Stability and Control*, 3rd ed., 1996, ch. 4, the rotors' angular momentum h'
in the body-axis moment equations), i.e. the generalized force

    Q_gyro = [0; -omega x h_e; 0]    on the rows of omega, [N m],

which does no work (omega . (omega x h_e) = 0): it couples pitch and yaw without changing the energy. h_e [kg m^2/s]
in body axes (x forward, y right, z down), e.g. n engines of polar inertia J spinning at Omega about +x:
h_e = (n J Omega, 0, 0). Chosen at model construction (:attr:`flexsim.model.terms.Terms.engine_angular_momentum`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexsim._kernels.layout import _f1, _flag, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class GyroscopicData:
    """The engines' rotor angular momentum (:attr:`flexsim.model.terms.Terms.engine_angular_momentum`)."""

    engine_h: np.ndarray = packed(1, "h_e (3,): rotor angular momentum of all engines, body axes [kg m^2/s]")
    has_gyroscopic: int = packed(0, "1 with a rotor angular momentum", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): h_e from its terms."""
        h = model.terms.engine_angular_momentum
        return dict(engine_h=np.zeros(3) if h is None else np.asarray(h, float), has_gyroscopic=h is not None)


ENGINE_H = GyroscopicData.index["engine_h"]
HAS_GYROSCOPIC = GyroscopicData.index["has_gyroscopic"]


@kernel
def gyroscopic_force(F, I, vel, f):
    """f[3:6] += -omega x h_e (module docstring); vel (n_v,) V = [v, omega, s, eta] [m/s, rad/s]; f (n_v,) in place."""
    if not _flag(I, HAS_GYROSCOPIC):
        return
    h = _f1(F, I, ENGINE_H)
    p, q, r = vel[3], vel[4], vel[5]
    f[3] -= q * h[2] - r * h[1]
    f[4] -= r * h[0] - p * h[2]
    f[5] -= p * h[1] - q * h[0]
