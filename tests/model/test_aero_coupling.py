"""Strip aerodynamics coupled to the structure, on the restrained Goland wing.

* The strip loads assembled into generalized forces equal Theodorsen's closed-form rigid-section loads
  with C = 1 (NACA Rep. 496; Hodges & Pierce 2011 ch. 5; the quasi-steady limit of Peters' loads,
  paper eq. 27) applied strip by strip, including the apparent-mass terms for arbitrary accelerations
  (1e-9 relative).
* Added mass in still air: a uniform cantilever with the CG on the elastic axis at mid-chord (a = 0) has
  closed-form frequencies with m -> m + pi rho b^2 and I_theta -> I_theta + pi rho b^4 / 8 (Theodorsen's
  apparent mass; Bisplinghoff, Ashley & Halfman 1955 ch. 5). Strip quadrature error O(1/N^2): 200 strips,
  tolerance 1e-4.
* Aerodynamic damping: at 40 m/s (far below the wing's flutter speed) every eigenvalue of the linearised
  model has a negative real part, in still air none has; in the time domain at zero airspeed the wing
  oscillates without damping and conserves its energy (including the apparent-mass kinetic energy).
"""

from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

from flexsim.aero.theodorsen import theodorsen_operator
from flexsim.aircraft.definition import StripAero
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.atmosphere import isa_density
from flexsim.linear.linearize import jacobian
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.structure.shapes import bending_shapes, cantilever_beta_l, torsion_shapes

RHO0 = isa_density(0.0)


def _goland(**section_changes):
    a = load_aircraft("goland_wing")
    wing = a.components[0]
    strips = section_changes.pop("strips", None)
    if section_changes:
        wing = replace(wing, sections=replace(wing.sections, **section_changes))
    if strips is not None:
        wing = replace(wing, aero=replace(wing.aero, strips=strips))
    return replace(a, components=(wing,)), wing


def _tunnel(aircraft, speed, aero="quasi-steady"):
    return AircraftModel(aircraft, variant="restrained", aero=aero, gravity_m_s2=0.0,
                         restrained_velocity_m_s=[speed, 0.0, 0.0], altitude_m=0.0)


def test_generalized_airloads_equal_theodorsen_closed_form_strip_by_strip():
    aircraft, wing = _goland()
    speed = 80.0
    model = _tunnel(aircraft, speed)
    rng = np.random.default_rng(3)
    d = model.structure.dofs
    q, xi = 0.05 * rng.standard_normal(d.nq), 0.02 * rng.standard_normal(d.nxi)
    vel = np.r_[[speed, 0, 0, 0, 0, 0], 0.3 * rng.standard_normal(d.nq + d.nxi)]
    vdot = np.r_[np.zeros(6), 5.0 * rng.standard_normal(d.nq + d.nxi)]
    # mach = 0: the kernel has no compressibility factor (tested separately below)
    m_a, q_a, _ = model.aero.evaluate(q, xi, vel, np.zeros(0), np.zeros(4), RHO0, 0.0)
    q_aero = q_a - m_a @ vdot

    strips = model.aero.strips
    xs, width, b, a = strips.station_m, strips.width_m, strips.semichord_m, strips.a
    L = wing.length_m
    ub, pt = bending_shapes(xs, L, d.nq), torsion_shapes(xs, L, d.nxi)
    s, eta = vel[6 : 6 + d.nq], vel[6 + d.nq :]
    pos = np.stack([np.zeros(xs.size), pt @ xi], axis=-1)  # [h, theta]; h itself does not enter
    rate = np.stack([ub @ s, pt @ eta], axis=-1)
    acc = np.stack([ub @ vdot[6 : 6 + d.nq], pt @ vdot[6 + d.nq :]], axis=-1)
    loads = np.empty((xs.size, 2))  # [L up, M_EA nose up] per span, C = 1 (lambda0 = 0)
    for j in range(xs.size):
        op = theodorsen_operator(a[j], RHO0, b[j], speed)
        q34 = op.downwash_displacement @ pos[j] + op.downwash_rate @ rate[j]
        loads[j] = op.mass @ acc[j] + op.damping @ rate[j] + op.stiffness @ pos[j] + op.circulation * q34
    expected = np.r_[ub.T @ (-width * loads[:, 0]), pt.T @ (width * loads[:, 1])]
    np.testing.assert_allclose(q_aero[6:], expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())


