"""Control periods: one aircraft model, trimmed, stepped over fixed periods with held, rate-limited controls.

The integration layer of the gymnasium environments (:mod:`flexsim.envs`), single and batched. A
:class:`FlightDynamics` holds one :class:`~flexsim.model.aircraft_model.AircraftModel` (whose ``rhs(t, x, u)`` is
integrated unchanged), trims it with :func:`flexsim.trimming.trim`, computes the Jacobian of the trim
(:func:`flexsim.model.jacobian.jacobian`, once per trim, cached) and integrates a control period. An episode's
integration state (the ETD2RK stepper of its trim, Radau's Jacobian, the warm-start step of the ``solve_ivp`` methods) is
an immutable :class:`IntegrationState`, returned by :meth:`FlightDynamics.start` and taken (and returned, updated) by
every period, so one :class:`FlightDynamics` flies any number of episodes at once:

* zero-order hold: the control vector is constant over the period;
* actuator rate limits (:class:`ActuatorRates`): the applied controls move towards the commanded ones by at most
  rate * period (:func:`flexsim.sim._step_kernels.rate_limit_rows`, the one implementation), then are held;
* ETD2RK (:class:`flexsim.sim.fixed_step.ETD2RK`, the default, :func:`check_period_settings`): a fixed number
  of equal steps per period with the trim Jacobian as its linear part (its matrix functions computed once per
  trim); after every step the state is checked for non-finite values and for the ground contact, the crossing of
  altitude 0 located by linear interpolation within the step (:func:`flexsim.sim._step_kernels.ground_crossing`);
* DOP853 or Radau (``scipy.integrate.solve_ivp``): a restart per period (the right-hand side changes with the
  controls), warm-started with the step the solver reached in the previous period, shortened so that a whole
  number of steps fills the period; Radau gets the constant trim Jacobian; a terminal event at altitude 0.

:func:`advance_period` is the one route of a period of N aircraft (N = 1 for a single environment), with two paths
per row: rate limits, integration and measurements (:mod:`flexsim.sim.measurements`) in one compiled call
(:func:`flexsim.sim._step_kernels.period_rows`) per trim for the rows the kernels can fly (ETD2RK, a packed wind),
the products over the rows as matrix products from :data:`COMPILED_ROWS_BELOW` rows on; for the rest, which the
kernels cannot run (DOP853 or Radau, a Python wind callable, a replaced right-hand side), the same arithmetic in Python
order (the compiled rate limits, :meth:`FlightDynamics.advance`: the compiled ETD2RK stages around ``model.rhs`` or
``solve_ivp``, the compiled measurements). :func:`advance_rows` is the integration alone, for many rows at once
(used to check the compiled period against it). The wind field of each episode is passed per call and reaches ``model.rhs(t, x, u,
wind)``; nothing here stores it, so trims are in still air and do not depend on earlier episodes.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp

from flexsim import _kernels as _k
from flexsim._arrays import frozen_array, kernel_arg
from flexsim._threads import single_blas_thread
from flexsim.errors import positive_number
from flexsim.kinematics import euler_rate_matrix_inverse
from flexsim.model.aircraft_model import AircraftModel, Wind, check_model
from flexsim.model.jacobian import jacobian
from flexsim.model.sensors import ComponentSensor, SensorBank
from flexsim.sim import _step_kernels as _sk
from flexsim.sim import measurements as _ms
from flexsim.sim.fixed_step import ETD2RK
from flexsim.sim.measurements import MeasurementBatch, Measurements
from flexsim.sim.outputs import OutputMaps
from flexsim.sim.simulate import DEFAULT_MAX_STEP, IntegratorSettings
from flexsim.trimming import SteadyManoeuvre, TrimError, TrimPoint, trim

__all__ = ["IntegratorSettings", "ActuatorRates", "FlightDynamics", "IntegrationState", "StepOutcome", "BatchOutcome", "PeriodResult", "advance_rows",
           "advance_period", "SENSOR_COMPONENTS", "INTEGRATOR_METHODS", "FIXED_STEP_METHODS", "DEFAULT_MAX_STEP_S",
           "MAX_STEP_RANGE_S", "COMPILED_ROWS_BELOW", "TRIM_CACHE", "period_atol", "check_period_settings",
           "pack_period_winds", "select_packed_rows"]

#: Components carrying the structural sensors (tip deflection, twist and their rates), in order.
SENSOR_COMPONENTS = ("right_wing", "left_wing", "vtail")
#: Integration methods of the control periods (:func:`check_period_settings`; ``"auto"``: :meth:`IntegratorSettings.resolve`).
INTEGRATOR_METHODS = ("auto", "ETD2RK", "DOP853", "Radau")
#: The fixed-step methods among them (:mod:`flexsim.sim.fixed_step`); the others are ``solve_ivp`` methods.
FIXED_STEP_METHODS = ("ETD2RK",)
#: Default ETD2RK step [s] (:attr:`IntegratorSettings.max_step_s`): 1 step per 50 Hz control period.
DEFAULT_MAX_STEP_S = DEFAULT_MAX_STEP["ETD2RK"]
#: Allowed range of :attr:`IntegratorSettings.max_step_s` over a control period [s].
MAX_STEP_RANGE_S = (1e-4, 0.05)
#: Number of trims kept per :class:`FlightDynamics` (tasks with random targets trim every episode).
TRIM_CACHE = 16
#: From this many rows sharing one stepper on, the products of a period are matrix products over the rows
#: (``over_rows`` of :func:`flexsim.sim._step_kernels.stage_a`); below it row by row. Measured (benchmarks/bench_envs.py
#: --batched): row by row 2x faster at N = 1, equal near N = 16, 25 % slower at N = 256.
COMPILED_ROWS_BELOW = 32
#: Remaining fraction of a period below which a solver stop counts as having reached its end.
_SLIVER = 1e-12
#: Exceptions of the model that end one aircraft's period as a "model error".
_MODEL_ERRORS = (ValueError, ArithmeticError, np.linalg.LinAlgError)


@dataclass(frozen=True)
class ActuatorRates:
    """Rate limits of the actuators (applied to the commanded controls every control period).

    The notional GTM file has no actuator data; the defaults are typical of a 757-class transport
    (hydraulic surfaces 40-60 deg/s, engine spool-up from idle to full thrust in about 4 s).

    Attributes
    ----------
    thrust_fraction_per_s : float
        Largest thrust change per second as a fraction of the maximum thrust [1/s] (default 0.25).
    aileron_rad_s, elevator_rad_s, rudder_rad_s : float
        Largest surface rates [rad/s] (defaults 60, 40 and 60 deg/s).
    """

    thrust_fraction_per_s: float = 0.25
    aileron_rad_s: float = math.radians(60.0)
    elevator_rad_s: float = math.radians(40.0)
    rudder_rad_s: float = math.radians(60.0)

    def __post_init__(self) -> None:
        for name in ("thrust_fraction_per_s", "aileron_rad_s", "elevator_rad_s", "rudder_rad_s"):
            object.__setattr__(self, name, positive_number(name, getattr(self, name)))

    def limits(self, max_thrust_n: float) -> np.ndarray:
        """Rates of u = [T_e, delta_a, delta_e, delta_r]: [N/s, rad/s, rad/s, rad/s], shape (4,)."""
        return np.array([self.thrust_fraction_per_s * max_thrust_n, self.aileron_rad_s, self.elevator_rad_s, self.rudder_rad_s])


def period_atol(layout) -> np.ndarray:
    """The default per-state absolute tolerances of DOP853 and Radau over a control period, shape (n_states,), for a
    :class:`~flexsim.model.layout.StateLayout`: 10 times position 1e-3 m, Euler angles 1e-6 rad, bending 1e-5 m,
    torsion 1e-6 rad, body velocity 1e-4 m/s, body rates 1e-6 rad/s, bending rates 1e-4 m/s, torsion rates
    1e-5 rad/s, inflow 1e-3 m/s."""
    a = np.empty(layout.n_states)
    for name, value in (("position", 1e-3), ("euler", 1e-6), ("q", 1e-5), ("xi", 1e-6), ("v", 1e-4),
                        ("omega", 1e-6), ("s", 1e-4), ("eta", 1e-5), ("inflow", 1e-3)):
        a[getattr(layout, name)] = value
    return 10.0 * a


def check_period_settings(settings: IntegratorSettings) -> IntegratorSettings:
    """``settings`` when the control periods can use them (``method`` one of :data:`INTEGRATOR_METHODS`,
    ``max_step_s`` None or in :data:`MAX_STEP_RANGE_S`), else a ValueError naming the field, value and range.

    Over a period ``"auto"`` resolves as :func:`flexsim.sim.simulate.default_method` of the model in still air or a
    field of :mod:`flexsim.sim.disturbances` (the winds of the environments): ETD2RK for a model with aerodynamics,
    DOP853 without. ETD2RK (:class:`flexsim.sim.fixed_step.ETD2RK`) is a fixed-step second-order exponential
    integrator whose linear part is the Jacobian of the trim the episode starts from: it treats the stiff
    finite-state inflow states and the structural modes exactly to first order about the trim and does not damp
    them numerically (the 179 rad/s fin flutter mode keeps its growth rate), with 2 right-hand sides per step and
    no error control; each period is split into ``ceil(period / max_step_s)`` equal steps (default 0.02 s,
    :data:`DEFAULT_MAX_STEP_S`). DOP853 and Radau are ``scipy.integrate.solve_ivp`` methods with error control
    (``rtol``, default 1e-3; ``atol``, default :func:`period_atol`); Radau gets the constant trim Jacobian and damps
    lightly damped high-frequency modes (the fin flutter amplitude after 5 s is 22 % low at the default
    tolerances). Accuracy in ``docs/environments.md``.
    """
    if settings.method not in INTEGRATOR_METHODS:
        raise ValueError(f"integrator.method = {settings.method!r}: the control periods take one of {', '.join(INTEGRATOR_METHODS)}")
    lo, hi = MAX_STEP_RANGE_S
    if settings.max_step_s is not None and not lo <= settings.max_step_s <= hi:
        raise ValueError(f"max_step_s = {settings.max_step_s!r}: must be in [{lo:g}, {hi:g}] s for the control periods")
    return settings


@dataclass(frozen=True, eq=False)
class IntegrationState:
    """The integration state of one episode flown about one trim (:meth:`FlightDynamics.start`), an immutable value
    passed to each period (:meth:`FlightDynamics.advance`, :func:`advance_period`) and returned by it for the next.

    Attributes
    ----------
    manoeuvre : SteadyManoeuvre or None
        The trim the episode is flown about.
    stepper : ETD2RK or None
        ETD2RK: the step with the trim Jacobian as its linear part (its matrix functions computed once per trim).
    step_data : StepData or None
        The same as the compiled periods take it (:meth:`ETD2RK.step_data`).
    jac : ndarray or None
        Radau: the constant trim Jacobian of its Newton iterations.
    first_step_s : float or None
        DOP853 and Radau: the first step of the next period [s] (the step the solver reached in the previous one,
        shortened so that a whole number of steps fills the period); None: the solver's own choice.
    """

    manoeuvre: SteadyManoeuvre | None = None
    stepper: ETD2RK | None = None
    step_data: _sk.StepData | None = None
    jac: np.ndarray | None = None
    first_step_s: float | None = None


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
        The ground (altitude 0) stopped the integration.
    failure : str
        Empty, or why the integration failed (non-finite state, solver failure, model error).
    nfev, nlu : int
        Right-hand-side evaluations and LU factorisations of the period (ETD2RK: 2 evaluations per step and no
        factorisation; its matrix functions are computed once per trim, in :meth:`FlightDynamics.start`).
    state : IntegrationState or None
        The integration state of the next period (the one given, or with a new warm-start step).
    """

    x: np.ndarray
    time_s: float
    crashed: bool
    failure: str
    nfev: int
    nlu: int = 0
    state: IntegrationState | None = None


