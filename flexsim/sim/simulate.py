"""Time-domain simulation of the one nonlinear model, with events and a flight log written as it runs.

``simulate(model, x0 | TrimPoint, t_end_s, controls=..., wind=...)`` integrates ``model.rhs(t, x, u, wind)`` (Tuzcu &
Nguyen 2014, eqs. 4 and 33 with the strip aerodynamics of eqs. 25-31) with the integrators of
``scipy.integrate`` — the ``OdeSolver`` classes behind ``solve_ivp`` (Radau, DOP853, LSODA, BDF, RK45,
RK23), stepped here one step at a time so that every accepted step is sampled from its dense output onto
the output grid and the flight log while the integration proceeds, and events are located on the dense
output as ``solve_ivp`` does (Brent's method). The solver is restarted only where the right-hand side
changes character: at the breakpoints of a control schedule and at every control period of a feedback
controller (zero-order hold). Restarting at every log chunk instead cost 2.2x the run time of a gust
response with Radau (LU refactorisations), see ``docs/simulation.md``.

Default method (measured, ``benchmarks/bench_simulate.py`` and ``docs/simulation.md``): with aerodynamics,
**ETD2RK** (:mod:`flexsim.sim.fixed_step`, Cox & Matthews 2002) with the Jacobian of
:func:`flexsim.model.jacobian.jacobian` at the initial state as its linear part, by compiled steps
(:mod:`flexsim.sim.compiled_run`). The finite-state inflow and apparent-mass states give well-damped eigenvalues
down to about -650 s^-1 (|lambda| up to 1500 s^-1 on the GTM), which the exponential integrator takes exactly and
which hold an explicit method at its stability limit (DOP853 needs ~4300 right-hand sides per simulated second
whatever the tolerance). Radau (constant Jacobian) for a wind callable the compiled steps cannot evaluate. Without
aerodynamics the model is a lightly damped structure, and the default is DOP853.

Module layout: this module holds the settings, the events, the scipy stepping loop and :func:`simulate`;
:mod:`flexsim.sim.compiled_run` the compiled ETD2RK loop; :mod:`flexsim.sim.run_parts` what the two loops share.
"""

from __future__ import annotations

import math
import time
import uuid
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.integrate import BDF, DOP853, LSODA, RK23, RK45, Radau
from scipy.optimize import brentq

from flexsim._threads import single_blas_thread
from flexsim.errors import positive_number
from flexsim.model.jacobian import jacobian
from flexsim.model.aircraft_model import AircraftModel, Wind, check_model
from flexsim.sim.controls import ControlSchedule, Controls
from flexsim.sim.fixed_step import ETD2RKSolver
from flexsim.sim.compiled_run import COMPILED_CHUNK_S, RELINEARISE_DRIFT, compiled_wind, integrate_compiled
from flexsim.sim.outputs import OutputMaps
from flexsim.sim.recording import LogSink, resolve_log_path
from flexsim.sim.run_parts import RunEvent, RunOutcome, RunProblem, Sampler, Sinks, emit_step, segment_controls
from flexsim.sim.result import SimulationResult
from flexsim.sim.run_settings import DEFAULT_EVENTS, EventSettings, OutputSettings, SimEvent
from flexsim.trimming.solver import TrimPoint

__all__ = ["ControlSchedule", "IntegratorSettings", "EventSettings", "OutputSettings", "SimEvent", "simulate", "state_scales",
           "METHODS", "DEFAULT_EVENTS", "default_method",
           "DEFAULT_MAX_STEP", "RELINEARISE_DRIFT", "COMPILED_CHUNK_S"]

#: Integration methods by name (scipy.integrate OdeSolver classes).
METHODS = {"Radau": Radau, "DOP853": DOP853, "LSODA": LSODA, "BDF": BDF, "RK45": RK45, "RK23": RK23,
           "ETD2RK": ETD2RKSolver}
