"""Time-domain flight of the geometrically nonlinear aircraft from its nonlinear trim (quasi-steady strips).

The state is that of the free-flying structure (:mod:`flexsim.structure.free_flexible`, Su & Cesnik 2011 in Kane's
form), ``y = [X (3), quaternion (4), ε (n), v (3), ω (3), ε̇ (n)]``; its rate is :func:`free_flight_rhs` with the
generalized airloads and thrust of :meth:`flexsim.model.flexible_aircraft.FlexibleAircraft.airloads` added to ``Q``
(:meth:`~flexsim.model.flexible_aircraft.FlexibleAircraft.free_flight_rate`, the one combination also linearised
by :mod:`flexsim.linear.flexible_stability`).

Neglected (said in every result's ``warnings``): the strips are quasi-steady (no wake or inflow states, no apparent
mass); the density (and the compressibility factor) is held at the trim's. Each strip sees the wind where it is
(:func:`flexsim.sim.flexible_step.strip_wind`: a gust reaches the wing before the tail and the near tip before the far
one in a crosswind). Integration: scipy's ``solve_ivp`` with the implicit BDF method (variable order
1-5) — the structural roots reach ~6000 rad/s on the 8-element HALE, so an explicit method would be held to steps
of ~1e-4 s by stability alone, while BDF's step follows the accuracy of the slow motion; BDF reuses its
finite-difference Jacobian over many steps (Radau refactors each step). With ``step_s`` the run takes fixed
ROS2 steps instead (:mod:`flexsim.sim.flexible_step`), the integrator of the nonlinear HALE environment. SI units,
radians, body axes x forward, z down.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from flexsim.errors import positive_number
from flexsim.kinematics import euler_321_of_quaternion
from flexsim.sim.flexible_step import FlexibleStepper, body_wind, strip_wind
from flexsim.trimming.flexible_trim import FlexibleTrimPoint

__all__ = ["FlexibleRun", "simulate_flexible", "write_flexible_log"]

#: What every run neglects.
NEGLECTED = ("quasi-steady strips: no wake or inflow states, no apparent mass",
             "air density held at the trim's")


@dataclass(frozen=True, eq=False)
class FlexibleRun:
    """A run of the nonlinear aircraft (:func:`simulate_flexible`).

    Attributes
    ----------
    point : FlexibleTrimPoint
    t : ndarray, shape (K,)
        Sample times [s].
    states : ndarray, shape (K, 7 + 2 n + 6)
        Full states (module docstring).
    position_m : ndarray, shape (K, 3)
        Body origin, NED [m].
    euler_rad : ndarray, shape (K, 3)
        3-2-1 roll, pitch, yaw [rad].
    velocity_m_s, rate_rad_s : ndarray, shape (K, 3)
        ``v`` and ``ω``, body axes.
    strains : ndarray, shape (K, n)
    tip_positions_m : ndarray, shape (K, B, 3)
        Beam tips, body axes [m].
    tip_deflection_fraction : ndarray, shape (K, B)
        Upward tip displacement from the undeformed tip over the beam length (semispan on a wing half) [-].
    wind_body_m_s : ndarray, shape (K, 3)
        The wind at the body origin, body axes [m/s].
    controls : ndarray, shape (K, 4)
        The controls applied at each sample ``[T [N], δa, δe, δr [rad]]``.
    n_rhs : int
        Right-hand-side evaluations (Jacobian columns included).
    wall_s : float
        Wall time of the integration [s].
    warnings : tuple of str
    method : str
        The integrator ("BDF", or ROS2 with its step).
    """

    point: FlexibleTrimPoint
    t: NDArray
    states: NDArray
    position_m: NDArray
    euler_rad: NDArray
    velocity_m_s: NDArray
    rate_rad_s: NDArray
    strains: NDArray
    tip_positions_m: NDArray
    tip_deflection_fraction: NDArray
    wind_body_m_s: NDArray
    controls: NDArray
    n_rhs: int
    wall_s: float
    warnings: tuple
    method: str = "BDF"


def _positive(name: str, value, *, upper: float = math.inf) -> float:
    """:func:`flexsim.errors.positive_number`, and at most ``upper``."""
    v = positive_number(name, value)
    if v > upper:
        raise ValueError(f"{name} = {value!r}: must be a finite number in (0, {upper:g}]")
    return v


def simulate_flexible(model, point: FlexibleTrimPoint, t_end_s: float, *, controls: NDArray | Callable | None = None,
                 wind: Callable | None = None, sample_dt_s: float = 0.05, initial_state: NDArray | None = None,
                 rtol: float = 1e-6, atol: float = 1e-8, step_s: float | None = None) -> FlexibleRun:
    """Fly the nonlinear aircraft from ``point`` for ``t_end_s`` seconds (module docstring).

    Parameters
    ----------
    model : AircraftModel
        The model the trim was computed for (its gravity).
    point : FlexibleTrimPoint
        :func:`flexsim.trimming.flexible_trim.trim_flexible`.
    t_end_s : float
        Duration [s], in (0, 3600].
    controls : ndarray shape (4,) or callable ``t -> (4,)``, optional
        ``[T [N], δa, δe, δr [rad]]``; default the trim's, held.
    wind : callable ``(t, positions_ned (k, 3)) -> (k, 3)``, optional
        A wind field of :mod:`flexsim.sim.disturbances` (NED air velocity [m/s]); evaluated at the body origin.
    sample_dt_s : float
        Output spacing [s], in (0, t_end_s].
    initial_state : ndarray, optional
        Start here instead of the trim (:meth:`FlexibleTrimPoint.state` layout), e.g. a perturbed trim.
    rtol, atol : float
        BDF tolerances (relative in (0, 0.1], absolute > 0).
    step_s : float, optional
        Fly with fixed ROS2 steps of this length [s] instead (:mod:`flexsim.sim.flexible_step`: its Jacobian frozen at
        the initial state, controls held over each step; ``sample_dt_s`` must be a whole number of steps); ``rtol`` and
        ``atol`` then do not apply. About 60 times faster than BDF on the HALE, within 3.9 cm of its tip deflection
        through a 10 m/s gust at 10 ms.

    Returns
    -------
    FlexibleRun
    """
    from flexsim.model.aircraft_model import check_model

    check_model(model, nonlinear=True)
    if not isinstance(point, FlexibleTrimPoint):
        raise ValueError(f"point = {point!r}: must be a FlexibleTrimPoint (flexsim.trim_flexible)")
    t_end = _positive("t_end_s", t_end_s, upper=3600.0)
    dt = _positive("sample_dt_s", sample_dt_s, upper=t_end)
    rtol, atol = _positive("rtol", rtol, upper=0.1), _positive("atol", atol)
    structure = point.aircraft.free_structure(model.terms.gravity_m_s2)
    y0 = point.state() if initial_state is None else np.asarray(initial_state, float)
    if y0.shape != (structure.n_states,) or not np.all(np.isfinite(y0)):
        raise ValueError(f"initial_state: must be {structure.n_states} finite numbers, got shape {y0.shape}")
    if controls is None:
        u_of = lambda t: point.controls  # noqa: E731
    elif callable(controls):
        u_of = controls
    else:
        u = np.asarray(controls, float)
        if u.shape != (4,) or not np.all(np.isfinite(u)):
            raise ValueError(f"controls = {controls!r}: must be 4 finite numbers [T, δa, δe, δr] or a callable of t")
        u_of = lambda t: u  # noqa: E731
    if wind is not None and not callable(wind):
        raise ValueError(f"wind = {wind!r}: must be a wind field (t, positions_ned) -> velocities, or None")

    flex, rho = point.aircraft, point.density_kg_m3
    t_eval = np.arange(0.0, t_end + 0.5 * dt, dt)
    t_eval = t_eval[t_eval <= t_end]
    start = _time.perf_counter()
    if step_s is None:
        def rhs(t, y):
            return flex.free_flight_rate(structure, t, y, np.asarray(u_of(t), float), rho, strip_wind(wind, t, y))

        # scipy's finite-difference Jacobian (num_jac) tries steps that overflow for state components near 1e-11 and
        # then recovers; its RuntimeWarning is silenced here, a state that is not finite is refused below
        with np.errstate(over="ignore"):
            sol = solve_ivp(rhs, (0.0, t_end), y0, method="BDF", t_eval=t_eval, rtol=rtol, atol=atol)
        if sol.success and not np.all(np.isfinite(sol.y)):
            sol.success, sol.message = False, "the state is not finite"
        if not sol.success:
            raise RuntimeError(f"simulate_flexible: the integration stopped at t = "
                               f"{sol.t[-1] if sol.t.size else 0.0:.4g} s: {sol.message}")
        ts, ys, n_rhs = sol.t, sol.y.T, int(sol.nfev + sol.njev * structure.n_states)
        method = "BDF"
    else:
        stepper = FlexibleStepper.about(flex, structure, y0, np.asarray(u_of(0.0), float), rho, step_s)
        per_sample = dt / stepper.step_s
        if abs(per_sample - round(per_sample)) > 1e-9 * per_sample:
            raise ValueError(f"sample_dt_s = {dt!r}: must be a whole number of steps of step_s = {step_s!r}")
        per_sample = int(round(per_sample))
        ys, y = [y0.copy()], y0.copy()
        for i in range(t_eval.size - 1):
            for k in range(per_sample):
                t = t_eval[i] + k * stepper.step_s
                y = stepper.advance(t, y, np.asarray(u_of(t), float), wind, 1)
            if not np.all(np.isfinite(y)):
                raise RuntimeError(f"simulate_flexible: the state is not finite at t = {t_eval[i + 1]:.4g} s "
                                   f"(step_s = {step_s!r} too long for this motion)")
            ys.append(y)
        ts, ys = t_eval, np.array(ys)
        n_rhs = 2 * per_sample * (t_eval.size - 1) + 2 * structure.n_states
        method = f"ROS2, h = {stepper.step_s:g} s (Jacobian frozen at the initial state)"
    wall = _time.perf_counter() - start
    n = structure.n_strains
    flex = point.aircraft
    tips = np.array([flex.tip_positions(y[7:7 + n]) for y in ys])
    frac = -(tips - flex.undeformed_tips)[:, :, 2] / flex.beam_lengths_m
    return FlexibleRun(point=point, t=ts, states=ys, position_m=ys[:, :3],
                       euler_rad=np.array([euler_321_of_quaternion(y[3:7]) for y in ys]), velocity_m_s=ys[:, 7 + n:10 + n],
                       rate_rad_s=ys[:, 10 + n:13 + n], strains=ys[:, 7:7 + n], tip_positions_m=tips,
                       tip_deflection_fraction=frac, wind_body_m_s=np.array([body_wind(wind, t, y) for t, y in zip(ts, ys)]),
                       controls=np.array([np.asarray(u_of(t), float) for t in ts]),
                       n_rhs=n_rhs, wall_s=wall, warnings=NEGLECTED + tuple(
                           f"not in the nonlinear strips: {', '.join(flex.unmodelled)}" for _ in flex.unmodelled[:1]),
                       method=method)


def write_flexible_log(run: FlexibleRun, path, *, metadata: dict | None = None) -> None:
    """Write ``run`` as an MCAP flight log (:class:`flexsim.io.flight_log.FlightLogWriter`) with the deformed beam
    nodes (body axes) of every sample, so ``flexsim view`` shows the deformed structure. State: the rigid-body
    states; signals: airspeed, altitude and each beam's tip deflection (along body z, down positive) [m]."""
    from flexsim.io.flight_log import FlightLogWriter

    flex = run.point.aircraft
    comps = flex.beam_components
    state_names = ["x_north_m", "y_east_m", "z_down_m", "phi_rad", "theta_rad", "psi_rad", "v_x_m_s", "v_y_m_s",
                   "v_z_m_s", "omega_x_rad_s", "omega_y_rad_s", "omega_z_rad_s"]
    signal_names = ["airspeed_m_s", "altitude_m"] + [f"tip_deflection_{c}_m" for c in comps]
    kin0 = flex.kinematics(run.strains[0])
    topology = {c: int(k.node_positions.shape[0]) for c, k in zip(comps, kin0)}
    nodes = {c: [] for c in comps}
    for eps in run.strains:
        for c, k in zip(comps, flex.kinematics(eps)):
            nodes[c].append(k.node_positions)
    state = np.column_stack([run.position_m, run.euler_rad, run.velocity_m_s, run.rate_rad_s])
    airspeed = np.linalg.norm(run.velocity_m_s - run.wind_body_m_s, axis=1)
    defl = run.tip_positions_m[:, :, 2] - flex.undeformed_tips[None, :, 2]
    signals = np.column_stack([airspeed, -run.position_m[:, 2], defl])
    with FlightLogWriter(path, state_names=state_names, control_names=["thrust_N", "aileron_rad", "elevator_rad",
                                                                       "rudder_rad"],
                         signal_names=signal_names, structure_topology=topology,
                         metadata={"aircraft": flex.name, "model": "nonlinear strain-based beams, quasi-steady strips",
                                   **(metadata or {})}) as writer:
        writer.write_samples(run.t, position_m=run.position_m, euler_rad=run.euler_rad, state=state,
                             controls=run.controls, signals=signals, structure={c: np.array(v) for c, v in nodes.items()})
