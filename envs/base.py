"""The common gymnasium adapter of the flexsim tasks: spaces, action mapping, stepping, termination.

The physics and its integration over control periods live in flexsim (:mod:`flexsim.sim.periods`); a task
subclass only says how an episode starts (trim, perturbation, wind), which errors it tracks and how they are
rewarded (:class:`~flexsim.envs.config.TrackingReward`).
"""

from __future__ import annotations

import inspect
import math
import multiprocessing
import textwrap
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from flexsim.aircraft.definition import Aircraft
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.io.env_log import LogSample, flight_sample
from flexsim.io.viewer import ViewerUnavailableError, viewer_unavailable_reason
from flexsim.io.vocabulary import suffix_unit
from flexsim.model.aircraft_model import CONTROL_NAMES, AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.model.terms import Terms
from flexsim.sim.measurements import MeasurementBatch, Measurements
from flexsim.threads import limit_blas_threads
from flexsim.sim.periods import SENSOR_COMPONENTS, BatchOutcome, FlightDynamics, advance_period
from flexsim.trimming import SteadyManoeuvre

from flexsim.envs.config import (AERO_MODELS, DEFAULT_MAX_STEP_S, TURBULENCE_LEVELS, ActuatorRates, FlightLimits, InitialPerturbation,
                         IntegratorSettings, TrackingReward)
from flexsim.envs import row_kernels as _rk
from flexsim.envs.aircraft_defaults import limits_for_aircraft, task_for_aircraft
from flexsim.envs.batch import EpisodeBatch

__all__ = ["FlexSimEnv", "Episode", "RowsStep", "TERMINATION_CODES", "LogSample", "TERMINATION_REASONS",
           "ACTION_SPACE_DOC", "shared_docs"]

#: dtypes of the actions checked on the fast path of :meth:`FlexSimEnv._check_action` (others: the general path).
_FLOAT_ACTIONS = (np.dtype(np.float32), np.dtype(np.float64))
#: Values of ``info["termination_reason"]`` ("" while flying).
TERMINATION_REASONS = ("non_finite", "crash", "structural_limit", "gimbal_lock", "envelope")
#: What each termination reason tests, with the :class:`FlightLimits` fields (the docstrings' Episode End).
_REASON_DOCS = dict(zip(TERMINATION_REASONS, (
    "non-finite state or solver failure, e.g. a flutter blow-up", "altitude <= 0",
    "|wing tip deflection| > {wing_tip_deflection_m:g}\xa0m or |fin tip twist| > {fin_tip_twist_rad:g}\xa0rad",
    "|theta| >= {pitch_deg:g}\xa0deg",
    "Mach >= {max_mach:g}, |alpha| >= {alpha_deg:g}\xa0deg or airspeed <= {min_airspeed_m_s:g}\xa0m/s")))
#: ``info["termination_reason"]`` of each termination code (:func:`flexsim.envs.row_kernels.termination_rows`; 0: flying).
TERMINATION_CODES = ("", *TERMINATION_REASONS)


#: Action Space section shared by every FlexSim env docstring (gymnasium's template), see :func:`shared_docs`.
ACTION_SPACE_DOC = """    ``Box(low=[0, -1, -1, -1], high=[1, 1, 1, 1], dtype=float32)``, normalised; mapped linearly to the
    aircraft's limits (``Aircraft.control_limits()``; GTM values shown). Out-of-range values are clipped
    (``info["action_clipped"]``); NaN/inf or a wrong shape raise ``ValueError``. The applied controls
    then move towards the command at most at the actuator rates (``ActuatorRates``).

    | Num | Action   | Min | Max | Physical range (GTM)        | Rate limit      |
    |-----|----------|-----|-----|-----------------------------|-----------------|
    | 0   | thrust   | 0   | 1   | 0 to 356 kN (two engines)   | 25 % max / s    |
    | 1   | aileron  | -1  | 1   | -25 to 25 deg (TE down > 0) | 60 deg/s        |
    | 2   | elevator | -1  | 1   | -25 to 25 deg (TE down > 0) | 40 deg/s        |
    | 3   | rudder   | -1  | 1   | -25 to 25 deg (TE left > 0) | 60 deg/s        |
"""

#: The v0 entry of the Version History of the tasks whose default integrator moved from Radau to ETD2RK.
V0_HISTORY_DOC = """\
    * v0: initial version; default integrator ETD2RK instead of Radau for the finite-state model (the same
      trajectories to within the integration error, about 7 times faster), steps of 20 ms for LevelHold and
      Turn and 10 ms for GustAlleviation (``default_max_step_s``; accuracy in docs/environments.md); the
      quasi-steady model integrated with ETD2RK by default too, as ``simulate`` does (DOP853 before:
      ``IntegratorSettings(method="DOP853")``).
"""


def _unit(name: str) -> str:
    """The unit of an observation entry or task error from the SI suffix of its name ("-": none)."""
    return suffix_unit(name, "-")


def _bound(value: float) -> str:
    """An observation bound as the docstring table writes it (pi and pi/2 by name)."""
    text = {math.pi: "pi", math.pi / 2: "pi/2"}.get(abs(value), f"{abs(value):g}")
    return f"-{text}" if value < 0 else text