_IMPLICIT = ("Radau", "BDF", "LSODA")
#: Default relative tolerance per method family (accuracy checks in docs/simulation.md).
DEFAULT_RTOL = {"implicit": 1e-3, "explicit": 1e-6}
#: Allowed range of :attr:`IntegratorSettings.rtol`.
RTOL_RANGE = (1e-13, 0.1)
#: Default largest step [s]: ETD2RK's fixed step, and the bound of the adaptive methods (so that no gust or event
#: falls between two steps); errors of both in docs/simulation.md.
DEFAULT_MAX_STEP = {"ETD2RK": 0.02, "other": 0.05}
GIMBAL_LIMIT_DEG = 89.0
#: Default structural limit: |tip deflection| of a wing beyond this fraction of its length.
STRUCTURAL_LIMIT_FRACTION = 0.25
_EPS = np.finfo(float).eps


@dataclass(frozen=True, eq=False)
class IntegratorSettings:
    """How the one model is integrated: the settings of a :func:`simulate` run and of the control periods of the
    environments (:class:`flexsim.sim.periods.FlightDynamics`), frozen and validated on construction.

    A field left None takes its user's default in :meth:`resolve`, which returns the settings with every field set.

    Attributes
    ----------
    method : str
        ``"auto"`` (default; :func:`default_method` of the model and its wind) or one of :data:`METHODS`.
    rtol : float or None
        Relative tolerance in [1e-13, 0.1] (not used by ETD2RK); None: :data:`DEFAULT_RTOL` per method family for
        :func:`simulate`, 1e-3 for the control periods.
    atol : float, ndarray of shape (n_states,), or None
        Absolute tolerance, > 0 and finite: one number for every state entry, or one per entry (stored read-only);
        None: ``rtol * state_scales(model)`` for :func:`simulate`, per-state values for the control periods
        (:func:`flexsim.sim.periods.period_atol`).
    max_step_s : float or None
        Largest step [s], > 0 (``math.inf``: no limit); the fixed step of ETD2RK, which must be finite. None:
        :data:`DEFAULT_MAX_STEP` per method.

    Raises
    ------
    ValueError
        A field out of range; the message names the field, its value and the allowed range.
    """

    method: str = "auto"
    rtol: float | None = None
    atol: float | np.ndarray | None = None
    max_step_s: float | None = None

    def __post_init__(self) -> None:
        if self.method != "auto" and self.method not in METHODS:
            raise ValueError(f"method = {self.method!r}: must be 'auto' or one of {', '.join(METHODS)}")
        lo, hi = RTOL_RANGE
        if self.rtol is not None:
            if isinstance(self.rtol, bool) or not (isinstance(self.rtol, (int, float)) and lo <= self.rtol <= hi):
                raise ValueError(f"rtol = {self.rtol!r}: must be a number in [{lo:g}, {hi:g}]")
            object.__setattr__(self, "rtol", float(self.rtol))
        if self.atol is not None:
            try:
                atol = np.array(self.atol, dtype=float)
            except (TypeError, ValueError):
                raise ValueError(f"atol = {self.atol!r}: must be positive and finite (a number or one per state entry)") from None
            if atol.ndim > 1 or atol.size == 0 or not np.all(np.isfinite(atol)) or np.any(atol <= 0):
                raise ValueError(f"atol = {self.atol!r}: must be positive and finite (a number or one per state entry)")
            atol.setflags(write=False)
            object.__setattr__(self, "atol", float(atol) if atol.ndim == 0 else atol)
        if self.max_step_s is not None:
            step = self.max_step_s
            if isinstance(step, bool) or not (isinstance(step, (int, float)) and step > 0):
                raise ValueError(f"max_step_s = {step!r}: must be a number > 0 [s] (math.inf for no limit)")
            if self.method == "ETD2RK" and not math.isfinite(step):
                raise ValueError(f"max_step_s = {step!r}: ETD2RK takes fixed steps of max_step_s, which must be finite [s]")
            object.__setattr__(self, "max_step_s", float(step))

    def _key(self) -> tuple:
        atol = self.atol if not isinstance(self.atol, np.ndarray) else tuple(self.atol.tolist())
        return self.method, self.rtol, atol, self.max_step_s

    def __eq__(self, other: object) -> bool:
        return self._key() == other._key() if isinstance(other, IntegratorSettings) else NotImplemented

    def __hash__(self) -> int:
        return hash(self._key())

    def resolve(self, model: AircraftModel, wind: Wind | None = None, *, rtol: float | None = None,
                atol: np.ndarray | None = None) -> IntegratorSettings:
        """These settings with every field set for a run of ``model`` in ``wind``: ``"auto"`` -> :func:`default_method`,
        ``max_step_s`` :data:`DEFAULT_MAX_STEP` per method, ``rtol`` the caller's default ``rtol`` or :data:`DEFAULT_RTOL`
        per method family, ``atol`` the caller's default ``atol`` or ``rtol * state_scales(model)``; a number ``atol``
        becomes one per state entry."""
        method = default_method(model, wind) if self.method == "auto" else self.method
        step = self.max_step_s
        if step is None:
            step = DEFAULT_MAX_STEP["ETD2RK" if method == "ETD2RK" else "other"]
        rtol = self.rtol if self.rtol is not None else rtol
        if rtol is None:
            rtol = DEFAULT_RTOL["implicit" if method in _IMPLICIT else "explicit"]
        n = model.layout.n_states
        values = self.atol if self.atol is not None else atol
        if values is None:
            values = rtol * state_scales(model)
        values = np.asarray(values, dtype=float)
        if values.ndim == 1 and values.shape != (n,):
            raise ValueError(f"atol = {self.atol!r}: must be positive and finite (a number or {n} numbers)")
        return IntegratorSettings(method, rtol, np.broadcast_to(values, (n,)).copy(), step)

    def substeps(self, period_s: float) -> int:
        """Number of equal ETD2RK steps of at most ``max_step_s`` (None: :data:`DEFAULT_MAX_STEP` of ETD2RK) in a
        period of ``period_s`` [s]: ceil(period / max_step_s)."""
        step = DEFAULT_MAX_STEP["ETD2RK"] if self.max_step_s is None else self.max_step_s
        return max(1, math.ceil(period_s / step * (1.0 - 1e-12)))

    @property
    def implicit(self) -> bool:
        """An implicit scipy method (Radau, BDF, LSODA), which gets the constant Jacobian."""
        return self.method in _IMPLICIT

    @property
    def needs_jacobian(self) -> bool:
        """The method uses the constant Jacobian at the initial state (implicit methods and ETD2RK)."""
        return self.implicit or self.method == "ETD2RK"


