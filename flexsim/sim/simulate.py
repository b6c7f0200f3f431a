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
**Radau** with a constant Jacobian computed by :func:`flexsim.model.jacobian.jacobian` at the initial
state. The finite-state inflow and apparent-mass states give well-damped eigenvalues down to about
-650 s^-1 (|lambda| up to 1500 s^-1 on the GTM), which hold an explicit method at its stability limit:
DOP853 needs ~4300 right-hand sides per simulated second whatever the tolerance. Without aerodynamics the
model is a lightly damped structure, and the default is DOP853.
"""

from __future__ import annotations

import math
import os
import time
import uuid
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.integrate import BDF, DOP853, LSODA, RK23, RK45, Radau
from scipy.optimize import brentq

from flexsim._threads import single_blas_thread
from flexsim.model.jacobian import jacobian
from flexsim.model.aircraft_model import AircraftModel, Wind
from flexsim.sim.controls import ControlSchedule, Controls
from flexsim import _kernels as _k
from flexsim.sim.fixed_step import ETD2RK, ETD2RKSolver
from flexsim.sim.outputs import OutputMaps
from flexsim.sim.recording import LogSink, resolve_log_path
from flexsim.sim.result import SimulationResult
from flexsim.trim.solver import TrimPoint

__all__ = ["ControlSchedule", "IntegrationSettings", "SimEvent", "simulate", "state_scales", "METHODS", "DEFAULT_EVENTS", "default_method",
           "DEFAULT_MAX_STEP", "RELINEARISE_DRIFT", "COMPILED_CHUNK_S"]

#: Integration methods by name (scipy.integrate OdeSolver classes).
METHODS = {"Radau": Radau, "DOP853": DOP853, "LSODA": LSODA, "BDF": BDF, "RK45": RK45, "RK23": RK23,
           "ETD2RK": ETD2RKSolver}
_IMPLICIT = ("Radau", "BDF", "LSODA")
#: Built-in terminal events (the non-finite check is always on).
DEFAULT_EVENTS = ("ground", "structural_limit", "gimbal_lock")
#: Default relative tolerance per method family (accuracy checks in docs/simulation.md).
DEFAULT_RTOL = {"implicit": 1e-3, "explicit": 1e-6}
#: Default largest step [s]: ETD2RK's fixed step, and the bound of the adaptive methods (so that no gust or event
#: falls between two steps); errors of both in docs/simulation.md.
DEFAULT_MAX_STEP = {"ETD2RK": 0.01, "other": 0.05}
GIMBAL_LIMIT_DEG = 89.0
#: Default structural limit: |tip deflection| of a wing beyond this fraction of its length.
STRUCTURAL_LIMIT_FRACTION = 0.25
_EPS = np.finfo(float).eps


@dataclass(frozen=True)
class SimEvent:
    """A user event: the run stops (``terminal``) or logs a note when ``function(t, x)`` crosses zero.

    Attributes
    ----------
    name : str
        Short name, used in the reason and the log.
    function : callable
        ``function(t [s], x (n_states,)) -> float``, continuous in t along the trajectory.
    direction : int
        -1: only crossings from positive to negative count (default); +1 the reverse; 0 both.
    terminal : bool
        Stop the run (status ``event``) or only log the crossing.
    """

    name: str
    function: Callable[[float, np.ndarray], float]
    direction: int = -1
    terminal: bool = True

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise ValueError(f"SimEvent {self.name!r}: function = {self.function!r} must be callable function(t, x) -> float")
        if self.direction not in (-1, 0, 1):
            raise ValueError(f"SimEvent {self.name!r}: direction = {self.direction!r}: must be -1, 0 or +1")


@dataclass(frozen=True)
class _Event:
    """An event with a margin function (terminal events: positive while the run may go on)."""

    name: str
    function: Callable[[float, np.ndarray], float]
    direction: int
    terminal: bool
    status: str
    describe: Callable[[float, np.ndarray], str]
    #: ``margins(ts (k,), xs (k, n)) -> (k,)``: the function at many states at once (None: called per state).
    margins: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None

    def many(self, ts: np.ndarray, xs: np.ndarray) -> np.ndarray:
        """The margin function at the states xs (k, n) at times ts (k,), shape (k,)."""
        if self.margins is not None:
            return np.asarray(self.margins(ts, xs), dtype=float)
        return np.array([self.function(float(t), x) for t, x in zip(ts, xs)], dtype=float)


@dataclass(frozen=True)
class IntegrationSettings:
    """The numerical settings of one run, validated on construction (:func:`simulate` builds one with
    :meth:`resolve`, which fills in the defaults).

    Attributes
    ----------
    method : str
        One of :data:`METHODS` (``"auto"`` is resolved by :meth:`resolve`).
    rtol : float
        Relative tolerance in [1e-13, 0.1] (not used by ETD2RK).
    atol : ndarray, shape (n_states,)
        Absolute tolerance per state entry, > 0 and finite; stored read-only.
    max_step : float
        Largest step [s], > 0 (``math.inf``: no limit); the fixed step of ETD2RK, which must be finite.
    t_end_s : float
        End time [s], finite and > 0 (the run starts at 0).

    Raises
    ------
    ValueError
        A field out of range; the message names the field, its value and the allowed range.
    """

    method: str
    rtol: float
    atol: np.ndarray
    max_step: float
    t_end_s: float

    def __post_init__(self) -> None:
        if self.method not in METHODS:
            raise ValueError(f"method = {self.method!r}: must be 'auto' or one of {', '.join(METHODS)}")
        if isinstance(self.rtol, bool) or not (isinstance(self.rtol, (int, float)) and 1e-13 <= self.rtol <= 0.1):
            raise ValueError(f"rtol = {self.rtol!r}: must be a number in [1e-13, 0.1]")
        try:
            atol = np.array(self.atol, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"atol = {self.atol!r}: must be positive and finite numbers") from None
        if atol.ndim != 1 or atol.size == 0 or not np.all(np.isfinite(atol)) or np.any(atol <= 0):
            raise ValueError(f"atol = {self.atol!r}: must be positive and finite (one number per state entry)")
        atol.setflags(write=False)
        object.__setattr__(self, "atol", atol)
        if isinstance(self.max_step, bool) or not (isinstance(self.max_step, (int, float)) and self.max_step > 0):
            raise ValueError(f"max_step = {self.max_step!r}: must be a number > 0 [s] (math.inf for no limit)")
        if self.method == "ETD2RK" and not math.isfinite(self.max_step):
            raise ValueError(f"max_step = {self.max_step!r}: ETD2RK takes fixed steps of max_step, which must be finite [s]")
        if isinstance(self.t_end_s, bool) or not (isinstance(self.t_end_s, (int, float)) and math.isfinite(self.t_end_s)
                                                  and self.t_end_s > 0):
            raise ValueError(f"t_end_s = {self.t_end_s!r}: must be a finite number > 0 [s]")
        object.__setattr__(self, "rtol", float(self.rtol))
        object.__setattr__(self, "max_step", float(self.max_step))
        object.__setattr__(self, "t_end_s", float(self.t_end_s))

    @classmethod
    def resolve(cls, model: AircraftModel, t_end_s: float, *, method: str = "auto", rtol: float | None = None,
                atol: float | np.ndarray | None = None, max_step: float | None = None,
                wind: Wind | None = None) -> IntegrationSettings:
        """Settings of a run of ``model`` in ``wind`` with :func:`simulate`'s defaults: ``"auto"`` ->
        :func:`default_method`, ``rtol`` per method family (:data:`DEFAULT_RTOL`), ``atol = rtol *
        state_scales(model)`` (a scalar ``atol`` applies to every state entry), ``max_step`` :data:`DEFAULT_MAX_STEP`
        per method (ETD2RK: its fixed step)."""
        if method == "auto":
            method = default_method(model, wind)
        if max_step is None and method in METHODS:
            max_step = DEFAULT_MAX_STEP["ETD2RK" if method == "ETD2RK" else "other"]
        if method not in METHODS:
            raise ValueError(f"method = {method!r}: must be 'auto' or one of {', '.join(METHODS)}")
        if rtol is None:
            rtol = DEFAULT_RTOL["implicit" if method in _IMPLICIT else "explicit"]
        if isinstance(rtol, bool) or not (isinstance(rtol, (int, float)) and 1e-13 <= rtol <= 0.1):
            raise ValueError(f"rtol = {rtol!r}: must be a number in [1e-13, 0.1]")
        n = model.layout.n_states
        if atol is None:
            atol_v = rtol * state_scales(model)
        else:
            try:
                atol_v = np.broadcast_to(np.asarray(atol, dtype=float), (n,)).copy()
            except (TypeError, ValueError):
                raise ValueError(f"atol = {atol!r}: must be positive and finite (a number or {n} numbers)") from None
            if not np.all(np.isfinite(atol_v)) or np.any(atol_v <= 0):
                raise ValueError(f"atol = {atol!r}: must be positive and finite (a number or {n} numbers)")
        return cls(method=method, rtol=rtol, atol=atol_v, max_step=max_step, t_end_s=t_end_s)

    @property
    def implicit(self) -> bool:
        """An implicit scipy method (Radau, BDF, LSODA), which gets the constant Jacobian."""
        return self.method in _IMPLICIT

    @property
    def needs_jacobian(self) -> bool:
        """The method uses the constant Jacobian at the initial state (implicit methods and ETD2RK)."""
        return self.implicit or self.method == "ETD2RK"


@dataclass(frozen=True)
class _Problem:
    """What is integrated: the model, its disturbance, the control law, the initial state and the events."""

    model: AircraftModel
    wind: Wind | None
    ctrl: Controls
    x0: np.ndarray
    u0: np.ndarray
    jacobian: np.ndarray | None
    events: tuple[_Event, ...]


@dataclass(frozen=True)
class _Sinks:
    """Where the samples go: the result's and the log's samplers, the log, a progress callback and bar."""

    results: _Sampler
    logged: _Sampler
    log: LogSink | None
    callback: Callable[[float], None] | None
    bar: object | None

    def final(self, t: float, y: np.ndarray, u: np.ndarray) -> None:
        """The last state of a run (t [s], y (n,), u (4,)) into the result, and into the log if finite."""
        self.results.add(t, y, u)
        if self.log is not None and np.all(np.isfinite(y)):
            self.log.write(np.array([t]), y[None, :], u[None, :])

    def progress(self, t: float) -> None:
        """Report that the run reached t [s] (the callback and the progress bar)."""
        if self.callback is not None:
            self.callback(t)
        if self.bar is not None:
            self.bar.update(t - self.bar.n)

    def terminal_event(self, t: float, y: np.ndarray, u: np.ndarray, event, crossings: list) -> tuple[str, str]:
        """A terminal event at t [s], state y: the final sample, the crossing, the log's error; returns (status, reason)."""
        self.final(t, y, u)
        crossings.append((t, event.name))
        reason = event.describe(t, y)
        if self.log is not None:
            self.log.event(t, reason, "error")
        return event.status, reason


