"""V-g / V-f diagram of a very flexible aircraft's wing about its nonlinear trim.

At each speed of a sweep the geometrically nonlinear aircraft is trimmed in the manoeuvre
(:func:`flexsim.trimming.flexible_trim.trim_flexible`) and one wing, clamped at its trimmed root, is linearised about
the deformed equilibrium (:func:`flexsim.linear.flexible_flutter.wing_system`: strain-based beam, Peters finite-state
strips, the preload's and the steady airloads' stiffness). Its oscillatory roots below ``max_frequency_rad_s`` (the
converged band, as in :func:`~flexsim.linear.flexible_flutter.wing_stability`) are continued from speed to speed by
the correlation of the velocity part ``δε̇`` of their eigenvectors (:func:`flexsim.linear.vg.track_branches`, the MAC of
Allemang & Brown 1982, as the linear model's V-g diagram), and each branch is named by the strain type that stores
most of its first root's strain energy (``½ K_kk |δε_k|²`` summed over the elements, K the beam's constant diagonal
stiffness, Su & Cesnik 2011 eq. 9: flap curvature → "bending", chord curvature → "chordwise bending", twist →
"torsion", extension → "extension"), numbered by frequency.
Crossings of Re(λ) = 0 are refined by regula falsi (Illinois) on the speed with the branch continued by MAC, to
:data:`flexsim.linear.vg.CROSSING_TOL_M_S`. The result is a :class:`flexsim.linear.vg.VgDiagram` (aerodynamic model
``"unsteady"``: Peters strips), so it is plotted and written like the linear model's. SI units, radians.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Sequence

import numpy as np

from flexsim.atmosphere import speed_of_sound
from flexsim.linear.flexible_flutter import MAX_FREQUENCY_RAD_S, NEGLECTED, wing_system
from flexsim.linear.vg import (CROSSING_ITERATIONS, CROSSING_TOL_M_S, MIN_FREQUENCY_RAD_S, MIN_MAC, VgCrossing,
                               VgDiagram, VgTrack, mac, track_branches)
from flexsim.model.aircraft_model import check_model
from flexsim.model.terms import NonlinearBeams
from flexsim.structure.strain_beam import STRAIN_NAMES, stiffness_matrix
from flexsim.trimming.flexible_trim import FlexibleTrimError, FlexibleTrimPoint, trim_flexible
from flexsim.trimming.manoeuvre import SteadyManoeuvre

__all__ = ["flexible_vg", "MODE_WORDS"]

#: The name of a branch dominated by each strain type.
MODE_WORDS = {"flap curvature": "bending", "chord curvature": "chordwise bending", "twist": "torsion",
              "extension": "extension"}


def _at(manoeuvre: SteadyManoeuvre, speed: float) -> SteadyManoeuvre:
    return SteadyManoeuvre(float(speed), manoeuvre.altitude_m, climb_angle_rad=manoeuvre.climb_angle_rad,
                           load_factor=manoeuvre.load_factor)


def _roots(model, point: FlexibleTrimPoint, component: str, inflow_states: int, max_frequency_rad_s: float):
    """Oscillatory roots (upper half-plane, MIN_FREQUENCY_RAD_S <= Im <= max) and the velocity part of their vectors."""
    system = wing_system(model, point, component, inflow_states)
    n = system.n_structural
    vals, vecs = np.linalg.eig(system.state_matrix)
    keep = (vals.imag >= MIN_FREQUENCY_RAD_S) & (vals.imag <= max_frequency_rad_s)
    return vals[keep], vecs[n:2 * n, keep], vecs[:n, keep]


def _kind(beam, strains: np.ndarray) -> str:
    """The strain type storing most of the strain energy ``½ K_kk |δε_k|²`` of a root's strains (module docstring)."""
    spe = beam.strains_per_element
    energy = np.zeros(4)
    for k, part in enumerate(np.diag(stiffness_matrix(beam)) * np.abs(strains) ** 2):
        energy[k % spe + 4 - spe] += part
    return MODE_WORDS[STRAIN_NAMES[int(np.argmax(energy))]]


