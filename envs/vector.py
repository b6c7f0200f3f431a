"""Batched environments: N aircraft of one FlexSim task stepped in one call (gymnasium 1.x ``VectorEnv``).

``gymnasium.make_vec("FlexSim/GTM-LevelHold-v0", num_envs=N, vectorization_mode="vector_entry_point")``
(every FlexSim id) gives a :class:`FlexSimVectorEnv`: N sub-environments of the task class that share one
:class:`~flexsim.sim.periods.FlightDynamics` (one model build, one trim, one Jacobian and one matrix
exponential for all N), each with its own episode (state, wind field, random stream, and the integration state
:class:`~flexsim.sim.periods.IntegrationState`, an immutable value per row). All N episodes live in one :class:`~flexsim.envs.batch.EpisodeBatch` (sub-environment i is its
row i), so a step is one pass of array code over the stepping rows (:meth:`FlexSimEnv._step_rows`, the code the
single env runs with one row): the actions checked and clipped as one array, one
:func:`flexsim.sim.periods.advance_period` call (rate limits, integration and measurements of all rows, compiled),
termination, task errors, reward parts and observations; the info is built as gymnasium's vector info arrays
directly.

Each sub-environment's trajectory equals the single environment's with the same seed and actions (exactly for
``solve_ivp`` methods, to rounding for ETD2RK, whose products are matrix products over the rows from
:data:`flexsim.sim.periods.COMPILED_ROWS_BELOW` rows on: tests/envs/test_vector_batched.py).

Conventions (gymnasium 1.x, as :class:`gymnasium.vector.SyncVectorEnv`): ``metadata["autoreset_mode"]``
(``NEXT_STEP`` by default; ``SAME_STEP`` and ``DISABLED`` with ``options["reset_mask"]``); ``reset(seed=s)``
seeds sub-env i with ``s + i`` (or a list of seeds); batched ``observation_space``/``action_space`` and
``single_*`` spaces; ``info`` dicts with a value array and a ``_key`` mask per key; the time limit
(``max_episode_steps`` of the id) sets ``truncated``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, ClassVar

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from flexsim.aircraft.definition import Aircraft
from flexsim.aircraft.toml_loader import load_aircraft

from flexsim.envs.base import TERMINATION_CODES, FlexSimEnv, RowsStep, check_reset_options
from flexsim.envs.batch import EpisodeBatch
from flexsim.model.aircraft_model import CONTROL_NAMES
from flexsim.envs.flutter_margin import FlutterMarginEnv, WingFlutterMarginEnv
from flexsim.envs.gust_alleviation import GustAlleviationEnv, HaleGustAlleviationEnv
from flexsim.envs.level_hold import LevelHoldCaptureEnv, LevelHoldEnv
from flexsim.envs.turn import TurnEnv

__all__ = ["FlexSimVectorEnv", "LevelHoldVectorEnv", "LevelHoldCaptureVectorEnv", "TurnVectorEnv", "GustAlleviationVectorEnv", "FlutterMarginVectorEnv",
           "WingFlutterMarginVectorEnv", "HaleGustAlleviationVectorEnv"]

#: Attributes of the sub-environments that the batched step reads from the first one only (all equal).
_SHARED = ("limits", "task", "reward_definition")


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
        self.envs: list[FlexSimEnv] = [first] + [self.env_class(dynamics=first.dynamics, **env_kwargs)
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
        #: The episodes of all sub-environments, row i of sub-environment i.
        self._batch = EpisodeBatch(n, first.dynamics.layout.n_states, len(first.task_errors_spec))
        for i, env in enumerate(self.envs):
            env._attach(self._batch, i)
        self._low = self.single_action_space.low.astype(np.float64)
        self._high = self.single_action_space.high.astype(np.float64)

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
        check_reset_options(options, ("reset_mask",))
        options = dict(options) if options else {}
        mask = options.pop("reset_mask", None)
        if mask is None:
            mask = np.ones(n, dtype=np.bool_)
        elif not (isinstance(mask, np.ndarray) and mask.dtype == np.bool_ and mask.shape == (n,) and mask.any()):
            raise ValueError(f"options['reset_mask'] = {mask!r}: must be a numpy bool array of shape ({n},) with a True entry")
        infos: dict = {}
        for i in np.flatnonzero(mask):
            self._obs[i], info = self.envs[i].reset(seed=seeds[i], options=options or None)
            self._elapsed[i] = 0
            self._needs_reset[i] = False
            infos = self._add_info(infos, info, i)
        self._terminations[mask] = False
        self._truncations[mask] = False
        self._autoreset[mask] = False
        return self._obs.copy(), infos

    def step(self, actions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict]:
        """Step every sub-environment with its row of ``actions`` (shape (num_envs, 4)): one pass of array code over
        the stepping rows (:meth:`FlexSimEnv._step_rows`: one :func:`flexsim.sim.periods.advance_period` call)."""
        n = self.num_envs
        a, clipped = self._check_actions(actions)
        rewards = np.zeros(n, dtype=np.float64)
        infos: dict = {}
        if self.autoreset_mode == AutoresetMode.NEXT_STEP:
            for i in np.flatnonzero(self._autoreset):
                self._obs[i], info = self.envs[i].reset()
                self._elapsed[i] = 0
                self._terminations[i] = self._truncations[i] = False
                infos = self._add_info(infos, info, i)
            stepping = np.flatnonzero(~self._autoreset)
        else:
            if self.autoreset_mode == AutoresetMode.DISABLED and self._needs_reset.any():
                raise RuntimeError(f"step(): sub-environments {np.flatnonzero(self._needs_reset).tolist()} ended (or were never "
                                   "reset); with autoreset_mode 'Disabled' call reset(options={'reset_mask': ...}) for them first")
            stepping = np.arange(n)
        if stepping.size:
            FlexSimEnv._check_steppable(self._batch, stepping)
            out = self.envs[0]._step_rows(self._batch, stepping, a[stepping], clipped[stepping])
            self._elapsed[stepping] += 1
            trunc = (self._elapsed[stepping] >= self.max_episode_steps if self.max_episode_steps is not None
                     else np.zeros(stepping.size, dtype=np.bool_))
            self._obs[stepping] = out.obs
            rewards[stepping] = out.reward
            self._terminations[stepping] = out.terminated
            self._truncations[stepping] = trunc
            ended = out.terminated | trunc
            same_step = self.autoreset_mode == AutoresetMode.SAME_STEP and ended.any()
            keep = ~ended if same_step else np.ones(stepping.size, dtype=np.bool_)
            infos = self._step_infos(infos, stepping, out, keep)
            if same_step:
                for r in np.flatnonzero(ended):
                    i = int(stepping[r])
                    infos = self._add_info(infos, {"final_obs": out.obs[r], "final_info": self.envs[0]._step_info(out, r)}, i)
                    self._obs[i], info = self.envs[i].reset()
                    self._elapsed[i] = 0
                    infos = self._add_info(infos, info, i)
        ended = self._terminations | self._truncations
        self._autoreset = ended.copy()
        if self.autoreset_mode == AutoresetMode.DISABLED:
            self._needs_reset |= ended
        return self._obs.copy(), rewards, self._terminations.copy(), self._truncations.copy(), infos

    def _check_actions(self, actions: Any) -> tuple[np.ndarray, np.ndarray]:
        """The actions (num_envs, 4) as float64, clipped to the action space, and which rows were clipped."""
        n = self.num_envs
        raw = np.asarray(actions)
        if raw.shape != (n, 4):
            raise ValueError(f"actions: expected shape ({n}, 4) (one action per sub-environment), got shape {raw.shape}")
        if raw.dtype.kind not in "iuf":
            raise ValueError(f"actions: must be real numbers [thrust, aileron, elevator, rudder] per row, got dtype {raw.dtype}")
        a = raw.astype(np.float64)
        bad = ~np.isfinite(a)
        if bad.any():
            i, j = np.argwhere(bad)[0]
            raise ValueError(f"actions[{i}]: action: values must be finite, got action[{j}] ({CONTROL_NAMES[j]}) = {a[i, j]}")
        clipped = np.clip(a, self._low, self._high)
        return clipped, np.any(clipped != a, axis=1)

    def _step_infos(self, infos: dict, rows: np.ndarray, out: RowsStep, keep: np.ndarray) -> dict:
        """Add the step info of ``rows[keep]`` to ``infos`` as gymnasium's vector info arrays (value array and ``_key``
        mask per key, nested for the dicts), built from the arrays of ``out`` (as ``_add_info`` of each row's info)."""
        n = self.num_envs
        sel = rows[keep]
        if not sel.size:
            return infos
        mask = np.zeros(n, dtype=np.bool_)
        mask[sel] = True

        def put(target: dict, key: str, values: np.ndarray, dtype) -> None:
            if key in target:
                array = target[key]
            else:
                array = np.full(n, None, dtype=object) if dtype is object else np.zeros(n, dtype=dtype)
            array[sel] = values[keep]
            target[key] = array
            target[f"_{key}"] = target.get(f"_{key}", np.zeros(n, dtype=np.bool_)) | mask

        def nested(key: str, values: dict) -> None:
            sub = infos.get(key, {})
            for name, v in values.items():
                put(sub, name, v, np.float64)
            infos[key] = sub
            infos[f"_{key}"] = infos.get(f"_{key}", np.zeros(n, dtype=np.bool_)) | mask

        put(infos, "time_s", out.outcome.time_s, np.float64)
        nested("reward_parts", out.parts)
        put(infos, "termination_reason", np.array(TERMINATION_CODES, dtype=object)[out.codes], object)
        put(infos, "action_clipped", out.clipped, np.bool_)
        nested("task_errors", out.errors)
        put(infos, "nfev", out.outcome.nfev, np.int64)
        put(infos, "nlu", out.outcome.nlu, np.int64)
        put(infos, "solver_failure", out.outcome.failure, object)
        return infos

    def render(self) -> tuple | None:
        """One frame per sub-environment (``render_mode="rgb_array"``), else None."""
        if self.render_mode is None:
            return None
        return tuple(env.render() for env in self.envs)

    def __reduce_ex__(self, protocol):
        """Refused with a clear message: an environment holds compiled models, an integrator's state and open
        resources that do not travel between processes; build one in each process instead."""
        raise TypeError(f"{type(self).__name__} cannot be pickled (copied to another process or saved): make a new one "
                        "there with gymnasium.make_vec(id, num_envs, ...) - e.g. gymnasium's AsyncVectorEnv takes functions that make the "
                        "environments, and FlexSimVectorEnv steps many episodes in one process")

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
        if name in _SHARED and any(v != values[0] for v in values[1:]):
            raise ValueError(f"set_attr({name!r}): a {type(self).__name__} steps all aircraft with one {name} (its first "
                             "sub-environment's); pass one value for all")
        for env, value in zip(self.envs, values):
            setattr(env, name, value)


def _vector_class(env_class: type[FlexSimEnv]) -> type[FlexSimVectorEnv]:
    """The batched class of a task class: ``LevelHoldEnv`` -> ``LevelHoldVectorEnv`` (its vector entry point)."""
    name = env_class.__name__.removesuffix("Env") + "VectorEnv"
    return type(name, (FlexSimVectorEnv,), {"env_class": env_class, "__module__": __name__, "__qualname__": name,
                                            "__doc__": f"``{env_class.env_id}`` batched (:class:`FlexSimVectorEnv`)."})


LevelHoldVectorEnv = _vector_class(LevelHoldEnv)
LevelHoldCaptureVectorEnv = _vector_class(LevelHoldCaptureEnv)
TurnVectorEnv = _vector_class(TurnEnv)
GustAlleviationVectorEnv = _vector_class(GustAlleviationEnv)
FlutterMarginVectorEnv = _vector_class(FlutterMarginEnv)
WingFlutterMarginVectorEnv = _vector_class(WingFlutterMarginEnv)
HaleGustAlleviationVectorEnv = _vector_class(HaleGustAlleviationEnv)