@dataclass(frozen=True)
class BatchOutcome:
    """Results of one control period of N aircraft: the :class:`StepOutcome` fields as arrays over the rows (``x``
    (N, n), ``time_s`` (N,), ``crashed`` (N,) bool, ``failure`` (N,) object array of str, ``nfev`` and ``nlu`` (N,)
    int), ``failed`` (N,) bool: the rows whose ``failure`` is not empty, and ``states``, the N integration states of
    the next period (:attr:`StepOutcome.state`)."""

    x: np.ndarray
    time_s: np.ndarray
    crashed: np.ndarray
    failure: np.ndarray
    nfev: np.ndarray
    nlu: np.ndarray
    failed: np.ndarray
    states: tuple = ()

    def row(self, i: int) -> StepOutcome:
        """The :class:`StepOutcome` of row i."""
        return StepOutcome(self.x[i].copy(), float(self.time_s[i]), bool(self.crashed[i]), str(self.failure[i]), int(self.nfev[i]),
                           int(self.nlu[i]), self.states[i] if self.states else None)

    @classmethod
    def of(cls, outcomes: list[StepOutcome]) -> BatchOutcome:
        """The batch of single :class:`StepOutcome` s, in order."""
        failure = np.array([o.failure for o in outcomes], dtype=object)
        return cls(np.array([o.x for o in outcomes], dtype=float), np.array([o.time_s for o in outcomes], dtype=float),
                   np.array([o.crashed for o in outcomes], dtype=bool), failure, np.array([o.nfev for o in outcomes], dtype=np.int64),
                   np.array([o.nlu for o in outcomes], dtype=np.int64), failure != "", tuple(o.state for o in outcomes))


