"""Accuracy of the integrators on the named manoeuvres against DOP853 at rtol 1e-9 (``docs/simulation.md``).

:func:`manoeuvre_errors` runs one named manoeuvre (:mod:`flexsim.sim.manoeuvres`) with DOP853 at
:data:`REFERENCE_RTOL` (8th-order Dormand-Prince, scipy) and with each :class:`IntegratorChoice`, and returns the
largest differences at the common 100 Hz output samples (:class:`ManoeuvreErrors`): altitude [m], airspeed [m/s]
and bank angle [deg] for an aircraft with rigid-body states, and the right-wing tip deflection [m], also as a
fraction of the tip excursion of the reference (the largest |tip(t) - tip(0)|). The Goland flutter onset runs to
3.1 s with the structural limit moved to 100 m, so that every run covers the same growing oscillation (about 300x).

Used by ``benchmarks/bench_simulate.py --manoeuvres``, ``tools/docs_figures_static.py`` (the table of
``docs/simulation.md``) and ``tests/sim/test_accuracy.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexsim.sim.manoeuvres import build_manoeuvre
from flexsim.sim.result import SimulationResult
from flexsim.sim.run_settings import EventSettings
from flexsim.sim.simulate import DEFAULT_MAX_STEP, METHODS, IntegratorSettings

__all__ = ["IntegratorChoice", "ManoeuvreErrors", "manoeuvre_errors", "DEFAULT_CHOICE", "PREVIOUS_CHOICE",
           "RADAU_CHOICE", "REFERENCE_RTOL", "RUN_OPTIONS"]

#: Relative tolerance of the DOP853 reference.
REFERENCE_RTOL = 1e-9
#: Options of the runs of a manoeuvre beyond its defaults (all integrators and the reference).
RUN_OPTIONS = {"flutter-onset": {"events": EventSettings(wing_tip_deflection_m=100.0), "t_end_s": 3.1}}


@dataclass(frozen=True)
class IntegratorChoice:
    """An integrator and its step or tolerance.

    Attributes
    ----------
    label : str
        Name in tables ("default", ...).
    method : str
        One of :data:`flexsim.sim.simulate.METHODS`.
    step_s : float or None
        ETD2RK: the fixed step [s] > 0 (``max_step``); None for the others.
    rtol : float or None
        The relative tolerance of an adaptive method (None: simulate's default).
    """

    label: str
    method: str
    step_s: float | None = None
    rtol: float | None = None

    def __post_init__(self) -> None:
        if self.method not in METHODS:
            raise ValueError(f"method = {self.method!r}: must be one of {', '.join(METHODS)}")
        if self.method == "ETD2RK" and not (isinstance(self.step_s, (int, float)) and math.isfinite(self.step_s)
                                            and self.step_s > 0):
            raise ValueError(f"step_s = {self.step_s!r}: ETD2RK needs a finite fixed step > 0 [s]")

    def settings(self) -> IntegratorSettings:
        """The :class:`~flexsim.sim.simulate.IntegratorSettings` of this choice (``integrator`` of ``simulate``)."""
        return IntegratorSettings(self.method, None if self.rtol is None else float(self.rtol), None,
                                  None if self.step_s is None else float(self.step_s))

    @property
    def name(self) -> str:
        """"ETD2RK 20 ms", "Radau rtol 1e-3"."""
        if self.method == "ETD2RK":
            return f"ETD2RK {self.step_s * 1e3:g} ms"
        return f"{self.method} rtol {self.rtol:.0e}" if self.rtol is not None else self.method


#: simulate's default with aerodynamics, the default before it (10 ms steps) and the default before that.
DEFAULT_CHOICE = IntegratorChoice("default", "ETD2RK", step_s=DEFAULT_MAX_STEP["ETD2RK"])
PREVIOUS_CHOICE = IntegratorChoice("previous default", "ETD2RK", step_s=0.01)
RADAU_CHOICE = IntegratorChoice("Radau", "Radau", rtol=1e-3)


@dataclass(frozen=True)
class ManoeuvreErrors:
    """Largest errors of one run against the reference at the common 100 Hz samples.

    Attributes
    ----------
    manoeuvre : str
    choice : IntegratorChoice
    status : str
        The run's status (``completed`` for every comparison the docs quote).
    duration_s : float
        Simulated time of the reference [s].
    altitude_m, airspeed_m_s, bank_deg : float or None
        Largest |difference| [m], [m/s], [deg]; None without rigid-body states.
    tip_m : float
        Largest |difference| of the right-wing tip deflection [m].
    tip_excursion_m : float
        Largest |tip(t) - tip(0)| of the reference [m].
    nfev : int
        Right-hand-side evaluations of the run.
    wall_time_s : float
        Its wall time [s] (on the machine and load of the run).
    """

    manoeuvre: str
    choice: IntegratorChoice
    status: str
    duration_s: float
    altitude_m: float | None
    airspeed_m_s: float | None
    bank_deg: float | None
    tip_m: float
    tip_excursion_m: float
    nfev: int
    wall_time_s: float

    @property
    def tip_relative(self) -> float:
        """The tip error as a fraction of the tip excursion."""
        return self.tip_m / self.tip_excursion_m


def _errors(name: str, choice: IntegratorChoice, run: SimulationResult, ref: SimulationResult) -> ManoeuvreErrors:
    if run.t.size != ref.t.size or not np.allclose(run.t, ref.t, rtol=0.0, atol=1e-9):
        raise RuntimeError(f"{name}, {choice.name}: {run.status} at t = {run.t[-1]:.4f} s ({run.reason}); the reference "
                           f"ran to {ref.t[-1]:.4f} s: no common samples to compare")
    tip_ref = ref.tip_deflection_m()
    rigid = run.model.layout.rigid

    def worst(a, b):
        return float(np.abs(a - b).max())

    return ManoeuvreErrors(
        manoeuvre=name, choice=choice, status=run.status, duration_s=float(ref.t[-1]),
        altitude_m=worst(run.altitude_m, ref.altitude_m) if rigid else None,
        airspeed_m_s=worst(run.airspeed_m_s, ref.airspeed_m_s) if rigid else None,
        bank_deg=math.degrees(worst(run.euler_rad[:, 0], ref.euler_rad[:, 0])) if rigid else None,
        tip_m=worst(run.tip_deflection_m(), tip_ref), tip_excursion_m=float(np.abs(tip_ref - tip_ref[0]).max()),
        nfev=int(run.nfev), wall_time_s=float(run.wall_time_s))


def manoeuvre_errors(name: str, choices: tuple[IntegratorChoice, ...] = (DEFAULT_CHOICE, PREVIOUS_CHOICE, RADAU_CHOICE),
                     *, duration_s: float | None = None) -> tuple[ManoeuvreErrors, ...]:
    """Errors of each integrator of ``choices`` on the named manoeuvre against DOP853 at :data:`REFERENCE_RTOL`.

    Parameters
    ----------
    name : str
        One of :func:`flexsim.sim.manoeuvres.manoeuvre_names`.
    choices : tuple of IntegratorChoice
    duration_s : float, optional
        Run length [s] instead of the manoeuvre's (flutter-onset: 3.1 s).

    Raises
    ------
    ValueError
        Unknown manoeuvre or bad duration (from :func:`~flexsim.sim.manoeuvres.build_manoeuvre`).
    RuntimeError
        A run stopped before the reference's end (no common samples).
    """
    setup = build_manoeuvre(name, duration_s=duration_s)
    options = dict(RUN_OPTIONS.get(name, {}))
    if duration_s is not None:
        options.pop("t_end_s", None)
    ref = setup.simulate(integrator=IntegratorSettings(method="DOP853", rtol=REFERENCE_RTOL), **options)
    return tuple(_errors(name, c, setup.simulate(integrator=c.settings(), **options), ref) for c in choices)
