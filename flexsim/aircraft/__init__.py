"""flexsim.aircraft subpackage."""