def _scale(name: str, value: float) -> str:
    """A reward scale with the unit of its error (whole degrees in deg)."""
    unit, deg = _unit(name), math.degrees(value)
    if unit == "rad" and abs(deg - round(deg)) < 1e-9:
        return f"{round(deg)}\xa0deg"
    return f"{value:g}" if unit == "-" else f"{value:g}\xa0{unit}"


def _paragraph(text: str) -> str:
    """``text`` wrapped to the docstrings' width and indented, not at a no-break space (then written as a space)."""
    lines = textwrap.fill(text, 116, initial_indent="    ", subsequent_indent="    ", break_on_hyphens=False)
    return lines.replace("\xa0", " ")


def _observation_doc(cls) -> str:
    """The Observation Space section: the Box, then a table row per entry (:meth:`FlexSimEnv._observation_entries`)."""
    rows = [("Num", "Name", "Min", "Max", "Unit", "Observation"), *(
        (str(i), f"``{name}``", _bound(lo), _bound(hi), _unit(name), what)
        for i, (_, name, lo, hi, what) in enumerate(cls._observation_entries()))]
    widths = [max(len(r[j]) for r in rows) for j in range(6)]
    lines = ["    | " + " | ".join(c.ljust(w) for c, w in zip(r, widths)) + " |" for r in rows]
    lines.insert(1, "    |" + "|".join("-" * (w + 2) for w in widths) + "|")
    return "\n".join([_paragraph(
        f"``Box({len(rows) - 1},)`` float32 with finite bounds; values are clipped to them (and NaN replaced by 0), so "
        "observations stay finite even at termination. ``env.observation_structure`` maps block names to slices, "
        "``env.observation_names`` names every entry."), "", *lines])


def _reward_doc(cls) -> str:
    """The Rewards section, from the default task's :class:`TrackingReward`."""
    r = (cls.default_task or cls.task_type()).reward
    parts = [f"``alive`` +{r.alive:g}",
             *(f"``{t.error}`` -{t.weight:g} min((e\xa0/\xa0{_scale(t.error, t.scale)})^2,\xa01)" for t in r.terms),
             f"``control_rate`` -{r.control_rate_weight:g} min(mean((da\xa0/\xa0{r.control_rate_scale:g})^2),\xa01) "
             "with da the change of the normalised action",
             f"``termination`` -{r.termination_penalty:g} on a terminating step"]
    low = r.alive - sum(t.weight for t in r.terms) - r.control_rate_weight - r.termination_penalty
    return _paragraph('Per step (``TrackingReward``; the parts are in ``info["reward_parts"]`` and sum exactly to the '
                      f"reward): {'; '.join(parts)}. Per-step reward in [{round(low, 9):g}, {r.alive:g}].")


def _termination_doc(cls) -> str:
    """The Termination part of Episode End: the common terminations with the :class:`FlightLimits` defaults."""
    lim = FlightLimits()
    values = {**{f.name: getattr(lim, f.name) for f in fields(lim)}, "pitch_deg": math.degrees(lim.max_abs_pitch_rad),
              "alpha_deg": math.degrees(lim.max_abs_alpha_rad)}
    reasons = ", ".join(f'``"{k}"`` ({v.format(**values)})' for k, v in _REASON_DOCS.items())
    return "    ### Termination\n" + _paragraph(f'``info["termination_reason"]``: {reasons}. Bounds: ``FlightLimits``.')


def _truncation_doc(cls) -> str:
    """The Truncation part of Episode End: the time limit of the id."""
    steps = cls.max_episode_steps
    return f"    ### Truncation\n    ``TimeLimit`` at ``max_episode_steps`` = {steps} ({steps / 50:g} s at 50 Hz)."


def _arguments_doc(cls) -> str:
    """The Arguments section: the ``gymnasium.make`` call with this task's defaults, and the choices."""
    defaults = {}
    for klass in reversed(cls.__mro__[:cls.__mro__.index(FlexSimEnv) + 1]):
        defaults.update((k, p.default) for k, p in inspect.signature(klass.__init__).parameters.items())
    return _paragraph(
        f'``gymnasium.make("{cls.env_id}", aircraft="{defaults["aircraft"]}", aero="{defaults["aero"]}", '
        f'control_rate_hz={defaults["control_rate_hz"]}, turbulence="{cls.default_turbulence}", render_mode=None, '
        f"task={cls.task_type.__name__}(), integrator=IntegratorSettings(max_step_s={cls.default_max_step_s:g}), "
        "actuator_rates=ActuatorRates(), limits=FlightLimits(), perturbation=InitialPerturbation())``. ``turbulence`` "
        f"is one of {', '.join(map(repr, TURBULENCE_LEVELS))}; ``aero`` one of {', '.join(map(repr, AERO_MODELS))}; "
        "``control_rate_hz`` 5 to 1000 Hz; ``render_mode`` 'rgb_array' (matplotlib image) or 'human' (Rerun viewer, "
        "spawned on the first frame). With another ``aircraft`` than the bundled GTM and ``task``/``limits`` None, the task "
        "flies that aircraft's cruise point and the limits come from its envelope and trim (flexsim.envs.aircraft_defaults).")


#: The generated parts of the env docstrings (:func:`shared_docs`): marker -> the section text of a class.
_DOC_PARTS = {"<action space>": lambda cls: ACTION_SPACE_DOC.rstrip("\n"), "<observation>": _observation_doc,
              "<rewards>": _reward_doc, "<termination>": _termination_doc, "<truncation>": _truncation_doc,
              "<arguments>": _arguments_doc, "<v0 history>": lambda cls: V0_HISTORY_DOC.rstrip("\n")}


