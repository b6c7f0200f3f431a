"""Calibration of an aircraft's uncertain structural data: stiffness and mass scales per component.

The notional GTM (``flexsim/aircraft/data/gtm.md``) is assembled from public data; its stiffness
distributions are thin-box estimates and its gross mass is uncertain (100-157 t). :class:`StructuralScaling`
is the set of dimensionless factors the calibration against the paper's Table 3 adjusts
(``studies/calibrate_gtm.py``, ``docs/calibration.md``);
:meth:`StructuralScaling.apply` returns a new :class:`~flexsim.aircraft.definition.Aircraft` whose
section tables (and masses) are multiplied by them. Geometry and aerodynamics do not change.

Each factor is validated on construction against the bounds stated in :data:`BOUNDS` (the physically
plausible range argued in ``docs/calibration.md``); a value outside raises ``ValueError`` naming the
field, the value and the range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

from flexsim.aircraft.definition import Aircraft, Component, LumpedMass

__all__ = ["StructuralScaling", "BOUNDS"]

#: Allowed range of each factor [-] (see docs/calibration.md for the argument behind each bound).
BOUNDS: dict[str, tuple[float, float]] = {
    "wing_ei": (0.5, 2.0),
    "wing_gj": (0.1, 2.0),
    "fuselage_ei": (0.5, 2.0),
    "fuselage_gj": (0.5, 2.0),
    "htail_stiffness": (0.5, 3.0),
    "vtail_stiffness": (0.5, 3.0),
    "mass": (1.0, 1.574),
}

_WINGS = ("right_wing", "left_wing")
_HTAILS = ("right_htail", "left_htail")


@dataclass(frozen=True)
class StructuralScaling:
    """Dimensionless multipliers of the section stiffness tables (1 = the file's values).

    Attributes
    ----------
    wing_ei, wing_gj : float
        Factors on EI and GJ [-] of both wing halves (symmetric aircraft).
    fuselage_ei, fuselage_gj : float
        Factors on the fuselage's EI (both bending planes) and GJ [-].
    htail_stiffness : float
        Factor on EI and GJ of both horizontal-stabilizer halves [-].
    vtail_stiffness : float
        Factor on EI and GJ of the vertical stabilizer [-].
    mass : float
        Factor on every mass and inertia (section tables, lumped masses, engines) and, with them, on every
        EI and GJ [-] (on top of the factors above), so that the natural frequencies do not change: the
        research note's option A (1, 100 t, a 757 in mid-cruise) to option B (1.574, 157.4 t, the
        sub-scale T2's weight scaled by the cube of the length ratio), gtm-notional.md item 4.
    """

    wing_ei: float = 1.0
    wing_gj: float = 1.0
    fuselage_ei: float = 1.0
    fuselage_gj: float = 1.0
    htail_stiffness: float = 1.0
    vtail_stiffness: float = 1.0
    mass: float = 1.0

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            lo, hi = BOUNDS[f.name]
            try:
                v = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"StructuralScaling.{f.name} = {value!r}: must be a number in [{lo}, {hi}]") from None
            if not (math.isfinite(v) and lo <= v <= hi):
                raise ValueError(f"StructuralScaling.{f.name} = {value!r}: must be in [{lo}, {hi}] (docs/calibration.md)")
            object.__setattr__(self, f.name, v)

    def factors(self, component: str) -> tuple[float, float]:
        """(EI factor, GJ factor) [-] for the component named ``component``, the mass factor included."""
        k = self.mass
        if component in _WINGS:
            return k * self.wing_ei, k * self.wing_gj
        if component == "fuselage":
            return k * self.fuselage_ei, k * self.fuselage_gj
        if component in _HTAILS:
            return k * self.htail_stiffness, k * self.htail_stiffness
        if component == "vtail":
            return k * self.vtail_stiffness, k * self.vtail_stiffness
        return k, k

    def apply(self, aircraft: Aircraft) -> Aircraft:
        """A copy of ``aircraft`` with its stiffness (and, for ``mass`` != 1, mass) tables multiplied."""
        k = self.mass

        def scaled(c: Component) -> Component:
            k_ei, k_gj = self.factors(c.name)
            s = c.sections
            return replace(c, sections=replace(s, ei_nm2=s.ei_nm2 * k_ei, gj_nm2=s.gj_nm2 * k_gj, mass_kg_per_m=s.mass_kg_per_m * k,
                                               torsional_inertia_kg_m=s.torsional_inertia_kg_m * k))

        def heavier(m: LumpedMass) -> LumpedMass:
            return m if k == 1.0 else replace(m, mass_kg=m.mass_kg * k, inertia_kg_m2=m.inertia_kg_m2 * k)

        return replace(aircraft, components=tuple(scaled(c) for c in aircraft.components),
                       lumped_masses=tuple(heavier(m) for m in aircraft.lumped_masses),
                       engines=tuple(heavier(e) for e in aircraft.engines))