class PeriodResult(NamedTuple):
    """One control period of N aircraft (:func:`advance_period`): the integration ``outcome``, the applied controls
    ``u`` (N, 4) [N, rad] and the measurements of the states reached ``meas``."""

    outcome: BatchOutcome
    u: np.ndarray
    meas: MeasurementBatch


def _evict(cache: dict) -> None:
    """Drop the oldest entries of an insertion-ordered cache beyond :data:`TRIM_CACHE`."""
    while len(cache) > TRIM_CACHE:
        del cache[next(iter(cache))]


class FlightDynamics:
    """One flexsim model of an aircraft, with trim, Jacobian cache, actuators and the period integrator.

    Parameters
    ----------
    model : AircraftModel
        The free-flying model flown (its aircraft, terms and variant), with aerodynamics.
    integrator : IntegratorSettings
        Method and tolerances or step (checked by :func:`check_period_settings`, resolved for the model).
    rates : ActuatorRates
    control_dt_s : float
        Control period [s].

    Attributes
    ----------
    method : str
        The integration method in use.
    substeps : int
        ETD2RK steps per control period (0 for the ``solve_ivp`` methods).
    rate_step : ndarray, shape (4,)
        The largest control change per period [N, rad].
    outputs : OutputMaps
        The output layer of the model (names, air data, structural outputs, deformed beams, flight signals).
    """

    def __init__(self, model: AircraftModel, integrator: IntegratorSettings, rates: ActuatorRates,
                 control_dt_s: float) -> None:
        if not isinstance(model, AircraftModel) or model.aero is None or model.variant.kind.value != "free":
            raise ValueError(f"model = {model!r}: must be a free-flying AircraftModel with aerodynamics")
        check_model(model)
        aircraft = model.aircraft
        self.aircraft = aircraft
        #: The aerodynamic model's name ("unsteady" or "quasi-steady").
        self.aero = model.terms.aero.model
        self.integrator_settings = integrator
        self.actuator_rates = rates
        self.model = model
        self.layout = self.model.layout
        self.outputs = OutputMaps(self.model)
        # a rigid or absent component does not deform: its sensors read zero (no coordinates, empty shape rows)
        still = lambda name: ComponentSensor(name, *(frozen_array(np.zeros(0), np.int64) for _ in range(4)),
                                             *(frozen_array(np.zeros(0)) for _ in range(3)))
        self.sensors = {name: self.outputs.sensors.get(name) or still(name) for name in SENSOR_COMPONENTS}
        bank = SensorBank.of(self.sensors, SENSOR_COMPONENTS, self.layout.n_states)
        #: What the compiled measurements need of the model (:class:`flexsim.sim.measurements.MeasureData`).
        self.measure_data = _ms.measure_data(self.layout, bank.matrix, len(SENSOR_COMPONENTS))
        #: Columns of a measurement row.
        self.n_measurements = _ms.SENSORS_AT + bank.matrix.shape[1]
        self._still = self.model.pack_winds([None])._replace(rows=frozen_array(np.zeros((0, 4)), np.int64))
        resolved = check_period_settings(integrator).resolve(self.model, None, rtol=1e-3, atol=period_atol(self.layout))
        self.method, self.rtol, self.atol = resolved.method, resolved.rtol, resolved.atol
        self.dt = float(control_dt_s)
        self.substeps = resolved.substeps(self.dt) if self.method in FIXED_STEP_METHODS else 0
        lo, hi = aircraft.control_limits()
        self.u_low, self.u_high = lo, hi
        self.rate_limits = rates.limits(float(hi[0]))
        self.rate_step = self.rate_limits * self.dt
        self._trims: dict[SteadyManoeuvre, TrimPoint] = {}
        self._jacobians: dict[SteadyManoeuvre, np.ndarray] = {}
        self._steppers: dict[SteadyManoeuvre, ETD2RK] = {}
        self._clear: dict[int, tuple] = {}
        self._last_packed: tuple | None = None  # (wind, packed) of the last wind flown by advance (_packed_wind)
        z = self._z = self.layout.position.start + 2

        def ground(t: float, y: np.ndarray, u: np.ndarray, wind) -> float:
            return -y[z]

        ground.terminal = True
        ground.direction = -1.0
        self._ground = ground

    # ------------------------------------------------------------------ trim and Jacobian
    def trim(self, manoeuvre: SteadyManoeuvre) -> TrimPoint:
        """Still-air trim of ``manoeuvre`` (the last :data:`TRIM_CACHE` trims are cached: trims are deterministic).

        Raises TrimError for a statically divergent trim (``TrimPoint.stability``): no episode starts from it."""
        point = self._trims.pop(manoeuvre, None)
        if point is None:
            point = trim(self.model, manoeuvre)
            if point.stability.is_divergent:
                raise TrimError(f"cannot start an episode from the trim of {self.model.aircraft.name} in "
                                f"{manoeuvre.describe()}: it is not an equilibrium the aircraft stays in, "
                                f"{point.stability.message}")
        self._trims[manoeuvre] = point
        _evict(self._trims)
        return point

    @single_blas_thread
    def start(self, manoeuvre: SteadyManoeuvre) -> IntegrationState:
        """The integration state of an episode flown about the (still-air) trim of ``manoeuvre``.

        For Radau and ETD2RK, the Jacobian d rhs / dx at that trim is computed once and cached per manoeuvre
        (:data:`TRIM_CACHE` of them): for Radau it only steers the Newton iterations; for ETD2RK it is the linear
        part, whose matrix functions for the step ``dt / substeps`` are computed here too, once per manoeuvre.
        """
        if self.method not in ("Radau", *FIXED_STEP_METHODS):
            return IntegrationState(manoeuvre)
        jac = self._jacobians.pop(manoeuvre, None)
        if jac is None:
            point = self.trim(manoeuvre)
            jac = jacobian(self.model, point.x, point.u, controls=False)[0]
        self._jacobians[manoeuvre] = jac
        _evict(self._jacobians)
        if self.method == "Radau":
            return IntegrationState(manoeuvre, jac=jac)
        stepper = self._steppers.pop(manoeuvre, None)
        if stepper is None:
            stepper = ETD2RK(jac, self.dt / self.substeps)
        self._steppers[manoeuvre] = stepper
        _evict(self._steppers)
        return IntegrationState(manoeuvre, stepper, stepper.step_data(self.model, self.substeps))

    # ------------------------------------------------------------------ actuators
    def rate_limit(self, applied: np.ndarray, command: np.ndarray) -> np.ndarray:
        """Controls after one period of rate-limited motion from ``applied`` towards ``command`` (rows (m, 4) or (4,);
        :func:`flexsim.sim._step_kernels.rate_limit_rows`)."""
        a = np.ascontiguousarray(applied, dtype=float)
        rows = a.reshape(-1, 4)
        out = np.empty_like(rows)
        _sk.rate_limit_rows(rows, np.ascontiguousarray(command, dtype=float).reshape(-1, 4), self.rate_step, out)
        return out.reshape(a.shape)

    # ------------------------------------------------------------------ integration
    @single_blas_thread
    def advance(self, state: IntegrationState, x: np.ndarray, u: np.ndarray, t0: float, t1: float,
                wind: Wind | None = None) -> StepOutcome:
        """Integrate ``rhs`` from t0 to t1 [s] with the controls ``u`` held (zero-order hold) in the wind field
        ``wind`` (``wind(t, positions_ned_m)``; None: still air), from the episode's integration ``state`` (what
        :meth:`start` or the previous period returned; the next one is ``StepOutcome.state``).

        With ETD2RK, t1 - t0 must be the control period ``dt`` (its step is fixed); in still air or a field of
        :mod:`flexsim.sim.disturbances` the period is the compiled step of one row (:meth:`ETD2RK.advance_rows`), with a
        Python wind callable steps around ``model.rhs``.
        """
        if not isinstance(state, IntegrationState):
            raise ValueError(f"state = {state!r}: must be the IntegrationState that start() or the previous period returned")
        if self.substeps:
            return self._advance_etd2rk(state, x, u, t0, t1, wind, self._packed_wind(wind))
        span = t1 - t0
        first = None if state.first_step_s is None else min(state.first_step_s, span)
        options = {"jac": state.jac} if self.method == "Radau" else {}
        try:
            with np.errstate(all="ignore"):
                sol = solve_ivp(self.model.rhs, (t0, t1), x, method=self.method, args=(u, wind), rtol=self.rtol,
                                atol=self.atol, first_step=first, events=self._ground, **options)
        except _MODEL_ERRORS as exc:
            return StepOutcome(x, t0, False, f"model error: {exc}", 0, state=state)
        if sol.status < 0 and t1 - sol.t[-1] <= _SLIVER * span and np.all(np.isfinite(sol.y[:, -1])):
            # scipy stops with "step size less than spacing between numbers" when rounding leaves a
            # remaining interval of a few ulp; the state there is the state at t1 to within |f| * 1e-12 s
            sol.status, sol.t[-1] = 0, t1
        if sol.status < 0 or not np.all(np.isfinite(sol.y[:, -1])):
            good = np.flatnonzero(np.all(np.isfinite(sol.y), axis=0))
            last = int(good[-1]) if good.size else None
            x_end = sol.y[:, last] if last is not None else x
            t_end = float(sol.t[last]) if last is not None else t0
            return StepOutcome(x_end.copy(), t_end, False, f"non-finite state or solver failure: {sol.message}", sol.nfev, sol.nlu,
                               state)
        steps = np.diff(sol.t)
        if steps.size > 1:
            h = float(steps[:-1].max())
            # a whole number of steps per period, 1e-6 long so that rounding cannot leave a sliver at the end
            # (scipy fails when the remaining step is below its spacing of numbers)
            state = replace(state, first_step_s=span / math.ceil(span / h * (1.0 - 1e-9)) * (1.0 + 1e-6))
        elif steps.size == 1:
            state = replace(state, first_step_s=span)
        return StepOutcome(sol.y[:, -1].copy(), float(sol.t[-1]), sol.status == 1, "", sol.nfev, sol.nlu, state)

    def check_span(self, span) -> None:
        """Refuse period lengths ``span`` [s] (scalar or (N,)) other than the control period (ETD2RK's fixed steps)."""
        spans = np.asarray(span, float).reshape(-1)
        bad = np.flatnonzero(~(np.abs(spans - self.dt) <= 1e-9 * self.dt))
        if bad.size:
            raise ValueError(f"t1 - t0 = {float(spans[bad[0]])!r} s: ETD2RK steps whole control periods, must be dt = {self.dt!r} s")

    def _advance_etd2rk(self, state: IntegrationState, x: np.ndarray, u: np.ndarray, t0: float, t1: float,
                        wind: Wind | None, packed: _k.BatchWind | None) -> StepOutcome:
        """ETD2RK over one period: the compiled step (:meth:`ETD2RK.advance_rows`, one row) with the wind ``packed``
        for one row; with ``packed`` None (a Python wind callable, or a right-hand side the kernels do not evaluate,
        :meth:`_packed_wind`) the steps around ``model.rhs`` (:meth:`_advance_fixed`)."""
        if packed is None:
            return self._advance_fixed(state, x, u, t0, t1, wind)
        if state.stepper is None:
            raise ValueError("state: has no ETD2RK stepper; pass the IntegrationState that start() returned (ETD2RK needs "
                             "the trim Jacobian)")
        self.check_span(t1 - t0)
        res = state.stepper.advance_rows(self.model, x, u, float(t0), float(t1), self.substeps, packed)
        return self.rows_outcome(res.x, res.t, res.status, res.steps, np.array([float(t0)]), (state,),
                                 np.reshape(u, (1, 4)), (wind,)).row(0)

    def _advance_fixed(self, state: IntegrationState, x: np.ndarray, u: np.ndarray, t0: float, t1: float,
                       wind: Wind | None) -> StepOutcome:
        """ETD2RK over one period around ``model.rhs`` (a Python wind callable, or a right-hand side the kernels do not
        evaluate): ``substeps`` equal steps (:meth:`ETD2RK.step`: the compiled stages), each checked as the compiled
        step checks it (:func:`flexsim.sim._step_kernels.step_end`) and reported as it reports it (:meth:`rows_outcome`);
        a model error with the message of the exception ``model.rhs`` raised."""
        stepper = state.stepper
        if stepper is None:
            raise ValueError("state: has no ETD2RK stepper; pass the IntegrationState that start() returned (ETD2RK needs "
                             "the trim Jacobian)")
        self.check_span(t1 - t0)
        k, h = self.substeps, stepper.h
        rhs = self.model.rhs
        x = np.asarray(x, dtype=float)
        x_end = np.empty_like(x)
        t, status, taken = t0, _sk.ROW_RUNNING, k
        with np.errstate(all="ignore"):
            for i in range(1, k + 1):
                t_next = t1 if i == k else t0 + i * h
                try:
                    x_next = stepper.step(rhs, t, x, (u, wind))
                except _MODEL_ERRORS as exc:
                    return StepOutcome(x.copy(), t, False, f"model error: {exc}", 2 * i, state=state)
                status, t_end = _sk.step_end(x, x_next, float(t), float(t_next), self._z, x_end)
                if status != _sk.ROW_RUNNING:
                    taken = i
                    if status == _sk.ROW_GROUND:
                        x, t = x_end, t_end
                    break
                x, t = x_next, t_next
        return self.rows_outcome(x[None, :], np.array([float(t)]), np.array([status]), np.array([taken]),
                                 np.array([float(t0)]), (state,)).row(0)

    def rows_outcome(self, x, t, status, taken, t0, states, u=None, winds=None) -> BatchOutcome:
        """The :class:`BatchOutcome` of ETD2RK rows (the compiled step, or the steps around ``model.rhs``) flown with the
        integration ``states`` (N): states x (N, n) and times t (N,) [s] reached, status codes and steps begun (N,) of
        :func:`flexsim.sim._step_kernels.period_end`, period starts t0 (N,) [s] (read for stopped rows only; None if no
        row stopped); a row with a model error reads the model's message (:meth:`model_error`, with the rows' held
        controls ``u`` (N, 4) and wind fields ``winds``; without them "model error")."""
        states = tuple(states)
        m = len(t)
        clear = self._clear.get(m)
        if clear is None:  # the arrays of a period in which no row stopped, shared by such periods: not to be written
            clear = self._clear[m] = (np.full(m, "", dtype=object), np.zeros(m, dtype=np.bool_), np.zeros(m, dtype=np.int64),
                                      np.full(m, 2 * self.substeps, np.int64))
        failure, none, nlu, nfev = clear
        if not np.count_nonzero(status):
            return BatchOutcome(x, t, none, failure, nfev, nlu, none, states)
        failure = failure.copy()
        for r in np.flatnonzero(status == _sk.ROW_MODEL_ERROR):
            failure[r] = "model error" if u is None else self.model_error(states[r], x[r], u[r], float(t[r]), winds[r])
        for r in np.flatnonzero(status == _sk.ROW_NON_FINITE):
            t_start = t0[r] + (taken[r] - 1) * states[r].stepper.h
            failure[r] = f"non-finite state: ETD2RK step {int(taken[r])} of {self.substeps} from t = {float(t_start):.6g} s"
        return BatchOutcome(x, t, status == _sk.ROW_GROUND, failure, 2 * taken, nlu, failure != "", states)

    def model_error(self, state: IntegrationState, x: np.ndarray, u: np.ndarray, t: float, wind: Wind | None) -> str:
        """The failure of a row that the compiled step stopped with a model error (``ROW_MODEL_ERROR``) at state ``x``
        (n,), time ``t`` [s], controls ``u`` (4,) held: "model error: " and the message of ``model.rhs``, which the
        kernel cannot give, at x, or, where the right-hand side can be evaluated there, at the stage state of the step
        from x (:func:`flexsim.sim._step_kernels.stage_a`, as the kernel computes it); "model error" if neither raises.
        Two right-hand sides at most: the period is not flown again."""
        rhs = self.model.rhs
        with np.errstate(all="ignore"):
            try:
                k1 = rhs(t, x, u, wind)
                stepper = state.stepper
                if stepper is not None:
                    xs, f1 = np.array(x, dtype=float, ndmin=2), np.array(k1, dtype=float, ndmin=2)
                    d, a = np.empty_like(xs), np.empty_like(xs)
                    _sk.stage_a(stepper.h_phi1, f1, xs, np.ones(1, np.bool_), False, d, a)
                    rhs(t + stepper.h, a[0], u, wind)
            except _MODEL_ERRORS as exc:
                return f"model error: {exc}"
        return "model error"

    def _packed_wind(self, wind: Wind | None) -> _k.BatchWind | None:
        """``wind`` packed for one row of the compiled step (the last one packed is kept), or None where the compiled
        step cannot fly it: a wind that is not a field of :mod:`flexsim.sim.disturbances` (a Python callable), or a
        model whose right-hand side is not the compiled one (no compiled kernel data, or ``rhs`` replaced)."""
        if not _compiled_rhs(self.model):
            return None
        last = self._last_packed
        if last is not None and last[0] is wind:
            return last[1]
        try:
            packed = self.model.pack_winds([wind])
        except ValueError:
            return None
        self._last_packed = (wind, packed)
        return packed

    # ------------------------------------------------------------------ outputs
    def measure(self, x: np.ndarray, t: float, wind: Wind | None = None) -> Measurements:
        """Air data, attitude and structural sensors of state ``x`` at time ``t`` [s] in the wind field ``wind``
        (:meth:`measure_batch` of one state)."""
        return self.measure_batch(np.asarray(x, dtype=float)[None, :], np.array([float(t)]), [wind]).row(0)

    def measure_batch(self, x: np.ndarray, t: np.ndarray, winds=None, packed=None) -> MeasurementBatch:
        """:class:`~flexsim.sim.measurements.MeasurementBatch` of states x (N, n) at times t (N,) [s], aircraft i in
        the wind ``winds[i]``.

        ``winds``: a sequence of N wind fields (None entries: still air) or None (all in still air); ``packed``: the
        same winds packed by the model's ``pack_winds`` (then the air data are computed in the compiled
        :func:`flexsim.sim.measurements.measure_rows` too), or None (then each wind is asked in Python,
        :meth:`OutputMaps.air_velocity_body`). A wind field that cannot answer at a position gives still-air data.
        """
        x = kernel_arg(x)  # writable, as the compiled period passes it (one specialisation of measure_rows)
        n = x.shape[0]
        t = np.array(t, dtype=float) if np.shape(t) == (n,) else np.full(n, float(t))
        out = np.empty((n, self.n_measurements))
        wind, given, mode = self._still, np.zeros((0, 3)), _ms.WIND_STILL
        if winds is not None and not all(w is None for w in winds):
            if isinstance(packed, _k.BatchWind):
                wind, mode = packed, _ms.WIND_PACKED
            else:
                given, mode = self._air_velocity(t, x, winds), _ms.WIND_GIVEN
        _ms.measure_rows(x, mode, given, wind, self.measure_data, out)
        return MeasurementBatch(t, out, SENSOR_COMPONENTS)

    def _air_velocity(self, t, x, winds) -> np.ndarray:
        """Body-axes velocity relative to the air at the body origin (N, 3) [m/s] of winds given as callables."""
        out = np.array(x[:, self.layout.v])
        with np.errstate(all="ignore"):
            for i, wind in enumerate(winds):
                if wind is not None:
                    try:
                        out[i] = self.outputs.air_velocity_body(float(t[i]), x[i], wind)
                    except ValueError:  # a wind field that cannot answer at this position: still-air data
                        pass
        return out

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


