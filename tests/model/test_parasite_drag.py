"""Parasite drag items: closed forms of a body's drag and the GTM's realistic polar.

* In straight flight without rotation every drag item moves with the body velocity v, so the items'
  resultant is F = -1/2 rho |v| v sum(f_i) and their moment about o is sum r_i x F_i (Raymer 2018, sec. 12.5:
  D = q f, f = C_D0 S); asserted to 1e-12.
* The bundled GTM (notional 757-200 class) with Raymer's component build-up, C_D0 = 0.0148: cruise L/D at
  9144 m, M 0.78 in 15-20 (a transport; before: 57 with induced drag only), and a glide at
  gamma = -atan(D/L) exactly (a steady glide balances weight by the aerodynamic force alone).
"""

import math
import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft, parse_aircraft
from flexsim.errors import AircraftDefinitionError
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.trimming import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


def test_drag_items_resultant_and_moment_in_straight_flight(gtm):
    model = AircraftModel(gtm, aero="quasi-steady")
    drag = model.parasite_drag
    assert drag is not None and drag.n_items == 8
    assert drag.area_m2.sum() / 181.25 == pytest.approx(0.01477, abs=5e-5)
    n_v = model.structure.dofs.n_v
    vel = np.zeros(n_v)
    vel[0:3] = [230.0, 3.0, 20.0]
    rho = 0.4
    q = np.zeros(model.structure.dofs.nq)
    gen = drag.generalized_force(q, vel, rho)
    v = vel[0:3]
    f_i = -0.5 * rho * np.linalg.norm(v) * v[None, :] * drag.area_m2[:, None]
    np.testing.assert_allclose(gen[0:3], f_i.sum(axis=0), rtol=1e-12)
    points = np.array([d.position_m for d in gtm.aero_settings.drag])
    np.testing.assert_allclose(gen[3:6], np.cross(points, f_i).sum(axis=0), rtol=1e-10, atol=1e-9 * np.abs(gen[3:6]).max())


def test_gtm_cruise_lift_to_drag_and_glide(gtm):
    model = AircraftModel(gtm, aero="quasi-steady")
    cruise = trim(model, SteadyManoeuvre.level(9144.0, mach=0.78))
    assert 15.0 <= cruise.lift_n / cruise.drag_n <= 20.0
    assert cruise.thrust_n == pytest.approx(cruise.drag_n, rel=0.01)  # thrust along body x, alpha = 5.6 deg
    glide = trim(model, SteadyManoeuvre.glide(9144.0, mach=0.78))
    assert glide.gamma == pytest.approx(-math.atan(glide.drag_n / glide.lift_n), abs=1e-9)
    summary = cruise.summary()
    assert summary["lift_to_drag"] == pytest.approx(summary["lift_kN"] / summary["drag_kN"])
    off = AircraftModel(gtm, aero=AeroOptions("quasi-steady", parasite_drag=False))
    assert off.parasite_drag is None
    induced = trim(off, SteadyManoeuvre.level(9144.0, mach=0.78))
    # induced drag only: below the elliptic wing's L/D = pi A / C_L (minimum induced drag, Prandtl's lifting line;
    # A = 7.88, S = 181.25 m^2), and not far below it (span efficiency e > 0.6 for a transport wing and its tail)
    c_l = induced.lift_n / (0.5 * model.air_density(induced.x) * induced.manoeuvre.speed_m_s**2 * 181.25)
    elliptic = math.pi * 7.88 / c_l
    assert 0.6 * elliptic < induced.lift_n / induced.drag_n < elliptic
    assert AircraftModel(gtm, aero=AeroOptions("quasi-steady", formulation="paper")).parasite_drag is None


def test_drag_item_errors_name_the_field():
    with open(load_aircraft("goland_wing").source, encoding="utf-8") as fh:
        base = fh.read()
    bad = base + '\n[[aero.drag]]\nname = "pod"\ncomponent = "right_wing"\nposition_m = [0.0, 3.0, 0.0]\ndrag_area_m2 = -1.0\n'
    with pytest.raises(AircraftDefinitionError, match="drag_area_m2"):
        parse_aircraft(bad)
    bad = base + '\n[[aero.drag]]\nname = "pod"\ncomponent = "fuselage"\nposition_m = [0.0, 3.0, 0.0]\ndrag_area_m2 = 1.0\n'
    with pytest.raises(AircraftDefinitionError, match="aero.drag.pod.component = 'fuselage'"):
        parse_aircraft(bad)
    bad = base + '\n[[aero.drag]]\nname = "pod"\ncomponent = "right_wing"\nposition_m = [0.0, 3.0, 0.0]\narea = 1.0\n'
    with pytest.raises(AircraftDefinitionError, match=r"aero.drag\[0\].area: unknown key"):
        parse_aircraft(bad)
    ok = parse_aircraft(base + '\n[[aero.drag]]\nname = "pod"\ncomponent = "right_wing"\nposition_m = [0.0, 6.0, 0.0]\ndrag_area_m2 = 0.5\n')
    assert ok.aero_settings.drag[0].drag_area_m2 == 0.5
    assert ok.subset(["right_wing"]).aero_settings.drag == ok.aero_settings.drag
