"""The result of a simulation: sampled time histories and named outputs.

All quantities are SI and radians with the unit in the name, named from the one output vocabulary
(:mod:`flexsim.io.vocabulary`, ``docs/logs.md``) and computed by the one output layer
(:class:`flexsim.sim.outputs.OutputMaps`), as in the flight log; frames as in ``docs/conventions.md`` (NED
inertial, FRD body axes, 3-2-1 Euler angles).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from flexsim.model.aircraft_model import AircraftModel, Wind
from flexsim.model.linear_range import linear_range_note
from flexsim.sim.outputs import OutputMaps
from flexsim.trimming.equilibrium import EquilibriumStability

__all__ = ["SimulationResult", "STATUSES"]

#: Possible values of :attr:`SimulationResult.status`.
STATUSES = ("completed", "ground_contact", "structural_limit", "gimbal_lock", "event", "non_finite", "solver_failure")


@dataclass(frozen=True, eq=False)
class SimulationResult:
    """Time histories of a simulation (N samples) and why it stopped.

    Attributes
    ----------
    t : ndarray, shape (N,)
        Sample times [s]: the output grid (``output_rate_hz``) and the final time.
    x : ndarray, shape (N, n_states)
        States, laid out as ``model.layout``.
    u : ndarray, shape (N, 4)
        Controls [T_e (N), delta_a, delta_e, delta_r (rad)] applied at the sample times.
    status : str
        One of :data:`STATUSES`: ``completed`` (reached t_end), ``ground_contact``, ``structural_limit``,
        ``gimbal_lock``, ``event`` (a user event), ``non_finite`` (the state or its derivative stopped
        being finite), ``solver_failure`` (the step size collapsed).
    reason : str
        One sentence saying why the run stopped, with the time and the quantity involved.
    model : AircraftModel
        The simulated model (outputs are computed from it).
    method : str
        Integration method used.
    rtol : float
        Relative tolerance used.
    nfev, njev, nlu : int
        Right-hand-side evaluations, Jacobian evaluations (scipy's count) and LU decompositions.
    wall_time_s : float
        Wall-clock time of the run: the constant Jacobian (implicit methods), the integration and the log [s].
    log_path : Path or None
        The flight log written, if any.
    events : tuple of (t [s], name)
        Event crossings in time order: non-terminal user events, then the terminal event that stopped the
        run (if any).
    wind : callable or None
        The disturbance the run was flown in (air data and loads are computed with it); None: still air.
    initial_stability : EquilibriumStability or None
        The classification of the trim the run started from (``TrimPoint.stability``,
        :mod:`flexsim.trimming.equilibrium`); None when it started from a state vector.
    """

    t: np.ndarray
    x: np.ndarray
    u: np.ndarray
    status: str
    reason: str
    model: AircraftModel
    method: str
    rtol: float
    nfev: int
    njev: int
    nlu: int
    wall_time_s: float
    log_path: Path | None = None
    events: tuple[tuple[float, str], ...] = ()
    wind: Wind | None = None
    initial_stability: EquilibriumStability | None = None

    # ------------------------------------------------------------------ run facts
    @property
    def completed(self) -> bool:
        """True if the run reached its end time."""
        return self.status == "completed"

    @property
    def duration_s(self) -> float:
        """Simulated time [s]."""
        return float(self.t[-1] - self.t[0]) if self.t.size else 0.0

    @property
    def real_time_factor(self) -> float:
        """Simulated time over wall time [-] (> 1: faster than real time)."""
        return self.duration_s / self.wall_time_s if self.wall_time_s > 0 else math.inf

    @cached_property
    def outputs(self) -> OutputMaps:
        """Names and output maps of the model (the run's wind is passed to them per call)."""
        return OutputMaps(self.model)

    @cached_property
    def linear_range(self) -> str | None:
        """One line when the run bends or twists a beam beyond the linear structure's range at any sample
        (:func:`flexsim.model.linear_range.linear_range_note`, the largest excursion), None within it."""
        return linear_range_note(self.model, self.x, " (largest of the run)") if self.t.size else None

    @property
    def terms(self) -> dict:
        """The physical terms of the simulated model as a JSON-ready dict (:meth:`flexsim.model.terms.Terms.record`,
        as :attr:`flexsim.linear.flutter.FlutterPoint.terms` and the flight log's header)."""
        return self.model.terms.record()

    # ------------------------------------------------------------------ states
    @cached_property
    def _unpacked(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        rows = [self.model.unpack(xk) for xk in self.x] or [self.model.unpack(self.model.layout.zeros())]
        sizes = [np.size(block) for block in rows[0]]
        return tuple(np.array([r[i] for r in rows[: len(self.x)]], dtype=float).reshape(len(self.x), sizes[i])  # type: ignore[return-value]
                     for i in range(5))

    @property
    def position_ned_m(self) -> np.ndarray:
        """Inertial position of the body origin, NED [m], shape (N, 3) (restrained: [0, 0, -H])."""
        pos = self._unpacked[0].copy()
        if not self.model.layout.rigid:
            pos[:, 2] = -self.model.variant.altitude_m
        return pos

    @property
    def altitude_m(self) -> np.ndarray:
        """Altitude H = -Z of the body origin [m], shape (N,)."""
        return -self.position_ned_m[:, 2]

    @property
    def euler_rad(self) -> np.ndarray:
        """Euler angles [phi, theta, psi] [rad], shape (N, 3)."""
        return self._unpacked[1]

    @property
    def velocity_body_m_s(self) -> np.ndarray:
        """Body-axes velocity of the body origin [U, V, W] (inertial, no wind) [m/s], shape (N, 3)."""
        return self._unpacked[4][:, 0:3]

    @property
    def body_rates_rad_s(self) -> np.ndarray:
        """Body angular velocity [P, Q, R] [rad/s], shape (N, 3)."""
        return self._unpacked[4][:, 3:6]

    @cached_property
    def air_velocity_body_m_s(self) -> np.ndarray:
        """Velocity of the body origin relative to the air, body axes [m/s], shape (N, 3)."""
        return np.array([self.outputs.air_velocity_body(float(tk), xk, self.wind) for tk, xk in zip(self.t, self.x)]).reshape(-1, 3)

    @cached_property
    def _air(self):
        return self.outputs.air_data(self.t, self.x, self.wind)

    @property
    def airspeed_m_s(self) -> np.ndarray:
        """True airspeed of the body origin [m/s], shape (N,)."""
        return self._air.airspeed_m_s

    @property
    def alpha_rad(self) -> np.ndarray:
        """Angle of attack atan(w_a / u_a) of the body axes relative to the air [rad], shape (N,)."""
        return self._air.alpha_rad

    @property
    def beta_rad(self) -> np.ndarray:
        """Sideslip asin(v_a / |v_a|) [rad], shape (N,)."""
        return self._air.beta_rad

    @property
    def modal_coordinates(self) -> tuple[np.ndarray, np.ndarray]:
        """Bending q [m], shape (N, nq), and torsion xi [rad], shape (N, nxi) (labels: ``modal_labels``)."""
        return self._unpacked[2], self._unpacked[3]

    @property
    def modal_labels(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """State names of the bending and torsion coordinates."""
        lay, names = self.model.layout, self.outputs.state_names
        return names[lay.q], names[lay.xi]

    # ------------------------------------------------------------------ structure and loads
    def tip_deflection_m(self, wing: str = "right_wing") -> np.ndarray:
        """Tip bending deflection of ``wing`` [m], positive down along z_i, shape (N,)."""
        return self.outputs.tip_deflection_m(wing, self.x)

    def tip_twist_rad(self, wing: str = "right_wing") -> np.ndarray:
        """Tip twist of ``wing`` [rad] (nose up on the right wing), shape (N,)."""
        return self.outputs.tip_twist_rad(wing, self.x)

    def root_bending_moment_n_m(self, wing: str = "right_wing") -> np.ndarray:
        """Mode-displacement root bending moment EI(0) w''(0) of ``wing`` [N m], shape (N,)."""
        return self.outputs.root_bending_moment_n_m(wing, self.x)

    @cached_property
    def _loads(self) -> dict[str, np.ndarray]:
        return self.outputs.series(("load_factor",) + (("wing_lift_N",) if "wing_lift_N" in self.outputs.signal_names else ()),
                                   self.t, self.x, self.u, self.wind)

    @property
    def load_factor(self) -> np.ndarray:
        """Aerodynamic + thrust force along -z_body over the weight [-], shape (N,)."""
        return self._loads["load_factor"]

    @property
    def wing_lift_n(self) -> np.ndarray:
        """Sum of the circulatory strip lifts of both wings [N], shape (N,) (zeros without aerodynamics)."""
        return self._loads.get("wing_lift_N", np.zeros(self.t.size))

    # ------------------------------------------------------------------ by name
    @property
    def signal_names(self) -> tuple[str, ...]:
        """Every name :meth:`signal` accepts: flight signals, state names and control names."""
        return self.outputs.signal_names + self.outputs.state_names + self.outputs.control_names

    def signal(self, name: str) -> np.ndarray:
        """Time history of a named quantity, shape (N,), named and computed as in the flight log.

        Flight signals (:attr:`OutputMaps.signal_names`: ``airspeed_m_s``, ``mach``, ``alpha_rad``, ``beta_rad``,
        ``altitude_m``, ``heading_rate_rad_s``, ``load_factor``, ``wing_lift_N``, ``tip_deflection_<c>_m``,
        ``tip_twist_<c>_rad``, their rates, ``root_bending_moment_<c>_N_m``), any state name (e.g.
        ``q_right_wing_1_m``, ``phi_rad``, ``omega_y_rad_s``) or control name (``thrust_N``, ``aileron_rad``,
        ``elevator_rad``, ``rudder_rad``); definitions and units: :data:`flexsim.io.vocabulary.QUANTITIES`.

        Raises
        ------
        KeyError
            Unknown name; the message lists the available ones.
        """
        out = self.outputs
        if name in out.signal_names:
            if name in ("airspeed_m_s", "alpha_rad", "beta_rad", "mach"):
                return np.asarray(getattr(self._air, name), dtype=float)
            if name in self._loads:
                return self._loads[name]
            return out.series(name, self.t, self.x, self.u, self.wind)[name]
        if name in out.state_names:
            return self.x[:, out.state_names.index(name)]
        if name in out.control_names:
            return self.u[:, out.control_names.index(name)]
        raise KeyError(f"no signal named {name!r}; available: {list(out.signal_names)}, the state names "
                       f"({out.state_names[0]}, ...) and the controls {list(out.control_names)}")

    def summary(self) -> str:
        """A few lines: status, reason, cost, the final flight condition and, when the run bends or twists a beam
        beyond the linear structure's range, one line saying so (:attr:`linear_range`)."""
        lines = [f"status: {self.status} — {self.reason}",
                 f"simulated {self.duration_s:.3f} s in {self.wall_time_s:.2f} s wall ({self.real_time_factor:.2f}x real time), "
                 f"method {self.method} (rtol {self.rtol:g}), {self.nfev} rhs evaluations, {self.nlu} LU decompositions"]
        if self.t.size:
            k = -1
            parts = [f"airspeed {self.airspeed_m_s[k]:.2f} m/s", f"altitude {self.altitude_m[k]:.1f} m"]
            if self.model.layout.rigid:
                phi, theta, psi = np.degrees(self.euler_rad[k])
                parts.append(f"phi/theta/psi {phi:.2f}/{theta:.2f}/{psi:.2f} deg")
            parts += [f"{w} tip {self.outputs.tip_deflection_m(w, self.x[k]):+.3f} m" for w in self.outputs.wings]
            lines.append(f"at t = {self.t[k]:.3f} s: " + ", ".join(parts))
        if self.linear_range is not None:
            lines.append(self.linear_range)
        if self.log_path is not None:
            lines.append(f"flight log: {self.log_path}")
        return "\n".join(lines)