def flexible_vg(model, manoeuvre: SteadyManoeuvre, speeds_m_s: Sequence[float], *, component: str = "right_wing",
                elements_per_beam: int | None = None, inflow_states: int | None = None,
                max_frequency_rad_s: float = MAX_FREQUENCY_RAD_S, refine: bool = True) -> VgDiagram:
    """The V-g / V-f diagram of ``component``'s wing about the nonlinear trim (module docstring).

    Parameters
    ----------
    model : AircraftModel
        Its flexible components need ``ei_chord_nm2``; gravity and density as in
        :func:`~flexsim.trimming.flexible_trim.trim_flexible`.
    manoeuvre : SteadyManoeuvre
        Symmetric (level, climb, pull-up); its speed is replaced by each of ``speeds_m_s``.
    speeds_m_s : sequence of float
        True airspeeds [m/s], increasing, at least 2.
    component : str
        The wing analysed.
    elements_per_beam, inflow_states : int, optional
        Default the model's ``terms.nonlinear_beams`` (8 for a model of the linear structure) and
        ``terms.aero.n_inflow``.
    max_frequency_rad_s : float
        Roots above it are left out (the discretisation's unconverged band), > 0 [rad/s].
    refine : bool
        Refine each crossing on its branch (default); False keeps the linear interpolation.

    Returns
    -------
    VgDiagram
        Tracks of kind ``"elastic"`` with aerodynamic model ``"unsteady"``; speeds that could not be trimmed in
        ``failed``; :data:`~flexsim.linear.flexible_flutter.NEGLECTED` in ``warnings``.
    """
    check_model(model, nonlinear=True)
    if model.aero is None:
        raise ValueError("the model has no aerodynamics (Terms(aero=None)): a V-g diagram needs its strips")
    speeds = np.asarray(speeds_m_s, dtype=float)
    if speeds.ndim != 1 or speeds.size < 2 or not np.all(np.isfinite(speeds)) or np.any(speeds <= 0) \
            or np.any(np.diff(speeds) <= 0):
        raise ValueError(f"speeds_m_s = {speeds_m_s!r}: must be at least 2 increasing true airspeeds > 0 [m/s]")
    if not (np.isfinite(max_frequency_rad_s) and max_frequency_rad_s > 0):
        raise ValueError(f"max_frequency_rad_s = {max_frequency_rad_s!r}: must be > 0 [rad/s]")
    beams = model.terms.nonlinear_beams or NonlinearBeams()
    if beams.stability != "clamped-wing":
        raise ValueError(f"nonlinear_beams.stability = {beams.stability!r}: the V-g diagram of the nonlinear beams "
                         "tracks the wing clamped at its trimmed root; the free aircraft's flutter is "
                         "fs.flutter(model, ...) (or stability='clamped-wing' for this diagram)")
    if elements_per_beam is not None:
        beams = replace(beams, elements_per_beam=elements_per_beam)
    inflow = model.terms.aero.n_inflow if inflow_states is None else inflow_states
    terms = replace(model.terms, nonlinear_beams=beams).record()

    points: list[FlexibleTrimPoint | None] = []
    steps, failed = [], []
    guess = None
    for v in speeds:
        try:
            point = trim_flexible(model, _at(manoeuvre, v), elements_per_beam=beams.elements_per_beam, guess=guess)
        except FlexibleTrimError as exc:
            points.append(None), steps.append((np.zeros(0, complex), np.zeros((0, 0), complex), None))
            failed.append(("unsteady", float(v), str(exc)))
            continue
        guess = point
        points.append(point), steps.append(_roots(model, point, component, inflow, max_frequency_rad_s))
    n_strains = next((p.aircraft.structure.beams[p.aircraft.beam_index(component)].n_coordinates
                      for p in points if p is not None), 0)
    strains = [d for _, _, d in steps]
    steps = [(vals, vecs if vecs.size else np.zeros((n_strains, 0), complex)) for vals, vecs, _ in steps]
    index = track_branches(steps) if n_strains else np.zeros((0, speeds.size), int)
    beam = next((p.aircraft.structure.beams[p.aircraft.beam_index(component)] for p in points if p is not None), None)

    tracks, firsts = [], []
    for row in index:
        lam = np.full(speeds.size, np.nan + 1j * np.nan)
        shapes = np.full((speeds.size, n_strains), np.nan + 1j * np.nan)
        for s, c in enumerate(row):
            if c >= 0:
                lam[s], shapes[s] = steps[s][0][c], steps[s][1][:, c]
        first = int(np.flatnonzero(row >= 0)[0])
        firsts.append((_kind(beam, strains[first][:, row[first]]), abs(lam[first].imag)))
        tracks.append((lam, shapes))
    counts: dict[str, int] = {}
    labels = [""] * len(tracks)
    for k in sorted(range(len(tracks)), key=lambda k: firsts[k][1]):
        word = firsts[k][0]
        counts[word] = counts.get(word, 0) + 1
        labels[k] = f"{component} {word} {counts[word]}"
    vg_tracks = tuple(VgTrack("unsteady", labels[k], "elastic", speeds.copy(), lam, shapes)
                      for k, (lam, shapes) in enumerate(tracks))

    a = float(speed_of_sound(float(manoeuvre.altitude_m)))
    crossings = []
    for track in vg_tracks:
        for i in track.brackets():
            crossings.append(_crossing(model, manoeuvre, track, i, points[i], component, inflow, max_frequency_rad_s,
                                       beams.elements_per_beam, a, refine))
    crossings.sort(key=lambda c: c.speed_m_s)
    kind = manoeuvre.describe().split(" at M ")[0]
    condition = f"{kind}, H = {manoeuvre.altitude_m:.0f} m; {component} clamped at the nonlinear trim's root"
    return VgDiagram(aircraft=model.aircraft.name, condition=condition, altitude_m=float(manoeuvre.altitude_m),
                     speed_of_sound_m_s=a, speeds_m_s=speeds, tracks=vg_tracks, crossings=tuple(crossings),
                     failed=tuple(failed), terms={"unsteady": terms}, warnings=(NEGLECTED,))