@dataclass(frozen=True)
class _Outcome:
    """How a run ended: ``status`` (:data:`flexsim.sim.result.STATUSES`), ``reason``, solver counts, and the
    event crossings ``(t [s], name)`` in time order."""

    status: str
    reason: str
    nfev: int
    njev: int
    nlu: int
    crossings: tuple[tuple[float, str], ...]


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
    return "ETD2RK" if _compiled_wind(model, wind) is not None else "Radau"


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


def _builtin_events(model: AircraftModel, outputs: OutputMaps, names: Sequence[str], limit_m) -> list[_Event]:
    lay = model.layout
    unknown = [n for n in names if n not in DEFAULT_EVENTS]
    if unknown:
        raise ValueError(f"events: unknown event(s) {unknown}; built-in events are {', '.join(DEFAULT_EVENTS)} (or SimEvent objects)")
    events: list[_Event] = []
    if "ground" in names and lay.rigid:
        iz = lay.position.start + 2
        events.append(_Event("ground", lambda t, x: -x[iz], -1, True, "ground_contact",
                             lambda t, x: f"ground contact: the body origin reached altitude 0 m at t = {t:.4f} s",
                             lambda ts, xs: -xs[:, iz]))
    if "gimbal_lock" in names and lay.rigid:
        ith = lay.euler.start + 1
        lim = math.radians(GIMBAL_LIMIT_DEG)
        events.append(_Event("gimbal_lock", lambda t, x: lim - abs(x[ith]), -1, True, "gimbal_lock",
                             lambda t, x: f"gimbal lock: |theta| = {math.degrees(abs(x[ith])):.2f} deg reached "
                                          f"{GIMBAL_LIMIT_DEG:g} deg at t = {t:.4f} s (3-2-1 Euler angles singular at 90 deg)",
                             lambda ts, xs: lim - np.abs(xs[:, ith])))
    if "structural_limit" in names:
        for wing in outputs.wings:
            length = model.aircraft.component(wing).length_m
            if limit_m is None:
                bound = STRUCTURAL_LIMIT_FRACTION * length
            else:
                bound = float(limit_m)
                if not (math.isfinite(bound) and bound > 0):
                    raise ValueError(f"structural_limit_m = {limit_m!r}: must be a finite number > 0 [m] (or None: "
                                     f"{STRUCTURAL_LIMIT_FRACTION:g} x wing length)")

            def margin(t, x, wing=wing, bound=bound):
                return bound - abs(float(outputs.tip_deflection_m(wing, x)))

            def describe(t, x, wing=wing, bound=bound):
                return (f"structural limit: {wing} tip deflection {float(outputs.tip_deflection_m(wing, x)):+.4f} m reached "
                        f"the bound +-{bound:.4g} m at t = {t:.4f} s")

            def margins(ts, xs, wing=wing, bound=bound):
                return bound - np.abs(outputs.tip_deflection_m(wing, xs))

            events.append(_Event(f"structural_limit:{wing}", margin, -1, True, "structural_limit", describe, margins))
    return events


