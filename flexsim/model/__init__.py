"""flexsim.model subpackage."""
