"""Rigid-body kinematics: skew matrices, 3-2-1 direction cosines, Euler-rate matrices.

Source: Tuzcu & Nguyen (2014), eqs. (3)-(4); the rotation sequence of the paper (psi about Z, theta about
y1, phi about x2) and the explicit matrices of ``docs/reference/aero-kinematics.md`` section 6.1.
Conventions: inertial axes XYZ north-east-down, body axes xyz x forward / y right / z down.
"""

from __future__ import annotations

import numpy as np

from flexsim import _kernels as _k

__all__ = ["skew", "dcm_321", "euler_rate_matrix", "euler_rate_matrix_inverse", "euler_321_of_quaternion"]


def skew(d: np.ndarray) -> np.ndarray:
    """Skew-symmetric cross-product matrix, paper eq. (3): ``skew(d) @ e == np.cross(d, e)``.

    Parameters
    ----------
    d : array_like, shape (..., 3)
        Vector(s), any units.

    Returns
    -------
    ndarray, shape (..., 3, 3)
    """
    d = np.asarray(d, dtype=float)
    out = np.zeros(d.shape[:-1] + (3, 3))
    out[..., 0, 1] = -d[..., 2]
    out[..., 0, 2] = d[..., 1]
    out[..., 1, 0] = d[..., 2]
    out[..., 1, 2] = -d[..., 0]
    out[..., 2, 0] = -d[..., 1]
    out[..., 2, 1] = d[..., 0]
    return out


def dcm_321(phi: float, theta: float, psi: float) -> np.ndarray:
    """Direction-cosine matrix of the 3-2-1 rotation sequence, ``C = R_x(phi) R_y(theta) R_z(psi)``.

    Maps components in the parent axes (inertial XYZ for the aircraft; body xyz for a component's
    x_i y_i z_i, paper Table 1) to components in the rotated axes. Paper eq. (4) and the text below it;
    reference aero-kinematics.md section 6.1.

    Parameters
    ----------
    phi, theta, psi : float
        Roll, pitch and yaw angles [rad].

    Returns
    -------
    ndarray, shape (3, 3)
    """
    return _k.dcm_321(float(phi), float(theta), float(psi))  # the one implementation (compiled kernel)


def euler_rate_matrix(phi: float, theta: float) -> np.ndarray:
    """Matrix E with ``omega = E @ [phi_dot, theta_dot, psi_dot]`` (paper eq. 4, body components).

    Parameters
    ----------
    phi, theta : float
        Roll and pitch angles [rad].

    Returns
    -------
    ndarray, shape (3, 3)
    """
    sf, cf = np.sin(phi), np.cos(phi)
    st, ct = np.sin(theta), np.cos(theta)
    return np.array([[1.0, 0.0, -st], [0.0, cf, sf * ct], [0.0, -sf, cf * ct]])


def euler_rate_matrix_inverse(phi: float, theta: float) -> np.ndarray:
    """Inverse of :func:`euler_rate_matrix`: ``[phi_dot, theta_dot, psi_dot] = E^-1 @ omega`` (eq. 4).

    Singular at theta = +-90 deg (the 3-2-1 gimbal lock); callers that fly through the vertical must
    detect it (the simulator raises an event).

    Parameters
    ----------
    phi, theta : float
        Roll and pitch angles [rad].

    Returns
    -------
    ndarray, shape (3, 3)
    """
    sf, cf = np.sin(phi), np.cos(phi)
    ct = np.cos(theta)
    tt = np.tan(theta)
    return np.array([[1.0, sf * tt, cf * tt], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]])


def euler_321_of_quaternion(quat: np.ndarray) -> np.ndarray:
    """3-2-1 Euler angles ``[phi, theta, psi]`` [rad] of a body→NED quaternion ``[q0, q1, q2, q3]`` (scalar first,
    normalised here): Stevens & Lewis (2003) eq. 1.8-17 inverted; ``dcm_321`` of the result is the quaternion's
    NED→body matrix. ``theta`` is clipped to ±pi/2 against round-off."""
    import math

    q0, q1, q2, q3 = np.asarray(quat, dtype=float) / np.linalg.norm(quat)
    return np.array([math.atan2(2 * (q0 * q1 + q2 * q3), 1 - 2 * (q1 * q1 + q2 * q2)),
                     math.asin(max(-1.0, min(1.0, 2 * (q0 * q2 - q3 * q1)))),
                     math.atan2(2 * (q0 * q3 + q1 * q2), 1 - 2 * (q2 * q2 + q3 * q3))])