def shared_docs(cls):
    """Class decorator: fill the generated lines of ``cls.__doc__`` (gymnasium's template) from the objects that define
    them: ``<observation>`` the table of the class's observation entries, ``<rewards>`` its default reward,
    ``<termination>`` the termination reasons with the ``FlightLimits`` defaults, ``<truncation>`` its time limit,
    ``<arguments>`` the ``gymnasium.make`` call with its defaults; ``<action space>`` and ``<v0 history>`` the shared
    texts. ``<action space>`` and ``<observation>`` are required."""
    doc = cls.__doc__ or ""
    for marker in ("<action space>", "<observation>"):
        if f"    {marker}\n" not in doc:
            raise RuntimeError(f"{cls.__name__} docstring lacks the {marker} line")
    for marker, part in _DOC_PARTS.items():
        doc = doc.replace(f"    {marker}\n", part(cls) + "\n")
    cls.__doc__ = doc
    return cls


@dataclass(frozen=True)
class Episode:
    """How an episode starts (returned by a task's :meth:`FlexSimEnv._new_episode`).

    Attributes
    ----------
    manoeuvre : SteadyManoeuvre
        The trim the aircraft starts from (and whose Jacobian ETD2RK and Radau use).
    x0 : ndarray
        Initial state (the trim state plus perturbations).
    wind : callable or None
        Wind field of the episode, ``wind(t, positions_ned_m)``.
    reference : dict of str to float
        Targets of the task (reported in the reset info).
    """

    manoeuvre: SteadyManoeuvre
    x0: np.ndarray
    wind: Any
    reference: dict


@dataclass(frozen=True)
class RowsStep:
    """One control period of m aircraft (:meth:`FlexSimEnv._step_rows`), arrays over the rows.

    Attributes
    ----------
    obs : ndarray, shape (m, n_obs), float32
    reward : ndarray, shape (m,)
    terminated : ndarray of bool, shape (m,)
    codes : ndarray of int, shape (m,)
        Index into :data:`TERMINATION_CODES`.
    parts : dict of str to ndarray (m,)
        Reward parts (``TrackingReward.part_names``).
    errors : dict of str to ndarray (m,)
        Task errors.
    outcome : BatchOutcome
        The integration of the period.
    clipped : ndarray of bool, shape (m,)
        The action was out of range and clipped.
    """

    obs: np.ndarray
    reward: np.ndarray
    terminated: np.ndarray
    codes: np.ndarray
    parts: dict
    errors: dict
    outcome: BatchOutcome
    clipped: np.ndarray


#: The keys ``reset(options=...)`` of a single environment understands: none (the episode's start is the task's).
RESET_OPTIONS: tuple[str, ...] = ()


def check_reset_options(options: Any, allowed: tuple[str, ...]) -> None:
    """``reset(options=...)``: None or a dict whose keys are in ``allowed``; anything else is refused (ValueError
    naming the key and the allowed ones), never ignored."""
    if options is None:
        return
    if not isinstance(options, dict):
        raise ValueError(f"options = {options!r}: must be None or a dict (got {type(options).__name__})")
    unknown = [k for k in options if k not in allowed]
    if unknown:
        raise ValueError(f"options[{unknown[0]!r}]: not an option of reset(); allowed: "
                         f"{', '.join(map(repr, allowed)) if allowed else 'none (give options=None)'}")