class HoldingRadau(Radau):
    """scipy's Radau IIA (order 5) that keeps its LU factors while the step is held at ``max_step``.

    scipy's Radau drops both LU factorisations (of MU/h I - J) whenever it proposes a step >= 1.2 times
    the last one; when that proposal is cut back to ``max_step`` at the next step, the same two matrices
    are factorised again. In quiet flight held at ``max_step`` this refactorised on every step: 1852 LU
    factorisations in the 60 s GTM benchmark, 44 with this class. With a constant Jacobian (``jac`` given
    as an array) and an accepted step of exactly ``max_step`` followed by another one, the factors of that
    step stay valid for the next and are kept. Everything else is scipy's algorithm unchanged (the same
    steps and results).

    It overrides scipy's private ``Radau._step_impl`` and uses the private attributes ``lu``, ``LU_real``,
    ``LU_complex``, ``h_abs`` and ``t_old`` (scipy/integrate/_ivp/radau.py), so :func:`simulate` uses it only
    with the scipy versions of :data:`HOLDING_RADAU_SCIPY` (plain Radau otherwise: the same steps, more LU
    factorisations); ``tests/sim/test_simulate.py`` pins its steps, results and LU count against scipy's Radau.
    """

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        factorise = self.lu
        self._factors: list = []

        def lu(a):
            f = factorise(a)
            self._factors.append(f)
            del self._factors[:-2]
            return f

        self.lu = lu

    def _step_impl(self):
        before = (self.LU_real, self.LU_complex)
        self._factors.clear()
        success, message = super()._step_impl()
        if (success and self.jac is None and self.LU_real is None and self.h_abs >= self.max_step
                and abs(self.t_bound - self.t) >= self.max_step):  # the next step is max_step again
            h = abs(self.t - self.t_old)
            if abs(h - self.max_step) <= 1e-9 * self.max_step:
                pair = tuple(self._factors) if len(self._factors) == 2 else before
                if pair[0] is not None:
                    self.LU_real, self.LU_complex = pair
        return success, message


