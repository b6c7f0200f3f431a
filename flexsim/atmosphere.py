"""International Standard Atmosphere (U.S. Standard Atmosphere 1976), the two lowest layers, closed form.

Source: *U.S. Standard Atmosphere, 1976*, NOAA/NASA/USAF (identical to ISO 2533 / ICAO ISA below 32 km):
constants in §1.2, eqs. 18 (geopotential altitude), 23 (temperature), 33a/33b (pressure), 42 (density),
50 (speed of sound).

Altitude handling: inputs are **geometric** altitude ``z`` above mean sea level [m] by default
(``geopotential=True`` for geopotential altitude ``H``). Internally everything uses geopotential altitude
``H = r0 z / (r0 + z)`` with ``r0 = 6 356 766 m``. Supported range: ``-5000 <= H <= 20000`` geopotential
metres, i.e. the troposphere (lapse rate -6.5 K/km, extended below sea level as the 1976 tables are) and
the isothermal lower stratosphere (216.65 K) up to its top; in geometric altitude that is
``-4996.07 <= z <= 20063.12`` m. Outside it a ``ValueError`` names the value and the range.

The scalar functions take a fast path (``math`` only, no arrays, a few hundred nanoseconds) because they
run inside ODE right-hand sides; arrays are evaluated vectorised.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

# The 1976 constants (§1.2) and the closed-form scalar state live once, in the compiled kernels
# (flexsim._kernels: EARTH_RADIUS r0 [m], G0 [m/s²], GAS_CONSTANT R*/M0 = 287.0531 J/(kg·K), GAMMA, T0 288.15 K,
# P0 101325 Pa, LAPSE_RATE -6.5 K/km, H_TROPOPAUSE 11 km geopotential, T_TROPOPAUSE 216.65 K, P_TROPOPAUSE
# 22632.06 Pa); this module adds the range checks, geometric altitude and array evaluation.
from flexsim._kernels import (  # noqa: E402
    _EXPONENT,
    _SCALE,
    EARTH_RADIUS,
    G0,
    GAMMA,
    GAS_CONSTANT,
    H_TROPOPAUSE,
    LAPSE_RATE,
    P0,
    P_TROPOPAUSE,
    T0,
    T_TROPOPAUSE,
    isa_scalar,
)

H_MIN = -5_000.0  # lowest supported geopotential altitude [m]
H_MAX = 20_000.0  # top of the isothermal layer, geopotential [m]
Z_MIN = EARTH_RADIUS * H_MIN / (EARTH_RADIUS - H_MIN)  # geometric equivalents [m]
Z_MAX = EARTH_RADIUS * H_MAX / (EARTH_RADIUS - H_MAX)


class AtmosphereState(NamedTuple):
    """ISA state at one altitude (or arrays of them). SI units."""

    density: float | NDArray  # kg/m³
    pressure: float | NDArray  # Pa
    temperature: float | NDArray  # K
    speed_of_sound: float | NDArray  # m/s


def _is_scalar(x: object) -> bool:
    """Python/numpy float or int (the fast path); numpy float64 is a float subclass."""
    return isinstance(x, (float, int))


def _range_error(altitude: object, geopotential: bool) -> ValueError:
    kind, low, high = ("geopotential", H_MIN, H_MAX) if geopotential else ("geometric", Z_MIN, Z_MAX)
    return ValueError(
        f"{kind} altitude {altitude!r} m is outside the supported ISA range [{low:.2f}, {high:.2f}] m"
    )


def _geopotential_scalar(altitude: float, geopotential: bool) -> float:
    altitude = float(altitude)  # numpy float64 -> float: faster arithmetic, plain-float results
    h = altitude if geopotential else EARTH_RADIUS * altitude / (EARTH_RADIUS + altitude)
    if not H_MIN <= h <= H_MAX:
        raise _range_error(altitude, geopotential)
    return h


def _geopotential_array(altitude: ArrayLike, geopotential: bool) -> NDArray:
    z = np.asarray(altitude, dtype=float)
    h = z if geopotential else geopotential_altitude(z)
    ok = (h >= H_MIN) & (h <= H_MAX)
    if not np.all(ok):
        raise _range_error(z[~ok].ravel()[0].item(), geopotential)
    return h


def _operand(x: ArrayLike) -> float | NDArray:
    return x if _is_scalar(x) else np.asarray(x, dtype=float)


def geopotential_altitude(z: ArrayLike) -> float | NDArray:
    """Geopotential altitude ``H = r0 z/(r0 + z)`` [m] from geometric ``z`` [m] (1976 standard eq. 18)."""
    z = _operand(z)
    return EARTH_RADIUS * z / (EARTH_RADIUS + z)


def geometric_altitude(h: ArrayLike) -> float | NDArray:
    """Geometric altitude ``z = r0 H/(r0 - H)`` [m] from geopotential ``H`` [m] (1976 standard eq. 18)."""
    h = _operand(h)
    return EARTH_RADIUS * h / (EARTH_RADIUS - h)


def _state_scalar(h: float) -> tuple[float, float, float]:
    """(density [kg/m³], pressure [Pa], temperature [K]) at geopotential ``h`` [m] (eqs. 23, 33a/33b, 42)."""
    return isa_scalar(float(h))


def _state_array(h: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    low = h <= H_TROPOPAUSE
    temperature = np.where(low, T0 + LAPSE_RATE * np.minimum(h, H_TROPOPAUSE), T_TROPOPAUSE)
    pressure = np.where(
        low,
        P0 * (temperature / T0) ** _EXPONENT,
        P_TROPOPAUSE * np.exp(-_SCALE * (np.maximum(h, H_TROPOPAUSE) - H_TROPOPAUSE)),
    )
    return pressure / (GAS_CONSTANT * temperature), pressure, temperature


def isa(altitude: ArrayLike, *, geopotential: bool = False) -> AtmosphereState:
    """ISA 1976 density, pressure, temperature and speed of sound (1976 standard eqs. 23, 33, 42, 50).

    Parameters
    ----------
    altitude : float or array_like
        Altitude above mean sea level [m], geometric unless ``geopotential`` is true.
    geopotential : bool, keyword-only
        Interpret ``altitude`` as geopotential altitude.

    Returns
    -------
    AtmosphereState
        Floats for a Python ``float``/``int`` input, arrays of the input's shape otherwise.

    Raises
    ------
    ValueError
        If any altitude is outside the supported range (see module docstring) or not finite.
    """
    if isinstance(altitude, bool):  # True is not 1 m
        raise ValueError(f"altitude = {altitude!r}: must be a number [m], got bool")
    if _is_scalar(altitude):
        density, pressure, temperature = _state_scalar(_geopotential_scalar(altitude, geopotential))
        return AtmosphereState(density, pressure, temperature, math.sqrt(GAMMA * GAS_CONSTANT * temperature))
    density, pressure, temperature = _state_array(_geopotential_array(altitude, geopotential))
    return AtmosphereState(density, pressure, temperature, np.sqrt(GAMMA * GAS_CONSTANT * temperature))


def isa_density(altitude: ArrayLike, *, geopotential: bool = False) -> float | NDArray:
    """ISA 1976 air density [kg/m³] only — the right-hand-side fast path (1976 standard eq. 42).

    Parameters and errors as in :func:`isa`.
    """
    if _is_scalar(altitude):
        return _state_scalar(_geopotential_scalar(altitude, geopotential))[0]
    return _state_array(_geopotential_array(altitude, geopotential))[0]


def speed_of_sound(altitude: ArrayLike, *, geopotential: bool = False) -> float | NDArray:
    """ISA 1976 speed of sound ``sqrt(γ R T)`` [m/s] (1976 standard eq. 50). Parameters as in :func:`isa`."""
    if _is_scalar(altitude):
        h = _geopotential_scalar(altitude, geopotential)
        return math.sqrt(GAMMA * GAS_CONSTANT * (T0 + LAPSE_RATE * min(h, H_TROPOPAUSE)))
    h = _geopotential_array(altitude, geopotential)
    return np.sqrt(GAMMA * GAS_CONSTANT * (T0 + LAPSE_RATE * np.minimum(h, H_TROPOPAUSE)))


def mach_to_true_airspeed(
    mach: ArrayLike, altitude: ArrayLike, *, geopotential: bool = False
) -> float | NDArray:
    """True airspeed ``V = M a(H)`` [m/s] from Mach number at an ISA altitude [m].

    Broadcasts ``mach`` against ``altitude``; parameters and errors as in :func:`isa`.
    """
    return _operand(mach) * speed_of_sound(altitude, geopotential=geopotential)


def true_airspeed_to_mach(
    speed: ArrayLike, altitude: ArrayLike, *, geopotential: bool = False
) -> float | NDArray:
    """Mach number ``M = V/a(H)`` from true airspeed [m/s] at an ISA altitude [m].

    Broadcasts ``speed`` against ``altitude``; parameters and errors as in :func:`isa`.
    """
    return _operand(speed) / speed_of_sound(altitude, geopotential=geopotential)
