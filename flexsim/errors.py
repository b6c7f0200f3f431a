"""Exception types raised by flexsim.

Every error names the offending field, its value and what is allowed, so that a user never has to
read a traceback from inside numpy to learn what was wrong with their input.
"""


class FlexsimError(Exception):
    """Base class of flexsim's own errors."""


class AircraftDefinitionError(FlexsimError, ValueError):
    """An aircraft definition (TOML file or dataclass arguments) is malformed.

    The message has the form ``"<file>: <field> = <value>: <what is allowed>"``.
    """
