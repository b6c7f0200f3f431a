"""Reference geometry of an aircraft's wing: area S, span b, mean chord c_bar = S / b and mean aerodynamic chord.

The quantities that make forces and moments nondimensional (C_L = L / (q S), C_m = M / (q S c_ref)) and that
handbook derivatives are written with (USAF DATCOM, Hoak et al. 1978, sec. 1.1 "reference area, reference
length"; Etkin & Reid, *Dynamics of Flight*, 3rd ed., 1996, sec. 2.3, the mean aerodynamic chord
c_bar_MAC = (1/S) integral c^2 dy over the span). Computed once from the wing's aerodynamic strips
(:class:`flexsim.model.strips.StripSet`), each a streamwise section of chord c_j = 2 b_j and spanwise width w_j
(normal to the flow), as the sums

    S = sum_j c_j w_j,   b = sum_j w_j,   c_bar = S / b,   MAC = sum_j c_j^2 w_j / sum_j c_j w_j

over the strips of the components ``right_wing`` and ``left_wing`` (the wing the file defines; a half wing alone,
e.g. a clamped wing, gives its own half). The wing's projection on the plane normal to the flow: a dihedral does
not change the strips' widths. SI units.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.model.strips import StripSet

__all__ = ["ReferenceGeometry", "WING_COMPONENTS"]

#: The components whose strips make the reference wing.
WING_COMPONENTS = ("right_wing", "left_wing")


@dataclass(frozen=True)
class ReferenceGeometry:
    """The wing's reference area, span and chords (module docstring), computed once per model.

    Attributes
    ----------
    area_m2 : float
        Reference area S [m^2].
    span_m : float
        Span b [m] (of the wing halves present).
    mean_chord_m : float
        Geometric mean chord c_bar = S / b [m].
    mac_m : float
        Mean aerodynamic chord, sum c^2 w / sum c w [m] (the length of the pitching-moment coefficient and of the
        static margin, :func:`flexsim.trimming.margin.static_margin`).
    components : tuple of str
        The wing's components whose strips were summed.
    """

    area_m2: float
    span_m: float
    mean_chord_m: float
    mac_m: float
    components: tuple[str, ...]

    def __post_init__(self) -> None:
        for name in ("area_m2", "span_m", "mean_chord_m", "mac_m"):
            value = getattr(self, name)
            if not (isinstance(value, float) and np.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} = {value!r}: must be a finite length or area > 0")

    @classmethod
    def of_strips(cls, strips: StripSet) -> "ReferenceGeometry | None":
        """The reference geometry of the wing strips of ``strips``; None when it has none (no wing component)."""
        comps = np.array(strips.component, dtype=object)
        idx = np.isin(comps, WING_COMPONENTS)
        if not idx.any():
            return None
        chord, width = 2.0 * strips.semichord_m[idx], strips.width_m[idx]
        area = float((chord * width).sum())
        span = float(width.sum())
        return cls(area_m2=area, span_m=span, mean_chord_m=area / span, mac_m=float((chord**2 * width).sum() / area),
                   components=tuple(c for c in WING_COMPONENTS if c in set(comps[idx])))
