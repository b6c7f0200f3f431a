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
from flexsim.atmosphere import H_MAX, H_MIN
from flexsim.model.jacobian import jacobian
from flexsim import _kernels as _k
from flexsim.model.aircraft_model import AircraftModel, Wind
from flexsim.model.sensors import SENSOR_QUANTITIES, SensorBank
from flexsim.sim import _step_kernels as _sk
from flexsim.sim.fixed_step import ETD2RK
from flexsim.sim.outputs import OutputMaps
from flexsim.kinematics import euler_rate_matrix_inverse
from flexsim.trim import SteadyManoeuvre, TrimError, TrimPoint, trim

from flexsim.envs import row_kernels as _rk
from flexsim.envs.config import FIXED_STEP_METHODS, ActuatorRates, IntegratorSettings

__all__ = ["FlightDynamics", "Measurements", "MeasurementBatch", "StepOutcome", "BatchOutcome", "SENSOR_COMPONENTS", "advance_rows",
           "rhs_rows"]

#: Components carrying the structural sensors (tip deflection, twist and their rates), in order.
SENSOR_COMPONENTS = ("right_wing", "left_wing", "vtail")
#: The components with a root bending moment output (:attr:`Measurements.root_bending_moment_n_m`).
_WING_HALVES = tuple(c for c in SENSOR_COMPONENTS if c != "vtail")
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


class MeasurementBatch:
    """:class:`Measurements` of N states at once (:meth:`FlightDynamics.measure_batch`): the same fields with a
    leading axis N (scalars become arrays (N,), vectors (N, 3); the structural dicts map a component to an
    array (N,)), so the same array code computes the task errors of one or many aircraft. The fields are views
    of one matrix, the rows of :func:`flexsim.envs.row_kernels.measure_rows`.

    Attributes
    ----------
    time_s : ndarray, shape (N,)
    matrix : ndarray, shape (N, SENSORS_AT + 5 C)
        The measurement rows (columns :data:`flexsim.envs.row_kernels.MEAS_COLUMNS`, then the structural
        outputs of the C :data:`SENSOR_COMPONENTS`).
    """

    __slots__ = ("time_s", "matrix")

    def __init__(self, time_s: np.ndarray, matrix: np.ndarray) -> None:
        self.time_s, self.matrix = time_s, matrix

    position_ned_m = property(lambda self: self.matrix[:, 0:3])
    euler_rad = property(lambda self: self.matrix[:, 3:6])
    body_rates_rad_s = property(lambda self: self.matrix[:, 6:9])
    airspeed_m_s = property(lambda self: self.matrix[:, 9])
    alpha_rad = property(lambda self: self.matrix[:, 10])
    beta_rad = property(lambda self: self.matrix[:, 11])
    mach = property(lambda self: self.matrix[:, 12])
    altitude_m = property(lambda self: self.matrix[:, 13])
    heading_rate_rad_s = property(lambda self: self.matrix[:, 14])

    @property
    def sensors(self) -> np.ndarray:
        """All structural outputs, (N, 5, C) (:meth:`flexsim.model.sensors.SensorBank.evaluate`)."""
        c = len(SENSOR_COMPONENTS)
        return self.matrix[:, _rk.SENSORS_AT:].reshape(-1, 5, c)

    def _structural(self, k: int, names=SENSOR_COMPONENTS) -> dict:
        s = _rk.SENSORS_AT + k * len(SENSOR_COMPONENTS)
        return {name: self.matrix[:, s + j] for j, name in enumerate(SENSOR_COMPONENTS) if name in names}

    tip_deflection_m = property(lambda self: self._structural(0))
    tip_deflection_rate_m_s = property(lambda self: self._structural(1))
    tip_twist_rad = property(lambda self: self._structural(2))
    tip_twist_rate_rad_s = property(lambda self: self._structural(3))
    root_bending_moment_n_m = property(lambda self: self._structural(4, _WING_HALVES))  # per wing half

    def row(self, i: int) -> Measurements:
        """The :class:`Measurements` of state i (floats and copies)."""
        def f(a):
            return float(a[i])

        return Measurements(f(self.time_s), self.position_ned_m[i].copy(), self.euler_rad[i].copy(), self.body_rates_rad_s[i].copy(),
                            f(self.airspeed_m_s), f(self.alpha_rad), f(self.beta_rad), f(self.mach), f(self.altitude_m),
                            f(self.heading_rate_rad_s), *({k: f(v) for k, v in d.items()} for d in (
                                self.tip_deflection_m, self.tip_deflection_rate_m_s, self.tip_twist_rad, self.tip_twist_rate_rad_s,
                                self.root_bending_moment_n_m)))


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