def _user_event(ev: SimEvent) -> _Event:
    return _Event(ev.name, lambda t, x: float(ev.function(t, x)), ev.direction, ev.terminal, "event",
                  lambda t, x: f"event {ev.name!r} at t = {t:.4f} s")


def _grid(rate_hz: float | None, t_end: float, what: str) -> np.ndarray | None:
    if rate_hz is None:
        return None
    if not (isinstance(rate_hz, (int, float)) and math.isfinite(rate_hz) and rate_hz > 0):
        raise ValueError(f"{what} = {rate_hz!r}: must be a finite number > 0 [Hz]")
    n = int(math.floor(t_end * rate_hz * (1 + 1e-12)))
    return np.arange(n + 1) / float(rate_hz)


class _Sampler:
    """Collects samples on a time grid (or every step) from each step's dense output."""

    def __init__(self, grid: np.ndarray | None) -> None:
        self.grid = grid
        self.next = 1  # index 0 (t = 0) is written at the start
        self.t: list[np.ndarray] = []
        self.x: list[np.ndarray] = []
        self.u: list[np.ndarray] = []

    def take(self, t_new: float, sol, y_new: np.ndarray, u_of, inclusive: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Samples up to t_new (a grid time at t_new itself only if ``inclusive``: at the end of a control
        segment it belongs to the next segment, whose control then applies); without a grid, t_new."""
        if self.grid is None:  # every accepted step, step ends included
            times = np.array([t_new])
            xs = y_new[None, :]
        else:
            edge = t_new * (1 + 4 * _EPS) + 1e-12 if inclusive else t_new - 1e-9 * max(1.0, abs(t_new))
            stop = int(np.searchsorted(self.grid, edge, side="right"))
            times = self.grid[self.next:stop]
            self.next = max(self.next, stop)
            if times.size == 0:
                return times, np.zeros((0, y_new.size)), np.zeros((0, 4))
            xs = sol(times).T
        us = u_of(times)
        self.t.append(times)
        self.x.append(xs)
        self.u.append(us)
        return times, xs, us

    def add(self, t: float, x: np.ndarray, u: np.ndarray) -> None:
        last = self.t[-1][-1] if self.t and self.t[-1].size else -math.inf
        if t > last:
            self.t.append(np.array([t]))
            self.x.append(x[None, :])
            self.u.append(u[None, :])

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return np.concatenate(self.t), np.concatenate(self.x), np.concatenate(self.u)


@single_blas_thread
def simulate(
    model: AircraftModel,
    initial: TrimPoint | np.ndarray,
    t_end_s: float,
    *,
    controls: np.ndarray | ControlSchedule | Callable[[float, np.ndarray], np.ndarray] | None = None,
    wind: Wind | None = None,
    method: str = "auto",
    rtol: float | None = None,
    atol: float | np.ndarray | None = None,
    max_step: float | None = None,
    control_period_s: float = 0.02,
    events: Sequence[str | SimEvent] = DEFAULT_EVENTS,
    structural_limit_m: float | None = None,
    output_rate_hz: float | None = 100.0,
    log_path: str | os.PathLike | bool | None = None,
    log_rate_hz: float = 50.0,
    metadata: Mapping[str, str] | None = None,
    notes: Sequence[tuple[float, str]] = (),
    progress: bool | Callable[[float], None] = False,
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
        feedback controller ``controls(t, x) -> u`` evaluated every ``control_period_s`` and held
        (zero-order hold). Default: the trim controls. Values beyond ``aircraft.control_limits()`` are
        rejected.
    wind : callable, optional
        Atmospheric disturbance ``wind(t, positions_ned_m) -> (k, 3)`` [m/s, NED] (gusts, turbulence:
        :mod:`flexsim.sim.disturbances`), passed to every ``model.rhs`` call; None (default): still air.
    method : str
        ``"auto"`` (:func:`default_method`: ETD2RK with aerodynamics in still air or a wind field of
        :mod:`flexsim.sim.disturbances`, Radau with any other wind callable, DOP853 without aerodynamics), or
        one of :data:`METHODS`. Implicit methods (Radau, BDF, LSODA) use a constant Jacobian from
        :func:`~flexsim.model.jacobian.jacobian` at the initial state. ``"ETD2RK"``: the exponential integrator
        with that Jacobian as its linear part and fixed steps of ``max_step``, by the compiled steps
        (:meth:`~flexsim.sim.fixed_step.ETD2RK.run`; re-linearised when the flight speed or air density has changed
        by more than :data:`RELINEARISE_DRIFT`) or, with a wind callable that is not a field of
        :mod:`flexsim.sim.disturbances`, by :class:`~flexsim.sim.fixed_step.ETD2RKSolver` from Python (no
        re-linearisation); errors against DOP853 in ``docs/simulation.md``; ``rtol`` and ``atol`` do not apply.
    rtol : float, optional
        Relative tolerance; default 1e-3 for implicit and 1e-6 for explicit methods (accuracy checks in
        ``docs/simulation.md``).
    atol : float or ndarray (n_states,), optional
        Absolute tolerance; default ``rtol * state_scales(model)``.
    max_step : float, optional
        Largest step [s] (default 0.05), so that no gust or event falls between two steps; the fixed step
        of ETD2RK (default 0.01) (:data:`DEFAULT_MAX_STEP`).
    control_period_s : float
        Period of a feedback controller [s] (default 0.02).
    events : sequence of str or SimEvent
        Built-in terminal events among ``"ground"`` (altitude of the body origin <= 0), ``"structural_limit"``
        (|tip deflection| of a wing >= the bound: the signature of flutter or overload), ``"gimbal_lock"``
        (|theta| >= 89 deg), plus user :class:`SimEvent` objects. A non-finite state always stops the run.
    structural_limit_m : float, optional
        Bound on |tip deflection| [m]; default 0.25 x each wing's length.
    output_rate_hz : float or None
        Rate of the result's samples [Hz] (default 100); None: every accepted step.
    log_path : str, Path, True or None
        Write a flight log (MCAP) there as the run proceeds; True: ``logs/simulation-<time>.mcap``.
    log_rate_hz : float
        Rate of the logged samples [Hz] (default 50).
    metadata : mapping of str to str, optional
        Extra run metadata for the log.
    notes : sequence of (t [s], text)
        Informational events for the log (e.g. when a gust arrives).
    progress : bool or callable
        True: a tqdm progress bar; a callable is called with the sim time [s] after every accepted step (the
        compiled ETD2RK: after every chunk of :data:`COMPILED_CHUNK_S` of steps).

    Returns
    -------
    SimulationResult
        With ``status`` and ``reason`` saying why the run stopped.

    Raises
    ------
    ValueError, FileNotFoundError
        Bad arguments (the message names the argument, its value and what is allowed).
    """
    x0, u_trim = _initial(model, initial)
    if not (isinstance(t_end_s, (int, float)) and math.isfinite(t_end_s) and t_end_s > 0):
        raise ValueError(f"t_end_s = {t_end_s!r}: must be a finite number > 0 [s]")
    t_end = float(t_end_s)
    ctrl = Controls(model, controls, u_trim, control_period_s)
    settings = IntegrationSettings.resolve(model, t_end, method=method, rtol=rtol, atol=atol, max_step=max_step,
                                           wind=wind)
    method, rtol = settings.method, settings.rtol
    out_grid = _grid(output_rate_hz, t_end, "output_rate_hz")
    log_grid = _grid(log_rate_hz, t_end, "log_rate_hz")
    if wind is not None and not callable(wind):
        raise ValueError(f"wind = {wind!r}: must be None or a callable wind(t, positions_ned_m) -> (k, 3) array [m/s]")
    outputs = OutputMaps(model)
    limit_names = [e for e in events if isinstance(e, str)]
    evs = _builtin_events(model, outputs, limit_names, structural_limit_m)
    for e in events:
        if isinstance(e, SimEvent):
            evs.append(_user_event(e))
        elif not isinstance(e, str):
            raise ValueError(f"events: {e!r} is neither a built-in event name nor a SimEvent")
    for ev in evs:
        if ev.status != "event" and not ev.function(0.0, x0) > 0:  # built-in limits: positive margins
            raise ValueError(f"initial state already stops the run: {ev.describe(0.0, x0)}")
    path = resolve_log_path(log_path)

    u0 = ctrl.held(0.0, x0) if ctrl.controller is not None else ctrl.schedule(0.0)
    wall0 = time.perf_counter()
    jac_matrix = jacobian(model, x0, u0, controls=False, wind=wind)[0] if settings.needs_jacobian else None
    problem = _Problem(model=model, wind=wind, ctrl=ctrl, x0=x0, u0=u0, jacobian=jac_matrix, events=tuple(evs))
    sink = None
    if path is not None:
        meta = {"aircraft": model.aircraft.name, "aircraft_source": str(model.aircraft.source),
                "variant": model.variant.value, "aero": "none" if model.aero is None else model.aero.options.model,
                "method": method, "rtol": f"{rtol:g}", "t_end_s": f"{t_end:g}", "run_id": uuid.uuid4().hex}
        meta.update({str(k): str(v) for k, v in (metadata or {}).items()})
        sink = LogSink(path, outputs, meta, wind=wind)
    bar = None
    if progress is True:
        from tqdm.auto import tqdm

        bar = tqdm(total=t_end, unit="sim s", disable=None)
    results = _Sampler(out_grid)
    logged = _Sampler(log_grid)
    sinks = _Sinks(results=results, logged=logged, log=sink, callback=progress if callable(progress) else None, bar=bar)
    results.add(0.0, x0, u0)
    try:
        if sink is not None:
            sink.event(0.0, f"simulation start: {model.aircraft.name} ({model.variant.value}, aero "
                            f"{meta['aero']}), method {method}, rtol {rtol:g}, t_end {t_end:g} s")
            for t_note, text in notes:
                sink.schedule(float(t_note), str(text))
            sink.write(np.zeros(1), x0[None, :], u0[None, :])
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            wind_data = _compiled_wind(model, wind) if method == "ETD2RK" else None
            if wind_data is not None:
                outcome = _integrate_compiled(problem, settings, sinks, wind_data)
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
                            wall_time_s=time.perf_counter() - wall0, log_path=path, events=outcome.crossings, wind=wind)


