"""Fuselage and nacelle moments, tail downwash and compressible induced drag (not in the paper).

* Lamb's closed-form apparent-mass coefficients of prolate spheroids (*Hydrodynamics*, 6th ed., 1932,
  sec. 373) against quadratures of their integral definitions (sec. 114) to 1e-9, the sphere limit 1/2 and the
  slender limit (k1 -> 0, k2 -> 1).
* Munk's moment (Munk 1924, NACA Rep. 184): in straight flight without rotation each body's couple is
  1/2 rho V^2 Vol (k2 - k1) sin(2 alpha) nose up and -1/2 rho V^2 Vol (k2 - k1) sin(2 beta) in yaw, with no
  resultant force; asserted to 1e-12 on the bundled GTM's fuselage and nacelles.
* Tail downwash (USAF DATCOM sec. 4.4.1): with Prandtl-Glauert strips the model's d eps/d alpha at Mach M is
  the incompressible gradient times the wing's lift-slope ratio 1/beta (to 1e-12: eps is linear in the wing
  lift), and close to the file's gradient / beta for a change of the body's angle of attack (2 %: the wing's
  dihedral and chordwise speeds weigh the strips' angles).
* Induced drag of the compressible strip lift: at a given lift it does not depend on the Mach number (the
  Trefftz-plane drag of a span loading is unchanged by the Prandtl-Glauert stretching along x), so
  D_i / L^2 is the same with and without the compressibility factor (to 1e-12).
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft, parse_aircraft
from flexsim.atmosphere import speed_of_sound
from flexsim.errors import AircraftDefinitionError
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.bodies import spheroid_apparent_mass
from flexsim.model.coupling import AeroOptions, tail_downwash


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


def test_spheroid_apparent_mass_against_lambs_integrals():
    # Lamb (1932) sec. 114: alpha0 = a b c int_0^inf dl / ((a^2 + l) D), beta0 the same with b^2 + l,
    # D = sqrt((a^2 + l)(b^2 + l)(c^2 + l)); the closed forms of sec. 373 must equal the quadratures
    from scipy.integrate import quad

    for fineness in (1.5, 2.0, 4.0, 10.0, 11.795):
        a, b = 0.5 * fineness, 0.5
        big_d = lambda lam: math.sqrt((a * a + lam) * (b * b + lam) ** 2)
        alpha0 = a * b * b * quad(lambda lam: 1.0 / ((a * a + lam) * big_d(lam)), 0.0, math.inf, epsabs=0, epsrel=1e-12)[0]
        beta0 = a * b * b * quad(lambda lam: 1.0 / ((b * b + lam) * big_d(lam)), 0.0, math.inf, epsabs=0, epsrel=1e-12)[0]
        k1, k2 = spheroid_apparent_mass(fineness)
        assert k1 == pytest.approx(alpha0 / (2 - alpha0), rel=1e-9) and k2 == pytest.approx(beta0 / (2 - beta0), rel=1e-9)
        assert alpha0 + 2 * beta0 == pytest.approx(2.0, rel=1e-9)
    k1, k2 = spheroid_apparent_mass(1.0 + 1e-6)  # sphere: 1/2
    assert k1 == pytest.approx(0.5, abs=1e-5) and k2 == pytest.approx(0.5, abs=1e-5)
    k1, k2 = spheroid_apparent_mass(1e3)  # slender limit (Lamb sec. 373): k1 -> 0, k2 -> 1
    assert k1 < 1e-5 and k2 > 0.9999
    with pytest.raises(ValueError, match="must be > 1"):
        spheroid_apparent_mass(0.9)


@pytest.mark.parametrize("alpha_deg, beta_deg", [(5.0, 0.0), (-12.0, 0.0), (0.0, 7.0), (3.0, -4.0)])
def test_munk_moment_closed_form(gtm, alpha_deg, beta_deg):
    model = AircraftModel(gtm, aero="quasi-steady")
    bodies = model.bodies
    assert bodies is not None and bodies.names == ("fuselage", "right_nacelle", "left_nacelle")
    speed, rho = 230.0, 0.5
    a, b = math.radians(alpha_deg), math.radians(beta_deg)
    vel = np.zeros(model.structure.dofs.n_v)
    vel[0:3] = speed * np.array([math.cos(a) * math.cos(b), math.sin(b), math.sin(a) * math.cos(b)])
    gen = bodies.generalized_force(np.zeros(model.structure.dofs.nq), vel, rho)
    c = rho * np.sum(bodies.volume_m3 * (bodies.k2 - bodies.k1))
    u, v, w = vel[0:3]
    # (v . x)(v x x) = u (0, w, -v): M_y = rho Vol dk u w = 1/2 rho V^2 Vol dk sin(2 alpha) when beta = 0
    np.testing.assert_allclose(gen[0:3], 0.0, atol=1e-9)
    np.testing.assert_allclose(gen[3:6], c * np.array([0.0, u * w, -u * v]), rtol=1e-12, atol=1e-9)
    if beta_deg == 0.0:
        assert gen[4] == pytest.approx(0.5 * rho * speed**2 * c / rho * math.sin(2 * a), rel=1e-12)
    if alpha_deg == 0.0:
        assert gen[5] == pytest.approx(-0.5 * rho * speed**2 * c / rho * math.sin(2 * b), rel=1e-12)


def test_options_switch_the_terms_off(gtm):
    assert AircraftModel(gtm, aero=AeroOptions("quasi-steady", body_moments=False)).bodies is None
    assert AircraftModel(gtm, aero=AeroOptions("quasi-steady", formulation="paper")).bodies is None
    assert AircraftModel(gtm, aero=AeroOptions("quasi-steady", downwash=False)).aero.downwash_gradient == 0.0
    assert AircraftModel(gtm, aero="quasi-steady").aero.downwash_gradient == pytest.approx(0.3327)
    paper = load_aircraft("gtm_paper")
    assert paper.aero_settings.bodies == () and paper.aero_settings.downwash_gradient == 0.0
    with pytest.raises(ValueError, match="body_moments = 1"):
        AeroOptions(body_moments=1)
    with pytest.raises(ValueError, match="downwash = 'yes'"):
        AeroOptions(downwash="yes")


def _straight_state(model, alpha, speed):
    vel = np.zeros(model.structure.dofs.n_v)
    vel[0:3] = speed * np.array([math.cos(alpha), 0.0, math.sin(alpha)])
    q, xi = np.zeros(model.structure.dofs.nq), np.zeros(model.structure.dofs.nxi)
    return q, xi, vel


def test_downwash_gradient_scales_with_the_wing_lift_slope(gtm):
    alt, mach = 9144.0, 0.78
    speed = mach * speed_of_sound(alt)
    beta = math.sqrt(1 - mach**2)
    u = np.zeros(4)
    eps = {}
    for comp in ("prandtl-glauert", "none"):
        model = AircraftModel(gtm, aero=AeroOptions("quasi-steady", compressibility=comp))
        co = model.aero
        for alpha in (0.04, 0.06):
            q, xi, vel = _straight_state(model, alpha, speed)
            kin = co.kinematics(q, xi, vel, np.zeros(0), u)
            eps[comp, alpha] = tail_downwash(co.dw_wing_weight, kin.u0, kin.wc, speed, co.compressibility_factor(mach), co.downwash_gradient)
            # the tail strips' normal velocity falls by eps V (n . z_b); the wing strips are unchanged
            shifted = co._with_downwash(kin, vel, mach)
            tail = np.isin(np.array(co.strips.component), ("right_htail", "left_htail"))
            np.testing.assert_allclose((shifted.wc - kin.wc)[~tail], 0.0, atol=0)
            np.testing.assert_allclose((shifted.wc - kin.wc)[tail], -eps[comp, alpha] * speed * co.dw_tail_nz[tail], rtol=1e-12)
            assert np.all(co.dw_tail_nz[tail] > 0.99)  # the tail's plunge direction is (nearly) body z: eps lowers its angle
    assert eps["prandtl-glauert", 0.06] / eps["none", 0.06] == pytest.approx(1.0 / beta, rel=1e-12)
    gradient = (eps["prandtl-glauert", 0.06] - eps["prandtl-glauert", 0.04]) / 0.02
    assert gradient == pytest.approx(0.3327 / beta, rel=0.02)


def test_downwash_lowers_the_tail_lift(gtm):
    on = AircraftModel(gtm, aero="quasi-steady")
    off = AircraftModel(gtm, aero=AeroOptions("quasi-steady", downwash=False))
    q, xi, vel = _straight_state(on, 0.06, 230.0)
    u = np.zeros(4)
    tail = np.isin(np.array(on.aero.strips.component), ("right_htail", "left_htail"))
    l_on = on.aero.strip_loads(q, xi, vel, np.zeros(0), u, 0.5, 0.7).lift_n_m
    l_off = off.aero.strip_loads(q, xi, vel, np.zeros(0), u, 0.5, 0.7).lift_n_m
    assert np.all(l_on[tail] < l_off[tail]) and np.array_equal(l_on[~tail], l_off[~tail])


def test_induced_drag_at_given_lift_is_independent_of_mach(gtm):
    u = np.zeros(4)
    ratio = {}
    for comp in ("prandtl-glauert", "none"):
        model = AircraftModel(gtm, aero=AeroOptions("quasi-steady", compressibility=comp, parasite_drag=False))
        q, xi, vel = _straight_state(model, 0.05, 230.0)
        loads = model.aero.strip_loads(q, xi, vel, np.zeros(0), u, 0.45, 0.78)
        lifting = np.abs(loads.lift_n_m) > 1.0
        ratio[comp] = loads.drag_n_m[lifting] / loads.lift_n_m[lifting] ** 2
    np.testing.assert_allclose(ratio["prandtl-glauert"], ratio["none"], rtol=1e-12)


def test_body_item_errors_name_the_field():
    with open(load_aircraft("gtm").source, encoding="utf-8") as fh:
        base = fh.read()
    item = '\n[[aero.body]]\nname = "pod"\ncomponent = "fuselage"\nposition_m = [20.0, 0.0, 0.0]\n'
    with pytest.raises(AircraftDefinitionError, match="aero.body.pod.volume_m3"):
        parse_aircraft(base + item + "length_m = 10.0\ndiameter_m = 2.0\nvolume_m3 = 40.0\n")  # > pi d^2 l / 4
    with pytest.raises(AircraftDefinitionError, match="aero.body.pod.diameter_m"):
        parse_aircraft(base + item + "length_m = 2.0\ndiameter_m = 2.0\nvolume_m3 = 1.0\n")
    with pytest.raises(AircraftDefinitionError, match=r"aero.body\[3\].volume: unknown key"):
        parse_aircraft(base + item + "length_m = 10.0\ndiameter_m = 2.0\nvolume = 1.0\n")
    with pytest.raises(AircraftDefinitionError, match="aero.downwash_gradient"):
        parse_aircraft(base.replace("downwash_gradient = 0.3327", "downwash_gradient = 1.0"))