# ---------------------------------------------------------------------- many aircraft
#: The modes of :func:`flexsim.sim._step_kernels.period_rows`, by (still air, products over the rows).
_PERIOD_MODES = {(still, over): _sk.PeriodMode(_ms.WIND_STILL if still else _ms.WIND_PACKED, over)
                 for still in (False, True) for over in (False, True)}


#: The right-hand side that the compiled kernels evaluate (:func:`_compiled_rhs`).
_KERNEL_RHS = AircraftModel.rhs


def _compiled_rhs(model) -> bool:
    """Whether the compiled step evaluates ``model.rhs``: a model with compiled kernel data whose ``rhs`` is the
    :class:`AircraftModel` one (not one replaced on its class, e.g. a stand-in right-hand side)."""
    return isinstance(getattr(model, "kernel_data", None), _k.KernelData) and type(model).rhs is _KERNEL_RHS


def _shared_stepper(dynamics: Sequence[FlightDynamics], states: Sequence[IntegrationState]) -> ETD2RK | None:
    """The ETD2RK stepper of all rows if they share one (same trim Jacobian and step) and one model with compiled
    data, else None."""
    first, model = states[0].stepper, dynamics[0].model
    if first is None or not dynamics[0].substeps or not _compiled_rhs(model):
        return None
    for d, st in zip(dynamics, states):
        if st.stepper is not first or d.model is not model:
            return None
    return first


