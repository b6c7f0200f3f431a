"""flexsim.aero subpackage."""