def _integrate(problem: _Problem, settings: IntegrationSettings, sinks: _Sinks) -> _Outcome:
    """The stepping loop: a solver per control segment; sample, log and check events after every step."""
    model, wind, ctrl, evs = problem.model, problem.wind, problem.ctrl, problem.events
    method, t_end, max_step = settings.method, settings.t_end_s, settings.max_step
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
            u_of = _segment_controls(ctrl, float(a), float(b), x, problem.u0)
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
                _emit(sinks, t_reached, sol, sol(t_reached), u_of, inclusive)
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
    return _Outcome(status=status, reason=reason, nfev=nfev, njev=sum(getattr(s_, "njev", 0) for s_ in solvers),
                    nlu=sum(getattr(s_, "nlu", 0) for s_ in solvers), crossings=tuple(crossings))


def _segment_controls(ctrl: Controls, a: float, b: float, x_a: np.ndarray, u0: np.ndarray) -> Callable:
    """The control law ``u_of(t)`` on the segment [a, b] (scalar t -> (4,), array t -> (len(t), 4)): the held
    output of a feedback controller, a constant, or the schedule's interpolation."""
    if ctrl.controller is not None:
        u_held = u0 if a == 0.0 else ctrl.held(a, x_a)

        def u_of(t, u_held=u_held):
            return np.broadcast_to(u_held, (np.size(t), 4)) if np.ndim(t) else u_held
        return u_of
    sched = ctrl.schedule
    u_a = sched(a)
    if np.array_equal(u_a, sched(b)):
        # constant on the segment (its ends are consecutive breakpoints): no interpolation per rhs
        u_a.setflags(write=False)

        def u_const(t, u_c=u_a):
            return np.broadcast_to(u_c, (np.size(t), 4)) if np.ndim(t) else u_c
        return u_const

    def u_sched(t, sched=sched):
        return sched.at(t) if np.ndim(t) else sched(t)
    return u_sched


