"""Batched environments: N aircraft of one FlexSim task stepped in one call (gymnasium 1.x ``VectorEnv``).

``gymnasium.make_vec("FlexSim/GTM-LevelHold-v0", num_envs=N, vectorization_mode="vector_entry_point")``
(every FlexSim id) gives a :class:`FlexSimVectorEnv`: N sub-environments of the task class that share one
:class:`~flexsim.envs.dynamics.FlightDynamics` (one model build, one trim, one Jacobian and one matrix
exponential for all N; :meth:`FlightDynamics.fork`), each with its own episode (state, wind field,
random stream). A step is

1. per aircraft, :meth:`FlexSimEnv.begin_step` (action check, actuator rate limits);
2. :func:`advance_batch`: all control periods integrated in one call: the ETD2RK steps of all aircraft
   flown about the same trim as matrix products over the rows of an (N, n) state array, with the
   right-hand sides of the rows from :func:`rhs_rows` (the one place to plug a compiled batched
   kernel in); other integrators fall back to each aircraft's ``FlightDynamics.advance``;
3. per aircraft, :meth:`FlexSimEnv.finish_step` (observation, reward, termination, info).

The physics is the one right-hand side ``AircraftModel.rhs``; each sub-environment's trajectory equals the
single environment's with the same seed and actions (exactly for ``solve_ivp`` methods, to rounding for
ETD2RK, whose products are GEMMs here: tests/envs/test_vector_batched.py).

Conventions (gymnasium 1.x, as :class:`gymnasium.vector.SyncVectorEnv`): ``metadata["autoreset_mode"]``
(``NEXT_STEP`` by default; ``SAME_STEP`` and ``DISABLED`` with ``options["reset_mask"]``); ``reset(seed=s)``
seeds sub-env i with ``s + i`` (or a list of seeds); batched ``observation_space``/``action_space`` and
``single_*`` spaces; ``info`` dicts with a value array and a ``_key`` mask per key; the time limit
(``max_episode_steps`` of the id) sets ``truncated``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, ClassVar

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from flexsim._threads import single_blas_thread
from flexsim.aircraft.definition import Aircraft
from flexsim.aircraft.toml_loader import load_aircraft

from flexsim.envs.base import FlexSimEnv
from flexsim.envs.dynamics import FlightDynamics, StepOutcome
from flexsim.envs.flutter_margin import FlutterMarginEnv, WingFlutterMarginEnv
from flexsim.envs.gust_alleviation import GustAlleviationEnv
from flexsim.envs.level_hold import LevelHoldCaptureEnv, LevelHoldEnv
from flexsim.envs.turn import TurnEnv

__all__ = ["FlexSimVectorEnv", "LevelHoldVectorEnv", "LevelHoldCaptureVectorEnv", "TurnVectorEnv", "GustAlleviationVectorEnv", "FlutterMarginVectorEnv",
           "WingFlutterMarginVectorEnv", "advance_batch", "rhs_rows"]

#: Exceptions of the model that end one aircraft's period as a "model error" (as ``FlightDynamics.advance``).
_MODEL_ERRORS = (ValueError, ArithmeticError, np.linalg.LinAlgError)


def rhs_rows(dynamics: Sequence[FlightDynamics], t: np.ndarray, x: np.ndarray, u: np.ndarray, winds: Sequence,
             errors: dict[int, Exception], packed: Any = None) -> np.ndarray:
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
        Filled with ``{row: exception}`` for rows whose model raised one of the model errors; their
        derivative rows are NaN.
    packed : optional
        The rows' winds packed once by the model's ``pack_winds`` (a compiled model's batch of wind data,
        rows in this order), or None.

    Returns
    -------
    ndarray, shape (m, n)
        x_dot of every row.

    Rows that share one model whose class offers ``rhs_batch(t, x, u, wind)`` (all rows in one compiled
    call; the wind fields of :mod:`flexsim.sim.disturbances` do not depend on t) go through it when they
    fly in still air or their winds come ``packed``; the rest, and all rows of a batch call that raised (to
    find which row failed), one by one through ``rhs``.
    """
    out = np.empty_like(x)
    batch = getattr(dynamics[0].model, "rhs_batch", None) if len(dynamics) > 1 else None
    if batch is not None and all(d.model is dynamics[0].model for d in dynamics):
        wind = packed if packed is not None else (None if all(w is None for w in winds) else False)
        if wind is not False:
            try:
                return np.asarray(batch(float(t[0]), x, u, wind), dtype=float).reshape(x.shape)
            except _MODEL_ERRORS:
                pass  # evaluated row by row below, which names the failing rows
    for i, dyn in enumerate(dynamics):
        try:
            out[i] = dyn.model.rhs(float(t[i]), x[i], u[i], winds[i])
        except _MODEL_ERRORS as exc:
            errors[i] = exc
            out[i] = np.nan
    return out


