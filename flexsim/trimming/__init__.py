"""Trim of the nonlinear model in steady manoeuvres (paper eqs. 34-39)."""

from flexsim.trimming.manoeuvre import SteadyManoeuvre
from flexsim.trimming.equilibrium import EquilibriumStability
from flexsim.trimming.solver import StripAngle, TrimError, TrimPoint, trim

__all__ = ["EquilibriumStability", "SteadyManoeuvre", "StripAngle", "TrimError", "TrimPoint", "trim"]