#: Range of scipy (major, minor) versions whose Radau internals HoldingRadau was tested against (by the tests
#: in tests/sim/test_simulate.py, on scipy 1.17); widen it after running them on another version.
HOLDING_RADAU_SCIPY = ((1, 17), (1, 17))


def radau_class(version: str | None = None) -> type[Radau]:
    """HoldingRadau for a tested scipy version (default: the installed one), else scipy's Radau."""
    import scipy

    major_minor = tuple(int(p) for p in (version or scipy.__version__).split(".")[:2])
    lo, hi = HOLDING_RADAU_SCIPY
    return HoldingRadau if lo <= major_minor <= hi else Radau


def state_scales(model: AircraftModel) -> np.ndarray:
    """Typical magnitudes of the state entries, shape (n_states,); the default ``atol`` is rtol times these.

    Position 1 m, Euler angles 0.01 rad, bending 0.01 m, torsion 1e-3 rad, velocity 0.1 m/s, body rates
    1e-3 rad/s, bending rates 0.01 m/s, torsion rates 0.01 rad/s, inflow 0.1 m/s.
    """
    lay = model.layout
    scale = np.empty(lay.n_states)
    for sl, value in ((lay.position, 1.0), (lay.euler, 1e-2), (lay.q, 1e-2), (lay.xi, 1e-3), (lay.v, 0.1),
                      (lay.omega, 1e-3), (lay.s, 1e-2), (lay.eta, 1e-2), (lay.inflow, 0.1)):
        scale[sl] = value
    return scale


def default_method(model: AircraftModel, wind: Wind | None = None) -> str:
    """The measured default (``docs/simulation.md``): with aerodynamics (stiff aero-lag states) ETD2RK by the compiled
    steps when the wind is still air or a field of :mod:`flexsim.sim.disturbances` (evaluated in the kernel), Radau
    for any other wind callable; DOP853 without aerodynamics (a lightly damped structure, not stiff)."""
    if model.aero is None:
        return "DOP853"
    return "ETD2RK" if compiled_wind(model, wind) is not None else "Radau"


