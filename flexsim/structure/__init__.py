"""flexsim.structure subpackage."""
