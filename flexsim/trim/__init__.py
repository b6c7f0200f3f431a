"""Trim of the nonlinear model in steady manoeuvres (paper eqs. 34-39)."""

from flexsim.trim.manoeuvre import SteadyManoeuvre
from flexsim.trim.equilibrium import EquilibriumStability
from flexsim.trim.solver import StripAngle, TrimError, TrimPoint, trim

__all__ = ["EquilibriumStability", "SteadyManoeuvre", "StripAngle", "TrimError", "TrimPoint", "trim"]
