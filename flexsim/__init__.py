"""flexsim: flexible aircraft in manoeuvring flight.

Implements the whole-aircraft flexible multibody model of Tuzcu & Nguyen, *Flutter of Maneuvering
Aircraft*, J. Aerosp. Eng. 28(4), 2015 (accepted manuscript 2014), built on Meirovitch & Tuzcu's unified
formulation (Lagrange's equations in quasi-coordinates).

Conventions (SI units and radians inside the library, body axes x forward / y right / z down) are in
``docs/conventions.md``.

The top-level API, one import for a script::

    import flexsim as fs

    model = fs.AircraftModel(fs.load_aircraft("gtm"), aero="unsteady")
    level = fs.trim(model, fs.SteadyManoeuvre.level(9144.0, mach=0.75))
    point = fs.flutter(model, fs.SteadyManoeuvre.level(0.0, mach=0.6))

The names below are loaded on first use (module ``__getattr__``, PEP 562), so ``import flexsim`` stays cheap and
a command pays only for what it uses; ``import flexsim.envs`` registers the gymnasium environments.
"""

from __future__ import annotations

__version__ = "0.1.0"

#: Public name -> module that defines it (loaded on first attribute access).
_API: dict[str, str] = {
    "load_aircraft": "flexsim.aircraft.toml_loader",
    "Aircraft": "flexsim.aircraft.definition",
    "AircraftModel": "flexsim.model.aircraft_model",
    "AeroOptions": "flexsim.model.coupling",
    "Terms": "flexsim.model.terms",
    "NonlinearBeams": "flexsim.model.terms",
    "DownwashLag": "flexsim._kernels.downwash_lag",
    "VariantSettings": "flexsim.model.variant",
    "SteadyManoeuvre": "flexsim.trimming",
    "TrimPoint": "flexsim.trimming",
    "TrimError": "flexsim.trimming",
    "EquilibriumStability": "flexsim.trimming",
    "trim": "flexsim.trimming",
    "LinearModel": "flexsim.linear.linearize",
    "linearize": "flexsim.linear.linearize",
    "Mode": "flexsim.linear.stability",
    "Spectrum": "flexsim.linear.stability",
    "spectrum": "flexsim.linear.stability",
    "flutter": "flexsim.linear.flutter",
    "FlutterAnalysis": "flexsim.linear.flutter",
    "FlutterPoint": "flexsim.linear.flutter",
    "FlutterNotFound": "flexsim.linear.flutter",
    "wind_tunnel": "flexsim.linear.flutter",
    "nonlinear_wing_tunnel": "flexsim.linear.beam_flutter",
    "FlexibleAircraft": "flexsim.model.flexible_aircraft",
    "flexible_aircraft": "flexsim.model.flexible_aircraft",
    "trim_flexible": "flexsim.trimming.flexible_trim",
    "FlexibleTrimPoint": "flexsim.trimming.flexible_trim",
    "FlexibleTrimError": "flexsim.trimming.flexible_trim",
    "flexible_flutter": "flexsim.linear.flexible_flutter",
    "simulate_flexible": "flexsim.sim.flexible_run",
    "FlexibleRun": "flexsim.sim.flexible_run",
    "FlexibleFlutterPoint": "flexsim.linear.flexible_flutter",
    "WindTunnelResult": "flexsim.linear.flutter",
    "SearchRange": "flexsim.linear.envelope",
    "search_range": "flexsim.linear.envelope",
    "vg_diagram": "flexsim.linear.vg",
    "VgDiagram": "flexsim.linear.vg",
    "VgTrack": "flexsim.linear.vg",
    "linear_system": "flexsim.linear.control",
    "LinearSystem": "flexsim.linear.control",
    "state_space": "flexsim.linear.control",
    "record_flutter_mode": "flexsim.linear.mode_animation",
    "simulate": "flexsim.sim.simulate",
    "IntegratorSettings": "flexsim.sim.simulate",
    "EventSettings": "flexsim.sim.run_settings",
    "OutputSettings": "flexsim.sim.run_settings",
    "SimulationResult": "flexsim.sim.result",
    "OneMinusCosineGust": "flexsim.sim.disturbances",
    "DrydenTurbulence": "flexsim.sim.disturbances",
}

__all__ = ["__version__", *_API]


def __getattr__(name: str):
    """The public API of :data:`_API`, imported when first asked for (PEP 562)."""
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module 'flexsim' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later look-ups do not come here
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_API))
