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


def positive_number(name: str, value, unit: str = "", *, allow_zero: bool = False) -> float:
    """``value`` as a float when it is a finite number > 0 (>= 0 with ``allow_zero``), else a ValueError naming
    ``name``, the value and the range (``unit``, e.g. ``"s"``, is written as ``[s]``)."""
    import math

    where = f"must be a finite number {'>=' if allow_zero else '>'} 0{f' [{unit}]' if unit else ''}"
    if isinstance(value, (bool, str, bytes)) or type(value).__name__ in ("bool", "bool_"):  # True is not 1 s, "3" not 3 m
        raise ValueError(f"{name} = {value!r}: {where}, got {type(value).__name__}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: {where}") from None
    if not (math.isfinite(v) and (v > 0.0 or (allow_zero and v == 0.0))):
        raise ValueError(f"{name} = {value!r}: {where}")
    return v