@single_blas_thread
def advance_batch(dynamics: Sequence[FlightDynamics], x: np.ndarray, u: np.ndarray, t0: np.ndarray, t1: np.ndarray,
                  winds: Sequence, rhs: Callable = rhs_rows, packed: Any = None) -> list[StepOutcome]:
    """Integrate one control period of many aircraft in one call (zero-order hold of each row's controls).

    Row i is what ``dynamics[i].advance(x[i], u[i], t0[i], t1[i], winds[i])`` returns (same checks: non-finite
    state, model error, crash located by linear interpolation within the ETD2RK step). Aircraft whose
    ETD2RK stepper is the same object (same trim Jacobian and step) are stepped together as matrix
    products over their rows, with right-hand sides from ``rhs`` (:func:`rhs_rows`); the others (the
    ``solve_ivp`` methods) one by one.

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
        The N winds packed by the model's ``pack_winds`` (a named tuple whose ``rows`` select each
        aircraft's wind data), or None.

    Returns
    -------
    list of StepOutcome, length N
    """
    n_rows = len(dynamics)
    outcomes: list[StepOutcome | None] = [None] * n_rows
    groups: dict[int, list[int]] = {}
    for i, dyn in enumerate(dynamics):
        if dyn.substeps and dyn.stepper is not None:
            groups.setdefault(id(dyn.stepper), []).append(i)
        else:
            outcomes[i] = dyn.advance(x[i], u[i], float(t0[i]), float(t1[i]), winds[i])
    for rows in groups.values():
        for i, out in zip(rows, _advance_etd2rk([dynamics[i] for i in rows], x[rows], u[rows], t0[rows], t1[rows],
                                                [winds[i] for i in rows], rhs, _subset(packed, rows))):
            outcomes[i] = out
    return outcomes  # type: ignore[return-value]


def _subset(packed: Any, rows) -> Any:
    """The packed winds of the given rows (None stays None)."""
    return None if packed is None else packed._replace(rows=packed.rows[np.asarray(rows, dtype=np.int64)])


def _advance_etd2rk(dyns, x, u, t0, t1, winds, rhs, packed=None) -> list[StepOutcome]:
    """ETD2RK periods of aircraft sharing one stepper (``FlightDynamics._advance_fixed`` over rows)."""
    first = dyns[0]
    stepper, k, h, dt = first.stepper, first.substeps, first.stepper.h, first.dt
    z = first.layout.position.start + 2  # down coordinate: altitude -x[z]
    span = t1 - t0
    bad = np.flatnonzero(~(np.abs(span - dt) <= 1e-9 * dt))
    if bad.size:
        raise ValueError(f"t1 - t0 = {span[bad[0]]!r} s: ETD2RK steps whole control periods, must be dt = {dt!r} s")
    m = len(dyns)
    out: list[StepOutcome | None] = [None] * m
    active = np.arange(m)
    x = np.array(x, dtype=float)
    t = np.array(t0, dtype=float)
    with np.errstate(all="ignore"):
        for i in range(1, k + 1):
            t_next = t1[active] if i == k else t0[active] + i * h
            nfev = 2 * i
            errors: dict[int, Exception] = {}
            rows_d = [dyns[j] for j in active]
            rows_u, rows_w, rows_p = u[active], [winds[j] for j in active], _subset(packed, active)

            def fun(tt, xx):
                return rhs(rows_d, tt, xx, rows_u, rows_w, errors, rows_p)

            xa, ta = x[active], t[active]
            x_next = stepper.step_rows(fun, ta, xa)
            keep = np.ones(active.size, bool)
            for r, j in enumerate(active):
                if r in errors:
                    out[j] = StepOutcome(xa[r].copy(), float(ta[r]), False, f"model error: {errors[r]}", nfev)
                elif not np.all(np.isfinite(x_next[r])):
                    out[j] = StepOutcome(xa[r].copy(), float(ta[r]), False,
                                         f"non-finite state: ETD2RK step {i} of {k} from t = {float(ta[r]):.6g} s", nfev)
                elif x_next[r, z] >= 0.0 > xa[r, z]:
                    s = xa[r, z] / (xa[r, z] - x_next[r, z])
                    out[j] = StepOutcome(xa[r] + s * (x_next[r] - xa[r]), float(ta[r] + s * (t_next[r] - ta[r])), True, "", nfev)
                else:
                    continue
                keep[r] = False
            x[active] = x_next
            t[active] = t_next
            active = active[keep]
            if not active.size:
                break
    for j in active:
        out[j] = StepOutcome(x[j].copy(), float(t1[j]), False, "", 2 * k)
    return out  # type: ignore[return-value]


