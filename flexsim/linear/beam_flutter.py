"""Nonlinear aeroelastic stability of a wing clamped in a wind tunnel (geometrically exact beam, strip theory).

At each tunnel speed ``U`` the wing's static equilibrium under its strip airloads (which follow the deformed strips),
gravity and any dead tip load is solved (:func:`flexsim.structure.beam_statics.solve_static`), the aeroelastic system is
linearised about it (:func:`flexsim.model.beam_aero.aeroelastic_system`: the preload's geometric stiffness, the steady
airloads' stiffness of the deformed strips, Peters' finite-state unsteady airloads), and its eigenvalues are examined:

* flutter: the lowest speed at which an oscillatory root crosses into the right half plane, growth measured by
  ``Re λ / |λ|`` (roots neutral to 1e-6, such as in-plane modes that the strips do not load, are skipped);
* divergence: the lowest speed at which the tangent stiffness ``K_T(U)`` (elastic, geometric and steady
  aerodynamic) loses positive definiteness — its least eigenvalue (of ``M⁻¹ K_T``) crosses zero — or at which the
  static equilibrium ceases to exist (reported with the speed at which Newton's method failed).

Scan with a fixed speed step, then Brent's method (scipy.optimize.brentq) on each bracketed crossing to 1e-4 m/s.
The scan can miss an instability confined between two scan points; the step is a setting.
Sources: Patil, Hodges & Cesnik, J. Aircraft 38(1) 2001 (the analysis and its validation case); Su & Cesnik 2011
(the beam). Units SI; angles in the settings in degrees (converted to radians inside).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from flexsim._arrays import frozen_array
from flexsim._threads import single_blas_thread
from flexsim.model.beam_aero import (LoadSum, StripAirloads, TunnelFlow, WingAero, aeroelastic_system,
                                     static_stiffness)
from flexsim.structure.beam_statics import BeamConvergenceError, BeamLoads, NewtonSettings, solve_static
from flexsim.structure.strain_beam import BeamProperties

__all__ = ["WingTunnelSettings", "WingStabilityPoint", "WingTunnelResult", "nonlinear_wing_tunnel",
           "StripRangeWarning", "LINEAR_LIFT_LIMIT_DEG"]

_NEUTRAL = 1e-6
#: Strip angle of attack beyond which the strips' linear lift (2π, no stall) is outside its range [deg]
#: (thin-airfoil lift is linear to about 10-12° on attached flow: Abbott & von Doenhoff 1959, ch. 7).
LINEAR_LIFT_LIMIT_DEG = 10.0


class StripRangeWarning(UserWarning):
    """A static equilibrium of the scan has strips beyond the linear lift range (the result is outside the model)."""


@dataclass(frozen=True)
class WingTunnelSettings:
    """Settings of :func:`nonlinear_wing_tunnel` (validated, frozen).

    Parameters
    ----------
    density_kg_m3 : float
        Air density [kg/m³] (PHC 2001: 0.0889, 20 km).
    speed_range_m_s : tuple of float
        ``(lowest, highest)`` tunnel speed of the scan [m/s], ``0 < lowest < highest``.
    speed_step_m_s : float
        Scan step [m/s] (default 1).
    root_pitch_deg : float
        Root pitch about the root section's ``e1`` axis, nose up [deg] (default 0; within ±30).
    gravity_m_s2 : float
        Acceleration of gravity along ``−z`` of the tunnel [m/s²] (default 0: no weight).
    tip_force_n : array_like, shape (3,)
        Dead tip force, global components [N] (default 0; PHC 2001 bend the wing with a vertical one).
    flow_direction : array_like, shape (3,)
        Unit vector of the free stream (default ``(0, −1, 0)``, see :class:`~flexsim.model.beam_aero.TunnelFlow`).
    newton : NewtonSettings
        Settings of the static solutions.
    """

    density_kg_m3: float
    speed_range_m_s: tuple[float, float]
    speed_step_m_s: float = 1.0
    root_pitch_deg: float = 0.0
    gravity_m_s2: float = 0.0
    tip_force_n: ArrayLike = field(default_factory=lambda: np.zeros(3))
    flow_direction: ArrayLike = field(default_factory=lambda: np.array([0.0, -1.0, 0.0]))
    newton: NewtonSettings = field(default_factory=NewtonSettings)

    def __post_init__(self) -> None:
        TunnelFlow(1.0, self.density_kg_m3, self.flow_direction)  # validates density and direction
        try:
            lo, hi = (float(v) for v in self.speed_range_m_s)
        except (TypeError, ValueError):
            raise ValueError(f"speed_range_m_s = {self.speed_range_m_s!r}: must be two speeds [m/s]") from None
        if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo < hi):
            raise ValueError(f"speed_range_m_s = {self.speed_range_m_s!r}: must be 0 < lowest < highest [m/s]")
        object.__setattr__(self, "speed_range_m_s", (lo, hi))
        step = self.speed_step_m_s
        if not isinstance(step, (int, float)) or isinstance(step, bool) or not 0 < step <= hi - lo:
            raise ValueError(f"speed_step_m_s = {step!r}: must be > 0 and at most the range's width {hi - lo:g} "
                             "[m/s]")
        pitch = self.root_pitch_deg
        if not isinstance(pitch, (int, float)) or isinstance(pitch, bool) or not -30 <= pitch <= 30:
            raise ValueError(f"root_pitch_deg = {pitch!r}: must be a number in [-30, 30] [deg] (strip theory "
                             "without stall)")
        g = self.gravity_m_s2
        if not isinstance(g, (int, float)) or isinstance(g, bool) or not 0 <= g <= 100:
            raise ValueError(f"gravity_m_s2 = {g!r}: must be a number in [0, 100] [m/s^2]")
        BeamLoads(tip_force_n=self.tip_force_n)  # validates the vector
        object.__setattr__(self, "tip_force_n", frozen_array(np.array(self.tip_force_n, dtype=float)))
        object.__setattr__(self, "flow_direction", frozen_array(np.array(self.flow_direction, dtype=float)))


@dataclass(frozen=True, eq=False)
class WingStabilityPoint:
    """An instability onset.

    Attributes
    ----------
    speed_m_s : float
        Onset speed [m/s].
    frequency_rad_s : float
        Frequency of the critical root [rad/s] (0 for divergence).
    tip_position_m : ndarray, shape (3,)
        Static tip position at the onset [m].
    tip_displacement_m : ndarray, shape (3,)
        Tip position minus the undeformed one [m].
    q : ndarray, shape (n,)
        Static strains at the onset.
    kind : str
        ``"flutter"``, ``"divergence"`` or ``"equilibrium lost"`` (Newton failed: the static solution ceased to
        exist at or below ``speed_m_s``).
    """

    speed_m_s: float
    frequency_rad_s: float
    tip_position_m: NDArray
    tip_displacement_m: NDArray
    q: NDArray
    kind: str


@dataclass(frozen=True, eq=False)
class WingTunnelResult:
    """Result of :func:`nonlinear_wing_tunnel`.

    Attributes
    ----------
    flutter, divergence : WingStabilityPoint or None
        The lowest onsets in the range (None: none found).
    speeds_m_s : ndarray, shape (k,)
        Scanned speeds [m/s].
    growth : ndarray, shape (k,)
        Largest ``Re λ / |λ|`` of the oscillatory roots at each speed (> 0: unstable).
    least_stiffness : ndarray, shape (k,)
        Least real eigenvalue of ``M⁻¹ K_T`` [1/s²] (< 0: statically unstable).
    tip_positions_m : ndarray, shape (k, 3)
        Static tip position at each speed [m].
    max_strip_alpha_deg : ndarray, shape (k,)
        Largest strip angle of attack of the static equilibrium at each speed [deg] (a :class:`StripRangeWarning`
        names the first speed beyond :data:`LINEAR_LIFT_LIMIT_DEG`).
    """

    flutter: WingStabilityPoint | None
    divergence: WingStabilityPoint | None
    speeds_m_s: NDArray
    growth: NDArray
    least_stiffness: NDArray
    tip_positions_m: NDArray
    max_strip_alpha_deg: NDArray


def _max_strip_alpha_deg(sol, flow: TunnelFlow) -> float:
    """Largest |angle of attack| of the strips at a static equilibrium [deg]: atan2(V_a·e3, −V_a·e2)."""
    rot = sol.kinematics.rotations
    va = flow.direction
    return float(np.degrees(np.abs(np.arctan2(rot[:, :, 2] @ va, -(rot[:, :, 1] @ va)))).max())


class _Analysis:
    """One wing in one tunnel setting: equilibria and eigenvalues per speed (warm starts, cached stiffness)."""

    def __init__(self, beam: BeamProperties, aero: WingAero, settings: WingTunnelSettings) -> None:
        pitch = np.radians(settings.root_pitch_deg)
        c, s = np.cos(pitch), np.sin(pitch)
        about_e1 = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
        self.beam = replace(beam, root_rotation=beam.root_rotation @ about_e1)
        self.aero, self.settings = aero, settings
        self.other = BeamLoads(tip_force_n=settings.tip_force_n, gravity_m_s2=[0.0, 0.0, -settings.gravity_m_s2])
        self.q = np.zeros(self.beam.n_coordinates)
        self.undeformed_tip = beam_tip(self.beam, self.q)

    def flow(self, speed: float) -> TunnelFlow:
        return TunnelFlow(float(speed), self.settings.density_kg_m3, self.settings.flow_direction)

    def equilibrium(self, speed: float):
        loads = LoadSum((self.other, StripAirloads(self.aero, self.flow(speed))))
        sol = solve_static(self.beam, loads, self.settings.newton, q0=self.q)
        self.q = sol.q
        return sol

    def evaluate(self, speed: float) -> tuple[float, float, float, object]:
        """(growth, frequency of the most unstable oscillatory root, least stiffness eigenvalue, equilibrium)."""
        sol = self.equilibrium(speed)
        flow = self.flow(speed)
        loaded = np.any(self.settings.tip_force_n) or self.settings.gravity_m_s2 > 0
        stiffness = static_stiffness(self.beam, sol.q, self.other if loaded else None, self.aero, flow,
                                     self.settings.newton.difference_step)
        system = aeroelastic_system(self.beam, self.aero, flow, sol.q, stiffness)
        roots = np.linalg.eigvals(system.state_matrix)
        ratio = roots.real / np.maximum(np.abs(roots), 1e-300)
        oscillatory = (np.abs(roots.imag) > 1e-6 * np.abs(roots)) & (np.abs(ratio) > _NEUTRAL)
        if np.any(oscillatory):
            i = np.argmax(np.where(oscillatory, ratio, -np.inf))
            growth, freq = float(ratio[i]), float(abs(roots[i].imag))
        else:
            growth, freq = -1.0, 0.0
        stiff = np.linalg.eigvals(np.linalg.solve(system.mass, stiffness))
        return growth, freq, float(stiff.real.min()), sol


def beam_tip(beam: BeamProperties, q: NDArray) -> NDArray:
    """Tip position [m] of ``beam`` at strains ``q``."""
    from flexsim.structure.strain_beam import beam_kinematics

    return beam_kinematics(beam, q).tip_position


def _point(analysis: _Analysis, speed: float, freq: float, sol, kind: str) -> WingStabilityPoint:
    tip = sol.tip_position_m.copy()
    return WingStabilityPoint(speed_m_s=float(speed), frequency_rad_s=float(freq), tip_position_m=tip,
                              tip_displacement_m=tip - analysis.undeformed_tip, q=sol.q.copy(), kind=kind)


@single_blas_thread
def nonlinear_wing_tunnel(beam: BeamProperties, aero: WingAero, settings: WingTunnelSettings) -> WingTunnelResult:
    """Flutter and divergence of a wing clamped in a wind tunnel, about its nonlinear static equilibrium.

    Parameters
    ----------
    beam : BeamProperties
        The wing as a geometrically exact beam (:mod:`flexsim.structure.strain_beam`); its clamp frame is the
        tunnel's, with ``e2`` towards the leading edge (the free stream comes from ``+y`` by default).
    aero : WingAero
        Chord, reference-axis position and inflow states of its strips.
    settings : WingTunnelSettings

    Returns
    -------
    WingTunnelResult
        Onsets and the scan's growth rates, least stiffness and static tip positions.

    Examples
    --------
    The Patil-Hodges-Cesnik wing at 20 km (docs/nonlinear-beams.md)::

        wing = BeamProperties(length_m=16.0, n_elements=16, gj_nm2=1e4, ei_flap_nm2=2e4, ei_chord_nm2=4e6,
                              mass_kg_per_m=0.75, torsion_inertia_kg_m=0.1)
        result = nonlinear_wing_tunnel(wing, WingAero(chord_m=1.0), WingTunnelSettings(0.0889, (20.0, 40.0)))
    """
    analysis = _Analysis(beam, aero, settings)
    lo, hi = settings.speed_range_m_s
    speeds = np.append(np.arange(lo, hi, settings.speed_step_m_s), hi)
    growth, least, tips, alphas = [], [], [], []
    flutter = divergence = None
    done = []
    previous = None
    for speed in speeds:
        try:
            g, f, k, sol = analysis.evaluate(speed)
        except BeamConvergenceError:
            if divergence is None:
                last = previous[3] if previous is not None else analysis.equilibrium(lo)
                divergence = _point(analysis, speed, 0.0, last, "equilibrium lost")
            break
        growth.append(g), least.append(k), tips.append(sol.tip_position_m.copy()), done.append(speed)
        alphas.append(_max_strip_alpha_deg(sol, analysis.flow(speed)))
        if alphas[-1] > LINEAR_LIFT_LIMIT_DEG and max(alphas[:-1], default=0.0) <= LINEAR_LIFT_LIMIT_DEG:
            warnings.warn(f"at {speed:g} m/s the static wing has strips at {alphas[-1]:.1f} deg angle of attack, "
                          f"beyond the strips' linear lift range ({LINEAR_LIFT_LIMIT_DEG:g} deg, no stall): results "
                          "from this speed on are outside the model's validity", StripRangeWarning, stacklevel=3)
        if previous is not None:
            q_prev = previous[3].q
            if flutter is None and previous[0] < 0 < g:
                flutter = _refine(analysis, previous[4], speed, q_prev, 0, "flutter")
            if divergence is None and previous[2] > 0 > k:
                divergence = _refine(analysis, previous[4], speed, q_prev, 2, "divergence")
            analysis.q = sol.q
        previous = (g, f, k, sol, speed)
        if flutter is not None and divergence is not None:
            break
    return WingTunnelResult(flutter=flutter, divergence=divergence, speeds_m_s=np.array(done),
                            growth=np.array(growth), least_stiffness=np.array(least),
                            tip_positions_m=np.array(tips).reshape(-1, 3), max_strip_alpha_deg=np.array(alphas))


def _refine(analysis: _Analysis, lo: float, hi: float, q_lo: NDArray, index: int, kind: str) -> WingStabilityPoint:
    """Brent's method on the bracketed crossing of ``evaluate(speed)[index]``, warm-started at ``q_lo``."""

    def value(speed):
        analysis.q = q_lo.copy()
        return analysis.evaluate(speed)[index]

    speed = brentq(value, lo, hi, xtol=1e-4)
    analysis.q = q_lo.copy()
    # the critical root, just past the crossing (at the crossing itself it is neutral and skipped)
    _, freq, _, sol = analysis.evaluate(min(speed + 2e-3, hi))
    analysis.q = q_lo.copy()
    sol = analysis.equilibrium(speed)
    return _point(analysis, speed, freq if kind == "flutter" else 0.0, sol, kind)