def _period_group(first: FlightDynamics, step_data: _sk.StepData, x: np.ndarray, applied: np.ndarray, command: np.ndarray,
                  k: np.ndarray, packed: _k.BatchWind, winds) -> _sk.PeriodOut:
    """One compiled call (:func:`flexsim.sim._step_kernels.period_rows`) for rows about one trim (``step_data``)."""
    m = x.shape[0]
    still = winds[0] is None if m == 1 else all(w is None for w in winds)
    out = _sk.PeriodOut(np.empty((m, 4)), np.empty((m, first.layout.n_states)), np.empty(m), np.empty(m, np.int64),
                        np.empty(m, np.int64), np.empty((m, first.n_measurements)))
    start = _sk.PeriodStart(x, applied, command, first.rate_step, k, first.dt)
    mode = _PERIOD_MODES[still, m >= COMPILED_ROWS_BELOW]
    _sk.period_rows(*_sk.period_args(first.model.kernel_data, packed, step_data, first.measure_data, start, mode, out))
    return out


@single_blas_thread
def advance_rows(dynamics: Sequence[FlightDynamics], states: Sequence[IntegrationState], x: np.ndarray, u: np.ndarray,
                 t0: np.ndarray, t1: np.ndarray, winds, packed=None) -> BatchOutcome:
    """Integrate one control period of many aircraft (zero-order hold of each row's controls u (N, 4)).

    Row i is what ``dynamics[i].advance(states[i], x[i], u[i], t0[i], t1[i], winds[i])`` returns (same checks:
    non-finite state, model error, ground contact located by linear interpolation within the ETD2RK step). Rows sharing
    one ETD2RK stepper, in still air or with their winds ``packed`` (the model's ``pack_winds`` of the N winds), take
    the compiled steps in one call (:meth:`ETD2RK.advance_rows`; matrix products over the rows from
    :data:`COMPILED_ROWS_BELOW` rows on); the others each aircraft's period (:meth:`FlightDynamics.advance`: the
    compiled step for one row, with its packed wind).
    """
    n = len(dynamics)
    first = dynamics[0]
    stepper = _shared_stepper(dynamics, states)
    still = all(w is None for w in winds)
    if stepper is not None and (still or isinstance(packed, _k.BatchWind)):
        t0, t1 = np.asarray(t0, float), np.asarray(t1, float)
        first.check_span(t1 - t0)
        res = stepper.advance_rows(first.model, x, u, t0, t1, first.substeps, None if still else packed,
                                   over_rows=n >= COMPILED_ROWS_BELOW)
        return first.rows_outcome(res.x, res.t, res.status, res.steps, t0, states, np.broadcast_to(u, (n, 4)), winds)
    outcomes = []
    for i, d in enumerate(dynamics):
        one = None if packed is None or not d.substeps else select_packed_rows(packed, slice(i, i + 1))
        if one is not None and _compiled_rhs(d.model):  # its wind already packed: the compiled step, one row
            outcomes.append(d._advance_etd2rk(states[i], x[i], u[i], float(t0[i]), float(t1[i]), winds[i], one))
        else:
            outcomes.append(d.advance(states[i], x[i], u[i], float(t0[i]), float(t1[i]), winds[i]))
    return BatchOutcome.of(outcomes)


