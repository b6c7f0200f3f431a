"""Static (stick-fixed) margin of a trimmed aircraft from the model's own aerodynamic forces.

Neutral point (Etkin & Reid, *Dynamics of Flight*, 3rd ed., 1996, sec. 2.3): the point about which the
pitching moment does not change with the angle of attack. With dL and dM_cg the changes of lift and of the
pitching moment about the centre of gravity for a change of the angle of attack (central differences of the
body-axis normal velocity w at the trim, elastic coordinates and controls held), the neutral point lies
h_n - h = -dM_cg / (dL c) mean chords behind the CG; that is the static margin. Lift is the aerodynamic force
along -z of the wind axes (:class:`~flexsim.trimming.TrimPoint`). The mean aerodynamic chord is that of the
right wing's strips, c = sum(c^2 w) / sum(c w) over the exposed wing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming.solver import TrimPoint

__all__ = ["StaticMargin", "static_margin", "static_margin_of_state"]


@dataclass(frozen=True)
class StaticMargin:
    """Neutral point behind the CG [m], the mean aerodynamic chord [m] and their ratio [-]."""

    neutral_point_aft_of_cg_m: float
    mean_chord_m: float

    @property
    def fraction_of_mac(self) -> float:
        """Static margin as a fraction of the mean aerodynamic chord (positive: statically stable)."""
        return self.neutral_point_aft_of_cg_m / self.mean_chord_m


def static_margin(model: AircraftModel, point: TrimPoint, dw_m_s: float = 0.5) -> StaticMargin:
    """Static margin of ``model`` at the trim ``point`` (module docstring).

    Raises
    ------
    ValueError
        When the model has no aerodynamics or no right wing, or is not free.
    """
    margin = static_margin_of_state(model, point.x, point.u, dw_m_s)
    if margin is None:
        raise ValueError("static margin: needs a free or quasi-rigid model with aerodynamic strips on a right wing")
    return margin


def static_margin_of_state(model: AircraftModel, x0: np.ndarray, u0: np.ndarray, dw_m_s: float = 0.5) -> StaticMargin | None:
    """:func:`static_margin` at the trim state ``x0`` and controls ``u0``; None where it is not defined (no
    aerodynamics, no right wing, a restrained model)."""
    if model.aero is None or "right_wing" not in model.aero.strips.component or not model.layout.rigid:
        return None
    lay = model.layout
    cg = model.structure.mass_properties.cg_m

    def lift_and_moment(dw: float) -> tuple[float, float]:
        x = np.array(x0, dtype=float)
        x[lay.v.start + 2] += dw
        f = model.aerodynamic_force(x, u0)
        force = f[0:3]
        v = x[lay.v]
        alpha = np.arctan2(v[2], v[0])
        lift = -(force[2] * np.cos(alpha) - force[0] * np.sin(alpha))
        return float(lift), float((f[3:6] - np.cross(cg, force))[1])

    l1, m1 = lift_and_moment(dw_m_s)
    l0, m0 = lift_and_moment(-dw_m_s)
    return StaticMargin(float(-(m1 - m0) / (l1 - l0)), model.reference_geometry.mac_m)