def _emit(sinks: _Sinks, t_reached: float, sol, y_reached, u_of, inclusive: bool) -> None:
    sinks.results.take(t_reached, sol, y_reached, u_of, inclusive)
    times, xs, us = sinks.logged.take(t_reached, sol, y_reached, u_of, inclusive)
    if sinks.log is not None and times.size:
        sinks.log.write(times, xs, us)


#: Simulated time per call of the compiled ETD2RK steps [s]: samples, events and the log are processed per chunk
#: (the log is flushed every 0.5 s of simulated time, so a killed run loses at most ~1 s of it).
COMPILED_CHUNK_S = 0.5
#: Relative change of the flight speed or air density since the linearisation beyond which the compiled ETD2RK
#: re-linearises (new Jacobian and matrix functions) at the end of a chunk.
RELINEARISE_DRIFT = 0.2


def _compiled_wind(model: AircraftModel, wind: Wind | None) -> _k.WindData | None:
    """The wind's arrays for the compiled steps (still air: NO_WIND); None if the wind is a plain callable (the
    steps then call ``model.rhs`` from Python: :class:`~flexsim.sim.fixed_step.ETD2RKSolver`)."""
    if wind is None or model.aero is None:
        return _k.NO_WIND
    data = getattr(wind, "wind_data", None)
    return data if isinstance(data, _k.WindData) else None


