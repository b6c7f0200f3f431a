"""The pieces shared by :func:`flexsim.sim.simulate.simulate`'s two run loops (scipy's steppers and the compiled ETD2RK
steps of :mod:`flexsim.sim.compiled_run`): the events, the problem, where the samples go, how a run ended, the
control law of a segment.

Units: times [s], states in the model's layout (:class:`flexsim.model.AircraftModel`), controls (4,)
[T_e (N), delta_a, delta_e, delta_r (rad)].
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from flexsim.model.aircraft_model import AircraftModel, Wind
from flexsim.sim.controls import Controls
from flexsim.sim.recording import LogSink

__all__ = ["RunEvent", "margin_rows", "RunProblem", "Sinks", "RunOutcome", "Sampler", "segment_controls", "emit_step"]

_EPS = np.finfo(float).eps


@dataclass(frozen=True)
class RunEvent:
    """An event with a margin function (terminal events: positive while the run may go on)."""

    name: str
    function: Callable[[float, np.ndarray], float]
    direction: int
    terminal: bool
    status: str
    describe: Callable[[float, np.ndarray], str]
    #: ``margins(ts (k,), xs (k, n)) -> (k,)``: the function at many states at once (None: called per state).
    margins: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None
    #: ``(c (n,), offset, absolute)`` if the function is ``offset - |c . x|`` (absolute) or ``offset + c . x``: the
    #: compiled run evaluates such margins of all events with one matrix product per chunk (:func:`margin_rows`).
    linear: tuple[np.ndarray, float, bool] | None = None

    def many(self, ts: np.ndarray, xs: np.ndarray) -> np.ndarray:
        """The margin function at the states xs (k, n) at times ts (k,), shape (k,)."""
        if self.margins is not None:
            return np.asarray(self.margins(ts, xs), dtype=float)
        return np.array([self.function(float(t), x) for t, x in zip(ts, xs)], dtype=float)


def margin_rows(events: tuple[RunEvent, ...] | list[RunEvent], n: int) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """``margins(ts (k,), xs (k, n)) -> (k, len(events))``: every event's margin function at many states, those with a
    ``linear`` form by one product of the states with their rows, the others by :meth:`RunEvent.many`."""
    lin = [e for e, ev in enumerate(events) if ev.linear is not None]
    other = [e for e, ev in enumerate(events) if ev.linear is None]
    rows = np.array([events[e].linear[0] for e in lin], dtype=float).reshape(len(lin), n).T.copy()  # (n, m_lin)
    offset = np.array([events[e].linear[1] for e in lin], dtype=float)
    absolute = np.array([events[e].linear[2] for e in lin], dtype=bool)

    def margins(ts: np.ndarray, xs: np.ndarray) -> np.ndarray:
        g = np.empty((len(ts), len(events)))
        if lin:
            v = xs @ rows
            g[:, lin] = np.where(absolute, offset - np.abs(v), offset + v)
        for e in other:
            g[:, e] = events[e].many(ts, xs)
        return g

    return margins


@dataclass(frozen=True)
class RunProblem:
    """What is integrated: the model, its disturbance, the control law, the initial state and the events."""

    model: AircraftModel
    wind: Wind | None
    ctrl: Controls
    x0: np.ndarray
    u0: np.ndarray
    jacobian: np.ndarray | None
    events: tuple[RunEvent, ...]
    #: End time of the run [s] (it starts at 0).
    t_end_s: float


@dataclass(frozen=True)
class Sinks:
    """Where the samples go: the result's and the log's samplers, the log, a progress callback and bar."""

    results: Sampler
    logged: Sampler
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
class RunOutcome:
    """How a run ended: ``status`` (:data:`flexsim.sim.result.STATUSES`), ``reason``, solver counts, and the
    event crossings ``(t [s], name)`` in time order."""

    status: str
    reason: str
    nfev: int
    njev: int
    nlu: int
    crossings: tuple[tuple[float, str], ...]


class Sampler:
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


def segment_controls(ctrl: Controls, a: float, b: float, x_a: np.ndarray, u0: np.ndarray) -> Callable:
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
            if not np.ndim(t):
                return u_c
            rows = np.empty((np.size(t), 4))  # (a copy: np.broadcast_to costs ~10x more per call)
            rows[:] = u_c
            return rows
        return u_const

    def u_sched(t, sched=sched):
        return sched.at(t) if np.ndim(t) else sched(t)
    return u_sched


def emit_step(sinks: Sinks, t_reached: float, sol, y_reached, u_of, inclusive: bool) -> None:
    sinks.results.take(t_reached, sol, y_reached, u_of, inclusive)
    if sinks.log is None:
        return  # no flight log: its samples would go nowhere
    times, xs, us = sinks.logged.take(t_reached, sol, y_reached, u_of, inclusive)
    if times.size:
        sinks.log.write(times, xs, us)
