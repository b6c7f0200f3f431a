"""An aircraft oscillating in one mode of its linearised equations, as frames for a 3-D recording.

A mode (eigenvalue lambda, velocity part phi of the eigenvector over V = [v, omega, s, eta], paper eq. 9; e.g. the
flutter mode of :class:`flexsim.linear.flutter.FlutterPoint`) has the displacements ``d = phi / lambda`` (the
paper's Figs. 11 and 16 show them). The frames show the real motion about the trim state x0 over a few periods,
``x(t) = x0 + a Re(d exp(i omega t))`` with omega = |Im lambda| (the growth or decay, zero at a flutter point, is left
out so that the shape is seen at one size):

* elastic coordinates q, xi (paper eq. 1): the deformed beams of every component by the model's kinematic maps
  (:meth:`flexsim.structure.model.StructuralModel.point_maps`, eqs. 5-6 and 18; linear in q and xi);
* the rigid-body part of a free aircraft: the translation ``a Re(d_v ...)`` of the body origin along the body axes of
  the trim (NED: C0^T times it) and the attitude change ``E^-1(phi0, theta0) a Re(d_omega ...)`` of the Euler angles
  (eq. 4, :func:`flexsim.kinematics.euler_rate_matrix_inverse`).

The scale a sets the largest elastic displacement of any beam node to ``peak_deflection_m`` (default 5 % of the
longest component): a linear mode has a shape, not an amplitude. :func:`record_flutter_mode` writes the Rerun
recording of a flutter point (:func:`flexsim.io.mode_recording.write_mode_recording`).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from flexsim.io.mode_recording import ModeAnimation, ParticipationBar, write_mode_recording
from flexsim.kinematics import dcm_321, euler_rate_matrix_inverse
from flexsim.model.aircraft_model import AircraftModel, check_model
from flexsim.model.naming import state_names

__all__ = ["mode_animation", "record_flutter_mode", "record_critical_mode", "check_recording_path", "PEAK_DEFLECTION_FRACTION"]

#: Default largest elastic node displacement, as a fraction of the longest component [-].
PEAK_DEFLECTION_FRACTION = 0.05


def mode_animation(model: AircraftModel, x0: np.ndarray, velocity_shape: np.ndarray, eigenvalue: complex, *,
                   participation: tuple[ParticipationBar, ...] = (), peak_deflection_m: float | None = None,
                   cycles: int = 2, frames_per_cycle: int = 36, n_nodes: int = 21, title: str = "",
                   description: str = "") -> ModeAnimation:
    """Frames of ``model`` oscillating in a mode about ``x0`` (module docstring).

    Parameters
    ----------
    model : AircraftModel
        Supplies the structure, the state layout and the names.
    x0 : ndarray, shape (n_states,) or (n_states - n_inflow,)
        Trim state (inflow states, if any, are not needed: they do not move the structure).
    velocity_shape : ndarray (complex), shape (n_v,)
        phi over V = [v, omega, s, eta] (:attr:`flexsim.linear.stability.Mode.shape`).
    eigenvalue : complex
        lambda [1/s]; oscillatory (Im lambda != 0).
    participation : tuple of ParticipationBar
        Bars of the recording.
    peak_deflection_m : float, optional
        Largest elastic displacement of a beam node [m], > 0 (default 5 % of the longest component).
    cycles, frames_per_cycle, n_nodes : int
        Periods shown (>= 1), frames per period (>= 8), beam nodes per component (>= 2).
    title, description : str
        Text of the recording.

    Returns
    -------
    ModeAnimation
    """
    lam = complex(eigenvalue)
    omega = abs(lam.imag)
    if not (math.isfinite(omega) and omega > 0.0):
        raise ValueError(f"eigenvalue = {eigenvalue!r}: must be oscillatory (Im != 0) to be animated")
    for name, value, low in (("cycles", cycles, 1), ("frames_per_cycle", frames_per_cycle, 8), ("n_nodes", n_nodes, 2)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
            raise ValueError(f"{name} = {value!r}: must be an integer >= {low}")
    dofs, lay = model.structure.dofs, model.layout
    shape = np.asarray(velocity_shape, complex)
    if shape.shape != (dofs.n_v,) or not np.all(np.isfinite(shape)):
        raise ValueError(f"velocity_shape: expected {dofs.n_v} finite complex numbers (V = [v, omega, s, eta]), "
                         f"got shape {shape.shape}")
    x0 = np.asarray(x0, float)
    if lay.n_inflow and x0.shape == (lay.inflow.start,):
        x0 = np.concatenate([x0, np.zeros(lay.n_inflow)])
    if x0.shape != (lay.n_states,):
        raise ValueError(f"x0: a state of {x0.size} entries for a model of {lay.n_states} states")
    disp = shape / lam
    nq = dofs.nq
    _, euler0, q0, xi0, _ = model.unpack(x0)
    dq, dxi = disp[6:6 + nq], disp[6 + nq:]
    comps = model.aircraft.components
    maps = {c.name: model.structure.point_maps(c.name, np.linspace(0.0, c.length_m, n_nodes)) for c in comps}
    rest = {name: m.positions(q0, xi0) for name, m in maps.items()}
    # node displacement per unit complex amplitude (the maps are linear in q and xi)
    unit = {name: (m.positions(q0 + dq.real, xi0 + dxi.real) - rest[name])
            + 1j * (m.positions(q0 + dq.imag, xi0 + dxi.imag) - rest[name]) for name, m in maps.items()}
    t = np.linspace(0.0, cycles * 2.0 * math.pi / omega, cycles * frames_per_cycle + 1)
    phase = np.exp(1j * omega * t)  # (N,)
    largest = max(float(np.linalg.norm((phase[:, None, None] * u[None]).real, axis=2).max()) for u in unit.values())
    if not largest > 0.0:
        raise ValueError("velocity_shape: the mode moves no beam node (no elastic displacement to show)")
    if peak_deflection_m is None:
        peak_deflection_m = PEAK_DEFLECTION_FRACTION * max(c.length_m for c in comps)
    if not (math.isfinite(peak_deflection_m) and peak_deflection_m > 0.0):
        raise ValueError(f"peak_deflection_m = {peak_deflection_m!r}: must be a finite number > 0 [m]")
    a = peak_deflection_m / largest
    motion = a * (phase[:, None] * disp[None, :]).real  # (N, n_v) displacement of V's coordinates
    structure = {name: rest[name][None] + a * (phase[:, None, None] * u[None]).real for name, u in unit.items()}
    c0 = dcm_321(*euler0)
    if lay.rigid:
        position = motion[:, 0:3] @ c0  # C0^T d_r for every frame
        euler = euler0[None, :] + motion[:, 3:6] @ euler_rate_matrix_inverse(euler0[0], euler0[1]).T
    else:
        position, euler = np.zeros((t.size, 3)), np.tile(euler0, (t.size, 1))
    names = state_names(model)
    el_names = tuple(names[lay.q.start:lay.q.stop]) + tuple(names[lay.xi.start:lay.xi.stop])
    el_values = np.column_stack([q0[None, :] + motion[:, 6:6 + nq], xi0[None, :] + motion[:, 6 + nq:]])
    if len(el_names) != el_values.shape[1]:  # a quasi-rigid model has no elastic states to name
        el_names, el_values = (), np.zeros((t.size, 0))
    return ModeAnimation(t, position, euler, structure, el_names, el_values, tuple(participation), omega, title,
                         description)


def record_flutter_mode(model: AircraftModel, point, path: str | os.PathLike, *, peak_deflection_m: float | None = None,
                        cycles: int = 2, frames_per_cycle: int = 36) -> Path:
    """Write a Rerun recording of a flutter point's mode (the aircraft oscillating, its participation as bars).

    Parameters
    ----------
    model : AircraftModel
        The model the flutter point was trimmed with (:attr:`flexsim.linear.flutter.FlutterAnalysis.qs`).
    point : FlutterPoint
        From :meth:`flexsim.linear.flutter.FlutterAnalysis.search`; a wind-tunnel point (no trim) is animated about
        the undeformed state.
    path : path
        The ``.rrd`` file to write.
    peak_deflection_m, cycles, frames_per_cycle :
        As in :func:`mode_animation`.

    Returns
    -------
    Path
        ``path``.
    """
    check_model(model)
    mode = point.mode
    x0 = model.layout.zeros() if point.trim is None else point.trim.x
    bars = tuple(ParticipationBar(p.label, p.magnitude, p.unit, p.phase_deg) for p in point.participation)
    hz = point.frequency_rad_s / (2.0 * math.pi)
    title = (f"{point.aero_model} flutter mode of {model.aircraft.name}: {point.frequency_rad_s:.4g} rad/s ({hz:.4g} Hz) "
             f"at M {point.mach:.4f}, V = {point.speed_m_s:.2f} m/s")
    flight = "wind tunnel" if point.trim is None else point.trim.manoeuvre.describe()
    lam = mode.eigenvalue
    peak = PEAK_DEFLECTION_FRACTION * max(c.length_m for c in model.aircraft.components) if peak_deflection_m is None \
        else peak_deflection_m
    description = "\n".join([
        f"* flight: {flight}",
        f"* eigenvalue: {lam.real:.5g} {'+' if lam.imag >= 0 else '-'} {abs(lam.imag):.5g}j 1/s "
        f"(damping ratio {mode.damping_ratio:.3g}), {mode.name}",
        f"* symmetry: {point.mode_symmetry}; bars normalised by {point.normalised_by} = 1 (phase 0)",
        f"* amplitude: scaled for display, the largest elastic node displacement is {peak:.3g} m "
        f"(a linear mode has a shape, not an amplitude); growth or decay left out",
        f"* frames: {cycles} periods of {2 * math.pi / point.frequency_rad_s:.4g} s, {frames_per_cycle} frames each "
        f"(played in a loop, slowed down to about 2 s per period)",
    ])
    animation = mode_animation(model, x0, mode.shape, lam, participation=bars, peak_deflection_m=peak, cycles=cycles,
                               frames_per_cycle=frames_per_cycle, title=title, description=description)
    return write_mode_recording(animation, path)



def check_recording_path(path: str | os.PathLike, option: str = "path") -> Path:
    """A recording to write: ends in ``.rrd``, not a directory, in an existing directory (ValueError or
    FileNotFoundError naming ``option`` otherwise), checked before any computation."""
    p = Path(path)
    if p.is_dir():
        raise ValueError(f"{option} = {str(path)!r}: is a directory; give a file name such as {str(p / 'mode.rrd')!r}")
    if p.suffix != ".rrd":
        raise ValueError(f"{option} = {str(path)!r}: must end in .rrd (a Rerun recording)")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise FileNotFoundError(f"{option} = {str(path)!r}: directory {str(parent)!r} does not exist")
    return p


def record_critical_mode(cases, rows, path: str | os.PathLike) -> str:
    """Record the mode of the lowest flutter point of a study (:func:`flexsim.linear.study.run_study`'s ``rows`` of
    ``cases``) with :func:`record_flutter_mode`; returns a line saying what was written (or that nothing was).

    The flutter point is found again by the case's own search started at the study's flutter Mach
    (:meth:`~flexsim.linear.flutter.FlutterAnalysis.search` with ``mach_guess``), which gives the eigenvector the
    study's rows do not keep.
    """
    from flexsim.linear.study import MODELS
    from flexsim.trimming import SteadyManoeuvre

    found = [(row["mach"], k) for k, row in enumerate(rows) if "mach" in row]
    if not found:
        return f"no flutter point in the searched range: no mode recording written to {path}"
    mach, k = min(found)
    case = cases[k]
    analysis = case.analysis()
    start = SteadyManoeuvre.level(case.altitude_m, mach=case.mach_min)
    gamma = None if case.climb_angle_deg is None else math.radians(case.climb_angle_deg)
    man = SteadyManoeuvre(start.speed_m_s, case.altitude_m, case.turn_radius_m, gamma, case.coordinated)
    point = analysis.search(man, mach_range=(case.mach_min, case.mach_max), mach_guess=mach, aero_model=MODELS[case.model])
    out = record_flutter_mode(analysis.qs, point, path)
    return (f"flutter mode of {case.model} at H = {case.altitude_m:g} m (M {point.mach:.4f}, "
            f"{point.frequency_rad_s:.4g} rad/s, {point.mode.name}) recorded to {out} "
            f"({out.stat().st_size} bytes; flexsim view {out})")
