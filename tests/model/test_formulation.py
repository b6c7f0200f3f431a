"""Force resolution as a selectable formulation and the density of the aerodynamics.

* "paper" (the paper's eq. 28 with d = l alpha_i0, docs/design.md "Force resolution"): the airloads of wing
  and stabilizer strips have no body-x component, so in steady level flight the body-x equilibrium is
  T_e = W sin(theta) exactly (thrust along body x, gravity's body-x component -W sin(theta), no rotation).
  The paper's Tables 2-3 satisfy it to 0.003 % (T_e / sin(theta) = 889.41-889.47 kN). Tolerance 1e-6: the
  trim residual is ~1e-13, so only round-off remains.
* "physical" (default) resolves lift normal to the local wind and drag along it: its T_e/(W sin theta) is
  far from 1 (0.14-0.18 on the calibrated GTM with induced drag only;
  0.53 with the GTM's parasite-drag items).
* One key in the aircraft file, one option in the API (AeroOptions.formulation overrides the file).
* aero_density_kg_m3: fixing the aerodynamics' density at the ISA value of the flight altitude reproduces the
  default exactly (the same numbers, bit for bit).
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft, parse_aircraft, resolve_aircraft_path
from flexsim.atmosphere import isa_density
from flexsim.errors import AircraftDefinitionError
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.trimming import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


@pytest.mark.parametrize("altitude_m, mach", [(0.0, 0.6742), (9144.0, 0.7791)])
def test_paper_formulation_level_trim_thrust_is_weight_times_sin_theta(gtm, altitude_m, mach):
    model = AircraftModel(gtm, aero=AeroOptions("quasi-steady", formulation="paper"))
    assert model.formulation == "paper"
    point = trim(model, SteadyManoeuvre.level(altitude_m, mach=mach), check_limits=False)
    weight = model.structure.mass_properties.mass_kg * model.terms.gravity_m_s2
    assert point.residual < 1e-8
    assert point.thrust_n / (weight * math.sin(point.theta)) == pytest.approx(1.0, abs=1e-6)


def test_physical_formulation_is_the_default_and_differs(gtm):
    model = AircraftModel(gtm, aero="quasi-steady")
    assert model.formulation == "physical"
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.7791), check_limits=False)
    weight = model.structure.mass_properties.mass_kg * model.terms.gravity_m_s2
    assert point.thrust_n / (weight * math.sin(point.theta)) < 0.7


def test_paper_formulation_steady_lifting_strips_carry_no_body_x_force(gtm):
    """At any symmetric steady state (no elastic rates) the generalized aero force on u vanishes."""
    model = AircraftModel(gtm, aero=AeroOptions("quasi-steady", formulation="paper"))
    x = trim(model, SteadyManoeuvre.level(3048.0, mach=0.7), check_limits=False).x.copy()
    rng = np.random.default_rng(3)
    _, _, q, xi, v = model.unpack(x)
    dofs = model.structure.dofs
    q_try, xi_try = q.copy(), xi.copy()
    for name in ("right_wing", "left_wing", "right_htail", "left_htail"):  # any deformation of the lifting surfaces
        b, t = dofs.bending[name], dofs.torsion[name]
        q_try[b] += 0.05 * rng.standard_normal(b.stop - b.start)
        xi_try[t] += 0.01 * rng.standard_normal(t.stop - t.start)
    vel = v.copy()
    vel[1] = vel[3] = vel[5] = 0.0  # symmetric: no sideslip, roll or yaw rate (the fin is unloaded)
    vel[6:] = 0.0
    _, q_a, _ = model.aero.evaluate(q_try, xi_try, vel, np.zeros(0), np.zeros(4), 0.5, 0.7)
    assert abs(q_a[0]) <= 1e-12 * abs(q_a[2])
    phys = AircraftModel(gtm, aero="quasi-steady")
    _, q_p, _ = phys.aero.evaluate(q_try, xi_try, vel, np.zeros(0), np.zeros(4), 0.5, 0.7)
    assert abs(q_p[0]) > 1e-3 * abs(q_p[2])  # the physical resolution does have one


def test_formulation_key_in_the_aircraft_file(tmp_path):
    text = resolve_aircraft_path("gtm").read_text().replace("schema_version = 1", 'schema_version = 1\nformulation = "paper"', 1)
    aircraft = parse_aircraft(text)
    assert aircraft.formulation == "paper"
    assert AircraftModel(aircraft, aero="quasi-steady").formulation == "paper"
    # the API option overrides the file
    assert AircraftModel(aircraft, aero=AeroOptions("quasi-steady", formulation="physical")).formulation == "physical"
    bad = text.replace('formulation = "paper"', 'formulation = "textbook"')
    with pytest.raises(AircraftDefinitionError, match=r"formulation = 'textbook': must be one of 'physical', 'paper'"):
        parse_aircraft(bad)
    with pytest.raises(ValueError, match="formulation = 'exact'"):
        AeroOptions("quasi-steady", formulation="exact")


def test_fixed_aero_density_at_the_flight_altitude_reproduces_the_default(gtm):
    altitude = 6096.0
    man = SteadyManoeuvre.level(altitude, mach=0.75)
    true = AircraftModel(gtm, aero="quasi-steady")
    fixed = AircraftModel(gtm, aero="quasi-steady", aero_density_kg_m3=float(isa_density(altitude)))
    point = trim(true, man, check_limits=False)
    assert np.array_equal(true.rhs(0.0, point.x, point.u), fixed.rhs(0.0, point.x, point.u))
    other = AircraftModel(gtm, aero="quasi-steady", aero_density_kg_m3=float(isa_density(0.0)))
    assert not np.allclose(true.rhs(0.0, point.x, point.u), other.rhs(0.0, point.x, point.u))
    with pytest.raises(ValueError, match="aero_density_kg_m3 = -1.0"):
        AircraftModel(gtm, aero="quasi-steady", aero_density_kg_m3=-1.0)


def test_simulated_manoeuvres_take_the_formulation():
    from flexsim.sim.manoeuvres import build_manoeuvre

    setup = build_manoeuvre("elevator-doublet", aero="quasi-steady", formulation="paper")
    assert setup.model.formulation == "paper"
    weight = setup.model.structure.mass_properties.mass_kg * setup.model.terms.gravity_m_s2
    level = setup.initial  # the cruise trim the doublet starts from
    assert level.thrust_n / (weight * math.sin(level.theta)) == pytest.approx(1.0, abs=1e-6)
