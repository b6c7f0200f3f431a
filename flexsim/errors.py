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


def _shown(value, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def expect_type(name: str, value, types: type | tuple[type, ...], what: str, hint: str = ""):
    """``value`` unchanged when it is an instance of ``types``; else a TypeError naming ``name``, what was given and
    ``what`` is expected (e.g. ``"an AircraftModel"``), with ``hint`` (how to get one) appended."""
    if isinstance(value, types):
        return value
    given = f"{type(value).__module__}.{type(value).__qualname__}".removeprefix("builtins.")
    raise TypeError(f"{name} = {_shown(value)}: must be {what}, not a {given}" + (f"; {hint}" if hint else ""))


def float_array(name: str, value, shape: tuple[int | None, ...] | None = None, *, finite: bool = True,
                what: str = "") -> "np.ndarray":
    """``value`` as a float64 array, checked where it enters the API: numbers only (no ragged nesting, strings or
    None), of ``shape`` (None entries: any length) and, with ``finite``, free of NaN and infinities. Each failure is
    a ValueError naming ``name``, the value and what is allowed (``what``: e.g. ``"[thrust N, aileron, elevator,
    rudder rad]"``)."""
    import numpy as np

    tail = f" {what}" if what else ""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {_shown(value)}: must be an array of numbers{tail} (same length in every row; "
                         "no strings or None)") from None
    if shape is not None and (a.ndim != len(shape) or any(n is not None and n != m for n, m in zip(shape, a.shape))):
        want = "(" + ", ".join("k" if n is None else str(n) for n in shape) + (",)" if len(shape) == 1 else ")")
        raise ValueError(f"{name} = {_shown(value)}: must have shape {want}{tail}, got shape {a.shape}")
    if finite and not np.all(np.isfinite(a)):
        bad = tuple(int(i) for i in np.argwhere(~np.isfinite(a))[0]) if a.ndim else ()
        where = f"[{', '.join(map(str, bad))}]" if bad else ""
        raise ValueError(f"{name}{where} = {a[bad] if bad else a}: must be finite (not NaN or infinite){tail}")
    return a
