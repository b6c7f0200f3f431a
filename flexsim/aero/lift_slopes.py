"""Sectional lift-curve slopes of the aircraft's strips from a vortex lattice of wing + stabilizer.

Source: Tuzcu & Nguyen (2014), "Numerical Model": Cl_alpha of each strip from a vortex-lattice model of
wing + horizontal stabilizer (Fig. 5-6); the fin is not in the lattice. Geometry only (the aircraft
definition), no structure: the strips themselves are built in :mod:`flexsim.model.strips`.
"""

from __future__ import annotations

import functools

import numpy as np

from flexsim.aero.vlm import LiftingSurface, VlmResult, solve_vlm
from flexsim.aircraft.definition import Aircraft, ContentKey
from flexsim.errors import AircraftDefinitionError

__all__ = ["vlm_surfaces", "strip_lift_slopes", "exposed_lift_slope"]

_BODY_TO_VLM = np.array([-1.0, 1.0, -1.0])
#: A half whose root leading edge is this close to y = 0 [m] is rooted on the centreline (rounding of the direction
#: cosines of its axes: 1e-16 m for a 1 m chord; any real offset of a root from the centreline is millimetres or more).
_ON_CENTRELINE_M = 1e-9


def vlm_surfaces(aircraft: Aircraft) -> tuple[LiftingSurface, ...]:
    """Vortex-lattice surfaces of the wing and horizontal-stabilizer halves (paper Fig. 5).

    Each half follows its elastic axis and streamwise chords (leading edge at ea_fraction * chord ahead of
    the axis) at the section-table stations, and is extended inboard to the centreline with its root
    chord to carry the lift across the fuselage; a half rooted on the centreline (y = 0, a wing continuous
    through it, as the PHC HALE's) is not extended. Coordinates: VLM frame (x aft, y right, z up).
    """
    out = []
    for comp in aircraft.components:
        if comp.aero is None or comp.name == "vtail":
            continue
        s = comp.sections.station_m
        axes = comp.axes_in_body
        ea = comp.root_m[None, :] + s[:, None] * axes[:, 0][None, :]
        chord_b = axes @ comp.chord_direction  # chord direction in body axes
        le = ea - (comp.sections.ea_fraction * comp.sections.chord_m)[:, None] * chord_b[None, :]
        le = le * _BODY_TO_VLM
        chord = comp.sections.chord_m.copy()
        if abs(le[0, 1]) <= _ON_CENTRELINE_M:  # rooted on the centreline (a continuous wing): no extension
            le[0, 1] = 0.0  # (the root's y is a round-off of the axes' cosines there)
        else:
            root = le[0].copy()
            root[1] = 0.0
            le = np.vstack([root, le])
            chord = np.concatenate([[chord[0]], chord])
        if le[-1, 1] < 0:  # left half: sections must run with increasing y
            le, chord = le[::-1], chord[::-1]
        if np.any(np.diff(le[:, 1]) <= 0.0):
            raise AircraftDefinitionError(
                f"components.{comp.name}.root_m = {comp.root_m.tolist()} (body axes): the half's leading edge runs "
                f"from y = {le[0, 1]:.6g} m to {le[-1, 1]:.6g} m but not monotonically away from the centreline; "
                f"a wing or stabilizer half must lie on one side of y = 0 (a continuous wing is two halves rooted "
                f"at y = 0)")
        n_seg = le.shape[0] - 1
        per_seg = max(1, int(np.ceil(36 / n_seg)))
        try:
            out.append(LiftingSurface(comp.name, le, chord, n_chordwise=4, n_spanwise=per_seg))
        except ValueError as exc:  # a planform the lattice cannot take: name the component and the way out
            raise AircraftDefinitionError(
                f"components.{comp.name}: the vortex lattice of the lift slopes (lift_slope = \"vlm\" on a wing or "
                f"stabilizer) cannot model its planform: {exc}; give every surface's aero.lift_slope as \"2pi\" or a "
                f"number") from None
    return tuple(out)


def strip_lift_slopes(aircraft: Aircraft, components: tuple[str, ...], position_body_m: np.ndarray) -> np.ndarray:
    """Incompressible sectional Cl_alpha [1/rad] at strip points from the wing + stabilizer VLM.

    Parameters
    ----------
    aircraft : Aircraft
    components : tuple of str, length n_s
    position_body_m : ndarray, shape (n_s, 3)
        Strip elastic-axis points, body axes [m] (their y locates the streamwise strip).

    Returns
    -------
    ndarray, shape (n_s,)
        NaN for strips of components not in the lattice (the fin).
    """
    result = _incompressible_vlm(aircraft.content_key())
    out = np.full(len(components), np.nan)
    names = {s.name for s in result.surfaces}
    comp = np.array(components)
    for name in names:
        idx = np.flatnonzero(comp == name)
        out[idx] = result.surface(name).lift_slope_at(position_body_m[idx, 1])
    return out


def exposed_lift_slope(aircraft: Aircraft, result: VlmResult) -> float:
    """Lift-curve slope dCL/dalpha [1/rad] of a lattice solution on its exposed surfaces, on ``result.s_ref_m2``.

    The lattice of :func:`vlm_surfaces` runs to the centreline; the strips cover only the exposed surfaces,
    outboard of each component's root (paper: no fuselage aerodynamics). This sums the sectional lift of the
    lattice's strips there, sum(cl_alpha c dy cos(Gamma)) / S_ref, for a like-for-like comparison with the strips.

    Parameters
    ----------
    aircraft : Aircraft
        The aircraft whose ``vlm_surfaces`` ``result`` solved.
    result : VlmResult
        A :func:`flexsim.aero.vlm.solve_vlm` solution of ``vlm_surfaces(aircraft)``.
    """
    total_m2 = 0.0
    for surf in result.surfaces:
        root_y = abs(aircraft.component(surf.name).root_m[1])
        outboard = np.abs(surf.y_m) >= root_y
        total_m2 += float(np.sum((surf.cl_alpha_per_rad * surf.chord_m * surf.width_m * np.cos(surf.dihedral_rad))[outboard]))
    return total_m2 / result.s_ref_m2


@functools.lru_cache(maxsize=8)
def _incompressible_vlm(key: ContentKey) -> VlmResult:
    """The M = 0 lattice solution of an aircraft, cached by its content: every model of one aircraft (a flutter
    analysis builds two or three) shares one solve (0.2-0.45 s each)."""
    return solve_vlm(vlm_surfaces(key.aircraft), mach=0.0)