def _initial(model: AircraftModel, initial: TrimPoint | np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
    if isinstance(initial, TrimPoint):
        x0, u0 = np.array(initial.x, dtype=float), np.array(initial.u, dtype=float)
    else:
        try:
            x0, u0 = np.array(initial, dtype=float), None
        except (TypeError, ValueError):
            raise ValueError(f"initial state: expected a TrimPoint or {model.layout.n_states} numbers, got {initial!r}") from None
    n = model.layout.n_states
    if x0.shape != (n,):
        raise ValueError(f"initial state: expected shape ({n},) (model.layout.n_states), got shape {x0.shape}")
    bad = np.flatnonzero(~np.isfinite(x0))
    if bad.size:
        raise ValueError(f"initial state: entry {bad[0]} = {x0[bad[0]]} is not finite")
    return x0, u0


def _builtin_events(model: AircraftModel, outputs: OutputMaps, names: Sequence[str], limit_m) -> list[RunEvent]:
    lay = model.layout
    events: list[RunEvent] = []
    if "ground" in names and lay.rigid:
        iz = lay.position.start + 2
        events.append(RunEvent("ground", lambda t, x: -x[iz], -1, True, "ground_contact",
                             lambda t, x: f"ground contact: the body origin reached altitude 0 m at t = {t:.4f} s",
                             lambda ts, xs: -xs[:, iz], (-_unit_row(lay.n_states, iz), 0.0, False)))
    if "gimbal_lock" in names and lay.rigid:
        ith = lay.euler.start + 1
        lim = math.radians(GIMBAL_LIMIT_DEG)
        events.append(RunEvent("gimbal_lock", lambda t, x: lim - abs(x[ith]), -1, True, "gimbal_lock",
                             lambda t, x: f"gimbal lock: |theta| = {math.degrees(abs(x[ith])):.2f} deg reached "
                                          f"{GIMBAL_LIMIT_DEG:g} deg at t = {t:.4f} s (3-2-1 Euler angles singular at 90 deg)",
                             lambda ts, xs: lim - np.abs(xs[:, ith]), (_unit_row(lay.n_states, ith), lim, True)))
    if "structural_limit" in names:
        for wing in outputs.wings:
            length = model.aircraft.component(wing).length_m
            if limit_m is None:
                bound = STRUCTURAL_LIMIT_FRACTION * length
            else:
                bound = float(limit_m)  # validated by EventSettings

            def margin(t, x, wing=wing, bound=bound):
                return bound - abs(float(outputs.tip_deflection_m(wing, x)))

            def describe(t, x, wing=wing, bound=bound):
                return (f"structural limit: {wing} tip deflection {float(outputs.tip_deflection_m(wing, x)):+.4f} m reached "
                        f"the bound +-{bound:.4g} m at t = {t:.4f} s")

            def margins(ts, xs, wing=wing, bound=bound):
                return bound - np.abs(outputs.tip_deflection_m(wing, xs))

            row = np.zeros(lay.n_states)
            row[outputs.sensors[wing].q_idx] = outputs.sensors[wing].w_tip  # tip deflection = row . x
            events.append(RunEvent(f"structural_limit:{wing}", margin, -1, True, "structural_limit", describe, margins,
                                   (row, bound, True)))
    return events


def _unit_row(n: int, i: int) -> np.ndarray:
    row = np.zeros(n)
    row[i] = 1.0
    return row


def _user_event(ev: SimEvent) -> RunEvent:
    return RunEvent(ev.name, lambda t, x: float(ev.function(t, x)), ev.direction, ev.terminal, "event",
                  lambda t, x: f"event {ev.name!r} at t = {t:.4f} s")


def _grid(rate_hz: float | None, t_end: float) -> np.ndarray | None:
    """Sample times 0, 1/rate, ... <= t_end [s] (rate validated by :class:`OutputSettings`); None: every step."""
    if rate_hz is None:
        return None
    n = int(math.floor(t_end * rate_hz * (1 + 1e-12)))
    return np.arange(n + 1) / float(rate_hz)


@single_blas_thread
def simulate(
    model: AircraftModel,
    initial: TrimPoint | np.ndarray,
    t_end_s: float,
    *,
    controls: np.ndarray | ControlSchedule | Callable[[float, np.ndarray], np.ndarray] | None = None,
    control_rate_hz: float = 50.0,
    wind: Wind | None = None,
    integrator: IntegratorSettings = IntegratorSettings(),
    events: EventSettings = EventSettings(),
    output: OutputSettings = OutputSettings(),
) -> SimulationResult:
    """Simulate the model from an initial state (or a trim) for ``t_end_s`` seconds.

    Parameters
    ----------
    model : AircraftModel
        Any variant.
    initial : TrimPoint or ndarray, shape (n_states,)
        Initial state (a trim point also supplies the default controls).
    t_end_s : float
        Duration [s] > 0 (the run starts at t = 0).
    controls : array (4,), ControlSchedule or callable, optional
        Constant controls [T_e (N), delta_a, delta_e, delta_r (rad)]; a piecewise-linear schedule; or a
        feedback controller ``controls(t, x) -> u`` evaluated at ``control_rate_hz`` and held
        (zero-order hold). Default: the trim controls. Values beyond ``aircraft.control_limits()`` are
        rejected.
    control_rate_hz : float
        Rate of a feedback controller [Hz], finite and > 0 (default 50: every 0.02 s), the environments'
        ``control_rate_hz``.
    wind : callable, optional
        Atmospheric disturbance ``wind(t, positions_ned_m) -> (k, 3)`` [m/s, NED] (gusts, turbulence:
        :mod:`flexsim.sim.disturbances`), passed to every ``model.rhs`` call; None (default): still air.
    integrator : IntegratorSettings
        Method, tolerances and step (the settings of the environments' control periods too). ``method="auto"``
        (default; :func:`default_method`: ETD2RK with aerodynamics in still air or a wind field of
        :mod:`flexsim.sim.disturbances`, Radau with any other wind callable, DOP853 without aerodynamics), or one of
        :data:`METHODS`. Implicit methods (Radau, BDF, LSODA) use a constant Jacobian from
        :func:`~flexsim.model.jacobian.jacobian` at the initial state. ``"ETD2RK"``: the exponential integrator
        with that Jacobian as its linear part and fixed steps of ``max_step_s``, by the compiled steps
        (:meth:`~flexsim.sim.fixed_step.ETD2RK.run`; re-linearised when the flight speed or air density has changed
        by more than :data:`RELINEARISE_DRIFT`) or, with a wind callable that is not a field of
        :mod:`flexsim.sim.disturbances`, by :class:`~flexsim.sim.fixed_step.ETD2RKSolver` from Python (no
        re-linearisation); errors against DOP853 in ``docs/simulation.md``; ``rtol`` and ``atol`` do not apply.
        Defaults: ``rtol`` 1e-3 for implicit and 1e-6 for explicit methods, ``atol`` ``rtol * state_scales(model)``,
        ``max_step_s`` 0.05 s (0.02 s, the fixed step, for ETD2RK) (:data:`DEFAULT_MAX_STEP`), so that no gust or
        event falls between two steps.
    events : EventSettings
        The built-in terminal events and user :class:`SimEvent` objects, and the structural limit
        (:class:`flexsim.sim.run_settings.EventSettings`; default :data:`DEFAULT_EVENTS`, each wing's bound 0.25 x
        its length). A non-finite state always stops the run.
    output : OutputSettings
        The result's sample rate, the flight log (path, rate, metadata, notes) and progress reporting
        (:class:`flexsim.sim.run_settings.OutputSettings`; default 100 Hz samples, no log).

    Returns
    -------
    SimulationResult
        With ``status`` and ``reason`` saying why the run stopped.

    Raises
    ------
    ValueError, FileNotFoundError
        Bad arguments (the message names the argument, its value and what is allowed).
    """
    check_model(model)
    for name, value, kind in (("integrator", integrator, IntegratorSettings), ("events", events, EventSettings),
                              ("output", output, OutputSettings)):
        if not isinstance(value, kind):
            raise ValueError(f"{name} = {value!r}: must be a {kind.__name__} (flexsim.sim.{kind.__name__})")
    x0, u_trim = _initial(model, initial)
    t_end = positive_number("t_end_s", t_end_s, "s")
    rate = control_rate_hz
    if isinstance(rate, bool) or not (isinstance(rate, (int, float)) and math.isfinite(rate) and rate > 0):
        raise ValueError(f"control_rate_hz = {rate!r}: must be a finite number > 0 [Hz]")
    ctrl = Controls(model, controls, u_trim, 1.0 / float(rate))
    settings = integrator.resolve(model, wind)
    method, rtol = settings.method, settings.rtol
    out_grid = _grid(output.rate_hz, t_end)
    log_grid = _grid(output.log_rate_hz, t_end)
    if wind is not None and not callable(wind):
        raise ValueError(f"wind = {wind!r}: must be None or a callable wind(t, positions_ned_m) -> (k, 3) array [m/s]")
    outputs = OutputMaps(model)
    limit_names = [e for e in events.names if isinstance(e, str)]
    evs = _builtin_events(model, outputs, limit_names, events.wing_tip_deflection_m)
    evs += [_user_event(e) for e in events.names if isinstance(e, SimEvent)]
    for ev in evs:
        if ev.status != "event" and not ev.function(0.0, x0) > 0:  # built-in limits: positive margins
            raise ValueError(f"initial state already stops the run: {ev.describe(0.0, x0)}")
    path = resolve_log_path(output.log_path)

    u0 = ctrl.held(0.0, x0) if ctrl.controller is not None else ctrl.schedule(0.0)
    wall0 = time.perf_counter()
    jac_matrix = jacobian(model, x0, u0, controls=False, wind=wind)[0] if settings.needs_jacobian else None
    problem = RunProblem(model=model, wind=wind, ctrl=ctrl, x0=x0, u0=u0, jacobian=jac_matrix, events=tuple(evs), t_end_s=t_end)
    sink = None
    if path is not None:
        meta = {"aircraft": model.aircraft.name, "aircraft_source": str(model.aircraft.source),
                "variant": model.variant.kind.value, "aero": "none" if model.aero is None else model.aero.options.model,
                "method": method, "rtol": f"{rtol:g}", "t_end_s": f"{t_end:g}", "run_id": uuid.uuid4().hex}
        meta.update(output.metadata)
        sink = LogSink(path, outputs, meta, wind=wind)
    bar = None
    progress = output.progress
    if progress is True:
        from tqdm.auto import tqdm

        bar = tqdm(total=t_end, unit="sim s", disable=None)
    results = Sampler(out_grid)
    logged = Sampler(log_grid)
    sinks = Sinks(results=results, logged=logged, log=sink, callback=progress if callable(progress) else None, bar=bar)
    results.add(0.0, x0, u0)
    try:
        if sink is not None:
            sink.event(0.0, f"simulation start: {model.aircraft.name} ({model.variant.kind.value}, aero "
                            f"{meta['aero']}), method {method}, rtol {rtol:g}, t_end {t_end:g} s")
            for t_note, text in output.notes:
                sink.schedule(t_note, text)
            sink.write(np.zeros(1), x0[None, :], u0[None, :])
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            wind_data = compiled_wind(model, wind) if method == "ETD2RK" else None
            if wind_data is not None:
                outcome = integrate_compiled(problem, settings, sinks, wind_data)
            else:
                outcome = _integrate(problem, settings, sinks)
    except BaseException as exc:
        if sink is not None:
            t_fail = logged.t[-1][-1] if logged.t and logged.t[-1].size else 0.0
            sink.event(float(t_fail), f"simulation aborted: {type(exc).__name__}: {exc}", "error")
        raise
    finally:
        if bar is not None:
            bar.close()
        if sink is not None:
            sink.close()
    t, x, u = results.arrays()
    return SimulationResult(t=t, x=x, u=u, status=outcome.status, reason=outcome.reason, model=model, method=method,
                            rtol=float(rtol), nfev=outcome.nfev, njev=outcome.njev, nlu=outcome.nlu,
                            wall_time_s=time.perf_counter() - wall0, log_path=path, events=outcome.crossings, wind=wind,
                            initial_stability=initial.stability if isinstance(initial, TrimPoint) else None)


def _integrate(problem: RunProblem, settings: IntegratorSettings, sinks: Sinks) -> RunOutcome:
    """The stepping loop: a solver per control segment; sample, log and check events after every step."""
    model, wind, ctrl, evs = problem.model, problem.wind, problem.ctrl, problem.events
    method, t_end, max_step = settings.method, problem.t_end_s, settings.max_step_s
    sink = sinks.log
    bounds = ctrl.boundaries(t_end)
    h_next = None
    g_old = [ev.function(0.0, problem.x0) for ev in evs]
    u_of = None  # the control law u_of(t) of the current segment
    solvers: list = []
    crossings: list[tuple[float, str]] = []
    etd_cache: dict = {}
    nfev = nonfinite = 0

    def fun(t, y):
        nonlocal nfev, nonfinite
        nfev += 1
        dy = model.rhs(t, y, u_of(t), wind)
        if not np.all(np.isfinite(dy)):
            nonfinite += 1
        return dy

    def finish(t: float, y: np.ndarray) -> None:
        sinks.final(t, y, u_of(t))

    def run() -> tuple[str, str]:
        nonlocal u_of, h_next
        x = problem.x0.copy()
        for a, b in zip(bounds[:-1], bounds[1:]):
            u_of = segment_controls(ctrl, float(a), float(b), x, problem.u0)
            if method == "ETD2RK":
                options = {"jac": problem.jacobian, "step": max_step, "cache": etd_cache}
            else:
                options = {"rtol": settings.rtol, "atol": settings.atol, "max_step": max_step}
                if h_next is not None:
                    options["first_step"] = min(h_next, b - a)
                if method == "LSODA":
                    options["jac"] = lambda t, y, j=problem.jacobian: j
                elif settings.implicit:
                    options["jac"] = problem.jacobian
            solver = (radau_class() if method == "Radau" else METHODS[method])(fun, float(a), x, float(b), **options)
            solvers.append(solver)
            steps: list[float] = []
            while solver.status == "running":
                if b - solver.t <= 1e-12 * max(1.0, abs(b)):
                    break  # landed on the boundary up to rounding (e.g. 0.25 + 0.05 < 6 * 0.05)
                message = solver.step()
                if solver.status == "failed":
                    finish(solver.t, solver.y)
                    if nonfinite:
                        return "non_finite", (f"non-finite state: the right-hand side stopped being finite near "
                                              f"t = {solver.t:.4f} s (solver: {message})")
                    return "solver_failure", f"solver failure at t = {solver.t:.4f} s: {message}"
                t_old, t_new, y_new = solver.t_old, solver.t, solver.y
                steps.append(t_new - t_old)
                if not np.all(np.isfinite(y_new)):
                    finish(t_old, x)
                    return "non_finite", f"non-finite state at t = {t_new:.4f} s"
                sol = solver.dense_output()
                hit = None
                for k, ev in enumerate(evs):
                    g_new = ev.function(t_new, y_new)
                    down = g_old[k] >= 0 >= g_new and g_old[k] != g_new
                    up = g_old[k] <= 0 <= g_new and g_old[k] != g_new
                    if (down and ev.direction <= 0) or (up and ev.direction >= 0):
                        t_ev = brentq(lambda tt, ev=ev: ev.function(tt, sol(tt)), t_old, t_new, xtol=4 * _EPS, rtol=4 * _EPS)
                        if ev.terminal and (hit is None or t_ev < hit[0]):
                            hit = (t_ev, ev)
                        elif not ev.terminal:
                            crossings.append((t_ev, ev.name))
                            if sink is not None:
                                sink.event(t_ev, f"event {ev.name!r} at t = {t_ev:.4f} s")
                    g_old[k] = g_new
                t_reached = t_new if hit is None else hit[0]
                inclusive = hit is not None or solver.status != "finished" or b >= t_end
                emit_step(sinks, t_reached, sol, sol(t_reached), u_of, inclusive)
                x = y_new
                sinks.progress(t_reached)
                if hit is not None:
                    t_ev, ev = hit
                    return sinks.terminal_event(t_ev, sol(t_ev), u_of(t_ev), ev, crossings)
            x = solver.y.copy()
            if steps:
                h_next = max(steps[-2:]) if len(steps) > 1 else steps[-1]
        finish(t_end, x)
        if sink is not None:
            sink.event(t_end, f"simulation completed at t = {t_end:g} s")
        return "completed", f"reached t_end = {t_end:g} s"

    status, reason = run()
    return RunOutcome(status=status, reason=reason, nfev=nfev, njev=sum(getattr(s_, "njev", 0) for s_ in solvers),
                    nlu=sum(getattr(s_, "nlu", 0) for s_ in solvers), crossings=tuple(crossings))