class FlexSimVectorEnv(VectorEnv):
    """N aircraft of one FlexSim task stepped in one call (module docstring).

    Parameters
    ----------
    num_envs : int
        Number of aircraft (>= 1).
    max_episode_steps : int or None
        Steps after which an episode is truncated (the id's value when made with ``gymnasium.make_vec``);
        None: never.
    autoreset_mode : AutoresetMode or str
        ``"NextStep"`` (default), ``"SameStep"`` or ``"Disabled"`` (gymnasium 1.x semantics).
    **env_kwargs
        Arguments of the task class (``aircraft``, ``aero``, ``control_rate_hz``, ``turbulence``, ``task``,
        ``integrator``, ...; as ``gymnasium.make`` of the id), the same for every sub-environment.
    """

    env_class: ClassVar[type[FlexSimEnv]] = FlexSimEnv

    def __init__(self, num_envs: int = 1, *, max_episode_steps: int | None = None,
                 autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP, **env_kwargs: Any) -> None:
        if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)) or num_envs < 1:
            raise ValueError(f"num_envs = {num_envs!r}: must be an integer >= 1")
        if max_episode_steps is not None and (isinstance(max_episode_steps, bool) or not isinstance(max_episode_steps, (int, np.integer))
                                              or max_episode_steps < 1):
            raise ValueError(f"max_episode_steps = {max_episode_steps!r}: must be an integer >= 1 or None")
        try:
            mode = AutoresetMode(autoreset_mode)
        except ValueError:
            raise ValueError(f"autoreset_mode = {autoreset_mode!r}: must be one of "
                             f"{', '.join(repr(m.value) for m in AutoresetMode)}") from None
        if env_kwargs.get("render_mode") == "human":
            raise ValueError("render_mode = 'human': a vector env renders 'rgb_array' frames (one per aircraft) or nothing")
        aircraft = env_kwargs.pop("aircraft", None)
        if aircraft is not None and not isinstance(aircraft, Aircraft):
            aircraft = load_aircraft(aircraft)
        if aircraft is not None:
            env_kwargs["aircraft"] = aircraft
        first = self.env_class(**env_kwargs)
        env_kwargs["aircraft"] = first.aircraft
        self.envs: list[FlexSimEnv] = [first] + [self.env_class(dynamics=first.dynamics.fork(), **env_kwargs)
                                                 for _ in range(int(num_envs) - 1)]
        self.num_envs = int(num_envs)
        self.max_episode_steps = None if max_episode_steps is None else int(max_episode_steps)
        self.autoreset_mode = mode
        self.render_mode = first.render_mode
        self.metadata = {**first.metadata, "autoreset_mode": mode}
        self.single_observation_space = first.observation_space
        self.single_action_space = first.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        n = self.num_envs
        self._obs = np.zeros((n, *self.single_observation_space.shape), dtype=self.single_observation_space.dtype)
        self._elapsed = np.zeros(n, dtype=np.int64)
        self._terminations = np.zeros(n, dtype=np.bool_)
        self._truncations = np.zeros(n, dtype=np.bool_)
        self._autoreset = np.zeros(n, dtype=np.bool_)
        self._needs_reset = np.ones(n, dtype=np.bool_)
        self._packed: Any = None  # the N episode winds packed for a compiled batched rhs; None: to pack; False: cannot

    # ------------------------------------------------------------------ gymnasium API
    def reset(self, *, seed: int | Sequence[int | None] | None = None, options: dict | None = None) -> tuple[np.ndarray, dict]:
        """Reset the sub-environments (all, or those of ``options["reset_mask"]``); seed i is ``seed + i``."""
        n = self.num_envs
        if seed is None:
            seeds: list = [None] * n
        elif isinstance(seed, (int, np.integer)) and not isinstance(seed, bool):
            seeds = [int(seed) + i for i in range(n)]
        else:
            seeds = list(seed)
            if len(seeds) != n:
                raise ValueError(f"seed: a list of seeds needs num_envs = {n} entries, got {len(seeds)}")
        options = dict(options) if options else {}
        mask = options.pop("reset_mask", None)
        if mask is None:
            mask = np.ones(n, dtype=np.bool_)
        elif not (isinstance(mask, np.ndarray) and mask.dtype == np.bool_ and mask.shape == (n,) and mask.any()):
            raise ValueError(f"options['reset_mask'] = {mask!r}: must be a numpy bool array of shape ({n},) with a True entry")
        infos: dict = {}
        for i in np.flatnonzero(mask):
            self._obs[i], info = self.envs[i].reset(seed=seeds[i], options=options or None)
            self._packed = None
            self._elapsed[i] = 0
            self._needs_reset[i] = False
            infos = self._add_info(infos, info, i)
        self._terminations[mask] = False
        self._truncations[mask] = False
        self._autoreset[mask] = False
        return self._obs.copy(), infos

    def step(self, actions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict]:
        """Step every sub-environment with its row of ``actions`` (shape (num_envs, 4)); the periods of all
        aircraft are integrated in one :func:`advance_batch` call."""
        n = self.num_envs
        a = np.asarray(actions)
        if a.shape[:1] != (n,):
            raise ValueError(f"actions: expected shape ({n}, 4) (one action per sub-environment), got shape {a.shape}")
        rewards = np.zeros(n, dtype=np.float64)
        infos: dict = {}
        stepping: list[int] = []
        if self.autoreset_mode == AutoresetMode.NEXT_STEP:
            for i in np.flatnonzero(self._autoreset):
                self._obs[i], info = self.envs[i].reset()
                self._packed = None
                self._elapsed[i] = 0
                self._terminations[i] = self._truncations[i] = False
                infos = self._add_info(infos, info, i)
            stepping = [i for i in range(n) if not self._autoreset[i]]
        else:
            if self.autoreset_mode == AutoresetMode.DISABLED and self._needs_reset.any():
                raise RuntimeError(f"step(): sub-environments {np.flatnonzero(self._needs_reset).tolist()} ended (or were never "
                                   "reset); with autoreset_mode 'Disabled' call reset(options={'reset_mask': ...}) for them first")
            stepping = list(range(n))
        periods = {}
        for i in stepping:
            try:
                periods[i] = self.envs[i].begin_step(a[i])
            except ValueError as exc:
                raise ValueError(f"actions[{i}]: {exc}") from None
        envs = [self.envs[i] for i in stepping]
        packed = self._packed_winds()
        outcomes = advance_batch([e.dynamics for e in envs], np.array([e.state for e in envs]),
                                 np.array([periods[i].u for i in stepping]),
                                 np.array([periods[i].t0_s for i in stepping]), np.array([periods[i].t1_s for i in stepping]),
                                 [e.wind for e in envs], packed=_subset(packed, stepping) if packed else None) if stepping else []
        for i, outcome in zip(stepping, outcomes):
            obs, rewards[i], term, _, info = self.envs[i].finish_step(periods[i], outcome)
            self._elapsed[i] += 1
            trunc = self.max_episode_steps is not None and self._elapsed[i] >= self.max_episode_steps
            self._obs[i], self._terminations[i], self._truncations[i] = obs, term, trunc
            if self.autoreset_mode == AutoresetMode.SAME_STEP and (term or trunc):
                infos = self._add_info(infos, {"final_obs": obs, "final_info": info}, i)
                self._obs[i], info = self.envs[i].reset()
                self._packed = None
                self._elapsed[i] = 0
            infos = self._add_info(infos, info, i)
        ended = self._terminations | self._truncations
        self._autoreset = ended.copy()
        if self.autoreset_mode == AutoresetMode.DISABLED:
            self._needs_reset |= ended
        return self._obs.copy(), rewards, self._terminations.copy(), self._truncations.copy(), infos

    def _packed_winds(self) -> Any:
        """The episode winds of all sub-environments packed once per reset by the model's ``pack_winds`` (a
        compiled model), or False where the model has none or a wind cannot be packed (evaluated per row)."""
        if self._packed is None:
            pack = getattr(self.envs[0].dynamics.model, "pack_winds", None)
            self._packed = False
            if pack is not None and all(e.dynamics.model is self.envs[0].dynamics.model for e in self.envs):
                try:
                    self._packed = pack([e.wind for e in self.envs])
                except ValueError:
                    pass
        return self._packed

    def render(self) -> tuple | None:
        """One frame per sub-environment (``render_mode="rgb_array"``), else None."""
        if self.render_mode is None:
            return None
        return tuple(env.render() for env in self.envs)

    def close_extras(self, **kwargs: Any) -> None:
        for env in self.envs:
            env.close()

    # ------------------------------------------------------------------ attributes (as SyncVectorEnv)
    def call(self, name: str, *args: Any, **kwargs: Any) -> tuple:
        """``getattr(env, name)(*args, **kwargs)`` (or the attribute itself) of every sub-environment."""
        out = []
        for env in self.envs:
            value = getattr(env, name)
            out.append(value(*args, **kwargs) if callable(value) else value)
        return tuple(out)

    def get_attr(self, name: str) -> tuple:
        """The attribute ``name`` of every sub-environment."""
        return tuple(getattr(env, name) for env in self.envs)

    def set_attr(self, name: str, values: Any) -> None:
        """Set attribute ``name`` of every sub-environment (one value for all, or a list of num_envs values)."""
        if not isinstance(values, (list, tuple)):
            values = [values] * self.num_envs
        if len(values) != self.num_envs:
            raise ValueError(f"values: need num_envs = {self.num_envs} values for {name!r}, got {len(values)}")
        for env, value in zip(self.envs, values):
            setattr(env, name, value)


