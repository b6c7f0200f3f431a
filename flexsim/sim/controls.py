"""Controls for a simulation: a piecewise-linear schedule, or a feedback controller held over each period.

``u = [T_e (N), delta_a, delta_e, delta_r (rad)]`` (paper, text after eq. 33; signs in
``docs/conventions.md``). Values beyond ``aircraft.control_limits()`` are rejected with the control, time
and limits named.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from flexsim.errors import float_array
from flexsim.model.aircraft_model import AircraftModel

__all__ = ["ControlSchedule", "Controls", "CONTROL_LABELS"]

#: Human-readable names of the control vector entries, with units.
CONTROL_LABELS = ("thrust T_e [N]", "aileron delta_a [rad]", "elevator delta_e [rad]", "rudder delta_r [rad]")


@dataclass(frozen=True, eq=False)
class ControlSchedule:
    """Controls as a piecewise-linear table of time (held constant before the first and after the last row).

    Attributes
    ----------
    times_s : array_like, shape (k,)
        Strictly increasing, finite times [s] (k >= 1).
    values : array_like, shape (k, 4)
        Controls [T_e (N), delta_a, delta_e, delta_r (rad)] at those times, finite.
    """

    times_s: np.ndarray
    values: np.ndarray

    def __post_init__(self) -> None:
        t = float_array("ControlSchedule.times_s", self.times_s, finite=False).copy()
        v = float_array("ControlSchedule.values", self.values, finite=False).copy()
        if t.ndim != 1 or t.size == 0:
            raise ValueError(f"ControlSchedule.times_s: expected a 1-D array of k >= 1 times [s], got shape {t.shape}")
        bad = np.flatnonzero(~np.isfinite(t))
        if bad.size:
            raise ValueError(f"ControlSchedule.times_s[{bad[0]}] = {t[bad[0]]}: times must be finite [s]")
        bad = np.flatnonzero(np.diff(t) <= 0.0)
        if bad.size:
            i = int(bad[0]) + 1
            raise ValueError(f"ControlSchedule.times_s[{i}] = {t[i]:g}: must be > times_s[{i - 1}] = {t[i - 1]:g} "
                             "(times must increase strictly)")
        if v.shape != (t.size, 4):
            raise ValueError(f"ControlSchedule.values: expected shape (k, 4) = ({t.size}, 4) "
                             f"([thrust N, aileron, elevator, rudder rad] per time), got shape {v.shape}")
        bad = np.argwhere(~np.isfinite(v))
        if bad.size:
            i, j = bad[0]
            raise ValueError(f"ControlSchedule.values[{i}, {j}] ({CONTROL_LABELS[j]} at t = {t[i]} s) = {v[i, j]}: must be finite")
        t.setflags(write=False)
        v.setflags(write=False)
        object.__setattr__(self, "times_s", t)
        object.__setattr__(self, "values", v)

    @classmethod
    def constant(cls, u: Sequence[float]) -> "ControlSchedule":
        """Constant controls u (4,)."""
        return cls(np.zeros(1), np.asarray(u, dtype=float).reshape(1, -1))

    def __call__(self, t: float) -> np.ndarray:
        """Controls at time t [s], shape (4,)."""
        return np.array([np.interp(t, self.times_s, self.values[:, j]) for j in range(4)])

    def at(self, t: np.ndarray) -> np.ndarray:
        """Controls at times t (k,) [s], shape (k, 4)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return np.stack([np.interp(t, self.times_s, self.values[:, j]) for j in range(4)], axis=-1)

    def check_limits(self, lower: np.ndarray, upper: np.ndarray) -> None:
        """Raise ValueError naming the first control, time and value outside [lower, upper]."""
        for i, j in np.argwhere((self.values < lower - 1e-9) | (self.values > upper + 1e-9)):
            raise ValueError(f"controls: {CONTROL_LABELS[j]} = {self.values[i, j]:.6g} at t = {self.times_s[i]:g} s "
                             f"is outside the aircraft's limits [{lower[j]:.6g}, {upper[j]:.6g}]")


class Controls:
    """The controls of one run: a schedule (continuous in t) or a feedback controller held over each period.

    Parameters
    ----------
    model : AircraftModel
        Supplies the control limits.
    controls : array (4,), ControlSchedule, callable(t, x) -> u, or None
        None takes ``u_trim``.
    u_trim : ndarray, shape (4,), or None
        Trim controls (from a TrimPoint initial state).
    period_s : float
        Control period of a feedback controller [s] > 0.

    Attributes
    ----------
    schedule : ControlSchedule or None
    controller : callable or None
    lower, upper : ndarray, shape (4,)
        Control limits.
    """

    def __init__(self, model: AircraftModel, controls, u_trim: np.ndarray | None, period_s: float) -> None:
        self.lower, self.upper = model.aircraft.control_limits()
        self.controller = None
        self.schedule: ControlSchedule | None = None
        if controls is None:
            if u_trim is None:
                raise ValueError("controls: give the controls (an array of 4, a ControlSchedule or a controller "
                                 "callable(t, x) -> u) when the initial state is not a TrimPoint")
            controls = u_trim
        if isinstance(controls, ControlSchedule):
            self.schedule = controls
        elif isinstance(controls, (np.ndarray, list, tuple)):
            u = float_array("controls", controls, (4,), what="[thrust N, aileron, elevator, rudder rad] (a constant "
                            "control vector; a ControlSchedule for controls that change)")
            self.schedule = ControlSchedule.constant(u)
        elif callable(controls):
            self.controller = controls
            if isinstance(period_s, bool) or not (isinstance(period_s, (int, float)) and math.isfinite(period_s) and period_s > 0):
                raise ValueError(f"period_s = {period_s!r}: the control period must be a finite number > 0 [s]")
        else:
            raise ValueError(f"controls = {controls!r}: must be an array of 4, a ControlSchedule or a callable(t, x) -> u")
        if self.schedule is not None:
            self.schedule.check_limits(self.lower, self.upper)
        self.period_s = float(period_s)

    def boundaries(self, t_end: float) -> np.ndarray:
        """Times where the right-hand side changes character (the solver restarts there)."""
        if self.schedule is not None:
            inner = self.schedule.times_s[(self.schedule.times_s > 0.0) & (self.schedule.times_s < t_end)]
        else:
            inner = np.arange(1, int(math.ceil(t_end / self.period_s - 1e-9))) * self.period_s
        return np.concatenate([[0.0], inner, [t_end]])

    def held(self, t: float, x: np.ndarray) -> np.ndarray:
        """The controller's output at the start of a control period, checked."""
        value = self.controller(t, x)
        try:
            u = np.array(value, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"controller returned {value!r} at t = {t:g} s: expected 4 finite numbers") from None
        if u.shape != (4,) or not np.all(np.isfinite(u)):
            raise ValueError(f"controller returned {u!r} at t = {t:g} s: expected 4 finite numbers [thrust N, aileron, elevator, rudder rad]")
        for j in range(4):
            if not self.lower[j] - 1e-9 <= u[j] <= self.upper[j] + 1e-9:
                raise ValueError(f"controller returned {CONTROL_LABELS[j]} = {u[j]:.6g} at t = {t:g} s, outside the "
                                 f"aircraft's limits [{self.lower[j]:.6g}, {self.upper[j]:.6g}] (saturate it in the controller)")
        return u
