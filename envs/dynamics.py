"""The physics behind the environments: one flexsim model, trimmed, stepped over control periods.

:class:`FlightDynamics` is the only place where the environments touch the model. It holds one
:class:`~flexsim.model.aircraft_model.AircraftModel` (whose ``rhs(t, x, u)`` is integrated unchanged),
trims it with :func:`flexsim.trim.trim`, computes the Jacobian of the trim with
:func:`flexsim.model.jacobian.jacobian` (once per trim, cached), and integrates a control period:

* zero-order hold: the control vector is constant over the period;
* actuator rate limits: the applied controls move towards the commanded ones by at most rate * dt per
  period (:meth:`FlightDynamics.rate_limit`), then are held;
* ETD2RK (:mod:`flexsim.sim.fixed_step`, the default for the finite-state model): a fixed number of
  equal steps per period with the trim Jacobian as its linear part (its matrix functions are computed
  once per trim); after every step the state is checked for non-finite values and for a crossing of
  altitude 0 (crash), located by linear interpolation between the two steps;
* DOP853 or Radau (``scipy.integrate.solve_ivp``): a restart per period (the right-hand side changes
  with the controls), warm-started with ``first_step`` = the step size the solver reached in the
  previous period, shortened so that a whole number of steps fills the period (a clipped last step
  would make Radau factorise again); Radau gets the constant trim Jacobian; a terminal event at
  altitude 0 (crash).

:class:`Measurements` are the outputs the environments observe (air data, attitude, structural sensors)
computed from the state by the one output layer, :class:`flexsim.sim.outputs.OutputMaps` (the same code and
names as the simulator's results and logs); nothing here depends on gymnasium. The episode's wind field is passed per call
(:meth:`FlightDynamics.advance`, :meth:`FlightDynamics.measure`) and reaches ``model.rhs(t, x, u, wind)``;
nothing here stores it, so trims are always in still air and do not depend on earlier episodes.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from flexsim._threads import single_blas_thread
from flexsim.aircraft.definition import Aircraft
from flexsim.atmosphere import speed_of_sound
from flexsim.model.jacobian import jacobian
from flexsim.model.aircraft_model import AircraftModel, Wind
from flexsim.sim.fixed_step import ETD2RK
from flexsim.sim.outputs import OutputMaps, air_angles, heading_rate
from flexsim.kinematics import euler_rate_matrix_inverse
from flexsim.trim import SteadyManoeuvre, TrimPoint, trim

from flexsim.envs.config import FIXED_STEP_METHODS, ActuatorRates, IntegratorSettings

__all__ = ["FlightDynamics", "Measurements", "StepOutcome", "SENSOR_COMPONENTS"]

#: Components carrying the structural sensors (tip deflection, twist and their rates), in order.
SENSOR_COMPONENTS = ("right_wing", "left_wing", "vtail")
#: Number of trims kept per environment (tasks with random targets trim every episode).
TRIM_CACHE = 16
#: Remaining fraction of a period below which a solver stop counts as having reached its end.
_SLIVER = 1e-12


def _evict(cache: dict) -> None:
    """Drop the oldest entries of an insertion-ordered cache beyond :data:`TRIM_CACHE`."""
    while len(cache) > TRIM_CACHE:
        del cache[next(iter(cache))]


@dataclass(frozen=True)
class Measurements:
    """Outputs of one state (SI, radians; structural signs as in ``docs/conventions.md``).

    Attributes
    ----------
    time_s : float
    position_ned_m, euler_rad, body_rates_rad_s : ndarray, shape (3,)
    airspeed_m_s, alpha_rad, beta_rad, mach : float
        Air data relative to the air at the body origin (wind included).
    altitude_m : float
    heading_rate_rad_s : float
        psi_dot = (q sin(phi) + r cos(phi)) / cos(theta) [rad/s] (the turn rate of a level turn).
    tip_deflection_m, tip_deflection_rate_m_s, tip_twist_rad, tip_twist_rate_rad_s : dict
        Per sensor component (:data:`SENSOR_COMPONENTS`): bending deflection w(L) (positive along z_i,
        i.e. down on a wing half), its rate, torsion psi(L) and its rate at the tip.
    root_bending_moment_n_m : dict
        Per wing half: EI(0) w''(0), the modal-curvature root bending moment [N m].
    """

    time_s: float
    position_ned_m: np.ndarray
    euler_rad: np.ndarray
    body_rates_rad_s: np.ndarray
    airspeed_m_s: float
    alpha_rad: float
    beta_rad: float
    mach: float
    altitude_m: float
    heading_rate_rad_s: float
    tip_deflection_m: dict
    tip_deflection_rate_m_s: dict
    tip_twist_rad: dict
    tip_twist_rate_rad_s: dict
    root_bending_moment_n_m: dict


@dataclass(frozen=True)
class StepOutcome:
    """Result of one control period.

    Attributes
    ----------
    x : ndarray
        State at the end (the last finite state if the integration failed).
    time_s : float
        Time reached [s] (earlier than the period's end after a crash event or a failure).
    crashed : bool
        The ground event (altitude 0) stopped the integration.
    failure : str
        Empty, or why the integration failed (non-finite state, solver failure, model error).
    nfev, nlu : int
        Right-hand-side evaluations and LU factorisations of the period (ETD2RK: 2 evaluations per step
        and no factorisation; its matrix functions are computed once per trim, in
        :meth:`FlightDynamics.start`).
    """

    x: np.ndarray
    time_s: float
    crashed: bool
    failure: str
    nfev: int
    nlu: int = 0


class FlightDynamics:
    """One flexsim model of an aircraft, with trim, Jacobian cache, actuators and the period integrator.

    Parameters
    ----------
    aircraft : Aircraft
    aero : {"unsteady", "quasi-steady"}
    integrator : IntegratorSettings
        Method and tolerances or step (``method="auto"`` resolved with ``aero``).
    rates : ActuatorRates
    control_dt_s : float
        Control period [s].

    Attributes
    ----------
    method : str
        The integration method in use.
    substeps : int
        ETD2RK steps per control period (0 for the ``solve_ivp`` methods).
    """

    def __init__(self, aircraft: Aircraft, aero: str, integrator: IntegratorSettings, rates: ActuatorRates,
                 control_dt_s: float) -> None:
        self.aircraft = aircraft
        self.aero = aero
        self.integrator_settings = integrator
        self.actuator_rates = rates
        self.model = AircraftModel(aircraft, aero=aero)
        self.layout = self.model.layout
        for name in SENSOR_COMPONENTS:
            aircraft.component(name)  # KeyError naming the missing component
        #: The output layer of the model: names, air data, structural outputs, deformed beams, flight signals.
        self.outputs = OutputMaps(self.model)
        missing = [name for name in SENSOR_COMPONENTS if name not in self.outputs.sensors]
        if missing:
            raise ValueError(f"aircraft {aircraft.name!r}: components {missing} have no elastic modes; the environments' "
                             f"structural sensors need bending and torsion modes on {', '.join(SENSOR_COMPONENTS)}")
        self.sensors = {name: self.outputs.sensors[name] for name in SENSOR_COMPONENTS}
        self.method = integrator.resolve(aero)
        self.rtol = integrator.rtol
        self.atol = integrator.atol(self.layout)
        self.dt = float(control_dt_s)
        self.substeps = integrator.substeps(self.dt) if self.method in FIXED_STEP_METHODS else 0
        lo, hi = aircraft.control_limits()
        self.u_low, self.u_high = lo, hi
        self.rate_limits = rates.limits(float(hi[0]))
        self._trims: dict[SteadyManoeuvre, TrimPoint] = {}
        self._jacobians: dict[SteadyManoeuvre, np.ndarray] = {}
        self._steppers: dict[SteadyManoeuvre, ETD2RK] = {}
        self._stepper: ETD2RK | None = None
        self._jac = None
        self._h_next = None
        z = self.layout.position.start + 2
        self._z = z

        def ground(t: float, y: np.ndarray, u: np.ndarray, wind) -> float:
            return -y[z]

        ground.terminal = True
        ground.direction = -1.0
        self._ground = ground

    def fork(self) -> FlightDynamics:
        """Another :class:`FlightDynamics` of the same model for a second episode running at the same time.

        It shares this one's model, sensors and caches (trims, Jacobians and ETD2RK matrix functions: each
        a deterministic function of the manoeuvre, never changed once computed) and has its own episode
        state (the ETD2RK stepper or Radau Jacobian of its episode, Radau's warm-start step). The
        sub-environments of :class:`flexsim.envs.vector.FlexSimVectorEnv` run on forks of one
        FlightDynamics, so N aircraft cost one model build, one trim and one matrix exponential.
        """
        twin = copy.copy(self)
        twin._jac, twin._stepper, twin._h_next = None, None, None
        return twin

    @property
    def stepper(self) -> ETD2RK | None:
        """The ETD2RK step of the current episode (None for the ``solve_ivp`` methods or before :meth:`start`)."""
        return self._stepper

    # ------------------------------------------------------------------ trim and Jacobian
    def trim(self, manoeuvre: SteadyManoeuvre) -> TrimPoint:
        """Still-air trim of ``manoeuvre`` (the last ``TRIM_CACHE`` trims are cached: trims are deterministic)."""
        point = self._trims.pop(manoeuvre, None)
        if point is None:
            point = trim(self.model, manoeuvre)
        self._trims[manoeuvre] = point
        _evict(self._trims)
        return point

    @single_blas_thread
    def start(self, manoeuvre: SteadyManoeuvre) -> None:
        """Prepare an episode flown about the (still-air) trim of ``manoeuvre``.

        For Radau and ETD2RK, the Jacobian d rhs / dx at that (still-air) trim is computed once and cached
        per manoeuvre (:data:`TRIM_CACHE` of them): for Radau it only steers the Newton iterations (the
        error control sets the accuracy); for ETD2RK it is the linear part, whose matrix functions for
        the step ``dt / substeps`` are computed here too, once per manoeuvre.
        """
        self._h_next = None
        self._jac, self._stepper = None, None
        if self.method not in ("Radau", *FIXED_STEP_METHODS):
            return
        jac = self._jacobians.pop(manoeuvre, None)
        if jac is None:
            point = self.trim(manoeuvre)
            jac = jacobian(self.model, point.x, point.u, controls=False)[0]
        self._jacobians[manoeuvre] = jac
        _evict(self._jacobians)
        if self.method == "Radau":
            self._jac = jac
            return
        stepper = self._steppers.pop(manoeuvre, None)
        if stepper is None:
            stepper = ETD2RK(jac, self.dt / self.substeps)
        self._steppers[manoeuvre] = stepper
        _evict(self._steppers)
        self._stepper = stepper

    # ------------------------------------------------------------------ actuators
    def rate_limit(self, applied: np.ndarray, command: np.ndarray) -> np.ndarray:
        """Controls after one period of rate-limited motion from ``applied`` towards ``command``."""
        step = self.rate_limits * self.dt
        return applied + np.clip(command - applied, -step, step)

    # ------------------------------------------------------------------ integration
    @single_blas_thread
    def advance(self, x: np.ndarray, u: np.ndarray, t0: float, t1: float, wind: Wind | None = None) -> StepOutcome:
        """Integrate ``rhs`` from t0 to t1 [s] with the controls ``u`` held (zero-order hold) in the wind
        field ``wind`` (``wind(t, positions_ned_m)``, :meth:`AircraftModel.rhs`; None: still air).

        With ETD2RK, t1 - t0 must be the control period ``dt`` (its step is fixed) and :meth:`start`
        must have been called.
        """
        if self.substeps:
            return self._advance_fixed(x, u, t0, t1, wind)
        span = t1 - t0
        first = None if self._h_next is None else min(self._h_next, span)
        options = {"jac": self._jac} if self.method == "Radau" else {}
        try:
            with np.errstate(all="ignore"):
                sol = solve_ivp(self.model.rhs, (t0, t1), x, method=self.method, args=(u, wind), rtol=self.rtol,
                                atol=self.atol, first_step=first, events=self._ground, **options)
        except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
            return StepOutcome(x, t0, False, f"model error: {exc}", 0)
        if sol.status < 0 and t1 - sol.t[-1] <= _SLIVER * span and np.all(np.isfinite(sol.y[:, -1])):
            # scipy stops with "step size less than spacing between numbers" when rounding leaves a
            # remaining interval of a few ulp; the state there is the state at t1 to within |f| * 1e-12 s
            sol.status, sol.t[-1] = 0, t1
        if sol.status < 0 or not np.all(np.isfinite(sol.y[:, -1])):
            good = np.flatnonzero(np.all(np.isfinite(sol.y), axis=0))
            last = int(good[-1]) if good.size else None
            x_end = sol.y[:, last] if last is not None else x
            t_end = float(sol.t[last]) if last is not None else t0
            return StepOutcome(x_end.copy(), t_end, False, f"non-finite state or solver failure: {sol.message}", sol.nfev, sol.nlu)
        steps = np.diff(sol.t)
        if steps.size > 1:
            h = float(steps[:-1].max())
            # a whole number of steps per period, 1e-6 long so that rounding cannot leave a sliver at the end
            # (scipy fails when the remaining step is below its spacing of numbers)
            self._h_next = span / math.ceil(span / h * (1.0 - 1e-9)) * (1.0 + 1e-6)
        elif steps.size == 1:
            self._h_next = span
        crashed = sol.status == 1
        return StepOutcome(sol.y[:, -1].copy(), float(sol.t[-1]), crashed, "", sol.nfev, sol.nlu)

    def _advance_fixed(self, x: np.ndarray, u: np.ndarray, t0: float, t1: float, wind: Wind | None) -> StepOutcome:
        """ETD2RK over one period: ``substeps`` equal steps, each checked for non-finite states and a crash."""
        stepper = self._stepper
        if stepper is None:
            raise RuntimeError("advance() called before start(): ETD2RK needs the trim Jacobian")
        span = t1 - t0
        if not abs(span - self.dt) <= 1e-9 * self.dt:
            raise ValueError(f"t1 - t0 = {span!r} s: ETD2RK steps whole control periods, must be dt = {self.dt!r} s")
        k, z, h = self.substeps, self._z, stepper.h
        rhs = self.model.rhs
        nfev = 0
        t = t0
        with np.errstate(all="ignore"):
            for i in range(1, k + 1):
                t_next = t1 if i == k else t0 + i * h
                nfev += stepper.nfev_per_step
                try:
                    x_next = stepper.step(rhs, t, x, (u, wind))
                except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
                    return StepOutcome(x.copy(), t, False, f"model error: {exc}", nfev)
                if not np.all(np.isfinite(x_next)):
                    return StepOutcome(x.copy(), t, False, f"non-finite state: ETD2RK step {i} of {k} from t = {t:.6g} s", nfev)
                if x_next[z] >= 0.0 > x[z]:
                    # altitude -x[z] crosses 0 within this step: the ground event, interpolated linearly
                    s = x[z] / (x[z] - x_next[z])
                    return StepOutcome(x + s * (x_next - x), t + s * (t_next - t), True, "", nfev)
                x, t = x_next, t_next
        return StepOutcome(x, t1, False, "", nfev)

    # ------------------------------------------------------------------ outputs
    def measure(self, x: np.ndarray, t: float, wind: Wind | None = None) -> Measurements:
        """Air data, attitude and structural sensors of state ``x`` at time ``t`` [s] in the wind field ``wind``."""
        lay, out = self.layout, self.outputs
        pos = x[lay.position]
        eul = x[lay.euler]
        w = x[lay.omega]
        altitude = float(-pos[2])
        with np.errstate(all="ignore"):
            try:
                v_air = out.air_velocity_body(t, x, wind)
            except ValueError:  # a wind field that cannot answer at this position: still-air data
                v_air = out.air_velocity_body(t, x, None)
            speed, alpha, beta = air_angles(v_air)
            try:
                mach = speed / speed_of_sound(altitude)
            except ValueError:
                mach = math.nan
            heading_rate_rad_s = heading_rate(eul, x[lay.velocity])
        tips, rates, twists, twist_rates, roots = {}, {}, {}, {}, {}
        for name, s in self.sensors.items():
            tips[name] = float(s.tip_deflection_m(x))
            rates[name] = float(s.tip_deflection_rate_m_s(x))
            twists[name] = float(s.tip_twist_rad(x))
            twist_rates[name] = float(s.tip_twist_rate_rad_s(x))
            if name != "vtail":
                roots[name] = float(s.root_bending_moment_n_m(x))
        return Measurements(float(t), pos.copy(), eul.copy(), w.copy(), speed, alpha, beta, mach, altitude, heading_rate_rad_s,
                            tips, rates, twists, twist_rates, roots)

    def euler_rates(self, x: np.ndarray) -> np.ndarray:
        """Theta_dot = E^-1 omega [rad/s] of state ``x``."""
        eul = x[self.layout.euler]
        return euler_rate_matrix_inverse(eul[0], eul[1]) @ x[self.layout.omega]

    def structure_nodes(self, x: np.ndarray) -> dict[str, np.ndarray]:
        """Deformed beam nodes of every component in body axes [m], shape (n_nodes, 3) each (:meth:`OutputMaps.structure`)."""
        return self.outputs.structure(x)

    def state_names(self) -> tuple[str, ...]:
        """A vocabulary name with unit for every entry of the state vector (:attr:`OutputMaps.state_names`)."""
        return self.outputs.state_names
