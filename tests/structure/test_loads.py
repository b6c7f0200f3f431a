"""Generalized forces through virtual work (eqs. 17-24) and gravity (eq. 32).

The generalized forces from the kinematic map, G(q)^T [f; mu], are checked against central finite
differences of the virtual work F . r(q, xi) of the same force at an independently written deformed
position (the kinematics of eqs. 5-6: bending w_i along z_i, torsion phi_i about x_i, the fuselage's
bending w_f, slope -w_f' and torsion phi_f at the attachment carrying the component). Tolerance 1e-7
relative: the positions are linear in the elastic coordinates, so central differences are exact up to
round-off.
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.kinematics import dcm_321
from flexsim.structure.loads import generalized_force
from flexsim.structure.model import StructuralModel
from flexsim.structure.sections import mass_points
from flexsim.structure.shapes import bending_shapes, torsion_shapes

E1, E3 = np.eye(3)[0], np.eye(3)[2]


@pytest.fixture(scope="module")
def gtm():
    return StructuralModel(load_aircraft("gtm"))


def _modal(shapes, length, n, x, coords, derivative=0):
    return shapes(x, length, n, derivative)[0] @ coords if n else 0.0


def _position(st, name, x, rho, q, xi):
    """Body-axes position of the point at station x, offset rho (component axes), written directly."""
    a, d = st.aircraft, st.dofs
    comp = a.component(name)
    c = comp.dcm
    w = _modal(bending_shapes, comp.length_m, comp.bending_modes, x, q[d.bending[name]])
    phi = _modal(torsion_shapes, comp.length_m, comp.torsion_modes, x, xi[d.torsion[name]])
    rho_b = c.T @ rho
    own = c.T @ np.array([x, 0.0, w]) + np.cross(phi * c.T @ E1, rho_b) + rho_b
    if name == "fuselage":
        return own
    fus = a.component("fuselage")
    xf = comp.root_m[0]
    wf = _modal(bending_shapes, fus.length_m, fus.bending_modes, xf, q[d.bending["fuselage"]])
    dwf = _modal(bending_shapes, fus.length_m, fus.bending_modes, xf, q[d.bending["fuselage"]], 1)
    phif = _modal(torsion_shapes, fus.length_m, fus.torsion_modes, xf, xi[d.torsion["fuselage"]])
    theta_f = np.array([phif, -dwf, 0.0])  # fuselage section rotation at the attachment
    root = comp.root_m + wf * E3 + np.cross(phif * E1, comp.root_m)
    return root + own + np.cross(theta_f, c.T @ (x * E1) + rho_b)


def _random(st, seed):
    rng = np.random.default_rng(seed)
    return 0.2 * rng.standard_normal(st.dofs.nq), 0.02 * rng.standard_normal(st.dofs.nxi), rng


@pytest.mark.parametrize("name", ["fuselage", "right_wing", "left_htail", "vtail"])
def test_point_force_generalized_forces_match_virtual_work(gtm, name):
    q, xi, rng = _random(gtm, hash(name) % 1000)
    comp = gtm.aircraft.component(name)
    x = 0.63 * comp.length_m
    rho = np.array([0.0, 0.7, -0.4])  # an offset point (e.g. a pylon-mounted mass) [m]
    force_b = rng.standard_normal(3) * 1e4  # body axes [N]
    f_c = comp.dcm @ force_b
    maps = gtm.point_maps(name, np.array([x]))
    gq = generalized_force(maps, q, f_c[None, :], np.cross(rho, f_c)[None, :])
    work = lambda qq, xx: force_b @ _position(gtm, name, x, rho, qq, xx)
    h = 1e-6
    nq = gtm.dofs.nq
    fd_q = np.array([(work(q + h * e, xi) - work(q - h * e, xi)) / (2 * h) for e in np.eye(nq)])
    fd_xi = np.array([(work(q, xi + h * e) - work(q, xi - h * e)) / (2 * h) for e in np.eye(xi.size)])
    scale = np.abs(gq).max()
    np.testing.assert_allclose(gq[6 : 6 + nq], fd_q, atol=1e-7 * scale)
    np.testing.assert_allclose(gq[6 + nq :], fd_xi, atol=1e-7 * scale)
    np.testing.assert_allclose(gq[0:3], force_b, rtol=1e-12)  # resultant force, eq. (20)


@pytest.mark.parametrize("name", ["right_wing", "vtail"])
def test_moment_about_origin_matches_virtual_rotation(gtm, name):
    # Eqs. (21)-(22): virtual rotation delta theta* about body axes. With the fuselage undeformed and no
    # torsion, the paper's moment arm r_fi + C_i^T (x e1 + u_i + rho) is the exact position.
    q, xi, rng = _random(gtm, 3)
    q[gtm.dofs.bending["fuselage"]] = 0.0
    xi[:] = 0.0
    comp = gtm.aircraft.component(name)
    x, rho = 0.4 * comp.length_m, np.array([0.0, -0.5, 0.3])
    force_b = rng.standard_normal(3) * 1e4
    f_c = comp.dcm @ force_b
    gq = generalized_force(gtm.point_maps(name, np.array([x])), q, f_c[None, :], np.cross(rho, f_c)[None, :])
    r = _position(gtm, name, x, rho, q, xi)
    h = 1e-6
    fd = np.array([(force_b @ (dcm_321(*(h * e)).T @ r) - force_b @ (dcm_321(*(-h * e)).T @ r)) / (2 * h) for e in np.eye(3)])
    np.testing.assert_allclose(gq[3:6], fd, atol=1e-7 * np.abs(gq[3:6]).max())


def test_gravity_equals_sum_of_weights_through_virtual_work(gtm):
    # Q_g = M(q) [g_b; 0] (eq. 32 through eqs. 17-24) equals the sum over every mass point of the
    # generalized force of its weight m_p g applied at its centre of mass.
    q, xi, _ = _random(gtm, 11)
    theta = np.array([0.1, 0.05, 0.7])
    model = AircraftModel(gtm.aircraft, aero=None)
    x = model.pack(euler_rad=theta, q=q, xi=xi)
    m, f = model.generalized_forces(x, np.zeros(4))
    f_el = -np.concatenate([np.zeros(6), gtm.k_bending @ q, gtm.k_torsion @ xi])
    q_gravity = f - f_el
    g_b = dcm_321(*theta) @ np.array([0.0, 0.0, model.terms.gravity_m_s2])
    total = np.zeros(gtm.dofs.n_v)
    pts = mass_points(gtm.aircraft)
    for name, xs, mbar in zip(pts.component, pts.x, pts.mbar):
        comp = gtm.aircraft.component(name)
        mass = mbar[:, 0, 0]
        s = np.stack([mbar[:, 5, 1], mbar[:, 3, 2], mbar[:, 4, 0]], axis=1)  # first moment from skew(S)
        g_c = comp.dcm @ g_b
        f_pts = mass[:, None] * g_c[None, :]
        mu = np.cross(s, g_c[None, :])  # moment of the weight about the reference point
        total += generalized_force(gtm.point_maps(name, xs), q, f_pts, mu)
    np.testing.assert_allclose(q_gravity, total, atol=1e-9 * np.abs(total).max())
    np.testing.assert_allclose(q_gravity[0:3], gtm.mass_properties.mass_kg * g_b, rtol=1e-12)


def test_thrust_acts_along_body_x_at_the_engines(gtm):
    # Eqs. (20)-(22): F = [T_e, 0, 0]; moment about o = sum_e r_e x F_e / n_e.
    q = np.zeros(gtm.dofs.nq)
    t = 50e3
    qt = gtm.thrust.force(t, q)
    np.testing.assert_allclose(qt[0:3], [t, 0.0, 0.0], atol=1e-9 * t)
    arms = [e.position_m for e in gtm.aircraft.engines]
    moment = sum(np.cross(r, [t / len(arms), 0.0, 0.0]) for r in arms)
    np.testing.assert_allclose(qt[3:6], moment, atol=1e-9 * t)
