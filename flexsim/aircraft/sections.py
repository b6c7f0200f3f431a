"""Section tables of a beam: spanwise (or lengthwise) section properties, linear between stations.

Part of the aircraft definition (:mod:`flexsim.aircraft.definition` re-exports :class:`SectionTable`), split from
that module to keep modules under ~800 lines. SI units, body-axes conventions and validation as there.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from flexsim.aircraft.checks import MAX_STATIONS, _fail, _frozen_array, _in_plausible
from flexsim.errors import AircraftDefinitionError

__all__ = ["SectionTable", "NONLINEAR_BEAM_FIELDS"]

#: Optional section fields that only the geometrically nonlinear beam uses (docs/nonlinear-beams.md): the
#: linear structure (the paper's, eq. 14) bends each beam in one plane and twists it, so it has no use for them.
#: Name -> what it is.
NONLINEAR_BEAM_FIELDS = {
    "ei_chord_nm2": "chordwise (in-plane, edgewise) bending stiffness",
    "ea_n": "extension stiffness",
    "flap_inertia_kg_m": "rotary inertia about the chordwise axis",
}


@dataclass(frozen=True, eq=False)
class SectionTable:
    """Spanwise (or lengthwise) tables of a beam's section properties, linear between stations.

    Attributes
    ----------
    station_m : ndarray, shape (k,)
        Stations x_i along the elastic axis, strictly increasing from 0 (root) to the length [m].
    mass_kg_per_m : ndarray, shape (k,)
        Mass per unit length [kg/m], >= 0.
    cg_offset_m : ndarray, shape (k,)
        Offset of the section centre of mass from the elastic axis along the streamwise chord, positive
        towards the trailing edge [m] (Theodorsen's x_theta * b). Must be 0 for a component without chord.
    torsional_inertia_kg_m : ndarray, shape (k,)
        Mass moment of inertia per unit length about the elastic axis [kg m^2/m]; must be at least
        mass * cg_offset^2 (it includes the offset by the parallel-axis theorem).
    ei_nm2 : ndarray, shape (k,)
        Bending rigidity EI_i for bending along z_i [N m^2] (paper eq. 14).
    gj_nm2 : ndarray, shape (k,)
        Torsional rigidity GJ_i [N m^2] (paper eq. 14).
    chord_m : ndarray, shape (k,)
        Streamwise chord of the section through the station [m] (0 for the fuselage).
    ea_fraction : ndarray, shape (k,)
        Elastic-axis position aft of the leading edge as a fraction of the chord [-]; Theodorsen's
        a = 2 ea_fraction - 1 (bundled GTM wing and stabilizer: ea_fraction = 0.375, a = -0.25; see
        ``docs/calibration.md`` section 1).
    ei_chord_nm2 : ndarray, shape (k,), or None
        Chordwise (in-plane, edgewise) bending rigidity EI_chord, for bending in the plane of the chord
        (about the section's normal axis) [N m^2], > 0. Optional (None: not given); used by the geometrically
        nonlinear beam only (:data:`NONLINEAR_BEAM_FIELDS`).
    ea_n : ndarray, shape (k,), or None
        Extension rigidity EA [N], > 0. Optional (None: not given, an inextensible beam); used by the
        geometrically nonlinear beam only.
    flap_inertia_kg_m : ndarray, shape (k,), or None
        Mass moment of inertia per unit length about the chordwise axis through the elastic axis [kg m^2/m]
        (the rotary inertia of flapwise bending). Optional (None: not given); used by the geometrically
        nonlinear beam only. The section is thin in span, so by the perpendicular-axis theorem the inertia about
        its normal axis is ``torsional_inertia_kg_m - flap_inertia_kg_m``; hence 0 <= flap_inertia_kg_m <=
        torsional_inertia_kg_m - mass_kg_per_m * cg_offset_m^2 (the normal-axis inertia about the centre of mass
        is not negative).
    """

    station_m: np.ndarray
    mass_kg_per_m: np.ndarray
    cg_offset_m: np.ndarray
    torsional_inertia_kg_m: np.ndarray
    ei_nm2: np.ndarray
    gj_nm2: np.ndarray
    chord_m: np.ndarray
    ea_fraction: np.ndarray
    ei_chord_nm2: np.ndarray | None = None
    ea_n: np.ndarray | None = None
    flap_inertia_kg_m: np.ndarray | None = None
    where: str = field(default="sections", repr=False)

    def __post_init__(self) -> None:
        w = self.where
        names = (
            "station_m",
            "mass_kg_per_m",
            "cg_offset_m",
            "torsional_inertia_kg_m",
            "ei_nm2",
            "gj_nm2",
            "chord_m",
            "ea_fraction",
        )
        arrays = {}
        names = names + tuple(name for name in NONLINEAR_BEAM_FIELDS if getattr(self, name) is not None)
        for name in names:
            arr = _frozen_array(f"{w}.{name}", getattr(self, name))
            if arr.ndim != 1:
                _fail(f"{w}.{name}", getattr(self, name), "must be a 1-D list of numbers")
            arrays[name] = arr
        k = arrays["station_m"].size
        if k > MAX_STATIONS:
            raise AircraftDefinitionError(f"{w}.station_m: {k} stations: at most {MAX_STATIONS} are allowed")
        if k < 2:
            _fail(f"{w}.station_m", getattr(self, "station_m"), "needs at least two stations (root and tip)")
        for name, arr in arrays.items():
            if arr.size != k:
                _fail(f"{w}.{name}", list(arr), f"must have {k} entries, one per station")
        st = arrays["station_m"]
        if st[0] != 0.0:
            _fail(f"{w}.station_m[0]", st[0], "must be 0 (the root)")
        bad = np.flatnonzero(np.diff(st) <= 0.0)
        if bad.size:
            i = int(bad[0]) + 1
            _fail(f"{w}.station_m[{i}]", float(st[i]), f"must be > station_m[{i - 1}] = {st[i - 1]} (strictly increasing)")
        for name, lo in (("mass_kg_per_m", 0.0), ("torsional_inertia_kg_m", 0.0), ("chord_m", 0.0)):
            bad = np.flatnonzero(arrays[name] < lo)
            if bad.size:
                i = int(bad[0])
                _fail(f"{w}.{name}[{i}]", float(arrays[name][i]), f"must be >= {lo}")
        for name in ("ei_nm2", "gj_nm2", "ei_chord_nm2", "ea_n"):
            if name not in arrays:
                continue
            bad = np.flatnonzero(arrays[name] <= 0.0)
            if bad.size:
                i = int(bad[0])
                _fail(f"{w}.{name}[{i}]", float(arrays[name][i]), "must be > 0")
        for name in ("mass_kg_per_m", "torsional_inertia_kg_m", "ei_nm2", "gj_nm2", "chord_m", "ei_chord_nm2", "ea_n"):
            if name in arrays:
                _in_plausible(f"{w}.{name}", arrays[name], name)
        _in_plausible(f"{w}.station_m[-1] (length)", st[-1], "length_m")
        ea = arrays["ea_fraction"]
        bad = np.flatnonzero((ea < 0.0) | (ea > 1.0))
        if bad.size:
            i = int(bad[0])
            _fail(f"{w}.ea_fraction[{i}]", float(ea[i]), "must be in [0, 1]")
        m, e, ith = arrays["mass_kg_per_m"], arrays["cg_offset_m"], arrays["torsional_inertia_kg_m"]
        bad = np.flatnonzero(np.abs(e) > arrays["chord_m"] + 1e-12)
        bad = bad[arrays["chord_m"][bad] > 0.0]
        if bad.size:
            i = int(bad[0])
            _fail(f"{w}.cg_offset_m[{i}]", float(e[i]), f"must be within one chord of the elastic axis (|cg_offset_m| <= chord_m = {arrays['chord_m'][i]:g} m)")
        chordless = arrays["chord_m"] == 0.0
        bad = np.flatnonzero(chordless & (e != 0.0))
        if bad.size:
            i = int(bad[0])
            _fail(f"{w}.cg_offset_m[{i}]", float(e[i]), "must be 0 where chord_m is 0 (no chordwise direction)")
        need = m * e**2
        bad = np.flatnonzero(ith < need * (1.0 - 1e-9))
        if bad.size:
            i = int(bad[0])
            _fail(
                f"{w}.torsional_inertia_kg_m[{i}]",
                float(ith[i]),
                f"must be >= mass_kg_per_m * cg_offset_m^2 = {need[i]:.6g} (inertia about the elastic axis)",
            )
        if "flap_inertia_kg_m" in arrays:
            flap = arrays["flap_inertia_kg_m"]
            bad = np.flatnonzero(flap < 0.0)
            if bad.size:
                i = int(bad[0])
                _fail(f"{w}.flap_inertia_kg_m[{i}]", float(flap[i]), "must be >= 0")
            room = ith - need
            bad = np.flatnonzero(flap > room + 1e-9 * np.maximum(ith, 1e-300))
            if bad.size:
                i = int(bad[0])
                _fail(f"{w}.flap_inertia_kg_m[{i}]", float(flap[i]),
                      f"must be <= torsional_inertia_kg_m - mass_kg_per_m * cg_offset_m^2 = {room[i]:.6g} (the rest, "
                      f"torsional_inertia_kg_m - flap_inertia_kg_m, is the inertia about the section's normal axis, "
                      f"perpendicular-axis theorem)")
        for name, arr in arrays.items():
            object.__setattr__(self, name, arr)

    @property
    def nonlinear_beam_fields(self) -> tuple[str, ...]:
        """Names of the optional fields given (:data:`NONLINEAR_BEAM_FIELDS`) that only the geometrically
        nonlinear beam uses; empty for a table of the paper's fields only."""
        return tuple(name for name in NONLINEAR_BEAM_FIELDS if getattr(self, name) is not None)

    @property
    def length_m(self) -> float:
        """Beam length L_i [m] (the last station)."""
        return float(self.station_m[-1])

    def at(self, name: str, x: np.ndarray) -> np.ndarray:
        """Property ``name`` interpolated linearly at stations ``x`` [m] (shape (k,) -> (k,))."""
        return np.interp(x, self.station_m, getattr(self, name))