def test_prandtl_glauert_factor_scales_circulatory_loads():
    # Paper, "Numerical Model": Cl_alpha / sqrt(1 - M^2); exact ratio of strip lifts at M = 0.6 and 0.
    # The bundled Goland file is incompressible ([aero] compressibility = "none"): switched on per model.
    aircraft, _ = _goland()
    model = AircraftModel(aircraft, variant="restrained", aero=AeroOptions("quasi-steady", compressibility="prandtl-glauert"),
                          gravity_m_s2=0.0, restrained_velocity_m_s=[100.0, 0.0, 0.0])
    d = model.structure.dofs
    q, xi, vel = np.zeros(d.nq), np.full(d.nxi, 0.01), np.r_[[100.0, 0, 0, 0, 0, 0], np.zeros(d.nq + d.nxi)]
    l0 = model.aero.strip_loads(q, xi, vel, np.zeros(0), np.zeros(4), RHO0, 0.0).lift_n_m
    l6 = model.aero.strip_loads(q, xi, vel, np.zeros(0), np.zeros(4), RHO0, 0.6).lift_n_m
    np.testing.assert_allclose(l6 / l0, 1.25, rtol=1e-12)
    off = _tunnel(aircraft, 100.0)  # the file's setting: no correction
    l6_off = off.aero.strip_loads(q, xi, vel, np.zeros(0), np.zeros(4), RHO0, 0.6).lift_n_m
    np.testing.assert_allclose(l6_off, l0, rtol=1e-15)


def test_still_air_added_mass_matches_closed_form_frequencies():
    aircraft, wing = _goland(cg_offset_m=np.zeros(2), ea_fraction=np.full(2, 0.5), strips=200)
    model = _tunnel(aircraft, 0.0)
    m_total, _ = model.generalized_forces(model.layout.zeros(), np.zeros(4))
    el = slice(6, None)
    w = np.sqrt(eigh(model.structure.stiffness[el, el], m_total[el, el], eigvals_only=True))
    sec = wing.sections
    b = sec.chord_m[0] / 2
    m_air = sec.mass_kg_per_m[0] + np.pi * RHO0 * b**2
    i_air = sec.torsional_inertia_kg_m[0] + np.pi * RHO0 * b**4 / 8
    L = wing.length_m
    bend = cantilever_beta_l(3) ** 2 * np.sqrt(sec.ei_nm2[0] / (m_air * L**4))
    tors = np.array([1.0, 3.0]) * np.pi / (2 * L) * np.sqrt(sec.gj_nm2[0] / i_air)
    np.testing.assert_allclose(w, np.sort(np.r_[bend, tors]), rtol=1e-4)


def _tip_release(model, t_end):
    d = model.structure.dofs
    q0 = np.zeros(d.nq)
    q0[0] = 0.05  # 10 cm tip deflection in the first bending mode (phi_1(L) = 2)
    xi0 = np.zeros(d.nxi)
    xi0[0] = 0.02
    x0 = model.pack(q=q0, xi=xi0, velocity=model.unpack(model.layout.zeros())[4])
    return x0, solve_ivp(model.rhs, (0.0, t_end), x0, args=(np.zeros(4),), method="DOP853", rtol=1e-9, atol=1e-11, dense_output=True)


