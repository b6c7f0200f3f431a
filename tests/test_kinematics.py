"""3-2-1 direction cosines and Euler-rate matrices (paper eq. 4, docs/reference/aero-kinematics.md §6.1)."""

import numpy as np

from flexsim.kinematics import dcm_321, euler_rate_matrix, euler_rate_matrix_inverse, skew


def _rx(a):
    return np.array([[1, 0, 0], [0, np.cos(a), np.sin(a)], [0, -np.sin(a), np.cos(a)]])


def _ry(a):
    return np.array([[np.cos(a), 0, -np.sin(a)], [0, 1, 0], [np.sin(a), 0, np.cos(a)]])


def _rz(a):
    return np.array([[np.cos(a), np.sin(a), 0], [-np.sin(a), np.cos(a), 0], [0, 0, 1]])


def test_dcm_is_product_of_elementary_rotations_and_orthonormal():
    # C = R_x(phi) R_y(theta) R_z(psi) (docs/reference/aero-kinematics.md §6.1); exact to 1e-15.
    rng = np.random.default_rng(0)
    for phi, theta, psi in rng.uniform(-1.5, 1.5, (20, 3)):
        c = dcm_321(phi, theta, psi)
        np.testing.assert_allclose(c, _rx(phi) @ _ry(theta) @ _rz(psi), atol=1e-15)
        np.testing.assert_allclose(c @ c.T, np.eye(3), atol=1e-14)


def test_paper_eq_35_level_flight_velocity():
    # Eq. (35): v = C [V, 0, 0] = V [cos theta, 0, sin theta] with phi = psi = 0.
    theta = np.deg2rad(3.06)
    np.testing.assert_allclose(dcm_321(0, theta, 0) @ [200.0, 0, 0], 200 * np.array([np.cos(theta), 0, np.sin(theta)]), atol=1e-12)


def test_euler_rates_generate_body_angular_velocity():
    # C_dot = -skew(omega) C with omega = E Theta_dot; central differences, 1e-8.
    rng = np.random.default_rng(1)
    theta_vec = rng.uniform(-1, 1, 3)
    rates = rng.uniform(-1, 1, 3)
    h = 1e-6
    c_dot = (dcm_321(*(theta_vec + h * rates)) - dcm_321(*(theta_vec - h * rates))) / (2 * h)
    omega = euler_rate_matrix(*theta_vec[:2]) @ rates
    np.testing.assert_allclose(c_dot, -skew(omega) @ dcm_321(*theta_vec), atol=1e-8)
    np.testing.assert_allclose(euler_rate_matrix_inverse(*theta_vec[:2]) @ euler_rate_matrix(*theta_vec[:2]), np.eye(3), atol=1e-14)


def test_skew_is_cross_product():
    a, b = np.array([1.0, -2.0, 0.5]), np.array([0.3, 4.0, -1.0])
    np.testing.assert_allclose(skew(a) @ b, np.cross(a, b), atol=1e-15)


def test_euler_321_of_quaternion_inverts_the_quaternion_of_the_angles():
    """Round trip through flexsim.trimming.flexible_turn.euler_quaternion (Stevens & Lewis eq. 1.8-17) to round-off,
    and the quaternion's matrix equals dcm_321 of the angles recovered (transposed: body→NED)."""
    from flexsim.kinematics import euler_321_of_quaternion
    from flexsim.structure.free_flexible import quaternion_matrix
    from flexsim.trimming.flexible_turn import euler_quaternion

    for angles in ((0.3, 0.2, -0.4), (-1.2, 1.4, 3.0), (0.0, -0.7, -2.5)):
        quat = euler_quaternion(*angles)
        back = euler_321_of_quaternion(2.0 * quat)  # any norm
        np.testing.assert_allclose(back, angles, atol=1e-12)
        np.testing.assert_allclose(quaternion_matrix(quat), dcm_321(*back).T, atol=1e-12)