class _Steps:
    """Cubic Hermite interpolant over consecutive step ends (t (k+1,), x and f (k+1, n)): the dense output of
    :class:`~flexsim.sim.fixed_step.ETD2RKSolver` for a chunk of compiled steps. ``sol(t)``: scalar t -> (n,),
    array t (m,) -> (n, m) (as scipy's ``DenseOutput``)."""

    def __init__(self, t: np.ndarray, x: np.ndarray, f: np.ndarray) -> None:
        self.t, self.x, self.f = t, x, f

    def __call__(self, t):
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        j = np.clip(np.searchsorted(self.t, tt, side="left") - 1, 0, self.t.size - 2)
        t0, h = self.t[j], self.t[j + 1] - self.t[j]
        s = ((tt - t0) / h)[:, None]
        h01, h10, h11 = s * s * (3 - 2 * s), s * (1 - s) ** 2, s * s * (s - 1)
        y0 = self.x[j]
        y = y0 + (self.x[j + 1] - y0) * h01 + h[:, None] * (self.f[j] * h10 + self.f[j + 1] * h11)
        return y[0] if np.ndim(t) == 0 else y.T


def _integrate_compiled(problem: _Problem, settings: IntegrationSettings, sinks: _Sinks, wind_data) -> _Outcome:
    """ETD2RK by the compiled steps (:meth:`ETD2RK.run`): the steps, samples, events and log of :func:`_integrate`
    with :class:`ETD2RKSolver`, processed per chunk of :data:`COMPILED_CHUNK_S` instead of per step."""
    model, wind, ctrl, evs = problem.model, problem.wind, problem.ctrl, problem.events
    t_end, h = settings.t_end_s, settings.max_step
    sink = sinks.log
    steppers: dict[float, ETD2RK] = {}
    g_old = np.array([ev.function(0.0, problem.x0) for ev in evs], dtype=float)
    crossings: list[tuple[float, str]] = []
    nfev = 0
    chunk = max(1, int(round(COMPILED_CHUNK_S / h)))
    lin = {"jac": problem.jacobian, "at": _flight_condition(model, problem.x0), "count": 1}

    def stepper(step: float) -> ETD2RK:  # as ETD2RKSolver._method
        if abs(step - h) <= 1e-9 * h:
            step = h
        key = round(step, 12)
        if key not in steppers:
            steppers[key] = ETD2RK(lin["jac"], step)
        return steppers[key]

    def finish(t: float, y: np.ndarray, u_of) -> None:
        sinks.final(t, y, u_of(t))

    def run() -> tuple[str, str]:
        nonlocal nfev, g_old
        x = problem.x0.copy()
        bounds = ctrl.boundaries(t_end)
        u_of = None
        for a, b in zip(bounds[:-1], bounds[1:]):
            a, b = float(a), float(b)
            u_of = _segment_controls(ctrl, a, b, x, problem.u0)
            u_a = np.array(u_of(a), dtype=float)
            controls = (a, u_a, (np.asarray(u_of(b), dtype=float) - u_a) / (b - a))
            f = model.rhs(a, x, u_a, wind)
            nfev += 1
            t = a
            while b - t > 1e-12 * max(1.0, abs(b)):
                if b - t > h * (1.0 + 1e-9):
                    steps = stepper(h).run(model, t, x, f, b, chunk, controls, wind_data)
                else:
                    steps = stepper(b - t).run(model, t, x, f, b, 1, controls, wind_data, land=True)
                k = steps.t.size - 1
                nfev += 2 * k
                bad = not (np.all(np.isfinite(steps.x[-1])) and np.all(np.isfinite(steps.f[-1])))
                if bad:
                    if np.all(np.isfinite(steps.x[-1])):
                        model.rhs(steps.t[-1], steps.x[-1], u_of(steps.t[-1]), wind)  # raises what rhs raises there
                    t_bad = float(steps.t[-1])
                    steps = steps._replace(t=steps.t[:-1], x=steps.x[:-1], f=steps.f[:-1])
                    k -= 1
                hit = None
                if k:
                    sol = _Steps(steps.t, steps.x, steps.f)
                    j_stop, hit = _chunk_events(evs, g_old, steps, sol, crossings, sink)
                    g_old = np.array([ev.function(float(steps.t[j_stop]), steps.x[j_stop]) for ev in evs], dtype=float)
                    t_reached = float(steps.t[j_stop]) if hit is None else hit[0]
                    finished = hit is None and not bad and j_stop == k and t_reached >= b  # the solver's "finished"
                    inclusive = not finished or b >= t_end
                    _emit_steps(sinks, steps, j_stop, t_reached, sol, u_of, inclusive)
                    sinks.progress(t_reached)
                if hit is not None:
                    t_ev, ev = hit
                    return sinks.terminal_event(t_ev, sol(t_ev), u_of(t_ev), ev, crossings)
                if bad:
                    finish(float(steps.t[-1]), steps.x[-1], u_of)
                    return "non_finite", (f"non-finite state: the state or the right-hand side stopped being finite at "
                                          f"t = {t_bad:.4f} s")
                t_step = float(steps.t[-1])
                t, x, f = t_step, steps.x[-1].copy(), steps.f[-1]
                now = _flight_condition(model, x)
                if now is not None and np.max(np.abs(now / lin["at"] - 1.0)) > RELINEARISE_DRIFT:
                    lin["jac"] = jacobian(model, x, u_of(t), t, controls=False, wind=wind)[0]
                    lin["at"], lin["count"] = now, lin["count"] + 1
                    steppers.clear()
            x = x.copy()
        finish(t_end, x, u_of)
        if sink is not None:
            sink.event(t_end, f"simulation completed at t = {t_end:g} s")
        return "completed", f"reached t_end = {t_end:g} s"

    status, reason = run()
    return _Outcome(status=status, reason=reason, nfev=nfev, njev=lin["count"], nlu=0, crossings=tuple(crossings))