@pytest.mark.parametrize("aero", ["quasi-steady", "unsteady"])
def test_wing_in_airflow_is_damped_by_the_air(aero):
    # Lyapunov's indirect method on the linearisation of rhs about the undeformed wing (an exact equilibrium:
    # rhs = 0): at 40 m/s, far below the flutter speed (131.6 m/s, tests/linear/test_flutter.py), every
    # eigenvalue has Re < 0, so a disturbed wing returns to equilibrium (measured max Re -0.30 1/s
    # quasi-steady, -0.50 1/s unsteady); in still air the same structure is undamped (|Re| at rounding level,
    # the time-domain counterpart is the energy test below), so the damping is the air's.
    aircraft, _ = _goland()
    eig = {}
    for speed in (40.0, 0.0):
        model = _tunnel(aircraft, speed, aero=aero)
        x0, u0 = model.layout.zeros(), np.zeros(4)
        assert np.abs(model.rhs(0.0, x0, u0)).max() < 1e-12
        eig[speed] = np.linalg.eigvals(jacobian(model, x0, u0)[0])
    assert eig[40.0].real.max() < -0.1
    assert np.abs(eig[0.0].real).max() < 1e-9 * np.abs(eig[0.0]).max()


def test_wing_in_still_air_oscillates_undamped_and_conserves_energy():
    aircraft, _ = _goland()
    model = _tunnel(aircraft, 0.0, aero="unsteady")
    lay = model.layout
    x0, sol = _tip_release(model, 2.0)

    def energy(x):
        m_total, _ = model.generalized_forces(x, np.zeros(4))
        v = x[lay.velocity]
        return 0.5 * v @ m_total[6:, 6:] @ v + model.strain_energy(x)

    e = np.array([energy(sol.sol(t)) for t in np.linspace(0, 2.0, 41)])
    assert np.abs(e / e[0] - 1).max() < 1e-6
    late = np.abs(sol.sol(np.linspace(1.5, 2.0, 200))[lay.q.start : lay.xi.stop]).max()
    assert late > 0.5 * np.abs(x0[lay.q.start : lay.xi.stop]).max()


def test_inflow_forcing_uses_the_solved_accelerations_not_lagged_ones():
    # Peters et al. 1995 (docs/reference/aero-kinematics.md §2.1): lambda_dot = A^-1 [c (w0_dot + w1_dot/2) - (u0/b) lambda].
    # w0_dot + w1_dot/2 is measured by central differences of w0 + w1/2 along x_dot = rhs(x): it contains
    # the accelerations that the right-hand side solves for in the same call (implicit coupling).
    model = AircraftModel(load_aircraft("gtm"), aero="unsteady")
    rng = np.random.default_rng(5)
    d = model.structure.dofs
    vel = np.r_[[230.0, 2.0, 12.0], 0.05 * rng.standard_normal(3), 0.2 * rng.standard_normal(d.n_v - 6)]
    x = model.pack(position_m=[0, 0, -6000.0], euler_rad=[0.05, 0.04, 0.0], q=0.2 * rng.standard_normal(d.nq),
                   xi=0.01 * rng.standard_normal(d.nxi), velocity=vel)
    x[model.layout.inflow] = 0.5 * rng.standard_normal(model.layout.n_inflow)
    u = np.array([40e3, 0.0, 0.0, 0.0])
    dx = model.rhs(0.0, x, u)

    def w34(xx):
        _, _, q, xi, v = model.unpack(xx)
        return model.aero.kinematics(q, xi, v, xx[model.layout.inflow], u).w34

    h = 1e-6
    forcing = (w34(x + h * dx) - w34(x - h * dx)) / (2 * h)
    coupling = model.aero
    idx = np.flatnonzero(coupling.strips.unsteady)
    lam = x[model.layout.inflow].reshape(idx.size, -1)
    u0 = model.aero.kinematics(*model.unpack(x)[2:], x[model.layout.inflow], u).u0[idx]
    b = coupling.strips.semichord_m[idx]
    expected = forcing[idx, None] * coupling.inflow.A_inv_c[None, :] - (u0 / b)[:, None] * (lam @ coupling.inflow.A_inv.T)
    np.testing.assert_allclose(dx[model.layout.inflow], expected.ravel(), rtol=1e-6, atol=1e-6 * np.abs(expected).max())