@single_blas_thread
def advance_period(dynamics: Sequence[FlightDynamics], states: Sequence[IntegrationState], x: np.ndarray, applied: np.ndarray,
                   command: np.ndarray, k: np.ndarray, winds, packed=None, python_winds=None) -> PeriodResult:
    """One control period of N aircraft: rate limits from the ``applied`` towards the ``command`` controls (N, 4)
    [N, rad], the integration of period ``k[i]`` (N,) int of row i, [k dt, (k + 1) dt] [s] with the control period
    ``dt`` of the dynamics, and the measurements of the states reached; the one route of the environments' periods.

    ``dynamics[i]`` flies row i from its integration state ``states[i]`` (:meth:`FlightDynamics.start` of its episode;
    those of the next period: ``outcome.states``; the rate limits and outputs are those of ``dynamics[0]``);
    ``winds`` the N wind fields, ``packed`` the same packed by :func:`pack_period_winds` (or the model's
    ``pack_winds``; None: none packed) and ``python_winds`` (N,) bool the rows whose wind it packed as still air because
    the kernels cannot evaluate it (a Python callable; None: none).

    Each row takes one of two paths (:func:`_kernel_rows` decides): the rows the kernels can fly (ETD2RK about a trim
    of the first row's compiled model, a packed wind) the compiled period, one call of
    :func:`flexsim.sim._step_kernels.period_rows` per trim (rate limits, ETD2RK steps, measurements; a row that stops
    with a model error reads the model's message, :meth:`FlightDynamics.model_error`); the others, by name what the
    kernels cannot run (DOP853 or Radau, a Python wind callable, a right-hand side other than the compiled one), the
    same arithmetic in Python order: the rate limits (:func:`flexsim.sim._step_kernels.rate_limit_rows`), each row's
    :meth:`FlightDynamics.advance` (ETD2RK: the compiled stages around ``model.rhs``; or ``solve_ivp``) and the
    measurements (:func:`flexsim.sim.measurements.measure_rows`). A row's result does not depend on the others'.
    """
    first = dynamics[0]
    m = len(dynamics)
    if python_winds is None and isinstance(packed, _k.BatchWind) and _shared_stepper(dynamics, states) is not None:
        out = _period_group(first, states[0].step_data, x, applied, command, k, packed, winds)  # the arrays as given
        return _compiled_result(first, out, k, states, winds)
    groups, python = _kernel_rows(dynamics, states, packed, python_winds)
    if not python.size and len(groups) == 1:  # every row about one trim, in a subset of the packed winds' rows
        return _compiled_result(first, _period_group(first, states[0].step_data, x, applied, command, k, packed, winds),
                                k, states, winds)
    parts: list[tuple[np.ndarray, BatchOutcome, np.ndarray, np.ndarray]] = []
    for rows in groups:  # one compiled call per trim, each on its rows
        sub = [winds[i] for i in rows]
        out = _period_group(first, states[rows[0]].step_data, x[rows], applied[rows], command[rows], k[rows],
                            select_packed_rows(packed, rows), sub)
        res = _compiled_result(first, out, k[rows], [states[i] for i in rows], sub)
        parts.append((rows, res.outcome, res.u, res.meas.matrix))
    if python.size:
        parts.append((python, *_python_rows(dynamics, states, x, applied, command, k, winds, packed, python_winds, python)))
    return _join(first, m, parts)


