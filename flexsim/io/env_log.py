"""The flight-log recorder of the flexsim environments (:mod:`flexsim.envs`), a gymnasium wrapper."""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from flexsim.io.output_paths import check_not_link
from flexsim.io.flight_log import FlightLogWriter
from flexsim.io.vocabulary import CONTROL_NAMES as LOG_CONTROL_NAMES

__all__ = ["FlightLogRecorder", "LogSample", "flight_sample"]


@dataclass(frozen=True)
class LogSample:
    """One flight-log sample of an environment's current state (the arguments of :meth:`FlightLogWriter.write`)."""

    time_s: float
    position_ned_m: np.ndarray
    euler_rad: np.ndarray
    state: np.ndarray
    controls: np.ndarray
    signals: np.ndarray
    structure: dict


def flight_sample(dynamics, time_s: float, x: np.ndarray, u: np.ndarray, wind, task_values) -> LogSample:
    """The flight-log sample of state ``x`` at ``time_s`` [s] with the applied controls ``u`` [N, rad] in ``wind`` on
    ``dynamics`` (:class:`flexsim.sim.periods.FlightDynamics`): the simulator's flight signals by the one output layer
    (:meth:`flexsim.sim.outputs.OutputMaps.signals`; NaN where a failed state cannot be evaluated), then
    ``task_values`` (an env's task errors and reward); non-finite signals are written as 0."""
    out = dynamics.outputs
    with np.errstate(all="ignore"):
        try:
            flight = out.signals(time_s, x, u, wind)
        except (ValueError, ArithmeticError, np.linalg.LinAlgError):  # a failed state: logged as far as it goes
            flight = np.full(len(out.signal_names), np.nan)
    signals = np.concatenate([flight, np.asarray(task_values, float)])
    lay = dynamics.layout
    return LogSample(time_s, x[lay.position].copy(), x[lay.euler].copy(), x.copy(), u.copy(),
                     np.nan_to_num(signals, nan=0.0, posinf=0.0, neginf=0.0), out.structure(x))


