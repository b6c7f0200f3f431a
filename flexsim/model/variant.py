"""The variant of a model: which degrees of freedom are free, and where a restrained structure sits (one frozen object).

A model (:class:`flexsim.model.aircraft_model.AircraftModel`) is one value: the aircraft, its physical terms
(:class:`flexsim.model.terms.Terms`) and its variant, :class:`VariantSettings`. The variant says which degrees of
freedom are integrated (docs/design.md, "Model variants") and, for a restrained aircraft, the wind tunnel it sits in
(attitude, stream velocity, altitude, density); for a quasi-rigid one, the values of its frozen elastic coordinates.
Shapes that depend on the aircraft (``frozen_q``, ``frozen_xi``) are checked when a model is built.

Example::

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.model.variant import VariantSettings

    wing = load_aircraft("goland_wing")
    tunnel = VariantSettings("restrained", restrained_velocity_m_s=(120.0, 0.0, 0.0), air_density_kg_m3=1.02)
    model = AircraftModel(wing, aero="quasi-steady", gravity_m_s2=0.0, variant=tunnel)
    print(model.variant.kind.value, model.variant.restrained_velocity_m_s)  # restrained (120.0, 0.0, 0.0)
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from enum import Enum

from flexsim.atmosphere import speed_of_sound

__all__ = ["Variant", "VariantSettings"]


class Variant(str, Enum):
    """Model variants built from one definition (docs/design.md, "Model variants").

    FREE: free-flying flexible aircraft (6 rigid-body + all elastic DOFs).
    RESTRAINED: rigid-body motion fixed, the aircraft clamped at its body origin o (ground vibration
    test; with a single-component aircraft, a clamped wing).
    QUASI_RIGID: elastic coordinates frozen at given values, rigid-body DOFs free.
    """

    FREE = "free"
    RESTRAINED = "restrained"
    QUASI_RIGID = "quasi-rigid"


def _vector(name: str, value, length: int | None) -> tuple[float, ...] | None:
    if value is None:
        return None
    try:
        out = tuple(float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be a sequence of numbers (or None)") from None
    if length is not None and len(out) != length:
        raise ValueError(f"{name} = {value!r}: must have {length} entries")
    if not all(math.isfinite(v) for v in out):
        raise ValueError(f"{name} = {value!r}: every entry must be finite")
    return out


@dataclass(frozen=True)
class VariantSettings:
    """The variant of a model and the options that belong to it (validated on construction, errors name the field).

    Attributes
    ----------
    kind : Variant or str
        ``"free"`` (default), ``"restrained"`` or ``"quasi-rigid"`` (:class:`Variant`).
    restrained_euler_rad : tuple of 3 float or None
        Attitude [phi, theta, psi] of a restrained aircraft [rad] (sets the direction of gravity); None: zero.
    restrained_velocity_m_s : tuple of 3 float or None
        Body-axes velocity [m/s] of a restrained aircraft: the air flows past the clamped structure at minus this
        velocity (a wind tunnel). None: zero (still air).
    altitude_m : float
        Altitude of a restrained aircraft [m] (air density and speed of sound; ISA range). A free aircraft uses its
        own altitude -Z. Default 0.
    air_density_kg_m3 : float or None
        Air density of a restrained aircraft [kg/m^3], in (0, 10], instead of the ISA density at ``altitude_m`` (a
        wind tunnel at a given density; the speed of sound stays ISA's at ``altitude_m``). Restrained variant only.
    frozen_q, frozen_xi : tuple of float or None
        Values of the elastic coordinates of a quasi-rigid model [m], [rad]; None: zero. Their lengths are checked
        against the aircraft's nq and nxi when a model is built.
    """

    kind: Variant = Variant.FREE
    restrained_euler_rad: tuple[float, float, float] | None = None
    restrained_velocity_m_s: tuple[float, float, float] | None = None
    altitude_m: float = 0.0
    air_density_kg_m3: float | None = None
    frozen_q: tuple[float, ...] | None = None
    frozen_xi: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        try:
            kind = Variant(self.kind)
        except ValueError:
            raise ValueError(f"variant = {self.kind!r}: must be one of {', '.join(v.value for v in Variant)}") from None
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "restrained_euler_rad", _vector("restrained_euler_rad", self.restrained_euler_rad, 3))
        object.__setattr__(self, "restrained_velocity_m_s",
                           _vector("restrained_velocity_m_s", self.restrained_velocity_m_s, 3))
        h = self.altitude_m
        if isinstance(h, bool) or not isinstance(h, numbers.Real) or not math.isfinite(h):
            raise ValueError(f"altitude_m = {h!r}: must be a finite altitude [m]")
        object.__setattr__(self, "altitude_m", float(h))
        speed_of_sound(self.altitude_m)  # validates the ISA range with a clear message
        rho = self.air_density_kg_m3
        if rho is not None:
            if kind is not Variant.RESTRAINED:
                raise ValueError(f"air_density_kg_m3 = {rho!r}: only for the restrained variant (a wind tunnel); "
                                 "a free or quasi-rigid aircraft takes the ISA density at its own altitude")
            if isinstance(rho, bool) or not (isinstance(rho, numbers.Real) and math.isfinite(rho) and 0.0 < rho <= 10.0):
                raise ValueError(f"air_density_kg_m3 = {rho!r}: must be a density in (0, 10] kg/m^3")
            object.__setattr__(self, "air_density_kg_m3", float(rho))
        object.__setattr__(self, "frozen_q", _vector("frozen_q", self.frozen_q, None))
        object.__setattr__(self, "frozen_xi", _vector("frozen_xi", self.frozen_xi, None))

    def record(self) -> dict:
        """The variant as a JSON-ready dict (for result rows and log headers): every field by name, tuples as lists."""
        out = {}
        for name in self.__dataclass_fields__:
            v = getattr(self, name)
            out[name] = v.value if isinstance(v, Variant) else (list(v) if isinstance(v, tuple) else v)
        return out
