"""The free-flying GTM in vacuum: rigid-body modes and conservation laws.

Conservation: without external forces the equations of motion (eq. 33) conserve the total energy
T + V and the inertial linear momentum C^T p_v and angular momentum C^T rho_omega + R x C^T p_v
(docs/design.md). A 10 s DOP853 integration at rtol = 1e-8 from a perturbed state must conserve them to
the integrator tolerance: we assert relative drifts below 1e-8 (measured: about 1e-10).
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel

G = 9.80665


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


def test_free_gtm_has_exactly_six_zero_frequency_modes(gtm):
    analysis = in_vacuo_modes(AircraftModel(gtm, gravity_m_s2=0.0, aero=None))
    w = analysis.frequencies_rad_s
    assert analysis.n_rigid == 6
    assert np.all(w[:6] <= 1e-6 * w[6])
    assert w[6] > 1.0  # the first elastic mode is a real vibration (here ~2 Hz)


def _perturbed_state(model, seed=1):
    rng = np.random.default_rng(seed)
    d = model.structure.dofs
    vel = np.r_[[200.0, 3.0, 5.0], [0.05, 0.1, 0.08], 0.05 * rng.standard_normal(d.n_v - 6)]
    return model.pack(
        position_m=[0.0, 0.0, -3000.0],
        euler_rad=[0.1, 0.05, 0.3],
        q=0.05 * rng.standard_normal(d.nq),
        xi=0.01 * rng.standard_normal(d.nxi),
        velocity=vel,
    )


def test_energy_and_momenta_conserved_in_vacuum(gtm):
    model = AircraftModel(gtm, gravity_m_s2=0.0, aero=None, structural_damping=0.0)  # conservative: no damping
    x0 = _perturbed_state(model)
    sol = solve_ivp(model.rhs, (0.0, 10.0), x0, args=(np.zeros(4),), method="DOP853", rtol=1e-8, atol=1e-10)
    assert sol.success
    energy = lambda x: model.kinetic_energy(x) + model.strain_energy(x)
    e0, e1 = energy(x0), energy(sol.y[:, -1])
    p0, h0 = model.momentum_inertial(x0)
    p1, h1 = model.momentum_inertial(sol.y[:, -1])
    assert abs(e1 - e0) / e0 < 1e-8
    assert np.linalg.norm(p1 - p0) / np.linalg.norm(p0) < 1e-8
    assert np.linalg.norm(h1 - h0) / np.linalg.norm(h0) < 1e-8
    # the run really exercised elastic and rigid motion
    assert np.ptp(sol.y[model.layout.q, :]) > 1e-2
    assert np.ptp(sol.y[model.layout.euler, :]) > 0.1


def test_free_fall_accelerates_at_g_without_rotation_or_deformation(gtm):
    # Exact result: with G(q) [g_b; 0] = [C_i g_b; 0], gravity gives M V_dot = M [g_b; 0], so
    # V_dot = [g_b, 0, ...]: the inertial velocity grows as g t along Z, nothing else moves.
    model = AircraftModel(gtm, aero=None, structural_damping=0.0)
    x0 = model.pack(euler_rad=[0.2, -0.1, 0.5])
    dx = model.rhs(0.0, x0, np.zeros(4))
    lay = model.layout
    c = dx[lay.v]
    from flexsim.kinematics import dcm_321

    np.testing.assert_allclose(dcm_321(0.2, -0.1, 0.5).T @ c, [0.0, 0.0, G], atol=1e-9 * G)
    np.testing.assert_allclose(dx[lay.omega], 0.0, atol=1e-12)
    np.testing.assert_allclose(dx[lay.s.start : lay.eta.stop], 0.0, atol=1e-10)
    sol = solve_ivp(model.rhs, (0.0, 5.0), x0, args=(np.zeros(4),), method="DOP853", rtol=1e-10, atol=1e-12)
    xe = sol.y[:, -1]
    np.testing.assert_allclose(xe[lay.position], [0.0, 0.0, 0.5 * G * 25.0], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(xe[lay.euler], [0.2, -0.1, 0.5], atol=1e-10)
    assert np.abs(xe[lay.q.start : lay.xi.stop]).max() < 1e-10