def _crossing(model, manoeuvre, track: VgTrack, i: int, base: FlexibleTrimPoint, component: str, inflow: int,
              max_frequency: float, elements: int, a: float, refine: bool) -> VgCrossing:
    """The crossing of ``track`` between speeds i and i + 1: regula falsi (Illinois) on the speed, the root at each new
    speed the one with the largest MAC to the branch's root at the bracket's lower end (module docstring)."""
    v0, v1 = float(track.speeds_m_s[i]), float(track.speeds_m_s[i + 1])
    l0, l1 = complex(track.eigenvalues[i]), complex(track.eigenvalues[i + 1])
    direction = "unstable" if l1.real > 0 else "stable"
    ref = track.shapes[i][:, None]
    refined = False
    speed = v0 - l0.real * (v1 - v0) / (l1.real - l0.real)
    freq = abs((l0 + (l1 - l0) * (speed - v0) / (v1 - v0)).imag)
    if refine:
        lo, hi, f_lo, f_hi, side = v0, v1, l0.real, l1.real, 0
        for _ in range(CROSSING_ITERATIONS):
            s = hi - f_hi * (hi - lo) / (f_hi - f_lo)
            try:
                point = trim_flexible(model, _at(manoeuvre, s), elements_per_beam=elements, guess=base)
            except FlexibleTrimError:
                break
            vals, vecs, _ = _roots(model, point, component, inflow, max_frequency)
            if not vals.size:
                break
            m = mac(ref, vecs)[0]
            k = int(np.argmax(m))
            if m[k] < MIN_MAC:
                break
            lam = complex(vals[k])
            speed, freq, refined = s, abs(lam.imag), True
            if abs(hi - lo) < CROSSING_TOL_M_S or lam.real == 0.0:
                break
            if (lam.real > 0) == (f_hi > 0):
                hi, f_hi = s, lam.real
                f_lo = f_lo / 2 if side == 1 else f_lo
                side = 1
            else:
                lo, f_lo = s, lam.real
                f_hi = f_hi / 2 if side == -1 else f_hi
                side = -1
            if abs(hi - lo) < CROSSING_TOL_M_S:
                break
    return VgCrossing("unsteady", track.label, track.kind, float(speed), float(speed / a), float(freq), direction,
                      refined)