class LevelHoldVectorEnv(FlexSimVectorEnv):
    """``FlexSim/GTM-LevelHold-v0`` batched (:class:`FlexSimVectorEnv`)."""

    env_class = LevelHoldEnv


class LevelHoldCaptureVectorEnv(FlexSimVectorEnv):
    """``FlexSim/GTM-LevelHold-v1`` batched (:class:`FlexSimVectorEnv`)."""

    env_class = LevelHoldCaptureEnv


class TurnVectorEnv(FlexSimVectorEnv):
    """``FlexSim/GTM-Turn-v0`` batched (:class:`FlexSimVectorEnv`)."""

    env_class = TurnEnv


class GustAlleviationVectorEnv(FlexSimVectorEnv):
    """``FlexSim/GTM-GustAlleviation-v0`` batched (:class:`FlexSimVectorEnv`)."""

    env_class = GustAlleviationEnv


class FlutterMarginVectorEnv(FlexSimVectorEnv):
    """``FlexSim/GTM-FlutterMargin-v0`` batched (:class:`FlexSimVectorEnv`)."""

    env_class = FlutterMarginEnv


class WingFlutterMarginVectorEnv(FlexSimVectorEnv):
    """``FlexSim/GTM-FlutterMargin-v1`` batched (:class:`FlexSimVectorEnv`)."""

    env_class = WingFlutterMarginEnv
