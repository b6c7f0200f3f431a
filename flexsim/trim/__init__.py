"""Trim of the nonlinear model in steady manoeuvres (paper eqs. 34-39)."""

from flexsim.trim.manoeuvre import SteadyManoeuvre
from flexsim.trim.solver import TrimError, TrimPoint, trim

__all__ = ["SteadyManoeuvre", "TrimError", "TrimPoint", "trim"]