def _compiled_result(first: FlightDynamics, out: _sk.PeriodOut, k: np.ndarray, states, winds) -> PeriodResult:
    """The :class:`PeriodResult` of rows flown by one compiled call (:func:`_period_group`)."""
    stopped = np.count_nonzero(out.status)
    return PeriodResult(first.rows_outcome(out.x, out.t, out.status, out.taken, k * first.dt if stopped else None, states,
                                           out.u, winds), out.u, MeasurementBatch(out.t, out.meas, SENSOR_COMPONENTS))


def _kernel_rows(dynamics: Sequence[FlightDynamics], states: Sequence[IntegrationState], packed,
                 python_winds) -> tuple[list[np.ndarray], np.ndarray]:
    """The rows of a period that the compiled kernels fly, grouped by their ETD2RK stepper (one per trim, int index
    arrays in order of first appearance), and the rest (int indices): a row is compiled when its wind is packed (in
    ``packed``, not marked in ``python_winds``) and it flies the first row's model, whose right-hand side the kernels
    evaluate (:func:`_compiled_rhs`), with ETD2RK from a state that has its stepper."""
    model = dynamics[0].model
    kernel = isinstance(packed, _k.BatchWind) and _compiled_rhs(model)
    groups: dict[int, list[int]] = {}
    python = []
    for i, (d, st) in enumerate(zip(dynamics, states)):
        if kernel and d.substeps and d.model is model and st.stepper is not None and not (
                python_winds is not None and python_winds[i]):
            groups.setdefault(id(st.stepper), []).append(i)
        else:
            python.append(i)
    return [np.array(rows, np.int64) for rows in groups.values()], np.array(python, np.int64)


