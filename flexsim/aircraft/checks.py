"""Validation helpers of the aircraft definition: plausible ranges and checks that raise
:class:`~flexsim.errors.AircraftDefinitionError` naming the field, the value and what is allowed.

Shared by :mod:`flexsim.aircraft.definition` and :mod:`flexsim.aircraft.sections` (split from the definition
module to keep modules under ~800 lines).
"""

from __future__ import annotations

import numpy as np

from flexsim.errors import AircraftDefinitionError

__all__ = ["PLAUSIBLE", "MAX_STATIONS"]

#: Plausible ranges of the definition's quantities (SI), checked on construction. They bound every
#: aircraft from a model glider to the largest transport (An-225: 84 m long, 88 m span, 640 t) with a
#: margin, so that unit mistakes (millimetres, N mm^2, grams) and typing slips (1e30) are caught with a
#: message instead of producing absurd frequencies or inertias. Name -> (low, high, unit).
PLAUSIBLE = {
    "length_m": (0.05, 150.0, "m"),
    "mass_kg_per_m": (0.0, 1.0e5, "kg/m"),
    "torsional_inertia_kg_m": (0.0, 1.0e5, "kg m^2/m"),
    "ei_nm2": (1.0, 1.0e12, "N m^2"),
    "gj_nm2": (1.0, 1.0e12, "N m^2"),
    "ei_chord_nm2": (1.0, 1.0e13, "N m^2"),
    "ea_n": (1.0, 1.0e13, "N"),
    "chord_m": (0.0, 50.0, "m"),
    "position_m": (-500.0, 500.0, "m"),
    "euler_rad": (-2.0 * np.pi, 2.0 * np.pi, "rad (+-360 deg)"),
    "mass_kg": (0.0, 1.0e6, "kg"),
    "inertia_kg_m2": (0.0, 1.0e9, "kg m^2"),
    "max_thrust_n": (0.0, 2.0e6, "N"),
    "total_mass_kg": (0.0, 2.0e6, "kg"),
    "elastic_frequency_rad_s": (0.1, 1.0e5, "rad/s"),
}
#: Largest number of stations in one section table (a few hundred describe any beam).
MAX_STATIONS = 10_000


def _in_plausible(where: str, arr: np.ndarray, key: str, lo_open: bool = False) -> None:
    """Raise AircraftDefinitionError naming the first entry of ``arr`` outside ``PLAUSIBLE[key]``."""
    lo, hi, unit = PLAUSIBLE[key]
    a = np.atleast_1d(np.asarray(arr, float))
    ok = ((a > lo) if lo_open else (a >= lo)) & (a <= hi)
    bad = np.flatnonzero(~ok.ravel())
    if bad.size:
        i = int(bad[0])
        index = "" if np.ndim(arr) == 0 else f"[{', '.join(map(str, np.unravel_index(i, a.shape)))}]"
        bracket = "(" if lo_open else "["
        _fail(f"{where}{index}", float(a.ravel()[i]),
              f"outside the plausible range {bracket}{lo:g}, {hi:g}] {unit} (check the units)")


def _plain(value: object) -> object:
    """numpy values as plain Python numbers/lists, so messages read ``[1.5, 1.4]``."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value



def _fail(where: str, value: object, allowed: str) -> None:
    raise AircraftDefinitionError(f"{where} = {_plain(value)!r}: {allowed}")


def _frozen_array(where: str, value: object, shape: tuple[int, ...] | None = None) -> np.ndarray:
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        _fail(where, value, "must be a number or an array of numbers")
    if shape is not None and arr.shape != shape:
        _fail(where, value, f"must have shape {shape}")
    if not np.all(np.isfinite(arr)):
        _fail(where, value, "must be finite")
    arr.setflags(write=False)
    return arr


def _check_scalar(where: str, value: object, lo: float, hi: float, lo_open: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        _fail(where, value, "must be a number")
    v = float(value)
    ok = (v > lo if lo_open else v >= lo) and v <= hi and np.isfinite(v)
    if not ok:
        bracket = "(" if lo_open else "["
        _fail(where, value, f"must be in {bracket}{lo}, {hi}]")
    return v

