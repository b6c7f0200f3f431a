"""The compiled ETD2RK run of :func:`flexsim.sim.simulate.simulate` (its default with aerodynamics): steps by
:meth:`flexsim.sim.fixed_step.ETD2RK.run` (one row of the kernel :func:`flexsim.sim._step_kernels.etd2rk_rows`) in chunks of
:data:`COMPILED_CHUNK_S`, with the samples, events and flight log of the scipy loop processed per chunk, and
re-linearisation when the flight condition drifts (:data:`RELINEARISE_DRIFT`). The method and its accuracy:
``docs/simulation.md``, "Integration and solver choice".
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import brentq

from flexsim import _kernels as _k
from flexsim.model.aircraft_model import AircraftModel, Wind
from flexsim.model.jacobian import jacobian
from flexsim.sim import _dense_kernels as _dk
from flexsim.sim.fixed_step import ETD2RK, step_accelerations
from flexsim.sim.run_parts import RunOutcome, RunProblem, Sinks, margin_rows, segment_controls

if TYPE_CHECKING:
    from flexsim.sim.simulate import IntegratorSettings

__all__ = ["COMPILED_CHUNK_S", "CHECK_INTERVAL_S", "HALVINGS", "RELINEARISE_DRIFT", "compiled_wind", "integrate_compiled", "flight_condition"]

_EPS = np.finfo(float).eps


#: Simulated time per call of the compiled ETD2RK steps [s]: samples, events and the flight log are processed per
#: chunk (a run killed with SIGKILL loses the chunk being computed and the log's samples since its last flush, at most
#: about 2.5 s of simulated time: some 25 ms of computing). Every return to Python costs ~0.5-1 ms (the interpreter's
#: code and data come back into the caches after the steps), so 2 s chunks took 6-16 % less CPU than 0.5 s chunks on
#: the 60 s benchmark (and 8-12 % less with a flight log, measured 2026-12-04: 0.67 s against 0.72-0.79 s CPU).
COMPILED_CHUNK_S = 2.0
#: Simulated time between the checks of the flight condition's drift (:data:`RELINEARISE_DRIFT`) and the sub-chunks a
#: failed chunk is repeated from [s]: a chunk is cut at the first such boundary where the drift exceeds the limit, so
#: re-linearisation happens at the same times as with chunks of this length (the chunk length before 2026-12-02).
CHECK_INTERVAL_S = 0.5
#: Times the step is halved at most when a chunk of steps fails (a state or derivative not finite, or outside the model's
#: range): the sub-chunk of :data:`CHECK_INTERVAL_S` is repeated with half the step, which is kept for the rest of the
#: run (1/8 of max_step at least).
HALVINGS = 3
#: Relative change of the flight speed or air density since the linearisation beyond which the compiled ETD2RK
#: re-linearises (new Jacobian and matrix functions) at the end of a sub-chunk (:data:`CHECK_INTERVAL_S`).
RELINEARISE_DRIFT = 0.2


def compiled_wind(model: AircraftModel, wind: Wind | None) -> _k.WindData | None:
    """The wind's arrays for the compiled steps (still air: NO_WIND); None if the wind is a plain callable (the
    steps then call ``model.rhs`` from Python: :class:`~flexsim.sim.fixed_step.ETD2RKSolver`)."""
    if wind is None or model.aero is None:
        return _k.NO_WIND
    data = getattr(wind, "wind_data", None)
    return data if isinstance(data, _k.WindData) else None


class _Steps:
    """Dense output over consecutive step ends (t (k+1,), x and f (k+1, n)) of a chunk of compiled steps: the quintic
    Hermite interpolant of :class:`~flexsim.sim.fixed_step.ETD2RKSolver`'s dense output
    (:func:`~flexsim.sim.fixed_step.quintic_hermite`, second derivatives with the linear part ``jac`` by
    :func:`~flexsim.sim.fixed_step.step_accelerations`: their means ``mean`` (k, n) from the compiled steps
    (:meth:`flexsim.sim.fixed_step.ETD2RK.run` with ``dense=True``) or, if None, for all steps of the chunk at the first sample
    that needs them; their half differences, needed only off the steps' ends and midpoints, likewise), evaluated by
    the compiled :func:`flexsim.sim._dense_kernels.hermite_samples`. ``sol(t)``: scalar t -> (n,), array t (m,) ->
    (n, m) (as scipy's ``DenseOutput``)."""

    def __init__(self, t: np.ndarray, x: np.ndarray, f: np.ndarray, jac: np.ndarray,
                 mean: np.ndarray | None = None) -> None:
        self.t, self.x, self.f, self.jac = t, x, f, jac
        self._mean, self._half_diff = mean, None
        self._none = np.zeros((0, x.shape[1]))  # for the kernel where the second derivatives are not needed

    def __call__(self, t):
        tt = np.ascontiguousarray(np.atleast_1d(np.asarray(t, dtype=float)))
        inside, off = _dk.sample_needs(self.t, tt)
        if inside and self._mean is None:
            self._mean, self._half_diff = step_accelerations(np.diff(self.t)[:, None], np.diff(self.x, axis=0),
                                                             self.f[:-1], self.f[1:], self.jac, difference=off)
        if off and self._half_diff is None:
            self._half_diff = (0.5 * (self.f[1:] - self.f[:-1])) @ self.jac.T  # as step_accelerations
        none = self._none
        y = np.empty((tt.size, self.x.shape[1]))
        _dk.hermite_samples(self.t, self.x, self.f, none if self._mean is None else self._mean,
                            none if self._half_diff is None else self._half_diff, tt, y)
        return y[0] if np.ndim(t) == 0 else y.T


def integrate_compiled(problem: RunProblem, settings: IntegratorSettings, sinks: Sinks, wind_data) -> RunOutcome:
    """ETD2RK by the compiled steps (:meth:`ETD2RK.run`): the steps, samples, events and log of :func:`_integrate`
    with :class:`ETD2RKSolver`, processed per chunk of :data:`COMPILED_CHUNK_S` instead of per step."""
    model, wind, ctrl, evs = problem.model, problem.wind, problem.ctrl, problem.events
    t_end = problem.t_end_s
    h = settings.max_step_s  # the current step: halved when a chunk fails (HALVINGS)
    halvings = 0
    sink = sinks.log
    steppers: dict[float, ETD2RK] = {}
    g_old = np.array([ev.function(0.0, problem.x0) for ev in evs], dtype=float)
    margins = margin_rows(evs, problem.x0.size)
    crossings: list[tuple[float, str]] = []
    nfev = 0
    chunk = max(1, int(round(CHECK_INTERVAL_S / h)))  # steps per sub-chunk (doubled with every halving of h)
    per_call = max(1, int(round(COMPILED_CHUNK_S / CHECK_INTERVAL_S)))  # sub-chunks per call of the compiled steps
    lin = {"jac": problem.jacobian, "at": flight_condition(model, problem.x0), "count": 1}
    wind_data = _k.pack_winds([wind_data])  # the one row of the compiled steps, packed once

    def stepper(step: float) -> ETD2RK:  # as ETD2RKSolver._method (h: the current step)
        if abs(step - h) <= 1e-9 * h:
            step = h
        key = round(step, 12)
        if key not in steppers:
            steppers[key] = ETD2RK(lin["jac"], step)
        return steppers[key]

    def finish(t: float, y: np.ndarray, u_of) -> None:
        sinks.final(t, y, u_of(t))

    def run() -> tuple[str, str]:
        nonlocal nfev, g_old, h, halvings, chunk
        x = problem.x0.copy()
        bounds = ctrl.boundaries(t_end)
        u_of = None
        for a, b in zip(bounds[:-1], bounds[1:]):
            a, b = float(a), float(b)
            u_of = segment_controls(ctrl, a, b, x, problem.u0)
            u_a = np.array(u_of(a), dtype=float)
            controls = (a, u_a, (np.asarray(u_of(b), dtype=float) - u_a) / (b - a))
            f = model.rhs(a, x, u_a, wind)
            nfev += 1
            t = a
            while b - t > 1e-12 * max(1.0, abs(b)):
                if b - t > h * (1.0 + 1e-9):
                    steps = stepper(h).run(model, t, x, f, b, chunk * per_call, controls, wind_data, dense=True)
                else:
                    steps = stepper(b - t).run(model, t, x, f, b, 1, controls, wind_data, land=True, dense=True)
                k = steps.t.size - 1
                nfev += 2 * k
                bad = not (np.all(np.isfinite(steps.x[-1])) and np.all(np.isfinite(steps.f[-1])))
                # the sub-chunks before a failed one are kept (the next call fails in that one and halves from its start)
                cut = chunk * ((k - 1) // chunk) if bad and k > chunk else k
                for j in range(chunk, cut, chunk):  # sub-chunk ends inside the chunk: cut at the first drift
                    now = flight_condition(model, steps.x[j])
                    if now is not None and np.max(np.abs(now / lin["at"] - 1.0)) > RELINEARISE_DRIFT:
                        cut = j
                        break
                if cut < k:
                    steps = steps._replace(t=steps.t[:cut + 1], x=steps.x[:cut + 1], f=steps.f[:cut + 1],
                                           mean=steps.mean[:cut])
                    k, bad = cut, False
                if bad and halvings < HALVINGS:
                    # the explicit remainder outgrew the step (far from the linearisation): the chunk again, h / 2
                    halvings += 1
                    h *= 0.5
                    chunk *= 2
                    if sink is not None:
                        sink.event(t, f"ETD2RK: the steps from t = {t:.4f} s left the finite numbers or the model's "
                                      f"range at t = {float(steps.t[-1]):.4f} s; repeated with steps of {h * 1e3:g} ms")
                    continue
                if bad:
                    if np.all(np.isfinite(steps.x[-1])):
                        model.rhs(steps.t[-1], steps.x[-1], u_of(steps.t[-1]), wind)  # raises what rhs raises there
                    t_bad = float(steps.t[-1])
                    steps = steps._replace(t=steps.t[:-1], x=steps.x[:-1], f=steps.f[:-1], mean=steps.mean[:-1])
                    k -= 1
                hit = None
                if k:
                    sol = _Steps(steps.t, steps.x, steps.f, lin["jac"], steps.mean)
                    j_stop, hit, g_old = _chunk_events(evs, margins, g_old, steps, sol, crossings, sink)
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
                now = flight_condition(model, x)
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
    return RunOutcome(status=status, reason=reason, nfev=nfev, njev=lin["count"], nlu=0, crossings=tuple(crossings))


def flight_condition(model: AircraftModel, x: np.ndarray) -> np.ndarray | None:
    """(|v_body| [m/s], air density [kg/m^3]) at state x, on which the stiff aerodynamic eigenvalues depend (inflow
    ~ V / b); None for a model without rigid-body states or aerodynamics (nothing drifts)."""
    lay = model.layout
    if not lay.rigid or model.aero is None:
        return None
    return np.array([float(np.linalg.norm(x[lay.v][:3])), model.air_density(x)])


def _crossings(directions: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Whether the margins cross zero between lo and hi (rows: steps, columns: events) in each event's direction
    (-1, +1 or 0 for both; as in :func:`_integrate`)."""
    moved = lo != hi
    down = (lo >= 0) & (hi <= 0) & moved
    up = (lo <= 0) & (hi >= 0) & moved
    return np.where(directions < 0, down, np.where(directions > 0, up, down | up))


def _chunk_events(evs, margins, g_old: np.ndarray, steps, sol, crossings: list,
                  sink) -> tuple[int, tuple | None, np.ndarray]:
    """Events over a chunk of steps: (index of the step where the run stops — the first with a terminal crossing,
    else the last —, (t, event) of the terminal hit or None, the margins at that step). Non-terminal crossings up to
    that step are appended to ``crossings`` and logged; times located by Brent's method on the dense output. The
    margins of all steps and events are evaluated at once (``margins``: :func:`~flexsim.sim.run_parts.margin_rows`)
    and checked for crossings together."""
    k = steps.t.size - 1
    if not evs:
        return k, None, g_old
    g = np.empty((k + 1, len(evs)))
    g[0] = g_old
    g[1:] = margins(steps.t[1:], steps.x[1:])
    if ((g > 0).all(axis=0) | (g < 0).all(axis=0)).all():  # no margin changes sign (the usual chunk)
        return k, None, g[k]
    cross = _crossings(np.array([ev.direction for ev in evs]), g[:-1], g[1:])
    if not cross.any():
        return k, None, g[k]
    j_stop = k
    for e, ev in enumerate(evs):
        if ev.terminal and cross[:, e].any():
            j_stop = min(j_stop, int(np.argmax(cross[:, e])) + 1)
    hit = None
    found = []
    for e, ev in enumerate(evs):
        for j in np.flatnonzero(cross[:j_stop, e]) + 1:
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
    return j_stop, hit, g[j_stop]


def _emit_steps(sinks: Sinks, steps, j_stop: int, t_reached: float, sol, u_of, inclusive: bool) -> None:
    """Samples of a chunk of compiled steps up to t_reached (within step j_stop): on the samplers' grids from the
    dense output, or, without a grid, every step end and t_reached (as :func:`emit_step` per step)."""
    for sampler, log in ((sinks.results, None), (sinks.logged, sinks.log)):
        if sampler is sinks.logged and log is None:
            continue  # no flight log: its samples would go nowhere
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
