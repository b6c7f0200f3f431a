"""flexsim.cli subpackage."""
