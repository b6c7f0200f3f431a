"""The episode state of N aircraft of one task as arrays over rows: what one env and the batched env step.

A :class:`~flexsim.envs.base.FlexSimEnv` keeps its episode (state, applied controls, previous action, time,
task references and errors, wind) in one row of an :class:`EpisodeBatch`: its own batch of one, or row i of
the batch of a :class:`~flexsim.envs.vector.FlexSimVectorEnv`, whose sub-environments all read and write the
one shared batch. A step of any set of rows is then one pass of array code over those rows
(:meth:`FlexSimEnv._step_rows`): the same code, and so the same numbers, for one aircraft or for 256.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from flexsim.sim.periods import pack_period_winds, select_packed_rows

__all__ = ["EpisodeBatch", "PATH_HISTORY"]

#: Samples of the flight path kept per aircraft for rendering.
PATH_HISTORY = 500


class EpisodeBatch:
    """Episode state of N aircraft (rows) of one task on one model.

    Parameters
    ----------
    n : int
        Number of aircraft.
    n_states : int
        State dimension of the model.
    n_errors : int
        Number of task errors (the task class's ``task_errors_spec``).

    Attributes
    ----------
    x : ndarray, shape (N, n_states)
        States.
    u : ndarray, shape (N, 4)
        Controls applied over the last period [N, rad, rad, rad].
    last_action : ndarray, shape (N, 4)
        Previous normalised action (float64).
    time_s : ndarray, shape (N,)
        Simulation time [s].
    steps : ndarray of int, shape (N,)
        Steps since the reset.
    started, ended : ndarray of bool, shape (N,)
        Reset at least once; episode terminated.
    errors : ndarray, shape (N, n_errors)
        Task errors of the current state, in ``task_errors_spec`` order.
    last_reward : ndarray, shape (N,)
    reference : dict of str to ndarray (N,)
        Task targets of each row's episode (floats; :class:`~flexsim.envs.base.Episode` ``reference``).
    winds : list
        Wind field of each row's episode (None: still air).
    dynamics : list
        The :class:`~flexsim.sim.periods.FlightDynamics` each row is flown on (normally one, shared).
    states : list
        The integration state of each row's episode (:class:`~flexsim.sim.periods.IntegrationState`, immutable: each
        period returns the next).
    """

    def __init__(self, n: int, n_states: int, n_errors: int) -> None:
        self.n = int(n)
        self.x = np.zeros((n, n_states))
        self.u = np.zeros((n, 4))
        self.last_action = np.zeros((n, 4))
        self.time_s = np.zeros(n)
        self.steps = np.zeros(n, dtype=np.int64)
        self.started = np.zeros(n, dtype=np.bool_)
        self.ended = np.zeros(n, dtype=np.bool_)
        self.errors = np.zeros((n, n_errors))
        self.last_reward = np.zeros(n)
        self.reference: dict[str, np.ndarray] = {}
        self.reference_dicts: list[dict] = [{} for _ in range(n)]
        self.winds: list[Any] = [None] * n
        self.dynamics: list[Any] = [None] * n
        self.states: list[Any] = [None] * n
        self._path = np.zeros((n, PATH_HISTORY, 3))
        self._path_count = np.zeros(n, dtype=np.int64)
        self._packed: Any = None  # the winds packed for the compiled model and the rows not packed (None: to pack)

    # ------------------------------------------------------------------ episodes
    def begin(self, row: int, dynamics, state, wind, x0: np.ndarray, u: np.ndarray, action: np.ndarray, reference: dict) -> None:
        """Start the episode of ``row`` on ``dynamics`` from its integration ``state`` (``dynamics.start``): state
        ``x0``, controls ``u`` (normalised ``action``), targets, wind."""
        self.x[row] = x0
        self.u[row] = u
        self.last_action[row] = action
        self.time_s[row] = 0.0
        self.steps[row] = 0
        self.started[row] = True
        self.ended[row] = False
        self.last_reward[row] = 0.0
        self.reference_dicts[row] = dict(reference)
        for key, value in reference.items():
            if key not in self.reference:
                self.reference[key] = np.full(self.n, np.nan)
            self.reference[key][row] = float(value)
        self.winds[row] = wind
        self.dynamics[row] = dynamics
        self.states[row] = state
        self._path_count[row] = 0
        self._packed = None

    def references(self, rows: np.ndarray | slice) -> dict[str, np.ndarray]:
        """The task targets of ``rows``, name -> (m,)."""
        return {key: value[rows] for key, value in self.reference.items()}

    # ------------------------------------------------------------------ winds
    def packed_winds(self) -> tuple[Any, Any]:
        """The winds of all rows packed once per reset, with the rows whose wind the kernels cannot evaluate
        (:func:`flexsim.sim.periods.pack_period_winds`: ``packed``, ``python_winds``)."""
        if self._packed is None:
            self._packed = pack_period_winds(self.dynamics, self.winds)
        return self._packed

    def invalidate_winds(self) -> None:
        """Pack the winds again before the next use (a row's wind field was replaced)."""
        self._packed = None

    def packed_rows(self, rows: np.ndarray | slice) -> tuple[Any, Any]:
        """:meth:`packed_winds` of ``rows`` only (the ``packed`` and ``python_winds`` arguments of
        :func:`flexsim.sim.periods.advance_period`; None stays None)."""
        packed, python = self.packed_winds()
        if packed is None or (rows == slice(0, self.n) if isinstance(rows, slice) else
                              (len(rows) == self.n and np.array_equal(rows, np.arange(self.n)))):
            return packed, python
        index = rows if isinstance(rows, slice) else np.asarray(rows, dtype=np.int64)
        return select_packed_rows(packed, index), None if python is None else python[index]

    # ------------------------------------------------------------------ flight path
    def record_path(self, rows: np.ndarray | slice, positions: np.ndarray) -> None:
        """Append one position (m, 3) [m] NED to the path of each of ``rows`` (indices or a slice)."""
        if isinstance(rows, slice):
            rows = np.arange(self.n)[rows]
        self._path[rows, self._path_count[rows] % PATH_HISTORY] = positions
        self._path_count[rows] += 1

    def path(self, row: int) -> np.ndarray:
        """The last (at most :data:`PATH_HISTORY`) positions of ``row``, oldest first, shape (k, 3) [m]."""
        k = int(self._path_count[row])
        if k <= PATH_HISTORY:
            return self._path[row, :k].copy()
        return np.roll(self._path[row], -(k % PATH_HISTORY), axis=0)
