"""The settings of a :func:`flexsim.sim.simulate.simulate` run besides its integrator: events and outputs.

Each is one frozen object, validated on construction (a clear error names the field, its value and the allowed range),
so that ``simulate`` takes a few settings objects instead of a long keyword list and every setting has one name
across simulation and environments (the integrator's :class:`~flexsim.sim.simulate.IntegratorSettings` is shared with
the environments; the structural limit is ``wing_tip_deflection_m`` as in the environments'
:class:`~flexsim.envs.config.FlightLimits`).

Example::

    from flexsim.sim.run_settings import EventSettings, OutputSettings

    events = EventSettings(("ground", "structural_limit"), wing_tip_deflection_m=4.0)
    output = OutputSettings(rate_hz=50.0, log_path=None)
    print(events.names, output.rate_hz)  # ('ground', 'structural_limit') 50.0
"""

from __future__ import annotations

import math
import numbers
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

__all__ = ["DEFAULT_EVENTS", "SimEvent", "EventSettings", "OutputSettings"]

#: Built-in terminal events (the non-finite check is always on).
DEFAULT_EVENTS = ("ground", "structural_limit", "gimbal_lock")


def _rate(name: str, value, optional: bool) -> float | None:
    if value is None and optional:
        return None
    if isinstance(value, bool) or not (isinstance(value, numbers.Real) and math.isfinite(value) and value > 0):
        extra = " (or None)" if optional else ""
        raise ValueError(f"{name} = {value!r}: must be a finite number > 0 [Hz]{extra}")
    return float(value)


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
class EventSettings:
    """What stops a run, or is noted in it.

    Attributes
    ----------
    names : tuple of str or SimEvent
        Built-in terminal events among ``"ground"`` (altitude of the body origin <= 0), ``"structural_limit"``
        (|tip deflection| of a wing >= ``wing_tip_deflection_m``: the signature of flutter or overload),
        ``"gimbal_lock"`` (|theta| >= 89 deg), plus user :class:`~flexsim.sim.simulate.SimEvent` objects. Default
        :data:`DEFAULT_EVENTS`. A non-finite state always stops the run.
    wing_tip_deflection_m : float or None
        Bound on |tip deflection| of every wing [m], finite and > 0; None (default): 0.25 x each wing's length.
    """

    names: tuple = DEFAULT_EVENTS
    wing_tip_deflection_m: float | None = None

    def __post_init__(self) -> None:
        if isinstance(self.names, (str, bytes)) or not hasattr(self.names, "__iter__"):
            raise ValueError(f"names = {self.names!r}: must be a sequence of built-in event names and SimEvent objects")
        names = tuple(self.names)
        for e in names:
            if isinstance(e, str):
                if e not in DEFAULT_EVENTS:
                    raise ValueError(f"names: unknown event {e!r}; built-in events are {', '.join(DEFAULT_EVENTS)} "
                                     "(or SimEvent objects)")
            elif not isinstance(e, SimEvent):
                raise ValueError(f"names: {e!r} is neither a built-in event name nor a SimEvent")
        object.__setattr__(self, "names", names)
        bound = self.wing_tip_deflection_m
        if bound is not None:
            if isinstance(bound, bool) or not (isinstance(bound, numbers.Real) and math.isfinite(bound) and bound > 0):
                raise ValueError(f"wing_tip_deflection_m = {bound!r}: must be a finite number > 0 [m] (or None: 0.25 x "
                                 "wing length)")
            object.__setattr__(self, "wing_tip_deflection_m", float(bound))


@dataclass(frozen=True, eq=False)
class OutputSettings:
    """What a run gives back and writes as it proceeds.

    Attributes
    ----------
    rate_hz : float or None
        Rate of the result's samples [Hz] (default 100); None: every accepted step.
    log_path : str, Path, True or None
        Write a flight log (MCAP) there as the run proceeds; True: ``logs/simulation-<time>.mcap``; None (default):
        no log.
    log_rate_hz : float
        Rate of the logged samples [Hz] (default 50).
    metadata : mapping of str to str
        Extra run metadata for the log (copied, read-only).
    notes : tuple of (t [s], text)
        Informational events for the log (e.g. when a gust arrives).
    progress : bool or callable
        True: a tqdm progress bar; a callable is called with the sim time [s] after every accepted step (the
        compiled ETD2RK: after every chunk of steps).
    """

    rate_hz: float | None = 100.0
    log_path: str | os.PathLike | bool | None = None
    log_rate_hz: float = 50.0
    metadata: Mapping[str, str] = field(default_factory=dict)
    notes: tuple = ()
    progress: bool | Callable[[float], None] = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "rate_hz", _rate("rate_hz", self.rate_hz, True))
        object.__setattr__(self, "log_rate_hz", _rate("log_rate_hz", self.log_rate_hz, False))
        path = self.log_path
        if path is not None and not isinstance(path, (bool, str, os.PathLike)):
            raise ValueError(f"log_path = {path!r}: must be a path, True (a new file under logs/) or None")
        if path is False:
            object.__setattr__(self, "log_path", None)
        meta = {} if self.metadata is None else self.metadata
        if not isinstance(meta, Mapping):
            raise ValueError(f"metadata = {self.metadata!r}: must be a mapping of str to str")
        object.__setattr__(self, "metadata", MappingProxyType({str(k): str(v) for k, v in meta.items()}))
        try:
            notes = tuple((float(t), str(text)) for t, text in self.notes)
        except (TypeError, ValueError):
            raise ValueError(f"notes = {self.notes!r}: must be a sequence of (time [s], text) pairs") from None
        if not all(math.isfinite(t) for t, _ in notes):
            raise ValueError(f"notes = {self.notes!r}: every time must be finite [s]")
        object.__setattr__(self, "notes", notes)
        if not (isinstance(self.progress, bool) or callable(self.progress)):
            raise ValueError(f"progress = {self.progress!r}: must be True, False or a callable progress(t_s)")
