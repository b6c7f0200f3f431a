"""flexsim.io subpackage."""
