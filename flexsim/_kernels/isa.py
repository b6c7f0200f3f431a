"""ISA 1976 (scalar, compiled) and the 3-2-1 rotation matrix of the kernels.

Sources: U.S. Standard Atmosphere 1976, eqs. 18, 23, 33a/b, 42, 50 (:mod:`flexsim.atmosphere` re-exports the
constants and wraps the arrays); the paper (Tuzcu & Nguyen 2014) eq. 4 for the rotation. SI units, radians.
"""

from __future__ import annotations

import math

import numpy as np

from flexsim._kernels.layout import kernel

# ISA 1976 constants (flexsim.atmosphere re-exports them)
EARTH_RADIUS = 6_356_766.0  # r0 [m]
G0 = 9.80665  # [m/s^2]
GAS_CONSTANT = 8.31432 / 28.9644e-3  # R* / M0 [J/(kg K)]
GAMMA = 1.4
T0 = 288.15  # [K]
P0 = 101_325.0  # [Pa]
LAPSE_RATE = -0.0065  # [K/m]
H_TROPOPAUSE = 11_000.0  # geopotential [m]
T_TROPOPAUSE = T0 + LAPSE_RATE * H_TROPOPAUSE
_EXPONENT = -G0 / (GAS_CONSTANT * LAPSE_RATE)
P_TROPOPAUSE = P0 * (T_TROPOPAUSE / T0) ** _EXPONENT
_SCALE = G0 / (GAS_CONSTANT * T_TROPOPAUSE)


@kernel
def isa_scalar(h_geopotential):
    """ISA 1976 (density [kg/m^3], pressure [Pa], temperature [K]) at geopotential altitude H [m]
    (1976 standard eqs. 23, 33a/33b, 42); H in [-5000, 20000] m is checked by the callers."""
    if h_geopotential <= H_TROPOPAUSE:
        temperature = T0 + LAPSE_RATE * h_geopotential
        pressure = P0 * (temperature / T0) ** _EXPONENT
    else:
        temperature = T_TROPOPAUSE
        pressure = P_TROPOPAUSE * math.exp(-_SCALE * (h_geopotential - H_TROPOPAUSE))
    return pressure / (GAS_CONSTANT * temperature), pressure, temperature


@kernel
def _geopotential(z):
    """H = r0 z / (r0 + z) [m] from geometric altitude z [m] (1976 standard eq. 18)."""
    return EARTH_RADIUS * z / (EARTH_RADIUS + z)


@kernel
def _sound_speed(h_geopotential):
    """sqrt(gamma R T) [m/s] (1976 standard eq. 50)."""
    return math.sqrt(GAMMA * GAS_CONSTANT * (T0 + LAPSE_RATE * min(h_geopotential, H_TROPOPAUSE)))


@kernel
def dcm_321(phi, theta, psi):
    """C = R_x(phi) R_y(theta) R_z(psi): inertial -> body components (paper eq. 4; kinematics.dcm_321)."""
    sf, cf = math.sin(phi), math.cos(phi)
    st, ct = math.sin(theta), math.cos(theta)
    sp, cp = math.sin(psi), math.cos(psi)
    c = np.empty((3, 3))
    c[0, 0], c[0, 1], c[0, 2] = ct * cp, ct * sp, -st
    c[1, 0], c[1, 1], c[1, 2] = sf * st * cp - cf * sp, sf * st * sp + cf * cp, sf * ct
    c[2, 0], c[2, 1], c[2, 2] = cf * st * cp + sf * sp, cf * st * sp - sf * cp, cf * ct
    return c

