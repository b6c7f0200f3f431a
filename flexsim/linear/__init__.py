"""flexsim.linear subpackage."""