class FlightLogRecorder(gym.Wrapper):
    """Record every episode to a flight log (protobuf MCAP, :class:`~flexsim.io.flight_log.FlightLogWriter`).

    The logs have the simulator's format and vocabulary (``docs/logs.md``, :mod:`flexsim.io.vocabulary`), computed
    by the same output layer (:class:`flexsim.sim.outputs.OutputMaps`): the full state (``x_north_m``, ...,
    ``q_<component>_<k>_m``, ``xi_<component>_<k>_rad``, ...), the applied controls ``thrust_N, aileron_rad,
    elevator_rad, rudder_rad``, the simulator's flight signals (air data, load factor, tip deflections and twists
    with their rates, root bending moments) followed by ``error_<task error>`` and ``reward``, the deformed beam
    nodes of every component and events (reset, termination with its reason, truncation); the header records the
    model's physical terms (:attr:`flexsim.io.flight_log.FlightLog.terms`). View one with
    ``python -m flexsim.io.rerun_view LOG.mcap --rrd out.rrd``.

    Parameters
    ----------
    env : gymnasium.Env
        A flexsim environment (possibly wrapped, e.g. by ``gymnasium.make``).
    path : str or os.PathLike
        Log file, suffix ``.mcap``; its directory must exist. Episode k is written to ``path`` with
        ``{episode}`` replaced by k (0-based) if the name contains it, otherwise episode 0 to ``path``
        and episode k >= 1 to ``<stem>-<k:04d>.mcap`` beside it. Each log is closed when the next
        episode starts or the wrapper is closed.
    metadata : dict of str to str, optional
        Extra run metadata stored in every log (``"run"`` record).

    Attributes
    ----------
    paths : list of Path
        The logs written so far.
    """

    def __init__(self, env: gym.Env, path: str | os.PathLike, metadata: dict[str, str] | None = None) -> None:
        super().__init__(env)
        if not all(hasattr(env.unwrapped, name) for name in ("log_sample", "signal_names", "dynamics")):
            raise ValueError(f"env = {env!r}: FlightLogRecorder needs a flexsim environment (FlexSimEnv)")
        path = check_not_link("path", path)
        if path.suffix != ".mcap":
            raise ValueError(f"path = {str(path)!r}: the suffix must be '.mcap'")
        if not path.parent.is_dir():
            raise FileNotFoundError(f"path = {str(path)!r}: directory {str(path.parent)!r} does not exist")
        self.pattern = path
        taken = self._existing_logs()
        if taken:
            raise FileExistsError(f"path = {str(path)!r}: {len(taken)} log(s) of an earlier recording are there "
                                  f"({', '.join(p.name for p in taken[:3])}{', ...' if len(taken) > 3 else ''}); they are "
                                  "not overwritten: give another name (e.g. with {episode} and a run name) or move them")
        self.run_metadata = dict(metadata or {})
        self.paths: list[Path] = []
        self._writer: FlightLogWriter | None = None
        self._episode = -1
        self._last_sample_t = float("-inf")

    def _existing_logs(self) -> list[Path]:
        """Files this recorder would write that exist already (episode 0's name and the episodes' pattern)."""
        name = self.pattern.name
        if "{episode}" in name:
            glob = name.replace("{episode}", "*")
        else:
            glob = f"{self.pattern.stem}-[0-9][0-9][0-9][0-9]*.mcap"
        found = sorted(self.pattern.parent.glob(glob))
        if "{episode}" not in name and (self.pattern.exists() or self.pattern.is_symlink()):
            found.insert(0, self.pattern)
        return found

    def _episode_path(self, k: int) -> Path:
        name = self.pattern.name
        if "{episode}" in name:
            return self.pattern.with_name(name.replace("{episode}", str(k)))
        return self.pattern if k == 0 else self.pattern.with_name(f"{self.pattern.stem}-{k:04d}.mcap")

    def _write(self) -> None:
        sample = self.env.unwrapped.log_sample()
        if sample.time_s <= self._last_sample_t:
            # A step that failed before time advanced (``non_finite`` in the first sub-step) has no new
            # sample; the termination event below still records what happened.
            return
        self._last_sample_t = sample.time_s
        self._writer.write(sample.time_s, position_m=sample.position_ned_m, euler_rad=sample.euler_rad, state=sample.state,
                           controls=sample.controls, signals=sample.signals, structure=sample.structure)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        obs, info = self.env.reset(seed=seed, options=options)
        self._close_writer()
        self._episode += 1
        base = self.env.unwrapped
        path = self._episode_path(self._episode)
        if path.exists() or path.is_symlink():  # written since this recorder started (e.g. by another recorder)
            raise FileExistsError(f"{str(path)!r}: exists; the recorder does not overwrite it (episode {self._episode})")
        metadata = {"aircraft": str(base.aircraft_source), "env": type(base).__name__, "episode": str(self._episode),
                    "seed": str(seed), "aero": base.dynamics.aero, "integrator": base.dynamics.method,
                    "control_rate_hz": f"{base.control_rate_hz:g}", "run_id": f"{type(base).__name__}-{self._episode}",
                    **self.run_metadata}
        nodes = base.dynamics.structure_nodes(base.state)
        self._writer = FlightLogWriter(path, state_names=base.dynamics.state_names(), control_names=LOG_CONTROL_NAMES,
                                       signal_names=base.signal_names(), structure_topology={k: len(v) for k, v in nodes.items()},
                                       metadata=metadata, terms=base.dynamics.model.terms.record(),
                                       formulation=base.dynamics.model.formulation)
        self.paths.append(path)
        self._last_sample_t = float("-inf")
        self._writer.event(0.0, f"reset: {type(base).__name__}, seed {seed}, reference {info.get('reference', {})}")
        self._write()
        return obs, info

    def step(self, action):
        obs, reward, terminated, truncated, info = self.env.step(action)
        if self._writer is not None:
            self._write()
            t = self.env.unwrapped.time_s
            if terminated:
                self._writer.event(t, f"terminated: {info.get('termination_reason', '')}", level="error")
            elif truncated:
                self._writer.event(t, "truncated (time limit)")
        return obs, reward, terminated, truncated, info

    def _close_writer(self) -> None:
        if self._writer is not None:
            self._writer.close()
            self._writer = None

    def close(self) -> None:
        self._close_writer()
        super().close()
