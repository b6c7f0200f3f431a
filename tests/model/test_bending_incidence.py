"""Swept-wing bending-incidence coupling, off by default (the paper's model).

Kinematic closed form: with the option on, a bending deflection q of a swept wing pitches each streamwise
strip by alpha_b = (p . -y_i) dw/dx = sin(Lambda) dw/dx (to 1e-3 with the GTM's 5 deg dihedral), w = U(x) q the
bending displacement along z_i (down), p the strip's pitch axis and Lambda the sweep (Bisplinghoff, Ashley &
Halfman 1955, sec. 8-4); asserted to 1e-12 against the shapes' derivatives.
An unswept wing (Goland) is unaffected. Effect on the GTM at 9144 m, M 0.78: the upward bending washes the
tip out (tip strip pitch +0.87 deg -> -0.48 deg) and relieves the wing (tip deflection 0.81 -> 0.67 m).
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.structure.shapes import bending_shapes
from flexsim.trimming import SteadyManoeuvre, trim


def test_strip_pitch_is_sweep_times_bending_slope():
    gtm = load_aircraft("gtm")
    on = AircraftModel(gtm, aero=AeroOptions("quasi-steady", bending_incidence=True))
    off = AircraftModel(gtm, aero=AeroOptions("quasi-steady"))
    assert not off.aero.bending_incidence and gtm.aero_settings.bending_incidence is False
    dofs = on.structure.dofs
    q = np.zeros(dofs.nq)
    q[dofs.bending["right_wing"]] = [-0.3, 0.05]
    xi, vel, u = np.zeros(dofs.nxi), np.zeros(dofs.n_v), np.zeros(4)
    d_alpha = on.aero.kinematics(q, xi, vel, np.zeros(0), u).alpha_el - off.aero.kinematics(q, xi, vel, np.zeros(0), u).alpha_el
    strips = on.aero.strips
    wing = gtm.component("right_wing")
    idx = [i for i, c in enumerate(strips.component) if c == "right_wing"]
    slope = bending_shapes(strips.station_m[idx], wing.length_m, wing.bending_modes, derivative=1) @ q[dofs.bending["right_wing"]]
    factor = -strips.p[idx, 1]  # p . (-y_i): sin(Lambda) up to the dihedral's second-order effect
    np.testing.assert_allclose(d_alpha[idx], factor * slope, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(factor, math.sin(wing.sweep), rtol=1e-3)
    others = [i for i, c in enumerate(strips.component) if c != "right_wing"]
    assert np.all(d_alpha[others] == 0.0)


def test_unswept_wing_is_unaffected_and_swept_wing_washes_out():
    goland = load_aircraft("goland_wing")
    kw = dict(variant="restrained", gravity_m_s2=0.0, restrained_velocity_m_s=[100.0, 0.0, 0.0])
    a = AircraftModel(goland, aero=AeroOptions("quasi-steady", bending_incidence=True), **kw)
    b = AircraftModel(goland, aero=AeroOptions("quasi-steady"), **kw)
    x = a.layout.zeros()
    x[a.layout.q] = 0.1
    np.testing.assert_allclose(a.rhs(0.0, x, np.zeros(4)), b.rhs(0.0, x, np.zeros(4)), rtol=1e-14, atol=1e-12)
    gtm = load_aircraft("gtm")
    on = AircraftModel(gtm, aero=AeroOptions("quasi-steady", bending_incidence=True))
    cruise = trim(on, SteadyManoeuvre.level(9144.0, mach=0.78))
    _, _, q, xi, vel = on.unpack(cruise.x)
    kin = on.aero.kinematics(q, xi, vel, np.zeros(0), cruise.u)
    tip = [i for i, c in enumerate(on.aero.strips.component) if c == "right_wing"][-1]
    assert kin.alpha_el[tip] < 0.0 < cruise.tip_twist_rad  # wash-out despite nose-up torsion
    assert -0.75 < cruise.tip_deflection_m < -0.6