class FlexSimEnv(gym.Env[np.ndarray, np.ndarray]):
    """Base class of the flexsim tasks (not registered itself; see the task classes for the docs).

    Parameters
    ----------
    aircraft : str, Path or Aircraft
        Bundled aircraft name (``"gtm"``), a TOML file, or a loaded :class:`Aircraft`.
    aero : {"unsteady", "quasi-steady"}
    control_rate_hz : float
        Control (and observation) rate [Hz], 5 to 1000 (default 50).
    turbulence : {"none", "light", "moderate", "severe"} or None
        Dryden turbulence level (MIL-F-8785C); None takes the task's default.
    render_mode : {"human", "rgb_array"} or None
    task : frozen dataclass, optional
        The task parameters (the task class's ``task_type``; default its defaults).
    integrator : IntegratorSettings, optional
    actuator_rates : ActuatorRates, optional
    limits : FlightLimits, optional
    perturbation : InitialPerturbation, optional
    dynamics : FlightDynamics, optional
        Run on this :class:`FlightDynamics` (another env's, built from the same aircraft, aero, integrator, actuator
        rates and control rate; checked) instead of building one: how :class:`flexsim.envs.vector.FlexSimVectorEnv`
        shares one model between its sub-environments (each episode's integration state is its own value,
        :class:`~flexsim.sim.periods.IntegrationState`).
    terms : Terms, optional
        The physical terms of the model flown (:class:`flexsim.model.terms.Terms`; default every term on). Its
        aerodynamic model must be ``aero`` (the one name of it; default "unsteady").
    """

    metadata: ClassVar[dict] = {"render_modes": ["human", "rgb_array"], "render_fps": 50}
    task_type: ClassVar[type]
    default_turbulence: ClassVar[str] = "none"
    #: ETD2RK step [s] of the task's default integrator (``IntegratorSettings(max_step_s=...)`` when ``integrator``
    #: is None): :data:`~flexsim.envs.config.DEFAULT_MAX_STEP_S`, finer for the tasks whose subject is the structure.
    default_max_step_s: ClassVar[float] = DEFAULT_MAX_STEP_S
    #: (name, bound, meaning) of the task errors in the observation, in order; set by each task class.
    task_errors_spec: ClassVar[tuple[tuple[str, float, str], ...]] = ()
    #: The registered id and its ``max_episode_steps`` (50 steps = 1 s at the default 50 Hz); set by each task class.
    env_id: ClassVar[str]
    max_episode_steps: ClassVar[int]
    #: Defaults of ``task`` (None: ``task_type()``) and ``perturbation`` when the argument is None.
    default_task: ClassVar[Any] = None
    default_perturbation: ClassVar[InitialPerturbation] = InitialPerturbation()

    def __init__(self, *, aircraft: str | Path | Aircraft = "gtm", aero: str = "unsteady", control_rate_hz: float = 50.0,
                 turbulence: str | None = None, render_mode: str | None = None, task: Any = None,
                 integrator: IntegratorSettings | None = None, actuator_rates: ActuatorRates | None = None,
                 limits: FlightLimits | None = None, perturbation: InitialPerturbation | None = None,
                 dynamics: FlightDynamics | None = None, terms: Terms | None = None) -> None:
        #: OpenBLAS thread counts set when built in a worker process (vector envs), else None.
        self.worker_blas_threads = limit_blas_threads(1) if multiprocessing.parent_process() is not None else None
        if aero not in AERO_MODELS:
            raise ValueError(f"aero = {aero!r}: must be one of {', '.join(AERO_MODELS)}")
        terms = Terms(aero=AeroOptions(aero)) if terms is None else terms
        if not isinstance(terms, Terms) or terms.aero is None or terms.aero.model != aero:
            raise ValueError(f"terms = {terms!r}: must be a flexsim.model.terms.Terms whose aero model is aero = {aero!r}")
        try:
            rate = float(control_rate_hz)
        except (TypeError, ValueError):
            rate = math.nan
        if not 5.0 <= rate <= 1000.0:
            raise ValueError(f"control_rate_hz = {control_rate_hz!r}: must be a number in [5, 1000] Hz")
        turbulence = self.default_turbulence if turbulence is None else turbulence
        if turbulence not in TURBULENCE_LEVELS:
            raise ValueError(f"turbulence = {turbulence!r}: must be one of {', '.join(TURBULENCE_LEVELS)}")
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode = {render_mode!r}: must be None or one of {', '.join(self.metadata['render_modes'])}")
        no_viewer = viewer_unavailable_reason()
        if render_mode == "human" and no_viewer is not None:
            raise ViewerUnavailableError(f"render_mode = 'human': cannot open a Rerun viewer: {no_viewer}; use "
                                         "render_mode='rgb_array' here, or record episodes with FlightLogRecorder and "
                                         "save them with `flexsim view LOG --save run.rrd`")
        derive = task is None  # the task's defaults are the GTM's: another aircraft's are derived (envs/aircraft_defaults.py)
        task = (self.default_task or self.task_type()) if task is None else task
        if not isinstance(task, self.task_type):
            raise ValueError(f"task = {task!r}: must be a {self.task_type.__name__}")
        for name, value, kind in (("integrator", integrator, IntegratorSettings), ("actuator_rates", actuator_rates, ActuatorRates),
                                  ("limits", limits, FlightLimits), ("perturbation", perturbation, InitialPerturbation)):
            if value is not None and not isinstance(value, kind):
                raise ValueError(f"{name} = {value!r}: must be a {kind.__name__} or None")
        self.aircraft = aircraft if isinstance(aircraft, Aircraft) else load_aircraft(aircraft)
        self.aircraft_source = self.aircraft.source
        task = task_for_aircraft(task, self.aircraft) if derive else task
        self.task = task
        self.turbulence = turbulence
        self.control_rate_hz = rate
        self.dt = 1.0 / rate
        self.limits = limits or FlightLimits()
        self.perturbation = perturbation or self.default_perturbation
        self.render_mode = render_mode
        # The modes this instance offers: without a display "human" cannot work, so gymnasium's check_env (which
        # makes every listed mode) checks "rgb_array" only there; the class metadata lists both.
        modes = [m for m in type(self).metadata["render_modes"] if m != "human" or no_viewer is None]
        self.metadata = {**type(self).metadata, "render_modes": modes, "render_fps": rate}
        integrator = integrator or IntegratorSettings(max_step_s=self.default_max_step_s)
        actuator_rates = actuator_rates or ActuatorRates()
        if dynamics is None:
            dynamics = FlightDynamics(AircraftModel(self.aircraft, terms=terms), integrator, actuator_rates, self.dt)
        elif not isinstance(dynamics, FlightDynamics):
            raise ValueError(f"dynamics = {dynamics!r}: must be a FlightDynamics or None")
        else:
            mine = (self.aircraft.content_key(), aero, terms, integrator, actuator_rates, self.dt)
            theirs = (dynamics.aircraft.content_key(), dynamics.aero, dynamics.model.terms, dynamics.integrator_settings,
                      dynamics.actuator_rates, dynamics.dt)
            for name, a, b in zip(("aircraft", "aero", "terms", "integrator", "actuator_rates", "control period dt"), mine, theirs):
                if a != b:
                    raise ValueError(f"dynamics: was built with {name} = {b!r}, this env has {name} = {a!r}; pass a FlightDynamics "
                                     "built with the same settings, or None")
        self.dynamics = dynamics
        if limits is None:
            self.limits = limits_for_aircraft(self.aircraft, dynamics, task)
        self.reward_definition: TrackingReward = task.reward
        lo, hi = self.dynamics.u_low, self.dynamics.u_high
        self._u_scale = hi.copy()  # 0 for a surface the aircraft does not have: its action has no effect
        self.action_space = spaces.Box(np.array([0.0, -1.0, -1.0, -1.0], np.float32), np.ones(4, np.float32), dtype=np.float32)
        self.observation_structure, low, high, self.observation_names = self._observation_layout()
        self.observation_space = spaces.Box(low, high, dtype=np.float32)
        self._obs_low, self._obs_high = low.astype(np.float64), high.astype(np.float64)
        #: The episode state (:class:`EpisodeBatch`) this env's episode lives in, at row ``self._row``: its own
        #: batch of one, or the shared batch of a FlexSimVectorEnv (:meth:`_attach`).
        self._batch = EpisodeBatch(1, self.dynamics.layout.n_states, len(self.task_errors_spec))
        self._row = 0
        self._linear_range_said = False  # the linear structure's range exceeded at a reset: said once (reset)
        self._error_names = tuple(spec[0] for spec in self.task_errors_spec)
        self._renderer = None
        self._constants: tuple | None = None  # the arguments of the compiled outputs from limits and reward (_kernel_constants)
        self._act_low, self._act_high = self.action_space.low.astype(np.float64), self.action_space.high.astype(np.float64)
        self._act_low_list, self._act_high_list = self._act_low.tolist(), self._act_high.tolist()
        self._zeros: dict[int, np.ndarray] = {}
        self._observe_data = _rk.ObserveData(self._u_scale, self._act_low, self._act_high, len(SENSOR_COMPONENTS), self._obs_low,
                                             self._obs_high)

    # ------------------------------------------------------------------ task hooks
    def _new_episode(self, rng: np.random.Generator) -> Episode:
        """The start of an episode, drawn from ``rng`` (implemented by each task class)."""
        raise NotImplementedError(f"{type(self).__name__} must implement _new_episode")

    def _task_errors(self, meas: MeasurementBatch, ref: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Task errors of m aircraft, name -> (m,), in the order of ``task_errors_spec``, from their measurements and
        targets (``ref``: name -> (m,), the episodes' ``reference``); array code (implemented by each task class)."""
        raise NotImplementedError(f"{type(self).__name__} must implement _task_errors")

    # ------------------------------------------------------------------ spaces
    #: Observation entries before and after the task errors: (block, name, low, high, meaning).
    _OBSERVATION_HEAD = (
        ("attitude", "roll_rad", -math.pi, math.pi, "roll phi"),
        ("attitude", "pitch_rad", -math.pi / 2, math.pi / 2, "pitch theta"),
        ("attitude", "heading_rad", -math.pi, math.pi, "heading psi (wrapped)"),
        *(("body_rates", f"{n}_rate_rad_s", -10.0, 10.0, f"body rate {s}")
          for n, s in zip(("roll", "pitch", "yaw"), "pqr")),
        ("air_data", "airspeed_m_s", 0.0, 600.0, "airspeed (relative to the air at the body origin)"),
        ("air_data", "alpha_rad", -math.pi, math.pi, "angle of attack alpha"),
        ("air_data", "beta_rad", -math.pi / 2, math.pi / 2, "sideslip beta"),
        ("altitude", "altitude_m", -1000.0, 25000.0, "altitude"))
    _OBSERVATION_TAIL = (
        *(item for c in SENSOR_COMPONENTS for item in (
            ("structure", f"tip_deflection_{c}_m", -50.0, 50.0, f"{c} tip deflection"),
            ("structure", f"tip_deflection_rate_{c}_m_s", -500.0, 500.0, f"{c} tip deflection rate"),
            ("structure", f"tip_twist_{c}_rad", -math.pi, math.pi, f"{c} tip twist"),
            ("structure", f"tip_twist_rate_{c}_rad_s", -1000.0, 1000.0, f"{c} tip twist rate"))),
        *(("controls", f"{n}_fraction", lo, 1.0, f"applied {n}, normalised like the action")
          for n, lo in zip(CONTROL_NAMES, (0.0, -1.0, -1.0, -1.0))))

    @classmethod
    def _observation_entries(cls) -> tuple[tuple[str, str, float, float, str], ...]:
        """(block, name, low, high, meaning) of each observation entry in order: the common head, the task errors
        (``task_errors_spec``, bounds +-bound), the structure and the applied controls."""
        errors = tuple(("task_errors", name, -bound, bound, what) for name, bound, what in cls.task_errors_spec)
        return cls._OBSERVATION_HEAD + errors + cls._OBSERVATION_TAIL

    @classmethod
    def _observation_layout(cls) -> tuple[dict[str, slice], np.ndarray, np.ndarray, tuple[str, ...]]:
        """(block -> slice, low, high, names) of the observation (:meth:`_observation_entries`)."""
        entries = cls._observation_entries()
        blocks = [e[0] for e in entries]
        structure = {b: slice(blocks.index(b), len(blocks) - blocks[::-1].index(b)) for b in dict.fromkeys(blocks)}
        return (structure, np.array([e[2] for e in entries], np.float32), np.array([e[3] for e in entries], np.float32),
                tuple(e[1] for e in entries))

    # ------------------------------------------------------------------ action mapping
    def action_to_controls(self, action: np.ndarray) -> np.ndarray:
        """Physical controls [N, rad, rad, rad] of a normalised action (thrust fraction, surface fractions)."""
        return np.asarray(action, float) * self._u_scale

    def controls_to_action(self, u: np.ndarray) -> np.ndarray:
        """Normalised action (float32) of physical controls [N, rad, rad, rad] (inverse of :meth:`action_to_controls`)."""
        scale = self._u_scale
        u = np.asarray(u, float)
        a = np.divide(u, scale, out=np.zeros_like(u), where=scale > 0)
        return np.clip(a, self.action_space.low, self.action_space.high).astype(np.float32)

    def _check_action(self, action: Any) -> tuple[np.ndarray, bool]:
        if type(action) is np.ndarray and action.shape == (4,) and action.dtype in _FLOAT_ACTIONS:
            # the usual action (a float array from the agent): checked and clipped on 4 Python floats, the values
            # of np.minimum(np.maximum(a, low), high) (numpy returns the second argument on ties, so here too)
            values = action.tolist()
            if all(map(math.isfinite, values)):
                clipped = [lo if v <= lo else (hi if v >= hi else v) for v, lo, hi in zip(values, self._act_low_list,
                                                                                      self._act_high_list)]
                return np.array(clipped), clipped != values
        what = "must be 4 real numbers [thrust, aileron, elevator, rudder]"
        # Only real numbers: numeric strings, booleans and complex values would otherwise be converted silently by
        # numpy (a string '0.5' parsed, True read as 1, an imaginary part dropped): the items of anything but a
        # numeric array are checked one by one, a numeric array by its dtype.
        try:
            raw = np.asarray(action)
            numeric = isinstance(action, np.ndarray) and raw.dtype.kind != "O"
            items = () if numeric else np.asarray(action, dtype=object).ravel()
        except (TypeError, ValueError):
            raise ValueError(f"action = {action!r}: {what}") from None
        bad = [v for v in items if isinstance(v, (bool, np.bool_, str, bytes, complex, np.complexfloating))
               or not isinstance(v, (int, float, np.integer, np.floating))]
        if bad:
            raise ValueError(f"action = {action!r}: {what}, got {type(bad[0]).__name__} {bad[0]!r}")
        if raw.dtype.kind not in "iufO":
            kind = {"b": "booleans", "c": "complex numbers", "U": "strings", "S": "bytes"}.get(raw.dtype.kind, f"dtype {raw.dtype}")
            raise ValueError(f"action = {action!r}: {what}, got {kind}")
        a = np.asarray(raw, dtype=np.float64)
        if a.shape != (4,):
            raise ValueError(f"action: expected shape (4,) [thrust, aileron, elevator, rudder], got shape {a.shape}")
        if not np.isfinite(a).all():
            names = ", ".join(f"action[{i}] ({CONTROL_NAMES[i]}) = {a[i]}" for i in np.flatnonzero(~np.isfinite(a)))
            raise ValueError(f"action: values must be finite, got {names}")
        clipped = np.minimum(np.maximum(a, self._act_low), self._act_high)
        return clipped, bool((clipped != a).any())

    # ------------------------------------------------------------------ gymnasium API
    def _attach(self, batch: EpisodeBatch, row: int) -> None:
        """Keep this env's episode in row ``row`` of ``batch`` (a FlexSimVectorEnv's shared batch)."""
        self._batch, self._row = batch, int(row)

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple[np.ndarray, dict]:
        check_reset_options(options, RESET_OPTIONS)
        super().reset(seed=seed)
        episode = self._new_episode(self.np_random)
        point = self.dynamics.trim(episode.manoeuvre)
        state = self.dynamics.start(episode.manoeuvre)
        b, i = self._batch, self._row
        trim_action = self.controls_to_action(point.u)
        b.begin(i, self.dynamics, state, episode.wind, np.asarray(episode.x0, dtype=float), point.u, trim_action.astype(np.float64),
                episode.reference)
        rows = np.array([i])
        meas = self.dynamics.measure_batch(b.x[rows], b.time_s[rows], [episode.wind])
        b.errors[i] = self._error_matrix(self._task_errors(meas, b.references(rows)))[0]
        if self.render_mode is not None:  # the flight path is drawn by render() only
            b.record_path(rows, meas.position_ned_m)
        obs = self._observe_rows(meas, b.errors[rows], b.u[rows])[0]
        info = {"time_s": 0.0, "trim_action": trim_action, "reference": dict(episode.reference)}
        if point.linear_range is not None:  # the trim bends a beam beyond the linear structure's range: one line, once
            info["linear_range"] = point.linear_range
            if not self._linear_range_said:
                self._linear_range_said = True
                gym.logger.warn("%s: %s", self.spec.id if self.spec else type(self).__name__, point.linear_range)
        if self.render_mode == "human":
            self.render()
        return obs, info

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict]:
        if not self._batch.started[self._row]:  # as _check_steppable, on the row's scalars (4 us less per step)
            raise RuntimeError("step() called before reset()")
        if self._batch.ended[self._row]:
            raise RuntimeError("step() called after the episode terminated; call reset()")
        a, clipped = self._check_action(action)
        out = self._step_rows(self._batch, slice(self._row, self._row + 1), a[None, :], np.array([clipped]))
        info = self._step_info(out, 0)
        if self.render_mode == "human":
            self.render()
        return out.obs[0], float(out.reward[0]), bool(out.terminated[0]), False, info

    @staticmethod
    def _step_info(out: RowsStep, r: int) -> dict:
        """The info dict of row r of a step (what :meth:`step` returns)."""
        return {"time_s": float(out.outcome.time_s[r]), "reward_parts": {k: float(v[r]) for k, v in out.parts.items()},
                "termination_reason": TERMINATION_CODES[out.codes[r]], "action_clipped": bool(out.clipped[r]),
                "task_errors": {k: float(v[r]) for k, v in out.errors.items()}, "nfev": int(out.outcome.nfev[r]),
                "nlu": int(out.outcome.nlu[r]), "solver_failure": str(out.outcome.failure[r])}

    @staticmethod
    def _check_steppable(batch: EpisodeBatch, rows) -> None:
        if not batch.started[rows].all():
            raise RuntimeError("step() called before reset()")
        if batch.ended[rows].any():
            raise RuntimeError("step() called after the episode terminated; call reset()")

    def _step_rows(self, b: EpisodeBatch, rows: np.ndarray | slice, a: np.ndarray, clipped: np.ndarray) -> RowsStep:
        """One control period of the aircraft ``rows`` (sorted indices, or a slice) of ``b`` with the checked, clipped
        actions ``a`` (m, 4): actuator rate limits, the integration and measurements (one
        :func:`flexsim.sim.periods.advance_period` call), the task errors, then termination, reward parts and
        observation (one :func:`flexsim.envs.row_kernels.finish_rows` call), all over the rows (the single env is this
        with one row)."""
        if not isinstance(rows, slice) and len(rows) == b.n:  # all rows, in order (rows are sorted and unique)
            rows = slice(0, b.n)
        steps = b.steps[rows]
        if isinstance(rows, slice):
            winds, dynamics, states = b.winds[rows], b.dynamics[rows], b.states[rows]
        else:
            winds, dynamics, states = [b.winds[i] for i in rows], [b.dynamics[i] for i in rows], [b.states[i] for i in rows]
        outcome, u, meas = advance_period(dynamics, states, b.x[rows], b.u[rows], a * self._u_scale, steps, winds,
                                          *b.packed_rows(rows))
        if not self.dynamics.substeps:  # DOP853, Radau: the next period's warm-start step (ETD2RK's states do not change)
            for i, state in zip(range(b.n)[rows] if isinstance(rows, slice) else rows, outcome.states):
                b.states[i] = state
        b.x[rows], b.u[rows], b.time_s[rows] = outcome.x, u, outcome.time_s
        b.steps[rows] = steps + 1
        errors = self._task_errors(meas, b.references(rows))
        error_matrix = self._error_matrix(errors)
        b.errors[rows] = error_matrix
        _, _, end_data, part_names = self._kernel_constants()
        m = len(steps)
        task_codes = self._task_termination(meas)
        out = _rk.FinishOut(np.empty(m, np.int64), np.empty((m, len(part_names))), np.empty(m),
                            np.empty((m, self._obs_low.shape[0]), np.float32))
        end = _rk.RowsEnd(meas.matrix, outcome.failed, outcome.crashed, self._no_task_codes(m) if task_codes is None else task_codes,
                          error_matrix, a - b.last_action[rows], u)
        _rk.finish_rows(*_rk.finish_args(end, end_data, self._observe_data, out))
        codes, parts, reward, obs = out
        terminated = codes > 0
        b.ended[rows] = terminated
        b.last_action[rows] = a
        b.last_reward[rows] = reward
        if self.render_mode is not None:
            b.record_path(rows, meas.position_ned_m)
        return RowsStep(obs, reward, terminated, codes, dict(zip(part_names, parts.T)), errors, outcome, clipped)

    def _kernel_constants(self) -> tuple:
        """(limits, reward, end data, part names): the arguments of :mod:`flexsim.envs.row_kernels` that come from
        ``self.limits`` and ``self.reward_definition`` (:class:`flexsim.envs.row_kernels.EndData`: limit data,
        reward-term error columns, reward data), built again when either attribute is replaced."""
        lim, reward, c = self.limits, self.reward_definition, self._constants
        if c is None or c[0] is not lim or c[1] is not reward:
            missing = [t.error for t in reward.terms if t.error not in self._error_names]
            if missing:
                raise ValueError(f"task.reward: terms {missing} name no task error of {type(self).__name__} (one of "
                                 f"{', '.join(self._error_names)})")
            limit_data = np.array([lim.wing_tip_deflection_m, lim.fin_tip_twist_rad, lim.max_abs_pitch_rad, lim.max_mach,
                                   lim.max_abs_alpha_rad, lim.min_airspeed_m_s])
            terms = np.array([self._error_names.index(t.error) for t in reward.terms], dtype=np.int64)
            c = self._constants = (lim, reward, _rk.EndData(limit_data, terms, reward.kernel_data), reward.part_names)
        return c

    def _error_matrix(self, errors: dict[str, np.ndarray]) -> np.ndarray:
        """The task errors as a matrix (m, n_errors) in ``task_errors_spec`` order."""
        names = tuple(errors)
        if names != self._error_names:
            raise RuntimeError(f"{type(self).__name__}._task_errors returned {names}, expected {self._error_names} (task_errors_spec)")
        values = list(errors.values())
        out = np.empty((len(values[0]) if values else 0, len(values)))
        for j, v in enumerate(values):
            out[:, j] = v
        return out

    def _task_termination(self, meas: MeasurementBatch) -> np.ndarray | None:
        """The task's own termination codes (m,) int of m aircraft (index into :data:`TERMINATION_CODES`, 0: none),
        applied where the common ones (:func:`flexsim.envs.row_kernels.termination_rows`: non-finite state or solver
        failure, crash, structural limit, gimbal lock, envelope) do not end the episode; None: none (default)."""
        return None

    def _no_task_codes(self, m: int) -> np.ndarray:
        """Zeros (m,) int: no task termination (shared per m, read by the kernel only)."""
        zeros = self._zeros.get(m)
        if zeros is None:
            zeros = self._zeros[m] = np.zeros(m, np.int64)
        return zeros

    def _observe_rows(self, meas: MeasurementBatch, errors: np.ndarray, u: np.ndarray) -> np.ndarray:
        """Observations (m, n_obs) float32 of m aircraft (measurements, task errors (m, k), applied controls (m, 4))."""
        obs = np.empty((len(errors), self._obs_low.shape[0]), np.float32)
        _rk.observe_rows(meas.matrix, np.ascontiguousarray(errors, dtype=float), np.ascontiguousarray(u, dtype=float),
                         self._observe_data, obs)
        return obs

    # ------------------------------------------------------------------ introspection
    # The episode state, read from this env's row of its EpisodeBatch.
    @property
    def _x(self) -> np.ndarray | None:
        return self._batch.x[self._row] if self._batch.started[self._row] else None

    @property
    def _u(self) -> np.ndarray:
        return self._batch.u[self._row]

    @property
    def _wind(self):
        return self._batch.winds[self._row]

    @_wind.setter
    def _wind(self, wind) -> None:  # another wind field for the rest of the episode (tests)
        self._batch.winds[self._row] = wind
        self._batch.invalidate_winds()

    @property
    def _errors(self) -> dict[str, float]:
        return {name: float(v) for name, v in zip(self._error_names, self._batch.errors[self._row])}

    @property
    def _reference(self) -> dict:
        return self._batch.reference_dicts[self._row]

    @property
    def state(self) -> np.ndarray:
        """A copy of the current model state (layout: ``self.dynamics.layout``)."""
        return None if self._x is None else self._x.copy()

    @property
    def wind(self):
        """The wind field of the current episode (``wind(t, positions_ned_m)``, or None for still air)."""
        return self._wind

    @property
    def applied_controls(self) -> np.ndarray:
        """Controls applied over the last period after rate limiting [N, rad, rad, rad]."""
        return self._u.copy()

    @property
    def time_s(self) -> float:
        """Simulation time [s]."""
        return float(self._batch.time_s[self._row])

    def measurements(self) -> Measurements:
        """Outputs of the current state."""
        return self.dynamics.measure(self._x, self.time_s, self._wind)

    def signal_names(self) -> tuple[str, ...]:
        """Names of the flight-log signals (:meth:`log_sample`): the simulator's flight signals
        (:attr:`flexsim.sim.outputs.OutputMaps.signal_names`), then ``error_<task error>`` and ``reward``."""
        return self.dynamics.outputs.signal_names + tuple(f"error_{name}" for name in self._error_names) + ("reward",)

    def log_sample(self) -> LogSample:
        """The current sample in flight-log form (:func:`flexsim.io.env_log.flight_sample`; names:
        :meth:`signal_names`, ``dynamics.state_names()``): the flight signals, the task errors and the last reward."""
        task_values = [*self._errors.values(), float(self._batch.last_reward[self._row])]
        return flight_sample(self.dynamics, self.time_s, self._x, self._u, self._wind, task_values)

    def render(self) -> np.ndarray | None:
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' or 'human' to the constructor")
            return None
        if self._x is None:
            raise RuntimeError("render() called before reset()")
        from flexsim.io.rendering import RerunStreamer, RgbRenderer

        if self._renderer is None:
            self._renderer = RgbRenderer() if self.render_mode == "rgb_array" else RerunStreamer()
        nodes = self.dynamics.structure_nodes(self._x)
        m = self.measurements()
        return self._renderer.draw(m, nodes, self._batch.path(self._row), self._u, self.task_label(), self._errors)

    def task_label(self) -> str:
        """Short title for renderings."""
        return type(self).__name__

    def __reduce_ex__(self, protocol):
        """Refused with a clear message: an environment holds compiled models, an integrator's state and open
        resources that do not travel between processes; build one in each process instead."""
        raise TypeError(f"{type(self).__name__} cannot be pickled (copied to another process or saved): make a new one "
                        "there with gymnasium.make(id, **kwargs) - e.g. gymnasium's AsyncVectorEnv takes functions that make the "
                        "environments, and FlexSimVectorEnv steps many episodes in one process")

    def close(self) -> None:
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
        super().close()