def _python_rows(dynamics, states, x, applied, command, k, winds, packed, python_winds, rows) -> tuple:
    """(outcome, u, measurement rows) of the rows ``rows`` that the kernels cannot fly (:func:`advance_period`): the
    rate limits, each row's :meth:`FlightDynamics.advance` and the measurements, the winds read as packed where they
    all are, else each asked in Python."""
    first = dynamics[0]
    u = first.rate_limit(applied[rows], command[rows])
    t0, t1 = k[rows] * first.dt, (k[rows] + 1) * first.dt
    sub = [winds[i] for i in rows]
    outcome = BatchOutcome.of([dynamics[i].advance(states[i], x[i], u[j], float(t0[j]), float(t1[j]), winds[i])
                               for j, i in enumerate(rows)])
    given = python_winds is not None and bool(np.any(python_winds[rows]))
    meas = first.measure_batch(outcome.x, outcome.time_s, sub, None if given else select_packed_rows(packed, rows))
    return outcome, u, meas.matrix


def _join(first: FlightDynamics, m: int, parts) -> PeriodResult:
    """The :class:`PeriodResult` of m rows from the parts (rows, outcome, u, measurement rows) that flew them."""
    n = first.layout.n_states
    x, t, u, meas = np.empty((m, n)), np.empty(m), np.empty((m, 4)), np.empty((m, first.n_measurements))
    crashed, failed = np.empty(m, np.bool_), np.empty(m, np.bool_)
    failure, nfev, nlu = np.empty(m, dtype=object), np.empty(m, np.int64), np.empty(m, np.int64)
    states: list = [None] * m
    for rows, o, u_rows, meas_rows in parts:
        x[rows], t[rows], u[rows], meas[rows] = o.x, o.time_s, u_rows, meas_rows
        crashed[rows], failed[rows], failure[rows], nfev[rows], nlu[rows] = o.crashed, o.failed, o.failure, o.nfev, o.nlu
        for j, i in enumerate(rows):
            states[i] = o.states[j]
    return PeriodResult(BatchOutcome(x, t, crashed, failure, nfev, nlu, failed, tuple(states)), u,
                        MeasurementBatch(t, meas, SENSOR_COMPONENTS))


def pack_period_winds(dynamics: Sequence[FlightDynamics | None], winds) -> tuple[_k.BatchWind | None, np.ndarray | None]:
    """The ``packed`` and ``python_winds`` arguments of :func:`advance_period` for rows flown on ``dynamics`` in
    ``winds``, made once (e.g. per reset): the winds packed by the model's ``pack_winds``, a wind that the kernels
    cannot evaluate (not a field of :mod:`flexsim.sim.disturbances`: a Python callable) packed as still air and marked
    True in ``python_winds`` (None where every wind is packed); (None, None) where the model packs no winds."""
    model = dynamics[0].model if len(dynamics) and dynamics[0] is not None else None
    if getattr(model, "pack_winds", None) is None:
        return None, None
    try:
        return model.pack_winds(winds), None
    except ValueError:
        python = np.array([w is not None and not isinstance(getattr(w, "wind_data", None), _k.WindData) for w in winds])
        return model.pack_winds([None if p else w for w, p in zip(winds, python)]), python


def select_packed_rows(packed: _k.BatchWind | None, rows: np.ndarray | slice) -> _k.BatchWind | None:
    """The winds ``packed`` by :func:`pack_period_winds` of ``rows`` only (int indices or a slice; None stays None)."""
    if packed is None:
        return None
    selected = packed.rows[rows]  # a view of the read-only rows, or a copy (index array)
    selected.flags.writeable = False  # read-only as pack_winds makes them (a writable array: one more compile)
    return packed._replace(rows=selected)