def _flight_condition(model: AircraftModel, x: np.ndarray) -> np.ndarray | None:
    """(|v_body| [m/s], air density [kg/m^3]) at state x, on which the stiff aerodynamic eigenvalues depend (inflow
    ~ V / b); None for a model without rigid-body states or aerodynamics (nothing drifts)."""
    lay = model.layout
    if not lay.rigid or model.aero is None:
        return None
    return np.array([float(np.linalg.norm(x[lay.v][:3])), model.air_density(x)])


def _crossing_steps(ev: _Event, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Whether the margin crosses zero between lo and hi in the event's direction (as in :func:`_integrate`)."""
    down = (lo >= 0) & (hi <= 0) & (lo != hi)
    up = (lo <= 0) & (hi >= 0) & (lo != hi)
    return down if ev.direction < 0 else up if ev.direction > 0 else down | up


def _chunk_events(evs, g_old: np.ndarray, steps, sol, crossings: list, sink) -> tuple[int, tuple | None]:
    """Events over a chunk of steps: (index of the step where the run stops — the first with a terminal crossing,
    else the last —, (t, event) of the terminal hit or None). Non-terminal crossings up to that step are appended
    to ``crossings`` and logged; times located by Brent's method on the dense output."""
    k = steps.t.size - 1
    if not evs:
        return k, None
    g = np.vstack([g_old[None, :], np.column_stack([ev.many(steps.t[1:], steps.x[1:]) for ev in evs])])
    j_stop = k
    for e, ev in enumerate(evs):
        cross = _crossing_steps(ev, g[:-1, e], g[1:, e])
        if ev.terminal and cross.any():
            j_stop = min(j_stop, int(np.argmax(cross)) + 1)
    hit = None
    found = []
    for e, ev in enumerate(evs):
        for j in np.flatnonzero(_crossing_steps(ev, g[:j_stop, e], g[1:j_stop + 1, e])) + 1:
            t_ev = brentq(lambda tt, ev=ev: ev.function(tt, sol(tt)), float(steps.t[j - 1]), float(steps.t[j]),
                          xtol=4 * _EPS, rtol=4 * _EPS)
            if ev.terminal:
                if hit is None or t_ev < hit[0]:
                    hit = (t_ev, ev)
            else:
                found.append((t_ev, ev.name))
    for t_ev, name in sorted(found):
        crossings.append((t_ev, name))
        if sink is not None:
            sink.event(t_ev, f"event {name!r} at t = {t_ev:.4f} s")
    return j_stop, hit


def _emit_steps(sinks: _Sinks, steps, j_stop: int, t_reached: float, sol, u_of, inclusive: bool) -> None:
    """Samples of a chunk of compiled steps up to t_reached (within step j_stop): on the samplers' grids from the
    dense output, or, without a grid, every step end and t_reached (as :func:`_emit` per step)."""
    for sampler, log in ((sinks.results, None), (sinks.logged, sinks.log)):
        if sampler.grid is None:
            times = np.append(steps.t[1:j_stop], t_reached)
            xs = np.vstack([steps.x[1:j_stop], sol(t_reached)[None, :]])
            us = u_of(times)
            sampler.t.append(times)
            sampler.x.append(xs)
            sampler.u.append(us)
        else:
            times, xs, us = sampler.take(t_reached, sol, steps.x[j_stop], u_of, inclusive)
        if log is not None and times.size:
            log.write(times, xs, us)