@dataclass(frozen=True)
class BatchOutcome:
    """Results of one control period of N aircraft (:func:`advance_rows`): the :class:`StepOutcome` fields as
    arrays over the rows (``x`` (N, n), ``time_s`` (N,), ``crashed`` (N,) bool, ``failure`` (N,) object array of
    str, ``nfev`` and ``nlu`` (N,) int)."""

    x: np.ndarray
    time_s: np.ndarray
    crashed: np.ndarray
    failure: np.ndarray
    nfev: np.ndarray
    nlu: np.ndarray

    def row(self, i: int) -> StepOutcome:
        """The :class:`StepOutcome` of row i."""
        return StepOutcome(self.x[i].copy(), float(self.time_s[i]), bool(self.crashed[i]), str(self.failure[i]), int(self.nfev[i]),
                           int(self.nlu[i]))

    @classmethod
    def of(cls, outcomes: list[StepOutcome]) -> BatchOutcome:
        """The batch of single :class:`StepOutcome` s, in order."""
        return cls(np.array([o.x for o in outcomes], dtype=float), np.array([o.time_s for o in outcomes], dtype=float),
                   np.array([o.crashed for o in outcomes], dtype=bool), np.array([o.failure for o in outcomes], dtype=object),
                   np.array([o.nfev for o in outcomes], dtype=np.int64), np.array([o.nlu for o in outcomes], dtype=np.int64))


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
        #: The structural outputs of :data:`SENSOR_COMPONENTS` in batched form (one product for N states).
        self.sensor_bank = SensorBank.of(self.sensors, SENSOR_COMPONENTS, self.layout.n_states)
        self._measure_data = self._kernel_measure_data()
        self._n_meas = _rk.SENSORS_AT + self.sensor_bank.matrix.shape[1]
        self._no_rows, self._no_given = np.zeros((0, 4), np.int64), np.zeros((0, 3))
        self.method = integrator.resolve(aero)
        self.rtol = integrator.rtol
        self.atol = integrator.atol(self.layout)
        self.dt = float(control_dt_s)
        self.substeps = integrator.substeps(self.dt) if self.method in FIXED_STEP_METHODS else 0
        lo, hi = aircraft.control_limits()
        self.u_low, self.u_high = lo, hi
        self.rate_limits = rates.limits(float(hi[0]))
        self._rate_step = self.rate_limits * self.dt  # the largest control change per period
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

    def _kernel_measure_data(self) -> tuple:
        """The arguments of :func:`flexsim.envs.row_kernels.measure_rows` that describe the model: first state
        index of R, Theta, v, omega; the structural outputs in the kernel's column order (output k of component
        c at C k + c) as the nonzero entries of the :class:`SensorBank` matrix, in state order; the ISA range."""
        lay, bank = self.layout, self.sensor_bank.matrix
        index = np.array([lay.position.start, lay.euler.start, lay.v.start, lay.omega.start], dtype=np.int64)
        c = len(SENSOR_COMPONENTS)
        ptr, idx, w = [0], [], []
        for o in range(bank.shape[1]):
            k, comp = divmod(o, c)
            column = bank[:, len(SENSOR_QUANTITIES) * comp + k]
            nz = np.flatnonzero(column)
            idx.extend(nz.tolist())
            w.extend(column[nz].tolist())
            ptr.append(len(idx))
        return (index, np.array(ptr, np.int64), np.array(idx, np.int64), np.array(w, float), np.array([H_MIN, H_MAX]))

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
        """Still-air trim of ``manoeuvre`` (the last ``TRIM_CACHE`` trims are cached: trims are deterministic).

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
        step = self._rate_step
        return applied + np.minimum(np.maximum(command - applied, -step), step)

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
        """Air data, attitude and structural sensors of state ``x`` at time ``t`` [s] in the wind field ``wind``
        (:meth:`measure_batch` of one state)."""
        return self.measure_batch(np.asarray(x, dtype=float)[None, :], np.array([float(t)]), [wind]).row(0)

    def measure_batch(self, x: np.ndarray, t: np.ndarray, winds=None, packed=None) -> MeasurementBatch:
        """:class:`MeasurementBatch` of states x (N, n) at times t (N,) [s], aircraft i in the wind ``winds[i]``.

        ``winds``: a sequence of N wind fields (None entries: still air) or None (all in still air);
        ``packed``: the same winds packed by the model's ``pack_winds`` (then the air data are computed in the
        compiled :func:`flexsim.envs.row_kernels.measure_rows` too), or None (then each wind is asked in Python,
        :meth:`OutputMaps.air_velocity_body`). The air data are relative to the air at the body origin; a wind
        field that cannot answer at a position gives still-air data for that row.
        """
        x = np.ascontiguousarray(x, dtype=float)
        n = x.shape[0]
        t = np.array(t, dtype=float) if np.shape(t) == (n,) else np.full(n, float(t))
        out = np.empty((n, self._n_meas))
        w = _k.NO_WIND
        rows, given, mode = self._no_rows, self._no_given, _rk.WIND_STILL
        if winds is not None and not all(wind is None for wind in winds):
            if isinstance(packed, _k.BatchWind):
                rows, w, mode = packed.rows, packed[1:], _rk.WIND_PACKED
            else:
                given, mode = self._air_velocity(t, x, winds), _rk.WIND_GIVEN
        _rk.measure_rows(x, mode, given, rows, *w, *self._measure_data, out)
        return MeasurementBatch(t, out)

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
#: Exceptions of the model that end one aircraft's period as a "model error" (as :meth:`FlightDynamics.advance`).
_MODEL_ERRORS = (ValueError, ArithmeticError, np.linalg.LinAlgError)


def rhs_rows(dynamics, t: np.ndarray, x: np.ndarray, u: np.ndarray, winds, errors: dict, packed=None) -> np.ndarray:
    """State derivatives of many aircraft: row i is ``dynamics[i].model.rhs(t[i], x[i], u[i], winds[i])``.

    Parameters
    ----------
    dynamics : sequence of FlightDynamics, length m
    t : ndarray, shape (m,)
        Times [s].
    x : ndarray, shape (m, n)
        States (layout ``dynamics[i].layout``).
    u : ndarray, shape (m, 4)
        Controls [N, rad, rad, rad].
    winds : sequence of wind fields or None, length m
    errors : dict
        Filled with ``{row: exception}`` for rows whose model raised one of the model errors (an entry already
        there is kept); their derivative rows are NaN.
    packed : optional
        The rows' winds packed once by the model's ``pack_winds`` (rows in this order), or None.

    Returns
    -------
    ndarray, shape (m, n)

    Rows that share one model whose class offers ``rhs_batch(t, x, u, wind)`` (all rows in one compiled call;
    each row equals ``rhs`` bit for bit; the wind fields of :mod:`flexsim.sim.disturbances` do not depend on t)
    go through it when they fly in still air or their winds come ``packed``; the rest, and all rows of a batch
    call that raised (to find which row failed), one by one through ``rhs``.
    """
    model = dynamics[0].model
    batch = getattr(model, "rhs_batch", None)
    if batch is not None and all(d.model is model for d in dynamics):
        wind = packed if packed is not None else (None if all(w is None for w in winds) else False)
        if wind is not False:
            try:
                return np.asarray(batch(float(t[0]), x, u, wind), dtype=float).reshape(x.shape)
            except _MODEL_ERRORS:
                pass  # evaluated row by row below, which names the failing rows
    out = np.empty_like(x)
    for i, dyn in enumerate(dynamics):
        try:
            out[i] = dyn.model.rhs(float(t[i]), x[i], u[i], winds[i])
        except _MODEL_ERRORS as exc:
            errors.setdefault(i, exc)  # the first error of the step (its second evaluation sees the NaN row)
            out[i] = np.nan
    return out


def _subset(packed, rows):
    """The packed winds of the given rows (None stays None)."""
    return None if packed is None else packed._replace(rows=packed.rows[np.asarray(rows, dtype=np.int64)])


@single_blas_thread
def advance_rows(dynamics, x: np.ndarray, u: np.ndarray, t0: np.ndarray, t1: np.ndarray, winds, rhs=rhs_rows,
                 packed=None) -> BatchOutcome:
    """Integrate one control period of many aircraft in one call (zero-order hold of each row's controls).

    Row i is what ``dynamics[i].advance(x[i], u[i], t0[i], t1[i], winds[i])`` returns (same checks: non-finite
    state, model error, crash located by linear interpolation within the ETD2RK step). Aircraft whose ETD2RK
    stepper is the same object (same trim Jacobian and step) are stepped together as matrix products over
    their rows (:meth:`ETD2RK.step_rows`), with right-hand sides from ``rhs`` (:func:`rhs_rows`: one compiled
    call for all rows); the others (the ``solve_ivp`` methods) one by one.

    Parameters
    ----------
    dynamics : sequence of FlightDynamics, length N
        Each aircraft's dynamics, after :meth:`FlightDynamics.start` of its episode.
    x : ndarray, shape (N, n)
    u : ndarray, shape (N, 4)
    t0, t1 : ndarray, shape (N,)
        Start and end of each period [s].
    winds : sequence, length N
    rhs : callable
        ``rhs(dynamics, t, x, u, winds, errors, packed) -> x_dot`` over rows (:func:`rhs_rows`).
    packed : optional
        The N winds packed by the model's ``pack_winds`` (a named tuple whose ``rows`` select each aircraft's
        wind data), or None.

    Returns
    -------
    BatchOutcome
    """
    n = len(dynamics)
    first = dynamics[0].stepper
    if first is not None and dynamics[0].substeps and all(d.stepper is first for d in dynamics):
        return _advance_etd2rk(dynamics, x, u, np.asarray(t0, float), np.asarray(t1, float), winds, rhs, packed)
    outcomes: list = [None] * n
    groups: dict[int, list[int]] = {}
    for i, dyn in enumerate(dynamics):
        if dyn.substeps and dyn.stepper is not None:
            groups.setdefault(id(dyn.stepper), []).append(i)
        else:
            outcomes[i] = dyn.advance(x[i], u[i], float(t0[i]), float(t1[i]), winds[i])
    for rows in groups.values():
        part = _advance_etd2rk([dynamics[i] for i in rows], x[rows], u[rows], t0[rows], t1[rows], [winds[i] for i in rows], rhs,
                               _subset(packed, rows))
        for r, i in enumerate(rows):
            outcomes[i] = part.row(r)
    return BatchOutcome.of(outcomes)


#: Below this many rows sharing one stepper, :func:`advance_rows` uses the compiled steps
#: (:meth:`ETD2RK.advance_rows`, no Python per substep); from it on, the matrix products over the rows
#: (:meth:`ETD2RK.step_rows`, GEMMs, with one compiled right-hand-side call per evaluation). Measured
#: (benchmarks/bench_envs.py --batched): compiled 2x faster at N = 1, equal near N = 16, 25 % slower at N = 256.
#: The environments' one compiled call per period (:func:`flexsim.envs.row_kernels.period_rows`) switches at the
#: same number of rows from the products row by row to GEMMs over the rows inside the call.
COMPILED_ROWS_BELOW = 32


def _advance_etd2rk(dyns, x, u, t0, t1, winds, rhs, packed=None) -> BatchOutcome:
    """ETD2RK periods of aircraft sharing one stepper (``FlightDynamics._advance_fixed`` over rows)."""
    first = dyns[0]
    stepper, k, dt = first.stepper, first.substeps, first.dt
    span = t1 - t0
    bad = np.flatnonzero(~(np.abs(span - dt) <= 1e-9 * dt))
    if bad.size:
        raise ValueError(f"t1 - t0 = {span[bad[0]]!r} s: ETD2RK steps whole control periods, must be dt = {dt!r} s")
    model = first.model
    compiled = (len(dyns) < COMPILED_ROWS_BELOW and rhs is rhs_rows and hasattr(stepper, "advance_rows")
                and isinstance(getattr(model, "kernel_data", None), _k.KernelData) and all(d.model is model for d in dyns)
                and (isinstance(packed, _k.BatchWind) or all(w is None for w in winds)))
    if not compiled:
        return _advance_etd2rk_products(dyns, x, u, t0, t1, winds, rhs, packed)
    res = stepper.advance_rows(model, x, u, t0, t1, k, packed)
    m = len(dyns)
    failure = np.full(m, "", dtype=object)
    if not res.status.any():  # every row completed its period (ROW_RUNNING = 0)
        return BatchOutcome(res.x, res.t, np.zeros(m, dtype=np.bool_), failure, 2 * res.steps, np.zeros(m, dtype=np.int64))
    crashed = res.status == _sk.ROW_GROUND
    for r in np.flatnonzero(res.status == _sk.ROW_NON_FINITE):
        t_start = t0[r] + (res.steps[r] - 1) * stepper.h
        failure[r] = f"non-finite state: ETD2RK step {int(res.steps[r])} of {k} from t = {float(t_start):.6g} s"
    out = BatchOutcome(res.x, res.t, crashed, failure, 2 * res.steps.astype(np.int64), np.zeros(m, dtype=np.int64))
    errors = np.flatnonzero(res.status == _sk.ROW_MODEL_ERROR)
    if errors.size:  # the model's message: these rows again through the right-hand side that raises it
        again = _advance_etd2rk_products([dyns[r] for r in errors], x[errors], u[errors], t0[errors], t1[errors],
                                         [winds[r] for r in errors], rhs, _subset(packed, errors))
        for name in ("x", "time_s", "crashed", "failure", "nfev"):
            getattr(out, name)[errors] = getattr(again, name)
    return out


def _advance_etd2rk_products(dyns, x, u, t0, t1, winds, rhs, packed=None) -> BatchOutcome:
    """:func:`_advance_etd2rk` as matrix products over the rows (:meth:`ETD2RK.step_rows`)."""
    first = dyns[0]
    stepper, k, h = first.stepper, first.substeps, first.stepper.h
    z = first.layout.position.start + 2  # down coordinate: altitude -x[z]
    m = len(dyns)
    x = np.array(x, dtype=float)
    x_end = x.copy()
    t = np.array(t0, dtype=float)
    t_end = np.array(t1, dtype=float)
    crashed = np.zeros(m, dtype=np.bool_)
    failure = np.full(m, "", dtype=object)
    nfev = np.full(m, 2 * k, dtype=np.int64)
    active = np.arange(m)
    full = True  # all rows active: no row selection
    rows_d, rows_u, rows_w, rows_p = dyns, u, winds, packed
    with np.errstate(all="ignore"):
        for i in range(1, k + 1):
            errors: dict[int, Exception] = {}

            def fun(tt, xx):
                return rhs(rows_d, tt, xx, rows_u, rows_w, errors, rows_p)

            xa, ta = (x, t) if full else (x[active], t[active])
            x_next = stepper.step_rows(fun, ta, xa)
            t_next = (t1[active] if not full else t1) if i == k else ta + h
            stop = ~np.isfinite(x_next).all(axis=1) | ((x_next[:, z] >= 0.0) & (xa[:, z] < 0.0))
            if errors:
                stop[list(errors)] = True
            for r in np.flatnonzero(stop):
                j = active[r]
                nfev[j] = 2 * i
                if r in errors:
                    x_end[j], t_end[j], failure[j] = xa[r], ta[r], f"model error: {errors[r]}"
                elif not np.all(np.isfinite(x_next[r])):
                    x_end[j], t_end[j] = xa[r], ta[r]
                    failure[j] = f"non-finite state: ETD2RK step {i} of {k} from t = {float(ta[r]):.6g} s"
                else:
                    s = xa[r, z] / (xa[r, z] - x_next[r, z])
                    x_end[j], t_end[j], crashed[j] = xa[r] + s * (x_next[r] - xa[r]), ta[r] + s * (t_next[r] - ta[r]), True
            if full and not stop.any():
                x, t = x_next, t_next
                continue
            keep = ~stop
            x[active] = x_next
            t[active] = t_next
            active = active[keep]
            full = False
            if not active.size:
                break
            rows_d = [dyns[j] for j in active]
            rows_u, rows_w, rows_p = u[active], [winds[j] for j in active], _subset(packed, active)
    if active.size:
        x_end[active] = x if full else x[active]
    return BatchOutcome(x_end, t_end, crashed, failure, nfev, np.zeros(m, dtype=np.int64))
