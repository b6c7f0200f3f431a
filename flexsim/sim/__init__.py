"""Time-domain simulation: events, flight logs, disturbances and named manoeuvres (``docs/simulation.md``).

Modules: :mod:`flexsim.sim.simulate` (``simulate``, ``HoldingRadau``, ``IntegratorSettings``: the one
settings class of the integration of ``simulate`` and of the control periods), :mod:`flexsim.sim.run_settings`
(``EventSettings``, ``OutputSettings``, ``SimEvent``: the other settings of ``simulate``),
:mod:`flexsim.sim.controls` (``ControlSchedule``), :mod:`flexsim.sim.result` (``SimulationResult``),
:mod:`flexsim.sim.outputs` (names and output maps shared by results and logs),
:mod:`flexsim.sim.recording` (log paths, the log sink), :mod:`flexsim.sim.disturbances`
(``OneMinusCosineGust``, ``DrydenTurbulence``, ``combine``), :mod:`flexsim.sim.manoeuvres`
(``build_manoeuvre``, ``manoeuvre_names``), :mod:`flexsim.sim.fixed_step` (``ETD2RK``, the fixed-step
exponential integrator of ``simulate`` and of the control periods), :mod:`flexsim.sim.periods` (``FlightDynamics``,
``advance_period``, ``ActuatorRates``: the control periods of the gymnasium environments,
single and batched), :mod:`flexsim.sim.measurements` (air data, attitude and structural sensors of many states). Import the function as ``from flexsim.sim.simulate import simulate``; the package
does not re-export it, so that ``flexsim.sim.simulate`` always names the module.
"""

from flexsim.sim.disturbances import DrydenTurbulence, OneMinusCosineGust, combine
from flexsim.sim.result import SimulationResult
from flexsim.sim.run_settings import EventSettings, OutputSettings
from flexsim.sim.simulate import ControlSchedule, IntegratorSettings, SimEvent

__all__ = ["ControlSchedule", "IntegratorSettings", "EventSettings", "OutputSettings", "SimEvent", "SimulationResult",
           "OneMinusCosineGust", "DrydenTurbulence", "combine"]
